#!/usr/bin/env bash
# Installs the dependencies, builds Peridot and runs the whole test suite (unit, verification,
# regression and example smoke tests), then the deck and mesh fuzzers for a minute and a half. This is what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
# Tests run two at a time, one OpenMP thread each (the thread-determinism test asks for 2 itself);
# passive waiting keeps OpenMP from spinning against the other test on a 2-core machine.
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
ctest --test-dir build --output-on-failure -j 2 "$@"
# The suite above runs the best SIMD target of this CPU (core/simd.hpp); the bond-loop tests run once more
# with each other target it has (avx2 is what an AVX2-only CPU runs; scalar takes the portable loops;
# SimdTargets compares every target on every model).
for target in avx2 sse4 scalar; do
  PERIDOT_SIMD=$target ./build/peridot info > /dev/null 2>&1 || continue  # not available on this CPU
  echo "bond-loop tests with PERIDOT_SIMD=$target"
  PERIDOT_SIMD=$target ./build/tests/peridot_tests --gtest_brief=1 \
    --gtest_filter='ModelInvariants*:LpsBondLoops*:BondFailureInForcePass*:UniformVolume*:Corr*:ThreadDeterminism*:LpsPlasticUniaxial*:LpsPlasticVolumetric*:LpsPlasticDissipation*:*LpsPlasticFamily*:LpsViscoelasticRelaxation*:LpsViscoelasticCreep*'
done
# Then the deck fuzzer for a minute and the mesh fuzzer for half a minute: any deck or Gmsh/Abaqus file that
# crashes the loader, the set-up or a mesh reader fails the run.
bash scripts/fuzz.sh 60
FUZZ_TARGET=mesh bash scripts/fuzz.sh 30
