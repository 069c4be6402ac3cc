#!/usr/bin/env bash
# Sets everything up and runs the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
