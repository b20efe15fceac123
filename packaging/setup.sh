#!/usr/bin/env bash
# PaintLab set-up for Debian 12 (bookworm): installs what is missing, builds,
# then runs the main job or the tests.
#
#   packaging/setup.sh run     install, build (Release), start the main job
#   packaging/setup.sh test    install, build Release, run every test (with clang-format and clang-tidy)
#   packaging/setup.sh sanitize  install, build with ASan+UBSan, run the tests there (before merging)
#   packaging/setup.sh deps    install the Debian packages only
#   packaging/setup.sh build   install and build Release only
#   packaging/setup.sh deb     install, build Release, make the Debian package
#                              build/release/paintlab_VERSION_amd64.deb (docs/PACKAGING.md)
#
# Idempotent: only missing packages are installed, and `apt-get update` runs
# only when a missing package has no install candidate (stale or empty lists).
# Works as root or through sudo. Every step is printed; a failure names the
# package or step that failed and exits non-zero.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mode=${1:-run}
jobs=$(nproc 2>/dev/null || echo 2)

# Every Debian package the project needs, now and for the issues planned
# (shared/ARCHITECTURE.md, shared/notes/debian12-stack.md).
packages=(
  # toolchain and test tools (nodejs: the Khronos glTF validator of the export test)
  build-essential cmake ninja-build pkg-config git python3 clang-format clang-tidy nodejs
  libgtest-dev libgmock-dev libbenchmark-dev
  # the Debian package: man pages from --help, its check (dpkg-dev, for dpkg-shlibdeps, comes with build-essential)
  help2man lintian
  # engine: linear algebra, parallelism, JSON, CLI, logging, colour tables
  libeigen3-dev libtbb-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  colord-data liblcms2-dev libceres-dev libnlopt-cxx-dev
  # database
  libsqlite3-dev sqlite3 nettle-dev
  # ray maps: ray tracing, images, HDR environments, meshes
  libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libassimp-dev assimp-testmodels zlib1g-dev
  # CC0 HDR environments (lat-long EXR) for the demo scene under a real sky
  blender-data
  # workstation: Qt6 + VTK (VTK's non-Qt modules only; debian12-stack.md trap 1)
  qt6-base-dev libqt6opengl6-dev qt6-svg-dev libvtk9-dev libgl-dev
  # headless GUI tests and screenshots
  xvfb xauth libgl1-mesa-dri libglx-mesa0
  # the plots' text (gui/plots/plot_widget.h: VTK's built-in font draws 0 like D)
  fonts-dejavu-core
)

# Every line carries the seconds since the start, so a CI log shows where its time went.
say() { printf '\033[1m[setup %4ds]\033[0m %s\n' "$SECONDS" "$*"; }
die() { printf '\033[1;31m[setup] FAILED:\033[0m %s\n' "$*" >&2; exit 1; }

as_root() {
  if [[ $(id -u) -eq 0 ]]; then "$@"
  elif command -v sudo >/dev/null 2>&1; then sudo "$@"
  else die "need root to run '$*' (run as root, or install sudo)"; fi
}

