#!/usr/bin/env bash
# The C++ sources follow .clang-format (Google style, 100 columns): `clang-format --dry-run --Werror`
# over every tracked C++ file (every such file outside build trees when there is no git checkout).
# `clang-format -i FILE` formats one. Usage: clang_format.sh SOURCE_DIR
set -euo pipefail
cd "$1"
if ! command -v clang-format >/dev/null; then
  echo "clang-format is not installed (scripts/install-deps.sh installs it)"
  exit 1
fi
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h')
else
  mapfile -t files < <(find . -path './build*' -prune -o \( -name '*.cpp' -o -name '*.hpp' \) -print)
fi
if [ "${#files[@]}" -eq 0 ]; then
  echo "no C++ sources found under $PWD"
  exit 1
fi
unformatted=0
for file in "${files[@]}"; do
  if ! clang-format --dry-run --Werror "$file" >/dev/null 2>&1; then
    echo "not formatted: $file"
    unformatted=$((unformatted + 1))
  fi
done
echo "${#files[@]} files checked, $unformatted not formatted"
[ "$unformatted" -eq 0 ]
