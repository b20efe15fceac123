#!/usr/bin/env bash
# deb_test.sh STEP OUT_DIR BUILD_DIR SOURCE_DIR VERSION GUI: the Debian package's tests
# (tests/package/CMakeLists.txt; docs/PACKAGING.md).
#   build    cpack -G DEB from the build (reused, not rebuilt); its name, files and Depends
#   lintian  no error; every warning is listed in docs/PACKAGING.md
#   cli      extracted (dpkg-deb -x): --version, plugins, multiangle and a helper command
#   gui      extracted: xvfb-run paintlab --screenshot on the demo scene
# The extracted programs run with an empty environment (no PAINTLAB_* variable)
# and, where the kernel lets us (a mount namespace), with the source and build
# trees covered by empty folders, so that nothing can come from them.
set -euo pipefail
step=$1 out=$2 build=$3 source=$4 version=$5 gui=$6  # gui: ON when the workstation is built
deb="$out/paintlab_${version}-1_amd64.deb"

fail() { echo "FAIL: $*" >&2; exit 1; }

# A fresh root with the package extracted, removed at exit.
extract() {
  [[ -f $deb ]] || fail "$deb is missing (the package.deb test builds it)"
  root=$(mktemp -d "${TMPDIR:-/tmp}/paintlab-deb-XXXXXX")
  trap 'rm -rf "$root"' EXIT
  dpkg-deb -x "$deb" "$root/pkg"
  mkdir -p "$root/home" "$root/run"
  chmod 700 "$root/run"
  pkg=$root/pkg
}

