#!/usr/bin/env bash
# Installs camsim's missing Debian 12 packages (apt, as root or with sudo), then configures
# and builds the Release build in build/ on all cores. Prints how long each part took.
#   scripts/setup.sh         README's first command: the packages of
#                            scripts/packages/render.txt; builds only the `camsim`
#                            executable and the Python module (target camsim_python)
#   scripts/setup.sh --test  for scripts/test.sh: render.txt and scripts/packages/test.txt
#                            (the test tools); builds everything, the test suite included
#   scripts/setup.sh --peer  render.txt and scripts/packages/peer.txt (Debian's blender, for
#                            `camsim bench --peer cycles`; opt-in, CI does not need it);
#                            builds as the default
#   CAMSIM_BUILD_DIR  build directory (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."

mode=render
case "${1:-}" in
  "") ;;
  --test) mode=test ;;
  --peer) mode=peer ;;
  *)
    echo "usage: scripts/setup.sh [--test | --peer]" >&2
    exit 2
    ;;
esac

# The package lists: one name a line, '#' comments and blank lines skipped.
read_packages() { sed -e 's/#.*//' -e 's/[[:space:]]//g' -e '/^$/d' "$@"; }
lists=(scripts/packages/render.txt)
if [ "$mode" = test ]; then lists+=(scripts/packages/test.txt); fi
if [ "$mode" = peer ]; then lists+=(scripts/packages/peer.txt); fi
mapfile -t packages < <(read_packages "${lists[@]}")

t0=$SECONDS
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  # The render packages without their recommends (make, libeigen3-dev, libpng-tools, ...:
  # nothing camsim uses); the test tools as Debian recommends them.
  no_recommends=()
  if [ "$mode" != test ]; then no_recommends=(--no-install-recommends); fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${no_recommends[@]}" \
    "${missing[@]}" >/dev/null
fi
echo "setup: packages: ${#missing[@]} of ${#packages[@]} were missing, installed in $((SECONDS - t0)) s" >&2

# The render build leaves the tests and micro-benchmarks out of a new build directory, so
# that CMake does not look for GoogleTest (not in render.txt); an existing one keeps its
# options and only the two targets are built. --test turns both on.
build_dir=${CAMSIM_BUILD_DIR:-build}
options=()
# Both unity-build the libraries (and the tests) (docs/testing.md, "Unity builds"): the
# gate's Release stage builds what README's first command builds, a third faster; a
# developer's own `cmake` build compiles every file on its own (CAMSIM_UNITY_BUILD's default).
# --test compiles the test executables at -O1 (CAMSIM_TEST_FLAGS; the libraries they test stay
# at Release's -O3): 165 -> 109 s to build them on 2 cores, the suite as fast (211 s, 218 at -O3).
if [ "$mode" = test ]; then
  options=(-DCAMSIM_BUILD_TESTS=ON -DCAMSIM_BUILD_BENCH=ON -DCAMSIM_UNITY_BUILD=ON
    -DCAMSIM_TEST_FLAGS=-O1)
elif [ ! -f "$build_dir/CMakeCache.txt" ]; then
  options=(-DCAMSIM_BUILD_TESTS=OFF -DCAMSIM_BUILD_BENCH=OFF -DCAMSIM_UNITY_BUILD=ON)
fi
t0=$SECONDS
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "${options[@]}" >/dev/null
targets=()
if [ "$mode" != test ]; then
  targets=(camsim)
  if grep -q '^CAMSIM_PYTHON:BOOL=ON' "$build_dir/CMakeCache.txt"; then
    targets+=(camsim_python)
  fi
fi
target_args=()
if ((${#targets[@]})); then target_args=(--target "${targets[@]}"); fi
cmake --build "$build_dir" -j"$(nproc)" "${target_args[@]}"
echo "setup: built ${targets[*]:-every target} in $build_dir/ in $((SECONDS - t0)) s" \
  "on $(nproc) cores" >&2
