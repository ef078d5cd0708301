#!/usr/bin/env bash
# The main job on an embedded default: install what building the program needs (and nothing the
# tests need), build the mosb program alone, generate a 300x300 grid with 3 objectives like the
# suite's Grid-300x300 (seed 1: not the suite's instance, whose seed spec/GENERATORS.md derives
# from the suite seed), inspect it and verify it fully.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh build
cmake --preset release >/dev/null
cmake --build --preset release --target mosb
mosb=build/release/tools/mosb
mkdir -p build/demo
"$mosb" generate grid --width 300 --height 300 --objectives 3 --seed 1 -o build/demo/Grid-300x300.mosb
"$mosb" inspect build/demo/Grid-300x300.mosb
"$mosb" verify --level full build/demo/Grid-300x300.mosb
