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
printf '%s\n' "${units[@]}" |
  xargs -P "$(nproc)" -n 4 clang-tidy -p "$build" --quiet --extra-arg=-Wno-unknown-warning-option
