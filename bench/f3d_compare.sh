#!/usr/bin/env bash
# The whole process a user waits for: `tessera render FILE -o OUT.png` against `f3d FILE
# --output OUT.png` (Debian's f3d, drawing through OpenGL on Xvfb's software GL), each at the
# same size, each run RUNS times in a row (the first run of each warms the page cache, and the
# median of all is reported). Prints a Markdown table; the models default to real files from
# Debian's assimp-testmodels and glmark2-data.
#
#   bench/f3d_compare.sh                      # 1920x1080, RUNS=5
#   RESOLUTION=1280x720 bench/f3d_compare.sh model.glb other.obj
#
# Needs f3d (apt-get install f3d) and Xvfb (xvfb); f3d gets its own X server for the whole run,
# started once, so that neither side pays for a server's start-up.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${TESSERA:-build/apps/tessera/tessera}
runs=${RUNS:-5}
resolution=${RESOLUTION:-1920x1080}
command -v f3d >/dev/null || { echo "f3d_compare: f3d not found (apt-get install f3d)" >&2; exit 1; }
command -v Xvfb >/dev/null || { echo "f3d_compare: Xvfb not found (apt-get install xvfb)" >&2; exit 1; }
[ -x "$exe" ] || { echo "f3d_compare: $exe not built (scripts/setup.sh)" >&2; exit 1; }
models=("$@")
if [ ${#models[@]} -eq 0 ]; then
  models=(/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
          /usr/share/glmark2/models/bunny.obj
          /usr/share/glmark2/models/horse.3ds)
fi

out=$(mktemp -d)
display=:$((90 + RANDOM % 400))
Xvfb "$display" -screen 0 1920x1080x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$out"' EXIT
sleep 1

# Wall seconds of one run of the command given, to the millisecond; the command must succeed.
wall() {
  local start end
  start=$(date +%s%N)
  "$@" >/dev/null 2>&1 || { echo "f3d_compare: failed: $*" >&2; exit 1; }
  end=$(date +%s%N)
  awk -v d=$((end - start)) 'BEGIN { printf "%.3f\n", d / 1e9 }'
}
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "| model | tessera render (s) | f3d --output (s) | f3d / tessera |"
echo "|---|---:|---:|---:|"
for model in "${models[@]}"; do
  [ -f "$model" ] || { echo "f3d_compare: no such file: $model" >&2; exit 1; }
  t=$(for _ in $(seq "$runs"); do
        wall "$exe" render "$model" -o "$out/tessera.png" --resolution "$resolution"
      done | median)
  f=$(for _ in $(seq "$runs"); do
        DISPLAY=$display wall f3d "$model" --output="$out/f3d.png" \
          --resolution="${resolution/x/,}"
      done | median)
  awk -v m="$(basename "$model")" -v t="$t" -v f="$f" \
    'BEGIN { printf "| %s | %.2f | %.2f | %.1fx |\n", m, t, f, f / t }'
done
