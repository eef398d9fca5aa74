#!/usr/bin/env bash
# Checks that the C++ files in the listed folders match .clang-format (clang-format 14, Debian 12).
# CI runs it before the tests (scripts/test.sh). A folder joins the list once it has been formatted
# whole: the whole tree is.
#
#   scripts/check-format.sh         list the files that differ and exit 1 (nothing is changed)
#   scripts/check-format.sh --fix   format those files in place
set -euo pipefail

cd "$(dirname "$0")/.."
folders=(sim io widgets app tests fuzz)

mapfile -t files < <(find "${folders[@]}" -type f \( -name '*.cpp' -o -name '*.h' \) | sort)
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
differ=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || differ+=("$f")
done
if ((${#differ[@]})); then
  echo "!! these files do not match .clang-format (fix: scripts/check-format.sh --fix):"
  printf '   %s\n' "${differ[@]}"
  exit 1
fi
echo "== clang-format: ${#files[@]} files in ${folders[*]} match .clang-format"
