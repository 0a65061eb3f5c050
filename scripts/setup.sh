#!/usr/bin/env bash
# Installs camsim's Debian 12 dependencies that are missing (as root, or with sudo),
# then configures and builds the Release build in build/ on all cores.
#   CAMSIM_BUILD_DIR  build directory (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake ninja-build g++ pkg-config git
  libembree-dev libtbb-dev libopenexr-dev openexr libopencolorio-dev opencolorio-tools
  libglm-dev libgtest-dev libgmock-dev libyaml-cpp-dev libpng-dev libtiff-dev
  libraw-bin dcraw libimage-exiftool-perl python3-matplotlib clang libclang-rt-14-dev clang-format
  colmap python3-opencv python3-numpy libmurmurhash-dev slurm-wlm munge
  pybind11-dev python3-dev python3-pytest libtinygltf-dev nlohmann-json3-dev libcli11-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

build_dir=${CAMSIM_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j"$(nproc)"
