#!/usr/bin/env bash
# Sets everything up and runs the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
# The loaders' fuzzers (OBJ, MTL, STL, glTF, .hdr, assimp's), 20 s each with ASan and UBSan, one per
# core at a time, in the clang build (build-asan/) the sanitizer run then reuses: the loaders
# compile once for both (scripts/asan_build.sh).
"$root/fuzz/run_all.sh" 20
# The unit suite (with the hostile corpus) under ASan+UBSan and the threaded render tests under
# TSan: lean -O1 builds of only what they run (scripts/sanitize.sh). 192 s on this project's 2-core
# AVX-512 machine (2026-12-04, f4d6f40); the whole of this script took 13m05s there in a clean clone,
# against 21m39s before the SSE2 and the sanitizer builds' AVX2 kernels took their lane operations
# inline (f4d6f40) and 46 min before the scalar kernels did (cfad94d). The suite grew to 19m52s
# (2026-12-05, ca21eee, Intel Xeon); 15m42s after the Vulkan backends made each pipeline on first
# use (ctest 294 -> 159 s) and the tests took a precompiled header (2026-12-06, a1049e2). Back up
# to 20m13s as tests were added (6e7445e); 16m23s after the Vulkan tests ran two at a time on one
# lavapipe thread each and the shade shader shrank for lavapipe's compiler (ctest 328 -> 150 s,
# 2026-12-06, AMD EPYC with AVX-512).
"$root/scripts/sanitize.sh"
# Last, so that its summary closes the output.
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
