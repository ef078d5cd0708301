#!/usr/bin/env bash
# References in a store (issue 45): (1) `mosb store pull` of a published store's reference files,
# their instances already present, against `curl` of the same files followed by `sha256sum -c`,
# from nginx on loopback (tests/store/nginx.conf); (2) `mosb eval RESULTS --reference STORE`
# against `--reference REFS/` (the same files, loose). Alternating rounds; figures: BENCHMARKS.md.
#
#   tests/bench/references_bench.sh
#
# The references are synthetic exact fronts (VECTORS two-objective vectors for each of the
# instances' one query, each coordinate moving by a random step of 1 to 1000, so that they pack
# about as a real front does, not a thousand times smaller), imported with `mosb solutions import
# --table`; RESULTS is an experiment of the example NAMOA* on the same instances. Environment:
# MOSB (default build/release/tools/mosb), EXAMPLES (default build/release/examples), WORK
# (default /tmp/mosb-references-bench), VECTORS (default 500000), ROUNDS (default 5), JOBS
# (default 4), PACK (default 1: the published references packed, as `suite release
# --pack-references` stores them; 0: raw, its default).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
mosb=$(realpath "${MOSB:-$here/../../build/release/tools/mosb}")
examples=$(realpath "${EXAMPLES:-$here/../../build/release/examples}")
work=${WORK:-/tmp/mosb-references-bench}
vectors=${VECTORS:-500000}
rounds=${ROUNDS:-5}
jobs=${JOBS:-4}
rm -rf "$work"
mkdir -p "$work/refs"
cd "$work"

"$mosb" generate grid --suite published --sizes 30,40 --pack >/dev/null
for instance in published/*.mosb; do
  name=$(basename "$instance" .mosb)
  /usr/bin/python3 -c "
import random, sys
n, rng = int(sys.argv[1]), random.Random(sys.argv[2])
print('query,c1,c2')
a, b = 0, 1000 * n
for i in range(n):  # steps as uneven as a road network's front: random, seeded by the name
    a += rng.randint(1, 1000)
    b -= rng.randint(1, 999)
    print('0,%d,%d' % (a, b))" "$vectors" "$name" >"$name.csv"
  "$mosb" solutions import --instance "$instance" --view Grid_2 --table "$name.csv" \
    --solver reference -o "refs/$name.Grid_2.sol" >/dev/null
  rm "$name.csv"
done
# Packed (format 1.6) as `suite release --pack-references` stores them; PACK=0 keeps them raw.
"$mosb" store add $([ "${PACK:-1}" = 0 ] || echo --pack) published refs/*.sol >/dev/null
cat >exp.toml <<EOF
name = "bench"
store = "$work/published"
benchmarks = ["Grid_2"]
limits = { time = "60s" }
[[solver]]
name = "namoa"
template = "$examples/namoa {instance} --view {view} --query {source} {target} --protocol"
EOF
"$mosb" experiment run exp.toml -o results >/dev/null

source "$here/serve_store.sh"
serve_store "$work/published" "$work/nginx"

/usr/bin/python3 - published/MANIFEST <<'EOF'
import json, sys
entries = [json.loads(line) for line in open(sys.argv[1]).read().splitlines()[1:]]
refs = [e for e in entries if e.get("kind") == "solutions"]
open("names", "w").writelines(e["file"] + "\n" for e in refs)
open("sums", "w").writelines("%s  %s\n" % (e["sha256"], e["file"]) for e in refs)
EOF
bytes=$(cd published && xargs -a ../names stat -c %s | paste -sd+ | bc)
echo "references: $(wc -l <names) files, $bytes bytes, $vectors vectors each; $jobs transfers" \
  "at once; $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"

seconds() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
for round in $(seq "$rounds"); do
  rm -rf store curl
  "$mosb" store pull store "$url" --no-references >/dev/null
  pull=$(seconds "$mosb" store pull store "$url" --file '*.sol' --jobs "$jobs")
  mkdir curl
  pipeline=$( (cd curl && seconds bash -c "sed 's|^|$url/|' ../names | xargs -P $jobs -n 1 curl -sfO \
    && sha256sum --quiet -c ../sums"))
  # The pipeline with the check the pull makes: each reference against its instance.
  checked=$( (cd curl && seconds bash -c "sed 's|\.Grid_2\.sol\$||' ../names | xargs -P $jobs -I{} \
    '$mosb' solutions verify --instance ../store/{}.mosb {}.Grid_2.sol"))
  local_eval=$(seconds "$mosb" eval results --reference refs)
  # The store's own files, loose: what the store adds beyond decoding them.
  rm -rf loose && mkdir loose && cp store/*.sol loose/
  loose_eval=$(seconds "$mosb" eval results --reference loose)
  store_eval=$(seconds "$mosb" eval results --reference store)
  awk -v r="$round" -v p="$pull" -v c="$pipeline" -v k="$checked" -v l="$local_eval" \
    -v o="$loose_eval" -v s="$store_eval" 'BEGIN { printf "round %d: pull %.2f s, curl + sha256sum %.2f s (%.2fx), then solutions verify --instance %.2f s (%.2fx); eval refs/ %.2f s, the stored files loose %.2f s, store %.2f s (%.2fx refs/, %.2fx loose)\n", r, p, c, c / p, k, (c + k) / p, l, o, s, s / l, s / o }'
done
