#!/usr/bin/env bash
# Regenerates the pictures in docs/images with tessera itself. Needs a build (scripts/setup.sh),
# ffmpeg (to put the AOVs side by side) and the Stanford bunny from Debian's glmark2-data.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
tessera="$root/build/apps/tessera/tessera"
out="$root/docs/images"
bunny=/usr/share/glmark2/models/bunny.obj
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

"$tessera" cube -w 240 -h 240 -fps 15 -dur 3s -axes -out "$out/cube.gif"

common=(--resolution 320,320)
"$tessera" render "$bunny" "${common[@]}" -o "$tmp/color.png"
"$tessera" render "$bunny" "${common[@]}" --aov id -o "$tmp/id.png"
"$tessera" render "$bunny" "${common[@]}" --aov normal -o "$tmp/normal.png"
ffmpeg -loglevel error -y -i "$tmp/color.png" -i "$tmp/id.png" -i "$tmp/normal.png" \
  -filter_complex hstack=inputs=3 "$out/aovs.png"
ls -la "$out"
