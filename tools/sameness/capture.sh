#!/usr/bin/env bash
# Captures the outputs a refactoring must leave unchanged, so that two builds
# can be compared with `diff -r`: fixed-seed Monte Carlo runs, the demo
# recipes' multi-angle colours and BRDF tables, the plan, the ray-map relight
# images and the database's exports and production sheets.
#
#   tools/sameness/capture.sh BUILD_DIR OUT_DIR
#   diff -r OUT_BEFORE OUT_AFTER && echo identical
#
# Wall-clock fields (seconds, times, rates) are removed from JSON before it is
# written: they differ run to run and are not results.
set -euo pipefail
build=$(cd "$1" && pwd)
out=$2
root=${PAINTLAB_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
cli="$build/cli/paintlab-cli"
recipes="$root/packaging/demo/recipes"
scenes="$root/packaging/demo/scenes"
mkdir -p "$out"
out=$(cd "$out" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Keys whose values are wall-clock measurements, timestamps or scratch paths, not results.
untimed() {
  jq -S 'walk(if type == "object" then with_entries(select(.key | test("(^|_)(seconds|secs|time|times|elapsed|ms|wall|cpu|per_second|rate|at)$|^database$"; "i") | not)) else . end)'
}
# An EXR's pixels, not its header (which may carry a date): OpenImageIO's SHA-1 of the data.
pixelHash() { oiiotool --hash "$1" | grep SHA-1 | sed 's/.*SHA-1: //'; }

step() { printf '[sameness] %s\n' "$*" >&2; }

for r in "$recipes"/*.json; do
  name=$(basename "$r" .json)
  step "$name: show, multiangle, eval, brdf"
  "$cli" show "$r" --json > "$out/$name.show.json"
  for preset in preview standard reference; do
    "$cli" multiangle "$r" --preset "$preset" --json | untimed > "$out/$name.multiangle.$preset.json"
  done
  "$cli" eval "$r" --wi 45,0 --wo 30,180 --json | untimed > "$out/$name.eval.json"
  "$cli" brdf "$r" --preset preview --step 15 --out "$scratch/brdf.json" >/dev/null
  untimed < "$scratch/brdf.json" > "$out/$name.brdf.json"
  "$cli" brdf "$r" --preset preview --step 15 --out "$out/$name.brdf.csv" >/dev/null
  step "$name: mc (fixed seed)"
  "$cli" mc "$r" --samples 4000 --seed 7 --bands 4 --json | untimed > "$out/$name.mc.json"
  "$cli" mc "$r" --samples 2000 --seed 3 --bands 4 --table --preset preview --step 15 \
    --out "$scratch/mc-table.json" >/dev/null
  untimed < "$scratch/mc-table.json" > "$out/$name.mc-table.json"
  "$cli" plan "$scenes/car_body_sky.json" "$r" --json | untimed > "$out/$name.plan.json"
done

for r in pearlescent-two-layer silver-metallic three-layer; do
  step "$r: mc --explicit-flakes (fixed seed)"
  "$cli" mc "$recipes/$r.json" --explicit-flakes --samples 3000 --seed 5 --bands 3 --tile-views 4 --json \
    | untimed > "$out/$r.mc-explicit.json"
  "$cli" mc "$recipes/$r.json" --explicit-flakes --histogram-only --samples 3000 --seed 5 --bands 3 \
    --tile-views 4 --json | untimed > "$out/$r.mc-histogram.json"
done

step "slab"
"$cli" slab --albedo 0.9 --optical-thickness 2 --g 0.75 --n 1.4 --json | untimed > "$out/slab.json"

step "ray map and relights"
"$cli" raymap build "$scenes/car_body_sky.json" --out "$scratch/car.prm" --width 160 --height 90 >/dev/null
# (The .prm file itself is not compared: its chunk order depends on thread timing.)
for name in pearlescent-two-layer silver-metallic solid-red three-layer; do
  "$cli" relight "$scratch/car.prm" --recipe "$recipes/$name.json" --preset preview \
    --out "$scratch/relight.exr" >/dev/null
  pixelHash "$scratch/relight.exr" > "$out/relight-$name.exr.sha1"
  "$cli" relight "$scratch/car.prm" --recipe "$recipes/$name.json" --preset preview \
    --out "$out/relight-$name.png" >/dev/null
done
"$cli" relight "$scratch/car.prm" --recipe "$recipes/silver-metallic.json" --preset preview --sparkle on \
  --out "$scratch/relight.exr" >/dev/null
pixelHash "$scratch/relight.exr" > "$out/relight-sparkle.exr.sha1"

step "database: exports and production sheets"
db="$scratch/p.db"
"$cli" db init --db "$db" >/dev/null
"$cli" db list --db "$db" --json | untimed > "$out/db-list.json"
"$cli" db export --all --kind pigment --out "$out/pigments.json" --db "$db" >/dev/null
"$cli" db export --all --kind pigment --out "$out/pigments.csv" --db "$db" >/dev/null
"$cli" db export --all --kind spectra --out "$out/spectra.csv" --db "$db" >/dev/null || true
first=$("$cli" db list --db "$db" --json | jq -r '.. | objects | select(has("recipes")) | .recipes[0].name' 2>/dev/null | head -1)
for n in "Solid red (iron oxide)" "$first"; do
  [[ -z $n || $n == null ]] && continue
  safe=$(echo "$n" | tr -c 'a-zA-Z0-9\n' '_')
  for f in csv json; do
    "$cli" db production "$n" --batch-kg 10 --out "$scratch/prod.$f" --db "$db" >/dev/null
    untimed < <( [[ $f == json ]] && cat "$scratch/prod.$f" || echo '{}' ) > "$out/prod-$safe.$f.json" || true
    [[ $f == csv ]] && grep -v -i 'generated\|date' "$scratch/prod.$f" > "$out/prod-$safe.csv" || true
  done
done
"$cli" db show "Solid red (iron oxide)" --json --db "$db" | untimed > "$out/db-show-red.json" || true
# Recipe and scene paths are echoed in some outputs: name the checkout <repo> so two checkouts compare.
grep -rlF "$root" "$out" | xargs -r sed -i "s|$root|<repo>|g"
step "done: $out"
