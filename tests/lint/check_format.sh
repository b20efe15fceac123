#!/usr/bin/env bash
# Fails if any C++ source differs from .clang-format; prints the files to fix
# and the command that fixes them.
set -euo pipefail
clang_format=$1
root=$2
cd "$root"
mapfile -t files < <(find engine database raymaps plugins gui cli tests -type f \( -name '*.cpp' -o -name '*.h' \) | sort)
bad=()
for f in "${files[@]}"; do
  if ! "$clang_format" --dry-run --Werror "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if ((${#bad[@]})); then
  echo "Not formatted per .clang-format (${#bad[@]} of ${#files[@]} files):"
  printf '  %s\n' "${bad[@]}"
  echo "Fix with: $clang_format -i ${bad[*]}"
  exit 1
fi
echo "clang-format: ${#files[@]} files formatted correctly"
