#!/usr/bin/env bash
# The independent Python reader (spec/reference, written from spec/FORMAT.md alone) must read
# exactly what the C++ writer wrote: the golden file and generated grids.
# Usage: reference_reader_test.sh MOSB DUMP_JSON PYTHON SOURCE_DIR
set -euo pipefail
mosb="$1" dump="$2" python="$3" source="$4"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$mosb" generate grid --width 30 --height 20 --objectives 3 --seed 4 -o "$work/grid.mosb" >/dev/null
"$mosb" generate grid --width 1 --height 1 --objectives 1 --seed 1 -o "$work/tiny.mosb" >/dev/null
for file in "$source/spec/golden/1.0/valid/small.mosb" "$work/grid.mosb" "$work/tiny.mosb"; do
  "$dump" "$file" > "$work/dump.json"
  "$python" "$source/spec/reference/compare_dump.py" "$file" "$work/dump.json"
done
# Solution files (file kind 2, spec/SOLUTIONS.md) are not instances: the reference reader refuses
# every golden one by its kind, never crashes on it.
for file in "$source"/spec/golden/1.1/solutions/valid/*.sol.mosb "$source"/spec/golden/1.3/solutions/valid/*.sol.mosb; do
  if "$python" "$source/spec/reference/mosb_reader.py" "$file" > "$work/out.txt" 2>&1; then
    echo "reference reader accepted solution file $file" >&2; exit 1
  fi
  grep -q "file_kind is 2 (solution file)" "$work/out.txt" || { cat "$work/out.txt" >&2; exit 1; }
done
