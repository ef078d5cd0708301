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
# Nor at GCC's precompiled headers (target_precompile_headers, tools/CMakeLists.txt): clang cannot
# read a .gch, so it gets the database without them, and each file is checked with its own includes.
db=$(mktemp -d)
trap 'rm -rf "$db"' EXIT
sed -E 's# -Winvalid-pch##g; s# -include [^ "]*/cmake_pch\.hxx##g' "$build/compile_commands.json" \
  >"$db/compile_commands.json"
printf '%s\n' "${units[@]}" |
  xargs -P "$(nproc)" -n 4 clang-tidy -p "$db" --quiet --extra-arg=-Wno-unknown-warning-option
