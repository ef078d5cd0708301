#!/usr/bin/env bash
# Builds the README's example report and its screenshot (docs/report.png): a generated Grid and
# NetMaker, the Moving AI map arena2 with one guard (from ../shared/data, when present), each with
# five queries solved by the example NAMOA* and BOA* through `mosb run`.
#   tools/report-example.sh [BUILD_DIR] [OUT_DIR]     (defaults: build/release, report-example)
set -euo pipefail
build=$(realpath "${1:-build/release}")
out=${2:-report-example}
mosb="$build/tools/mosb"
examples="$build/examples"
source_dir=$(cd "$(dirname "$0")/.." && pwd)
arena="$source_dir/../shared/data/movingai/arena2.map"
mkdir -p "$out"
cd "$out"
"$mosb" generate grid --width 30 --height 30 --objectives 3 -o grid.mosb >/dev/null
"$mosb" generate netmaker --vertices 1000 --amin 1 --amax 10 --locality 20 -o netmaker.mosb >/dev/null
runs=("grid.mosb Grid_2 namoa" "grid.mosb Grid_2 boa_star" "netmaker.mosb NetMaker-1k_3 namoa")
instances=(grid.mosb netmaker.mosb)
if [[ -f "$arena" ]]; then
  echo "120 100 25" > guards.txt
  "$mosb" convert guards --map "$arena" --guards guards.txt -o arena.mosb >/dev/null
  instances+=(arena.mosb)
  runs+=("arena.mosb Games-GUARDS_2 namoa" "arena.mosb Games-GUARDS_2 boa_star")
fi
for instance in "${instances[@]}"; do
  "$mosb" queries generate "$instance" --set q --count 5 --seed 3 --in-place 2>/dev/null
done
solutions=()
references=()
for r in "${runs[@]}"; do
  read -r instance view solver <<<"$r"
  sol="$solver-${instance%.mosb}.sol"
  "$mosb" run "$instance" --view "$view" --queries q --time-limit 60s --memory-limit 2G \
    --solver "$examples/$solver {instance} --view {view} --query {source} {target} --protocol" -o "$sol"
  solutions+=("$sol")
  if [[ $solver == namoa ]]; then references+=("$sol"); fi
done
"$mosb" report "${instances[@]}" --solutions "${solutions[@]}" --reference "${references[@]}" \
  --title "mosb report: example suite" -o report.html
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --screenshot="$PWD/report.png" \
  --window-size=1100,1300 "file://$PWD/report.html" 2>/dev/null
echo "wrote $out/report.html and $out/report.png"
