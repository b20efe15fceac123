#!/usr/bin/env bash
# gltf_validate.sh CLI RECIPES_DIR NPM_DIR VALIDATE_JS: every recipe of
# RECIPES_DIR exported by `brdf --out` as a sphere (.gltf), a panel (.glb)
# and the car body (.gltf) must pass the Khronos glTF validator (no error),
# run under node by VALIDATE_JS from NPM_DIR (packaging/setup.sh installs it
# there from tools/gltf_validator/package-lock.json). A file broken on
# purpose must fail, so the check cannot pass by not looking. Exits 77
# (skipped) only if node is not installed.
set -uo pipefail
cli=$1 recipes=$2 npm=$3 validate=$4
if ! command -v node >/dev/null 2>&1; then
  echo "SKIPPED: node (Debian's nodejs) is not installed, so the glTF validator cannot run"
  exit 77
fi
if [[ ! -f $npm/node_modules/gltf-validator/package.json ]]; then
  echo "FAIL: the glTF validator is not installed in $npm: run packaging/setup.sh test, which installs it" \
       "from tools/gltf_validator/package-lock.json"
  exit 1
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

jobs=()
for recipe in "$recipes"/*.json; do
  name=$(basename "$recipe" .json)
  jobs+=("$recipe sphere $out/$name-sphere.gltf" "$recipe panel $out/$name-panel.glb" "$recipe car $out/$name-car.gltf")
done
# Two at a time (the fits are single-threaded); each prints its ΔE00 line.
# shellcheck disable=SC2016 # the inner script expands its own arguments
printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 sh -c \
  '"$0" brdf "$1" --preset preview --object "$2" --out "$3" 2>&1 | grep -E "E00|error" | sed "s|^|$(basename "$3"): |"' "$cli"
shopt -s nullglob
files=("$out"/*.gltf "$out"/*.glb)
if ((${#files[@]} != ${#jobs[@]} || ${#files[@]} == 0)); then
  echo "FAIL: expected ${#jobs[@]} files, the exports wrote ${#files[@]}"
  exit 1
fi
node "$validate" "$npm" "${files[@]}" || { echo "FAIL: the validator found errors (above)"; exit 1; }

# The negative control: a POSITION accessor of bytes instead of floats is an error.
sed '0,/"componentType": 5126/s//"componentType": 5121/' "${files[0]}" > "$out/broken.gltf"
if node "$validate" "$npm" "$out/broken.gltf" >"$out/broken.log" 2>&1; then
  cat "$out/broken.log"
  echo "FAIL: the validator accepted a broken file: the check cannot see errors"
  exit 1
fi
echo "all ${#files[@]} exports validate; a broken file is refused"
