#!/usr/bin/env bash
# run_in_tmp.sh SCRIPT: runs the bash SCRIPT with $T set to a fresh temporary
# folder (removed afterwards) and HOME/XDG_DATA_HOME pointing into it, so CLI
# tests never touch the user's own database.
set -uo pipefail
T=$(mktemp -d "${TMPDIR:-/tmp}/paintlab-db-cli-XXXXXX")
trap 'chmod -R u+w "$T" 2>/dev/null; rm -rf "$T"' EXIT
export T HOME="$T/home" XDG_DATA_HOME="$T/xdg"
bash -c "$1"
