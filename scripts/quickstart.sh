#!/usr/bin/env bash
# Installs the dependencies, builds Peridot and runs the quickstart example (examples/quickstart).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --target peridot
build/peridot run examples/quickstart/deck.yaml
/usr/bin/python3 tools/peridot_results.py examples/quickstart/out/quickstart.e damage examples/quickstart/out/damage.png
