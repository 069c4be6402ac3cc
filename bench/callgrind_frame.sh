#!/usr/bin/env bash
# Instructions a frame, in total and by function, counted by callgrind (valgrind's; apt-get
# install valgrind): tessera_stagetimes runs 1 frame and then 5 under callgrind, and the difference
# over 4 is one frame without the start-up (model load, first allocations). Deterministic where the
# clock of a shared host is not, so it measures changes of a few per cent; valgrind runs no
# AVX-512, so use the avx2 (or sse2, scalar) kernels. The Release build names the functions; for
# source lines build with -g, and with clang -g -gdwarf-4 (valgrind 3.19 cannot read DWARF 5).
#
#   bench/callgrind_frame.sh STAGETIMES SCENE 1 WIDTH HEIGHT ISA MSAA [PROJECTION [SHADING [CAMERA]]] [TOP]
#   bench/callgrind_frame.sh build/bench/tessera_stagetimes bunny 1 1920 1080 avx2 4
#
# TOP (default 15): how many functions to list, by their own instructions (not their callees').
set -euo pipefail
[ $# -ge 7 ] || { sed -n '2,12p' "$0" >&2; exit 2; }
command -v valgrind > /dev/null || { echo "callgrind_frame: needs valgrind" >&2; exit 1; }
exe=$1 scene=$2 workers=$3 width=$4 height=$5 isa=$6 msaa=$7
shift 7
extra=() top=15
for a in "$@"; do
  if [[ $a =~ ^[0-9]+$ ]]; then top=$a; else extra+=("$a"); fi
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for frames in 1 5; do
  TESSERA_NOHASH=1 valgrind --tool=callgrind --callgrind-out-file="$out/$frames.out" \
    "$exe" "$scene" "$workers" "$frames" "$width" "$height" "$isa" "$msaa" "${extra[@]}" \
    > /dev/null 2> "$out/$frames.log" || { cat "$out/$frames.log" >&2; exit 1; }
done
python3 - "$out/1.out" "$out/5.out" "$top" <<'PY'
import collections, re, subprocess, sys

def own(path):
    """Instructions by function (exclusive), and the program's total."""
    text = subprocess.run(["callgrind_annotate", "--threshold=100", "--inclusive=no", "--auto=no", path],
                          capture_output=True, text=True, check=True).stdout
    by, total = collections.Counter(), 0
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+)\s+(?:\([^)]*\)\s+)?(\S.*)$", line)
        if not m:
            continue
        count, name = int(m.group(1).replace(",", "")), m.group(2)
        if "PROGRAM TOTALS" in name:
            total = count
        elif not name.startswith("=>") and "events annotated" not in name:
            by[re.sub(r"^\S*?:(?=\S)", "", name, count=1)[:140]] += count
    return by, total

one, total1 = own(sys.argv[1])
five, total5 = own(sys.argv[2])
print(f"a frame: {(total5 - total1) / 4e6:.2f} M instructions")
frame = {k: (v - one.get(k, 0)) / 4e6 for k, v in five.items()}
for name, m in sorted(frame.items(), key=lambda kv: -kv[1])[: int(sys.argv[3])]:
    print(f"{m:9.2f} M  {name}")
PY
