#!/usr/bin/env bash
# Sets everything up and runs the demo: writes cube.gif in the current folder.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/build/apps/tessera/tessera" cube "$@"
