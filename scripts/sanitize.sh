#!/usr/bin/env bash
# The unit suite under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/, the clang build
# the fuzz targets share: scripts/asan_build.sh) and the threaded render tests under
# ThreadSanitizer (build-tsan/, gcc), each a lean build at -O1 (no Vulkan, no benchmarks) of only
# the targets it runs. Exits non-zero on the first failing test
# binary or sanitizer report, printing the end of its log (kept in build-*/logs/).
#
#   scripts/sanitize.sh        JOBS=N sets the parallelism (default: nproc)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="${JOBS:-$(nproc)}"
command -v clang++ >/dev/null || { echo "sanitize: clang++ not found (scripts/setup.sh)" >&2; exit 1; }

# Every report ends the process with a failure; leaks are reports too.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=0"
# Known findings not yet fixed are listed, with why, in scripts/ubsan.supp.
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/scripts/ubsan.supp"
# Leaks inside Debian's libassimp, which we cannot fix (scripts/lsan.supp says which).
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"

# The whole unit suite but what needs a GPU, a display or timing: those run in the Release
# build (ctest), unsanitized.
# The viewer's input and state tests (no window) run in the Release build only: they parse
# nothing a user hands in, and their compile time is CI's to spend elsewhere.
asan_tests=(math_test scene_test render_test render_raster_test render_setup_test render_shading_test render_resolve_test msaa_test composite_test projection_test diagnostics_test
            io_image_test io_gif_test environment_test io_obj_test io_gltf_test io_gltf_files_test io_gltf_draco_test io_points_test
            io_stl_test io_assimp_test cli_test cli_validation_test
            cli_diagnostics_test hostile_test animation_test gltf_animation_test)
# The tests that render with several workers, the worker and page pools under them, and the
# texture copy that a frame's workers make together.
tsan_tests=(render_test)
tsan_filter='Renderer.ImageIsBitIdenticalForAnyWorkerCount:Renderer.AnAnimationIsTheSameForOneAndTwoWorkers:WorkerPool.*:PagePool.*:TextureCopy.*'

# The TSan build's configuration (the ASan build's is scripts/asan_build.sh's).
configure() {  # folder, compiler, extra cmake arguments...
  local build="$1" compiler="$2"
  shift 2
  mkdir -p "$build/logs"
  local generator=()
  if [ ! -f "$build/CMakeCache.txt" ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_BUILD_TYPE=None \
    "-DCMAKE_CXX_FLAGS=-O1 -g1 -fno-omit-frame-pointer" \
    -DTESSERA_VULKAN=OFF -DTESSERA_BENCH=OFF -DTESSERA_LEAN_KERNELS=ON "$@" \
    >"$build/logs/configure.log" 2>&1 || { cat "$build/logs/configure.log" >&2; exit 1; }
}

# Runs test binaries two at a time; each one's log in build/logs/NAME.log.
run_tests() {  # build folder, gtest filter, binaries...
  local build="$1" filter="$2"
  shift 2
  printf '%s\n' "$@" | xargs -P 2 -I{} sh -c \
    'if "$0/tests/{}" --gtest_filter="$1" --gtest_brief=1 >"$0/logs/{}.log" 2>&1; then
       echo "sanitize: {} passed ($(basename "$0"))"
     else
       echo "sanitize: {} FAILED ($(basename "$0")); the end of $0/logs/{}.log:" >&2
       tail -60 "$0/logs/{}.log" >&2
       exit 255
     fi' "$build" "$filter"
}

start=$SECONDS
# No window and no llvmpipe reference in `tessera` itself: the tests here use neither.
source "$root/scripts/asan_build.sh"
asan_build=$(configure_asan_build "$root")
cmake --build "$asan_build" -j"$jobs" --target "${asan_tests[@]}" tessera
run_tests "$asan_build" '*' "${asan_tests[@]}"

# GCC: its ThreadSanitizer runtime is a shared library, so render_test's own operator new (it
# counts allocations) replaces the runtime's; clang links its runtime statically and the two
# definitions collide.
configure "$root/build-tsan" g++ -DTESSERA_SANITIZE_THREAD=ON -DTESSERA_IO=OFF
cmake --build "$root/build-tsan" -j"$jobs" --target "${tsan_tests[@]}"
run_tests "$root/build-tsan" "$tsan_filter" "${tsan_tests[@]}"
echo "sanitize: ASan+UBSan and TSan runs passed in $((SECONDS - start)) s"
