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
# TSan: lean -O1 builds of only what they run (scripts/sanitize.sh). 457 s on an idle 2-core AVX2
# machine (2026-12-02); the whole of this script took 24m37s there.
"$root/scripts/sanitize.sh"
# Last, so that its summary closes the output.
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
