#!/usr/bin/env bash
# light_commands.sh CLI RECIPE: the light commands of paintlab-cli load none
# of the heavy libraries (issue 26, part 3; cli/CMakeLists.txt), and a
# command of the helper does load them, which shows that the check sees them.
# The dynamic loader's own record (LD_DEBUG=libs, inherited through exec)
# covers the libraries linked, their dependencies and anything dlopen'ed.
set -uo pipefail
cli=$1 recipe=$2
heavy='lib(embree|OpenImageIO|assimp|opencv|OpenEXR|openvdb|avcodec|Qt6|vtk|ceres|glog)'
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0

loaded() {  # the libraries the loader opened for the command "$@"
  LD_DEBUG=libs LD_DEBUG_OUTPUT=$log "$cli" "$@" >/dev/null 2>&1
  cat "$log".* 2>/dev/null | grep -Eo 'file=[^ ]+' | sort -u
  rm -f "$log".*
}

for args in "--version" "--help" "validate $recipe" "show $recipe" \
  "eval $recipe --preset preview --wi 45,0 --wo 30,180" "multiangle $recipe --preset preview" \
  "db --help" "plugins" "plugins --json"; do
  # shellcheck disable=SC2086 # the arguments are split on purpose
  found=$(loaded $args | grep -E "$heavy")
  if [[ -n $found ]]; then
    echo "FAIL: paintlab-cli $args loads:"; echo "$found"
    status=1
  fi
done

# `plugins` loads the plugin libraries (dlopen), so the loop above saw theirs too.
LD_DEBUG=libs LD_DEBUG_OUTPUT=$log "$cli" plugins >/dev/null 2>&1
merl_init=$(cat "$log".* 2>/dev/null | grep -c 'calling init: .*libpaintlab-plugin-merl')
rm -f "$log".*
if [[ $merl_init == 0 ]]; then
  echo "FAIL: paintlab-cli plugins does not load libpaintlab-plugin-merl.so: its libraries were not checked"
  status=1
fi

# The positive control: the helper's commands run with Embree and OpenImageIO.
control=$(loaded mc --help)
for lib in libembree3 libOpenImageIO; do
  if ! grep -q "$lib" <<<"$control"; then
    echo "FAIL: paintlab-cli mc --help does not load $lib: the check cannot see the heavy libraries"
    status=1
  fi
done
exit $status
