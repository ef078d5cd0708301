#!/usr/bin/env bash
# Every test: installs what is missing, then the release build and its tests, the style and static
# checks, and one clang build with AddressSanitizer and UndefinedBehaviorSanitizer (the `sanitize`
# preset) that serves both a bounded fuzz run of every parser and the tests again.
# MOSB_FUZZ_SECONDS sets the reader's fuzz time (default 20; tests/fuzz/run.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"

# The README's first Quick start command: dependencies, the release build, and the main job on
# its embedded default (so it runs in CI as the README promises).
echo "== bash tools/quickstart.sh"
bash tools/quickstart.sh

echo "== release tests"
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
