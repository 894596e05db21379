#!/usr/bin/env bash
# Installs the dependencies, builds Peridot and runs the whole test suite (unit, verification,
# regression and example smoke tests), then the deck fuzzer for a minute. This is what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
# Tests run two at a time, one OpenMP thread each (the thread-determinism test asks for 2 itself);
# passive waiting keeps OpenMP from spinning against the other test on a 2-core machine.
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
ctest --test-dir build --output-on-failure -j 2 "$@"
# Then the deck fuzzer for a minute: any deck that crashes the loader or the set-up fails the run.
bash scripts/fuzz.sh 60
