#!/usr/bin/env bash
# Times two builds against each other on a shared 2-core host: both at once, one pinned to each
# core, swapped every round, so that a spell of the host falls on both alike and a core slower
# than the other (a shared host's virtual cores differ, at times by 1.7x) counts against each build
# in turn. Each round runs `tessera_stagetimes ARGS` once per build (use 1 worker) and compares
# their mean frame times; the result is the geometric mean of NEW/OLD over the rounds (below 1:
# NEW is faster). Run OLD against itself to see the noise of the hour.
#
#   bench/ab.sh OLD_STAGETIMES NEW_STAGETIMES ROUNDS SCENE 1 FRAMES WIDTH HEIGHT ISA MSAA [...]
#   bench/ab.sh /tmp/before/tessera_stagetimes build/bench/tessera_stagetimes 8 \
#       bunny 1 60 1920 1080 avx512 4
set -euo pipefail
[ $# -ge 4 ] || { sed -n '2,11p' "$0" >&2; exit 2; }
old=$1 new=$2 rounds=$3
shift 3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
frame_ms() { grep -o 'total [0-9.]* ms' "$1" | cut -d' ' -f2; }
for ((r = 1; r <= rounds; ++r)); do
  core_old=$(((r + 1) % 2)) core_new=$((r % 2))
  TESSERA_NOHASH=1 taskset -c "$core_old" "$old" "$@" > "$out/old" 2>&1 &
  TESSERA_NOHASH=1 taskset -c "$core_new" "$new" "$@" > "$out/new" 2>&1 &
  wait
  a=$(frame_ms "$out/old") b=$(frame_ms "$out/new")
  [ -n "$a" ] && [ -n "$b" ] || { echo "ab: no frame time in a run:" >&2; cat "$out/old" "$out/new" >&2; exit 1; }
  echo "round $r: old $a ms (core $core_old), new $b ms (core $core_new)"
  echo "$a $b" >> "$out/pairs"
done
awk '{ s += log($2 / $1); n++ } END { printf "new/old: %.3f (geometric mean of %d rounds)\n", exp(s / n), n }' "$out/pairs"
