#!/usr/bin/env bash
# Whole-process start-up of paintlab-cli (issue 26, part 3): wall time by
# hyperfine (Debian package `hyperfine`, needed here only, not by CI) and
# the largest maximum resident set size over a few runs (/usr/bin/time).
# The CPU time (user + system, mean) moves less than the wall time when
# other work shares the cores.
# Figures go to docs/PERFORMANCE.md with the machine ("Command-line start-up").
#
#   tests/cli/bench_startup.sh [PAINTLAB_CLI] [RUNS]
#
# Speed is never asserted here; tests/cli/light_commands.sh checks which
# libraries the light commands load.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cli=${1:-$root/build/release/cli/paintlab-cli}
runs=${2:-30}
recipes=$root/packaging/demo/recipes
command -v hyperfine >/dev/null || { echo "bench_startup.sh: needs hyperfine (apt-get install hyperfine)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "bench_startup.sh: needs /usr/bin/time (apt-get install time)" >&2; exit 2; }

# name | arguments; the light commands first, then two that run in the helper.
cases=(
  "--version|--version"
  "--help|--help"
  "validate|validate $recipes/silver-metallic.json"
  "show|show $recipes/three-layer.json"
  "eval preview|eval $recipes/silver-metallic.json --preset preview --wi 45,0 --wo 30,180"
  "multiangle preview|multiangle $recipes/silver-metallic.json --preset preview"
  "plan --help (helper)|plan --help"
  "mc --help (helper)|mc --help"
)

printf '| command | wall mean ± σ (ms) | wall min (ms) | CPU user+sys (ms) | max RSS (MB) |\n|---|---|---|---|---|\n'
json=$(mktemp)
trap 'rm -f "$json"' EXIT
for c in "${cases[@]}"; do
  name=${c%%|*}
  args=${c#*|}
  # shellcheck disable=SC2086 # the arguments are split on purpose
  hyperfine --style none --warmup 3 --runs "$runs" -N --export-json "$json" "$cli $args" >/dev/null 2>&1
  read -r mean sd min cpu < <(jq -r '.results[0] | "\(.mean*1000) \(.stddev*1000) \(.min*1000) \((.user+.system)*1000)"' "$json")
  rss=0
  for _ in 1 2 3 4 5; do
    # shellcheck disable=SC2086
    k=$(/usr/bin/time -f %M "$cli" $args 2>&1 >/dev/null | tail -1)
    ((k > rss)) && rss=$k
  done
  printf "| \`%s\` | %.1f ± %.1f | %.1f | %.1f | %.1f |\n" "$name" "$mean" "$sd" "$min" "$cpu" "$(bc -l <<<"$rss/1024")"
done
