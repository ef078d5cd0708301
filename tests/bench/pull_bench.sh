#!/usr/bin/env bash
# `mosb store pull` of a published suite against `curl` (the same files, the same parallelism)
# followed by `sha256sum -c` against the MANIFEST's sums, both from nginx on loopback
# (tests/store/nginx.conf). Prints the wall time, throughput and peak memory of each, in
# alternating rounds. Figures: BENCHMARKS.md.
#
#   tests/bench/pull_bench.sh [SUITE_DIR]
#
# SUITE_DIR: a published store; default $WORK/suite, made by `mosb suite build` (packed) when
# absent. Environment: MOSB (default build/release/tools/mosb), WORK (default /tmp/mosb-pull-bench),
# JOBS (transfers at once, default 4), ROUNDS (default 3), BIG (default 1: also the peak memory of
# pulling one big file, below).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
mosb=${MOSB:-$here/../../build/release/tools/mosb}
work=${WORK:-/tmp/mosb-pull-bench}
suite=$(realpath -m "${1:-$work/suite}")
jobs=${JOBS:-4}
rounds=${ROUNDS:-3}
mkdir -p "$work"
[[ -f $suite/MANIFEST ]] || "$mosb" suite build "$suite" >/dev/null

source "$here/serve_store.sh"
serve_store "$suite" "$work/nginx"

# The file names and the "SHA-256  NAME" lines sha256sum -c reads, from the MANIFEST.
/usr/bin/python3 - "$suite/MANIFEST" "$work" <<'EOF'
import json, os, sys
entries = [json.loads(line) for line in open(sys.argv[1]).read().splitlines()[1:]]
with open(os.path.join(sys.argv[2], "names"), "w") as f:
    f.writelines(e["file"] + "\n" for e in entries)
with open(os.path.join(sys.argv[2], "sums"), "w") as f:
    f.writelines("%s  %s\n" % (e["sha256"], e["file"]) for e in entries)
EOF
files=$(wc -l <"$work/names")
bytes=$(cd "$suite" && xargs -a "$work/names" stat -c %s | paste -sd+ | bc)
echo "suite: $files files, $bytes bytes; $jobs transfers at once; $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"

figure() {  # label seconds peak_kib
  awk -v l="$1" -v s="$2" -v m="$3" -v b="$bytes" \
    'BEGIN { printf "%-28s %7.2f s  %8.1f MB/s  peak RSS %7.1f MB\n", l, s, b / s / 1e6, m / 1024 }'
}

for round in $(seq "$rounds"); do
  rm -rf "$work/store"
  read -r seconds peak < <(/usr/bin/time -f "%e %M" "$mosb" store pull "$work/store" "$url" \
    --jobs "$jobs" 2>&1 >/dev/null | tail -1)
  "$mosb" store verify "$work/store" >/dev/null
  figure "mosb store pull" "$seconds" "$peak"

  rm -rf "$work/curl" && mkdir "$work/curl"
  start=$(date +%s.%N)
  (cd "$work/curl" && xargs -a "$work/names" -P "$jobs" -I{} curl -sfS -o {} "$url/{}" &&
    sha256sum --quiet -c "$work/sums")
  end=$(date +%s.%N)
  figure "curl -P $jobs, then sha256sum -c" "$(echo "$end - $start" | bc)" 0

  # The check a pull makes beyond SHA-256 (content digest, verify --level full, packed files
  # decoded), on curl's download: what a user without `store pull` runs by hand.
  start=$(date +%s.%N)
  cp "$suite/MANIFEST" "$work/curl/"
  read -r seconds peak < <(/usr/bin/time -f "%e %M" "$mosb" verify --manifest "$work/curl/MANIFEST" \
    2>&1 >/dev/null | tail -1)
  end=$(date +%s.%N)
  figure "  mosb verify --manifest alone" "$(echo "$end - $start" | bc)" "$peak"

  rm -rf "$work/curl" && mkdir "$work/curl"
  start=$(date +%s.%N)
  (cd "$work/curl" && xargs -a "$work/names" -P "$jobs" -I{} curl -sfS -o {} "$url/{}")
  end=$(date +%s.%N)
  figure "curl -P $jobs alone" "$(echo "$end - $start" | bc)" 0
done

# Peak memory against file size (issue 24 §3): the pull of a store holding one Grid 1500x1500
# (171 MB unpacked, 13 MB packed at level 3), packed and unpacked, from a directory, beside the
# suite's (the bigger store's files are made once, in $WORK/big). BIG=0 skips it.
if [[ ${BIG:-1} != 0 ]]; then
  big=$work/big
  if [[ ! -f $big/packed/MANIFEST ]]; then
    rm -rf "$big" && mkdir -p "$big/src"
    "$mosb" generate grid --width 1500 --height 1500 -o "$big/src/big.mosb" >/dev/null
    "$mosb" pack --level 3 "$big/src/big.mosb" -o "$big/src/big.packed.mosb" >/dev/null
    "$mosb" store init "$big/packed" >/dev/null && "$mosb" store add "$big/packed" "$big/src/big.packed.mosb" >/dev/null
    "$mosb" store init "$big/unpacked" >/dev/null && "$mosb" store add "$big/unpacked" "$big/src/big.mosb" >/dev/null
  fi
  for source in "$suite" "$big/packed" "$big/unpacked"; do
    for j in 1 "$jobs"; do
      rm -rf "$work/store"
      read -r seconds peak < <(/usr/bin/time -f "%e %M" "$mosb" store pull "$work/store" "$source" \
        --jobs "$j" 2>&1 >/dev/null | tail -1)
      awk -v l="pull $(basename "$source") --jobs $j" -v s="$seconds" -v m="$peak" \
        'BEGIN { printf "%-28s %7.2f s  peak RSS %7.1f MB\n", l, s, m / 1024 }'
    done
  done
fi
