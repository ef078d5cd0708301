#!/usr/bin/env bash
# Style and static checks: every C/C++ file matches .clang-format, and the library, converters and
# the program pass .clang-tidy (warnings are errors). Usage: tools/lint.sh BUILD_DIR (a configured
# build with compile_commands.json).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:?usage: tools/lint.sh BUILD_DIR}"

mapfile -t sources < <(git ls-files '*.c' '*.cpp' '*.h' '*.hpp')
echo "clang-format: ${#sources[@]} files"
clang-format --dry-run --Werror "${sources[@]}"

mapfile -t units < <(git ls-files 'format/*.cpp' 'lib/*.cpp' 'converters/*.cpp' 'tools/*.cpp' 'capi/*.cpp' 'report/*.cpp')
echo "clang-tidy: ${#units[@]} translation units"
# The compile database is GCC's: clang must not stop at GCC-only warning flags.
# The program's sources are compiled as unity sources (tools/CMakeLists.txt), which the database
# lists instead of them: each source gets its unity source's command, so each is checked alone.
db=$(mktemp -d)
trap 'rm -rf "$db"' EXIT
/usr/bin/python3 - "$build/compile_commands.json" >"$db/compile_commands.json" <<'EOF'
import json, re, sys
entries = []
for entry in json.load(open(sys.argv[1])):
    if "/Unity/unity_" not in entry["file"]:
        entries.append(entry)
        continue
    for source in re.findall(r'#include "([^"]+)"', open(entry["file"]).read()):
        entries.append(dict(entry, file=source,
                            command=entry["command"].replace(entry["file"], source)))
json.dump(entries, sys.stdout)
EOF
printf '%s\n' "${units[@]}" |
  xargs -P "$(nproc)" -n 4 clang-tidy -p "$db" --quiet --extra-arg=-Wno-unknown-warning-option
