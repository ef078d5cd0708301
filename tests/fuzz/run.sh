#!/usr/bin/env bash
# Bounded fuzz runs: the binary reader for SECONDS (default 20), every other target for a third of
# that (at least 5 s). Seeds: spec/golden for the reader, tests/fuzz/corpus/<target>/ for the others.
# Usage: tests/fuzz/run.sh [SECONDS] [BUILD_DIR]. BUILD_DIR (default build/sanitize, the build CI
# tests) needs its fuzz targets built: cmake --preset sanitize && cmake --build --preset fuzz
# (or the whole `sanitize` build). Any build configured with MOSB_FUZZ=ON will do.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-20}"
build="${2:-$root/build/sanitize}"
bin="$build/tests/fuzz"
if [[ ! -x "$bin/mosb_fuzz_reader" ]]; then
  echo "tests/fuzz/run.sh: no fuzz targets in $bin; build them first:" \
    "cmake --preset sanitize && cmake --build --preset fuzz" >&2
  exit 1
fi
bin="$(cd "$bin" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

run() {  # target seconds seed-files... (MAX_LEN: the longest input, 64 KiB unless set)
  local target="$1" time="$2"
  shift 2
  mkdir -p "$work/$target"
  cp "$@" "$work/$target"/ 2>/dev/null || true
  echo "fuzzing $target for ${time}s from $(ls "$work/$target" | wc -l) seed files"
  "$bin/$target" -max_total_time="$time" -max_len="${MAX_LEN:-65536}" -timeout=10 -rss_limit_mb=4096 \
    -print_final_stats=1 "$work/$target" > "$work/$target.log" 2>&1 || {
    tail -n 60 "$work/$target.log"
    echo "fuzz target $target failed"
    exit 1
  }
  grep -E "^Done|stat::new_units_added" "$work/$target.log"
}

run mosb_fuzz_reader "$seconds" "$root"/spec/golden/*/valid/*.mosb "$root"/spec/golden/*/invalid/*.mosb
run mosb_fuzz_solutions "$((seconds / 3 > 5 ? seconds / 3 : 5))" "$root"/spec/golden/*/solutions/*/*.mosb
run mosb_fuzz_unpack "$((seconds / 3 > 5 ? seconds / 3 : 5))" "$root"/spec/golden/*/valid/*.mosb \
  "$root"/spec/golden/*/packed/*/*.mosb "$root"/spec/golden/1.6/solutions/*/*.mosb
run mosb_fuzz_streaming_verify "$((seconds / 3 > 5 ? seconds / 3 : 5))" \
  "$root"/spec/golden/*/valid/*.mosb "$root"/spec/golden/*/invalid/*.mosb \
  "$root"/spec/golden/*/packed/*/*.mosb
run mosb_fuzz_c_api "$((seconds / 3 > 5 ? seconds / 3 : 5))" "$root"/spec/golden/*/valid/*.mosb \
  "$root"/spec/golden/*/invalid/*.mosb "$root"/spec/golden/*/packed/*/*.mosb
for fuzzer in "$bin"/mosb_fuzz_*; do
  target="$(basename "$fuzzer")"
  [[ "$target" =~ ^mosb_fuzz_(reader|solutions|unpack|streaming_verify|c_api|profile)$ ]] && continue
  run "$target" "$((seconds / 3 > 5 ? seconds / 3 : 5))" "$root"/tests/fuzz/corpus/"$target"/*
done
# A profile file is read with a cap of 1 MiB: inputs may pass it, and a seed just past it starts
# the fuzzer there.
head -c 1048577 /dev/zero | tr '\0' '#' > "$work/past-the-cap.toml"
MAX_LEN=1048600 run mosb_fuzz_profile "$((seconds / 3 > 5 ? seconds / 3 : 5))" \
  "$root"/tests/fuzz/corpus/mosb_fuzz_profile/* "$work/past-the-cap.toml"