installed() { [[ $(dpkg-query -W -f='${Status}' "$1" 2>/dev/null) == "install ok installed" ]]; }
# (Output captured first: with pipefail, grep -q closing the pipe early would fail the pipeline.)
has_candidate() { local policy; policy=$(apt-cache policy "$1" 2>/dev/null); [[ $policy == *"Candidate: "[!\(]* ]]; }

install_packages() {
  command -v dpkg-query >/dev/null || die "this is not a Debian system (no dpkg-query); PaintLab targets Debian 12"
  local missing=()
  for p in "${packages[@]}"; do installed "$p" || missing+=("$p"); done
  if ((${#missing[@]} == 0)); then
    say "all ${#packages[@]} Debian packages already installed"
    return
  fi
  say "missing packages: ${missing[*]}"
  local need_update=0
  for p in "${missing[@]}"; do has_candidate "$p" || { need_update=1; break; }; done
  if ((need_update)); then
    say "package lists are stale or empty: apt-get update"
    as_root apt-get update || die "apt-get update"
  fi
  for p in "${missing[@]}"; do has_candidate "$p" || die "package '$p' is not available from the configured Debian sources"; done
  say "apt-get install ${missing[*]}"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" \
    || die "apt-get install of: ${missing[*]} (see the apt output above for the package that failed)"
  for p in "${missing[@]}"; do installed "$p" || die "package '$p' did not install"; done
  say "installed ${#missing[@]} packages"
}

build() {  # build PRESET
  local preset=$1
  local dir="$root/build/$preset"
  # A folder configured with another generator (Makefiles, before the presets
  # chose Ninja) cannot be reconfigured: its cache goes, its sources stay.
  if [[ -f $dir/CMakeCache.txt ]] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$dir/CMakeCache.txt"; then
    say "build/$preset was made with another generator: configuring it afresh"
    rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
  fi
  say "configure ($preset)"
  cmake -S "$root" --preset "$preset" >/dev/null || die "cmake configure ($preset)"
  say "build ($preset, $jobs jobs)"
  cmake --build "$root/build/$preset" -j "$jobs" || die "build ($preset)"
}

run_main_job() {
  local cli="$root/build/release/cli/paintlab-cli"
  local gui="$root/build/release/gui/paintlab"
  local out="$root/build/demo"
  if [[ -n ${DISPLAY:-} || -n ${WAYLAND_DISPLAY:-} || -n ${QT_QPA_PLATFORM:-} ]]; then
    say "main job: the PaintLab workstation on the demo database and the demo scene"
    exec "$gui"
  fi
  say "no display (neither DISPLAY nor WAYLAND_DISPLAY is set): the workstation needs one."
  say "  run it in a virtual X server:  xvfb-run -a $gui   (Qt's offscreen platform has no OpenGL for the plots)"
  say "meanwhile the command-line demo: the bundled recipes, and the demo scene relit with them"
  for recipe in "$root"/packaging/demo/recipes/*.json; do
    "$cli" validate "$recipe" || die "demo recipe $recipe does not validate"
    "$cli" show "$recipe" || die "paintlab-cli show $recipe"
    echo
  done
  mkdir -p "$out"
  "$cli" raymap build "$root/packaging/demo/scenes/car_body_sky.json" --out "$out/car_body_sky.prm" \
    || die "paintlab-cli raymap build (demo scene)"
  for name in pearlescent-two-layer silver-metallic solid-red; do
    "$cli" relight "$out/car_body_sky.prm" --recipe "$root/packaging/demo/recipes/$name.json" \
      --preset standard --out "$out/demo-car-$name.png" || die "paintlab-cli relight ($name)"
  done
  say "demo images: $out/demo-car-*.png"
  # The workstation itself, in a virtual X server: a screenshot once its first image is shown.
  xvfb-run -a -s "-screen 0 1600x1000x24" "$gui" --recipe "Blue pearl over black (two layers)" \
    --screenshot "$out/workstation.png" >/dev/null 2>&1 || die "the workstation did not start under xvfb-run"
  say "workstation screenshot (headless, under xvfb-run): $out/workstation.png"
}

# The package from the Release build (CPack's DEB generator; cmake/PaintLabPackaging.cmake).
make_package() {
  local dir="$root/build/release"
  say "package: cpack -G DEB in $dir"
  (cd "$dir" && cpack -G DEB -B "$dir" >"$dir/cpack.log" 2>&1) || { cat "$dir/cpack.log"; die "cpack -G DEB (log: $dir/cpack.log)"; }
  local deb
  deb=$(sed -n 's/^CPack: - package: \(.*\) generated\.$/\1/p' "$dir/cpack.log")
  [[ -f $deb ]] || { cat "$dir/cpack.log"; die "cpack named no package (log: $dir/cpack.log)"; }
  say "built $deb"
  say "  install it with:  apt install $deb"
}

# The Khronos glTF validator for the export test (tests/plugins/gltf_validate.sh):
# npm's gltf-validator at the version pinned in tools/gltf_validator/package-lock.json,
# installed into build/release/npm (never into the source tree). Idempotent: nothing
# is fetched when that lock is already installed. Without node the test is skipped.
install_gltf_validator() {
  local dir="$root/build/release/npm" src="$root/tools/gltf_validator"
  if ! command -v node >/dev/null 2>&1; then
    say "no node: the glTF validator test will be skipped (apt-get install nodejs npm)"
    return
  fi
  if [[ -f $dir/node_modules/gltf-validator/package.json ]] && cmp -s "$src/package-lock.json" "$dir/package-lock.json"; then
    say "glTF validator already installed ($dir)"
    return
  fi
  # Debian's nodejs comes without npm (NodeSource's bundles it: then Debian's npm would conflict).
  if ! command -v npm >/dev/null 2>&1; then
    say "apt-get install npm (for the glTF validator)"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends npm \
      || die "apt-get install npm (the glTF validator is installed with it)"
  fi
  say "glTF validator: npm ci in $dir (tools/gltf_validator/package-lock.json)"
  mkdir -p "$dir"
  cp "$src/package.json" "$src/package-lock.json" "$dir/"
  (cd "$dir" && npm ci --no-audit --no-fund --ignore-scripts >/dev/null) \
    || die "npm ci of the glTF validator in $dir (is the npm registry reachable?)"
}

run_tests() {
  install_gltf_validator
  say "tests: Release build (including clang-format and clang-tidy)"
  (cd "$root/build/release" && ctest --output-on-failure -j "$jobs") || die "tests (Release)"
  say "all tests passed"
}

# The sanitizer pass is not part of `test`: on 2 cores its build alone took
# ~35 min (with the GUI), and `test` must stay under CI's 40 minutes (docs/PERFORMANCE.md,
# "Build, test and CI time"). Run it before merging work that touches memory
# or threads.
run_sanitized_tests() {
  build asan
  say "tests: AddressSanitizer + UndefinedBehaviorSanitizer build"
  (cd "$root/build/asan" && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j "$jobs") \
    || die "tests (ASan+UBSan)"
  say "all tests passed under ASan+UBSan"
}

case $mode in
  deps) install_packages ;;
  build) install_packages; build release ;;
  run) install_packages; build release; run_main_job ;;
  test) install_packages; build release; run_tests ;;
  sanitize) install_packages; run_sanitized_tests ;;
  deb) install_packages; build release; make_package ;;
  *) die "unknown mode '$mode' (use: run, test, sanitize, deps, build or deb)" ;;
esac
