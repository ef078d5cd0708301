#!/usr/bin/env bash
# Every test: installs what is missing, then the release build and its tests, the style and static
# checks, a bounded fuzz run of every parser, and the tests again under AddressSanitizer and
# UndefinedBehaviorSanitizer.
# MOSB_FUZZ_SECONDS sets the fuzz time (default 60).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
jobs="$(nproc)"

echo "== release build and tests"
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs"
ctest --preset release -j "$jobs"

echo "== clang-format and clang-tidy"
bash tools/lint.sh build/release

echo "== fuzz the reader for ${MOSB_FUZZ_SECONDS:-60}s"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$jobs"
bash tests/fuzz/run.sh "${MOSB_FUZZ_SECONDS:-60}"

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize -j "$jobs"
ctest --preset sanitize -j "$jobs"
