#!/usr/bin/env bash
# Sourced by fuzz/run_all.sh and scripts/sanitize.sh: the one clang build (build-asan/) that the
# loaders' fuzz targets and the sanitizer run's unit tests share, so that the loaders compile
# once. -O1 with line tables, ASan and UBSan everywhere, the loaders also instrumented for the
# fuzzer's coverage (TESSERA_FUZZ in CMakeLists.txt); no Vulkan, window, llvmpipe reference or
# benchmarks; the test sources at -O0 (TESSERA_TEST_COMPILE_OPTIONS): half their compile time.
#
#   configure_asan_build ROOT      prints the build folder's path on success

configure_asan_build() {  # root
  local root="$1"
  local build="$root/build-asan"
  command -v clang++ >/dev/null ||
    { echo "asan build: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2; return 1; }
  mkdir -p "$build/logs"
  local generator=()
  # Ninja when it is there and the folder is new (a folder keeps the generator it was made with).
  if [ ! -f "$build/CMakeCache.txt" ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=None "-DCMAKE_CXX_FLAGS=-O1 -g1 -fno-omit-frame-pointer" \
    -DTESSERA_SANITIZE=ON -DTESSERA_FUZZ=ON -DTESSERA_VULKAN=OFF -DTESSERA_BENCH=OFF -DTESSERA_LEAN_KERNELS=ON \
    -DTESSERA_VIEWER=OFF -DTESSERA_OSMESA=OFF -DTESSERA_TEST_COMPILE_OPTIONS=-O0 \
    >"$build/logs/configure.log" 2>&1 || { cat "$build/logs/configure.log" >&2; return 1; }
  echo "$build"
}
