#!/usr/bin/env bash
# Sets everything up and runs the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
# The loaders' fuzzers (OBJ, MTL, STL, glTF, assimp's), 20 s each with ASan and UBSan, one per
# core at a time: about two minutes on 2 cores, most of it the clang build.
"$root/fuzz/run_all.sh" 20
# The unit suite (with the hostile corpus) under ASan+UBSan and the threaded render tests under
# TSan: two lean -O1 builds of only what they run (scripts/sanitize.sh). About 14 CPU-minutes,
# so about 7 to 8 minutes on 2 idle cores; measured 17m52s on a shared, loaded 2-core machine.
"$root/scripts/sanitize.sh"
# Last, so that its summary closes the output.
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
