#!/usr/bin/env bash
# expect.sh CODE PATTERN STREAM -- COMMAND...: runs COMMAND, fails unless it exits
# with CODE and STREAM (stdout|stderr) matches the extended regex PATTERN.
set -uo pipefail
code=$1 pattern=$2 stream=$3
shift 4
out=$(mktemp) err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
"$@" >"$out" 2>"$err"
actual=$?
status=0
if [[ $actual != "$code" ]]; then
  echo "FAIL: exit code $actual, expected $code: $*"
  status=1
fi
file=$out
[[ $stream == stderr ]] && file=$err
if ! grep -Eq -- "$pattern" "$file"; then
  echo "FAIL: $stream does not match /$pattern/"
  status=1
fi
if ((status)); then
  echo "--- stdout"; head -c 4000 "$out"; echo "--- stderr"; head -c 4000 "$err"
fi
exit $status
