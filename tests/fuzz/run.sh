#!/usr/bin/env bash
# Bounded fuzz run of the binary reader, seeded from spec/golden and a generated grid.
# Usage: tests/fuzz/run.sh [SECONDS]   (needs the `fuzz` preset built: cmake --build --preset fuzz)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-60}"
fuzzer="$root/build/fuzz/tests/fuzz/mosb_fuzz_reader"
corpus="$(mktemp -d)"
trap 'rm -rf "$corpus"' EXIT
cp "$root"/spec/golden/*/valid/*.mosb "$root"/spec/golden/*/invalid/*.mosb "$corpus"/
if [[ -x "$root/build/release/tools/mosb" ]]; then
  "$root/build/release/tools/mosb" generate grid --width 3 --height 2 --objectives 2 -o "$corpus/grid.mosb" >/dev/null
fi
echo "fuzzing the reader for ${seconds}s from $(ls "$corpus" | wc -l) seed files"
"$fuzzer" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 "$corpus" 2>&1 | tail -n 25
