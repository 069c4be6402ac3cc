#!/usr/bin/env bash
# Checks that two builds of tessera draw the same bits: the CRC-32 of the last frame (`tessera bench
# --crc`) of every built-in scene at 640x480 under every shading mode, at 1x and 4x MSAA, with the
# scalar, AVX2 and (where the CPU has it) AVX-512 kernels, of the twelfth frame of three scenes
# (the frames of a sequence keep their background tiles), and of the bunny filling a 1920x1080
# frame. A change to a kernel that must keep the images (a faster path, a reordering) runs this
# against the build before it; so does a review of such a change.
#
#   bench/same_bits.sh OLD_TESSERA NEW_TESSERA      # exit 0: every CRC equal; 1: some differ
#   bench/same_bits.sh build/apps/tessera/tessera   # one build: prints the CRCs
set -euo pipefail
[ $# -ge 1 ] && [ $# -le 2 ] || { sed -n '2,10p' "$0" >&2; exit 2; }

isas=(scalar avx2)
grep -qw avx512f /proc/cpuinfo && isas+=(avx512)

crcs() {
  local exe=$1
  for isa in "${isas[@]}"; do
    for msaa in 1 4; do
      for shading in gouraud smooth flat pbr; do
        "$exe" bench cube bunny dense fill textured --resolution 640x480 --frames 1 --warmup 0 \
          --simd "$isa" --msaa "$msaa" --shading "$shading" --workers 2 --crc |
          sed -n "s/^crc32 /$isa ${msaa}x $shading /p"
      done
      # The last of twelve frames: a sequence keeps its background tiles (RenderOptions::frame_kept).
      "$exe" bench cube bunny textured --resolution 640x480 --frames 12 --warmup 0 \
        --simd "$isa" --msaa "$msaa" --workers 2 --crc |
        sed -n "s/^crc32 /$isa ${msaa}x sequence /p"
      "$exe" bench bunny --resolution 1920,1080 --camera-position 0,0.2,3 --frames 1 --warmup 0 \
        --simd "$isa" --msaa "$msaa" --workers 1 --crc |
        sed -n "s/^crc32 bunny /$isa ${msaa}x close bunny /p"
    done
  done
}

if [ $# -eq 1 ]; then
  crcs "$1"
  exit 0
fi
old=$(mktemp) new=$(mktemp)
trap 'rm -f "$old" "$new"' EXIT
crcs "$1" > "$old"
crcs "$2" > "$new"
[ -s "$old" ] || { echo "same_bits: $1 printed no CRC" >&2; exit 1; }
if diff "$old" "$new" > /dev/null; then
  echo "same_bits: $(wc -l < "$old") images, the same bits"
else
  echo "same_bits: these images differ (old, then new):" >&2
  diff "$old" "$new" >&2 || true
  exit 1
fi
