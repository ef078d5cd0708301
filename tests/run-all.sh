#!/usr/bin/env bash
# Every test: installs what is missing, then the release build and its tests, the style and static
# checks, and one clang build with AddressSanitizer and UndefinedBehaviorSanitizer (the `sanitize`
# preset) that serves both a bounded fuzz run of every parser and the tests again.
# MOSB_FUZZ_SECONDS sets the reader's fuzz time (default 20; tests/fuzz/run.sh).
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

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build (clang; tests and fuzz targets)"
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize -j "$jobs"

echo "== fuzz every parser (the reader for ${MOSB_FUZZ_SECONDS:-20}s)"
bash tests/fuzz/run.sh "${MOSB_FUZZ_SECONDS:-20}" build/sanitize

echo "== AddressSanitizer + UndefinedBehaviorSanitizer tests"
ctest --preset sanitize -j "$jobs"