# isolated COMMAND...: COMMAND with only PATH, HOME and XDG_RUNTIME_DIR set,
# and the source and build trees hidden when a mount namespace is allowed
# (as root: unshare -m; otherwise a user namespace: unshare -rm).
isolated() {
  # shellcheck disable=SC2016  # expanded by the inner bash, from its arguments
  local hide='mount -t tmpfs tmpfs "$1" && { [[ -z $2 ]] || mount -t tmpfs tmpfs "$2"; } && shift 2 && exec "$@"'
  local inner="$build"
  [[ $build == "$source"/* ]] && inner=""  # already under the source tree
  local run=(env -i PATH=/usr/bin:/bin HOME="$root/home" XDG_RUNTIME_DIR="$root/run" LANG=C.UTF-8 "$@")
  local ns
  for ns in "-m" "-rm"; do
    if unshare $ns true 2>/dev/null; then
      unshare $ns bash -c "$hide" _ "$source" "$inner" "${run[@]}"
      return
    fi
  done
  echo "NOTE: no mount namespace here: the source and build trees stay visible (paths are still checked)" >&2
  "${run[@]}"
}

case $step in
build)
  rm -rf "$out"
  cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out" >"$out.log" 2>&1 || { cat "$out.log"; fail "cpack"; }
  [[ -f $deb ]] || fail "cpack did not write $deb: $(ls "$out")"
  listing=$(dpkg-deb -c "$deb")
  files=(usr/bin/paintlab-cli usr/libexec/paintlab/paintlab-cli-full
         usr/lib/paintlab/plugins/libpaintlab-plugin-merl.so
         usr/share/paintlab/recipes/pearlescent-two-layer.json usr/share/paintlab/scenes/car_body_sky.json
         usr/share/paintlab/ingredients/demo-ingredients.json usr/share/paintlab/measurements/blue-pearl-panel.json
         usr/share/man/man1/paintlab-cli.1.gz
         usr/share/doc/paintlab/copyright usr/share/doc/paintlab/changelog.Debian.gz)
  libs=(libc6 libembree3-3 libsqlite3-0)
  if [[ $gui == ON ]]; then
    files+=(usr/bin/paintlab usr/share/man/man1/paintlab.1.gz usr/share/applications/paintlab.desktop
            usr/share/icons/hicolor/scalable/apps/paintlab.svg)
    libs+=(libqt6widgets6)
  fi
  for file in "${files[@]}"; do
    grep -q " \./$file\$" <<<"$listing" || fail "$file is not in the package"
  done
  # Depends comes from dpkg-shlibdeps: the libraries the binaries link, with versions.
  depends=$(dpkg-deb -f "$deb" Depends)
  for lib in "${libs[@]}"; do
    grep -Eq "(^|, )$lib \(>= " <<<"$depends" || fail "Depends lacks $lib: $depends"
  done
  # The man pages hold every command's options (made from --help at build time).
  zcat "$build/man/paintlab-cli.1.gz" | grep -q '^\.SS "paintlab-cli multiangle"' || fail "paintlab-cli.1 lacks multiangle"
  if [[ $gui == ON ]]; then
    zcat "$build/man/paintlab.1.gz" | grep -q '\\-\\-screenshot' || fail "paintlab.1 lacks --screenshot"
  fi
  echo "built $deb ($(du -k "$deb" | cut -f1) kB); Depends: $depends"
  ;;
lintian)
  [[ -f $deb ]] || fail "$deb is missing (the package.deb test builds it)"
  # lintian warns that it runs as root (CI does); its verdict is on stdout.
  tags=$(lintian --fail-on error --tag-display-limit 0 "$deb" 2>/dev/null) || { echo "$tags"; fail "lintian reports errors"; }
  echo "${tags:-lintian: no tags}"
  while read -r level _ tag _; do
    [[ $level == W: ]] || continue
    grep -qF "\`$tag\`" "$source/docs/PACKAGING.md" || fail "lintian warning $tag is not explained in docs/PACKAGING.md"
  done <<<"$tags"
  ;;
cli)
  extract
  cli=$pkg/usr/bin/paintlab-cli
  printed=$(isolated "$cli" --version) || fail "--version"
  [[ $printed == "paintlab-cli $version" ]] || fail "--version printed '$printed'"
  # Plugins: searched only beside the program, every one loaded from the package.
  isolated "$cli" plugins --json >"$root/plugins.json"
  python3 - "$root/plugins.json" "$pkg/usr/lib/paintlab/plugins" <<'EOF' || fail "plugins"
import json, sys
listing, folder = json.load(open(sys.argv[1])), sys.argv[2]
assert listing["search_path"] == [folder], f"searched {listing['search_path']}, expected [{folder}]"
files = {p["name"]: p["file"] for p in listing["plugins"] if not p["built_in"]}
assert "merl" in files, f"no merl plugin in {files}"
assert all(f.startswith(folder + "/") for f in files.values()), f"a plugin from outside the package: {files}"
assert not listing["refused"], f"refused: {listing['refused']}"
print("plugins from the package:", ", ".join(sorted(files)))
EOF
  isolated "$cli" multiangle "$pkg/usr/share/paintlab/recipes/pearlescent-two-layer.json" --preset preview >"$root/ma.txt" \
    || fail "multiangle"
  if ! grep -q '45as110' "$root/ma.txt" || ! grep -qi 'flop' "$root/ma.txt"; then
    cat "$root/ma.txt"
    fail "multiangle output"
  fi
  # A helper command: the front end finds paintlab-cli-full in ../libexec/paintlab.
  isolated "$cli" mc "$pkg/usr/share/paintlab/recipes/raw-medium-slab.json" --samples 200 --json >"$root/mc.json" \
    || fail "mc (the helper program)"
  cat "$root/ma.txt"
  ;;
gui)
  extract
  # The demo scene must come from the package's share/paintlab: the source
  # tree's copy is hidden, and a workstation without a scene never shows the
  # image the screenshot waits for (the timeout then fails the test).
  isolated timeout 240 xvfb-run -a -s "-screen 0 1366x768x24" "$pkg/usr/bin/paintlab" \
    --recipe "Blue pearl over black (two layers)" --screenshot "$root/shot.png" >"$root/gui.log" 2>&1 \
    || { code=$?; tail -20 "$root/gui.log"; fail "paintlab --screenshot (exit $code; 124: no image within 240 s)"; }
  size=$(stat -c %s "$root/shot.png")
  ((size > 50000)) || fail "screenshot of $size bytes: a blank window?"
  ls "$root"/home/.cache/PaintLab/PaintLab/raymaps/car_body_sky-*.prm >/dev/null 2>&1 \
    || fail "no ray map of the demo scene car_body_sky.json was traced"
  echo "screenshot $size bytes; the demo scene traced from $pkg/usr/share/paintlab/scenes"
  ;;
*) fail "unknown step '$step'" ;;
esac
