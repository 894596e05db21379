#!/usr/bin/env bash
# Builds a fuzzer (clang, AddressSanitizer, UndefinedBehaviorSanitizer, libFuzzer) in build-fuzz and runs it for
# SECONDS (default 90): FUZZ_TARGET=deck (the default) on a corpus seeded with every example and test deck,
# FUZZ_TARGET=mesh on Gmsh and Abaqus meshes (fuzz/mesh_seeds.py). Fails (exit 1, the input in
# build-fuzz/findings/) on any input that crashes, trips a sanitizer, leaks, throws anything but an input error,
# or takes more than 10 s. Usage: scripts/fuzz.sh [SECONDS] [extra libFuzzer options, e.g. -runs=1000000]
# The mutation seed is FUZZ_SEED (default 1, so that a CI run explores the same inputs each time; give another
# number, or 0 for a random one, to explore further).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-90}
shift || true
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Fuzz -DPERIDOT_FUZZ=ON >/dev/null
target=${FUZZ_TARGET:-deck}
cmake --build build-fuzz --target "${target}_fuzzer"
corpus=build-fuzz/corpus
[ "$target" = deck ] || corpus=build-fuzz/corpus_$target
mkdir -p "$corpus" build-fuzz/findings
if [ "$target" = deck ]; then
  # The seeds, named after their paths (several folders have a deck.yaml). fuzz/regressions holds the inputs
  # that once failed (each fixed): every run starts by running them again under the sanitizers.
  for deck in examples/*/deck*.yaml tests/data/decks/*.yaml tests/regression/decks/*.yaml fuzz/regressions/*.yaml; do
    cp "$deck" "$corpus/seed_${deck//\//_}"
  done
else
  /usr/bin/python3 fuzz/mesh_seeds.py "$corpus"
fi
export OMP_NUM_THREADS=1
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  "./build-fuzz/fuzz/${target}_fuzzer" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=3072 \
  -artifact_prefix=build-fuzz/findings/ -print_final_stats=1 -seed="${FUZZ_SEED:-1}" "$@"
