#!/usr/bin/env bash
# clang-tidy over the library and application sources. It reads a copy of
# the build's compile_commands.json without the precompiled headers' forced
# include (cmake/PaintLabCompilerOptions.cmake): clang cannot load GCC's .gch
# files, and each file is checked as written, with its own #includes.
set -euo pipefail
run_clang_tidy=$1 clang_tidy=$2 source_dir=$3 binary_dir=$4
db_dir="$binary_dir/tidy"
mkdir -p "$db_dir"
sed -E -e 's/ -Winvalid-pch//g' -e 's/ -include [^ ]*cmake_pch\.hxx//g' \
  "$binary_dir/compile_commands.json" > "$db_dir/compile_commands.json"
exec "$run_clang_tidy" -quiet -clang-tidy-binary "$clang_tidy" -p "$db_dir" \
  "$source_dir/(engine|database|raymaps|plugins|cli|gui)/.*\.cpp$"
