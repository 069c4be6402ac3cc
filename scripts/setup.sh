#!/usr/bin/env bash
# Installs the Debian 12 packages tessera builds with, then configures and builds it in build/.
# Run as root (or with sudo available). Safe to run again: installed packages are not re-fetched.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  libtinyobjloader-dev libstb-dev libtinygltf-dev nlohmann-json3-dev libassimp-dev libdraco-dev libopenexr-dev
  libspng-dev libpng-dev zlib1g-dev libgif-dev libimagequant-dev
  ffmpeg glmark2-data libosmesa6-dev
  libsdl2-dev libsdl2-ttf-dev fonts-dejavu-core xvfb xauth xdotool
  libvulkan-dev glslc mesa-vulkan-drivers vulkan-validationlayers
  clang libclang-rt-14-dev
  assimp-testmodels
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: run as root to install packages" >&2; exit 1; }
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Ninja for a new build folder (it schedules the two cores better than make); a folder keeps the
# generator it was made with.
generator=()
if [ ! -f build/CMakeCache.txt ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
# The compiler of a new build folder (scripts/compiler.sh: clang unless CC or CXX is set). Debian
# 12's clang 14 gives the same bits as its GCC 12 and faster kernels: up to 12% a frame with AVX2
# and AVX-512 (the textured rows most, the cube's and fill's the same), five to seven times with
# SSE2 and without SIMD (docs/perf-notes/speed-2026-12-07.md, "Built with clang").
source scripts/compiler.sh
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release ${TESSERA_CMAKE_ARGS:-}
cmake --build build -j"$(nproc)"
