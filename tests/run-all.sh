#!/usr/bin/env bash
# Every test: installs what is missing, then the release build and its tests, the style and static
# checks, and one clang build with AddressSanitizer and UndefinedBehaviorSanitizer (the `sanitize`
# preset) that serves both a bounded fuzz run of every parser and the tests again.
# MOSB_FUZZ_SECONDS sets the reader's fuzz time (default 20; tests/fuzz/run.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"

# Every package the tests, the lint and the fuzzers need (the Quick start installs only the build's).
bash tools/install-deps.sh all

# The README's first Quick start command: the program built and the main job run on its embedded
# default (so it runs in CI as the README promises).
echo "== bash tools/quickstart.sh"
bash tools/quickstart.sh

echo "== release build"
cmake --build --preset release

# ctest with the given arguments; the tests it reports skipped (for want of something CI has:
# ../shared, nginx, root, ...) are appended to $skipped and listed at the end.
skipped=build/skipped-tests.txt
: >"$skipped"
run_ctest() {
  local log
  log=$(mktemp)
  ctest "$@" 2>&1 | tee "$log"
  sed -n 's/^[[:space:]]*[0-9]* - \(.*\) (Skipped)$/\1/p' "$log" >>"$skipped"
  rm -f "$log"
}

echo "== release tests"
run_ctest --preset release -j "$jobs"

echo "== clang-format and clang-tidy"
bash tools/lint.sh build/release

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build (clang; tests and fuzz targets)"
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize -j "$jobs"

echo "== fuzz every parser (the reader for ${MOSB_FUZZ_SECONDS:-20}s)"
bash tests/fuzz/run.sh "${MOSB_FUZZ_SECONDS:-20}" build/sanitize

echo "== AddressSanitizer + UndefinedBehaviorSanitizer tests"
run_ctest --preset sanitize -j "$jobs"

if [[ -s $skipped ]]; then
  echo "== skipped ($(wc -l <"$skipped"); each names what it lacked in its output above):"
  sed 's/^/  /' "$skipped"
else
  echo "== no test skipped"
fi
