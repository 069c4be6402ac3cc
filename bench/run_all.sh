#!/usr/bin/env bash
# Regenerates docs/perf.md from a fresh measurement: builds tessera (Release), runs every built-in
# scene at every standard resolution beside llvmpipe and alone with 1 and 2 workers, the bunny at
# 1080p with 1 and 2 workers beside llvmpipe too, with other shading (PBR too), culling and
# camera (the bunny filling the frame) and with 4x MSAA against 1x (llvmpipe at the same sample
# count), and UV spheres of 1k to 1M triangles at 1080p;
# then writes the raw results (docs/perf/*.jsonl), the plots (docs/perf/*.png) and the rendering
# section of docs/perf.md (between bench/report.py's markers; the rest of the page is left alone).
#
#   bench/run_all.sh                  # FRAMES=30 timed frames per scene and resolution
#   FRAMES=50 MAX_LOAD=0.5 bench/run_all.sh
#   SIMD=avx2 OUT=docs/perf/xeon-avx2 bench/run_all.sh   # narrower kernels than the CPU's widest
#
# MAX_LOAD: wait (up to WAIT_SECONDS, default 900) until the 1-minute load average is below it
# before measuring; the doc records the load before and after either way. Needs OSMesa
# (libosmesa6-dev), the bunny (glmark2-data) and matplotlib (python3-matplotlib), and two cores
# (the scaling runs pin to cores 0 and 1).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${BUILD_DIR:-build}
frames=${FRAMES:-30}
# OUT: where this run's results go. docs/perf is the page's main machine; a run on a machine of
# another instruction set goes beside it (OUT=docs/perf/avx2) and is tabled after the main one.
out=${OUT:-docs/perf}
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" -c "import matplotlib" 2>/dev/null ||
  { echo "run_all: the plots need matplotlib: apt-get install python3-matplotlib" >&2; exit 1; }

source scripts/compiler.sh  # clang for a new build folder, as scripts/setup.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DTESSERA_OSMESA=ON >/dev/null
cmake --build "$build" -j"${JOBS:-2}" --target tessera tessera_corelatency
exe="$build/apps/tessera/tessera"
# SIMD: tessera's tile kernels for every run (`tessera bench --simd`), e.g. avx2 on a machine with
# AVX-512, for the AVX2 rows when no AVX2-only machine is at hand; the report names the choice.
simd_flags=()
[ -n "${SIMD:-}" ] && simd_flags=(--simd "$SIMD")
# A cache line's round trip between cores 0 and 1, which moves by several times on a shared host
# and which every line the two workers share pays: measured at the start, before each scaling
# round and at the end, one JSON line each with "when" added.
core_latency() {
  "$build/bench/tessera_corelatency" 0 1 --json | sed "s/}\$/, \"when\": \"$1\"}/"
}
mkdir -p "$out"

load() { cut -d' ' -f1 /proc/loadavg; }
if [ -n "${MAX_LOAD:-}" ]; then
  waited=0
  while awk -v l="$(load)" -v m="$MAX_LOAD" 'BEGIN { exit !(l >= m) }'; do
    [ "$waited" -ge "${WAIT_SECONDS:-900}" ] && { echo "run_all: load still $(load)" >&2; break; }
    sleep 15
    waited=$((waited + 15))
  done
fi
load_before=$(load)
core_latency start > "$out/corelatency.jsonl"

bench() { "$exe" bench --json --vs llvmpipe --frames "$frames" "${simd_flags[@]}" "$@"; }
echo "run_all: every scene at every resolution ($frames frames each)" >&2
bench > "$out/matrix.jsonl"
echo "run_all: worker scaling and variants of the bunny at 1920x1080" >&2
# Worker scaling on the first two cores: one worker pinned to each of them (a shared host's two
# virtual cores are not always equally fast, and the speed-up is taken against the faster), then
# two workers on both; three rounds, one after the other, so that a spell of the host falls on
# all three alike. Each round measures tessera alone (100 frames in a row) and then beside
# llvmpipe (the rounds of five frames above, which also give llvmpipe's own scaling). Each line
# gets "cpus" and "round" added.
scaling_run() {
  local cpus=$1 round=$2
  shift 2
  taskset -c "$cpus" "$exe" bench --json "${simd_flags[@]}" "$@" |
    sed "s/}\$/, \"cpus\": \"$cpus\", \"round\": $round}/"
}
for round in 1 2 3; do
  core_latency "round $round" >> "$out/corelatency.jsonl"
  for reference in "--frames 100" "--vs llvmpipe --frames $frames"; do
    # shellcheck disable=SC2086 # the flags split on purpose
    scaling_run 0 "$round" $reference --workers 1 --resolution 1920,1080 bunny
    # shellcheck disable=SC2086
    scaling_run 1 "$round" $reference --workers 1 --resolution 1920,1080 bunny
    # shellcheck disable=SC2086
    scaling_run 0,1 "$round" $reference --workers 2 --resolution 1920,1080 bunny
  done
done > "$out/scaling.jsonl"
echo "run_all: worker scaling of every scene at every resolution (tessera alone)" >&2
# The same three configurations for every row of the matrix (issue 21 asks 1.8x on every row),
# tessera alone, 100 frames each, three rounds; scene by scene (the matrix's scenes, as
# matrix.jsonl names them), the three one after the other, so that a spell of the host falls on
# a scene's three alike (with every scene on one configuration before the next, a spell of
# tens of seconds took one configuration's rows alone: rows at 1.5x one round, 2.0x the next).
scenes=$(sed -n 's/^{"scene": "\([^"]*\)".*/\1/p' "$out/matrix.jsonl" | uniq)
for round in 1 2 3; do
  for scene in $scenes; do
    scaling_run 0 "$round" --frames 100 --workers 1 "$scene"
    scaling_run 1 "$round" --frames 100 --workers 1 "$scene"
    scaling_run 0,1 "$round" --frames 100 --workers 2 "$scene"
  done
done > "$out/matrix_scaling.jsonl"
{
  bench --resolution 1920,1080 --shading smooth bunny
  bench --resolution 1920,1080 --backface-type visible bunny
  bench --resolution 1920,1080 --shading flat bunny
  # glTF's BRDF per pixel on both sides (llvmpipe: the same GLSL as the Vulkan backends'): under
  # the bench's two view lights, and under one directional light (issue 19's PBR row).
  bench --resolution 1920,1080 --shading pbr bunny
  bench --resolution 1920,1080 --shading pbr --light directional:-0.4,-0.6,-1 bunny
  # The bunny filling the frame (issue 21's rows): bigger triangles, nearly every pixel shaded.
  for shading in gouraud flat smooth; do
    bench --resolution 1920,1080 --shading "$shading" --camera-position 0,0.2,3 bunny
  done
} > "$out/variants.jsonl"
echo "run_all: the bunny at 1920x1080 with 1x and 4x MSAA, three rounds" >&2
# The cost of 4x MSAA is the 4x median over the 1x median: each round measures the two back to
# back, so that a spell of the host falls on both alike; llvmpipe draws the same sample count
# (a multisampled framebuffer object, resolved and read back). Each line gets "round" added.
for round in 1 2 3; do
  for msaa in 1 4; do
    bench --resolution 1920,1080 --msaa "$msaa" bunny | sed "s/}\$/, \"round\": $round}/"
  done
done > "$out/msaa.jsonl"
echo "run_all: UV spheres of 1k to 1M triangles at 1920x1080" >&2
spheres=$(mktemp -d)
trap 'rm -rf "$spheres"' EXIT
for k in 16 32 64 128 256 512; do
  "$python" bench/sphere_obj.py "$k" "$spheres/sphere_$((4 * k * k)).obj"
  # The scene by its file name, not the temporary directory of this run.
  bench --resolution 1920,1080 "$spheres/sphere_$((4 * k * k)).obj" | sed "s|\"$spheres/|\"|"
done > "$out/spheres.jsonl"
load_after=$(load)
core_latency end >> "$out/corelatency.jsonl"

compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")
"$python" - "$out/machine.json" <<EOF
import json, platform, subprocess, sys
def cpuinfo(key, default="unknown"):
    return next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.split(":")[0].strip() == key), default)
cpu = cpuinfo("model name")
flags = cpuinfo("flags", "").split()
simd = [f for f in ("sse2", "avx2", "avx512f") if f in flags]
json.dump({
    "cpu": cpu, "family": cpuinfo("cpu family"), "model": cpuinfo("model"), "cores": int(subprocess.check_output(["nproc"]).strip()), "simd": simd,
    "compiler": subprocess.check_output(["$compiler", "--version"], text=True).splitlines()[0],
    "kernel": platform.release(),
    "commit": subprocess.check_output(["git", "rev-parse", "--short", "HEAD"], text=True).strip(),
    "dirty": bool(subprocess.check_output(["git", "status", "--porcelain", "--untracked-files=no", "--", ".", ":!docs"], text=True).strip()),
    "date": subprocess.check_output(["date", "-u", "+%Y-%m-%d %H:%M UTC"], text=True).strip(),
    "kernels": "${SIMD:-}", "frames": $frames, "load_before": float("$load_before"), "load_after": float("$load_after"),
}, open(sys.argv[1], "w"), indent=2)
EOF
# The main machine's results, then every other machine's kept beside them (docs/perf/*/).
others=()
for dir in docs/perf/*/; do
  [ -f "$dir/matrix.jsonl" ] && others+=("${dir%/}")
done
"$python" bench/report.py docs/perf docs/perf.md "${others[@]}"
echo "run_all: updated docs/perf.md and $out/" >&2
