#!/usr/bin/env bash
# Makes docs/images/viewer.png the way the viewer's window tests do: `tessera view` in a real
# window on a private Xvfb server, driven with xdotool, saved by the viewer's own F12 screenshot.
# Needs a build (scripts/setup.sh: xvfb and xdotool). Uses the Stanford bunny from Debian's
# glmark2-data when it is installed, else the built-in cube.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
tessera="$root/build/apps/tessera/tessera"
out="$root/docs/images/viewer.png"
model=/usr/share/glmark2/models/bunny.obj
[ -f "$model" ] || model=""
tmp="$(mktemp -d)"
xvfb_pid="" viewer_pid=""
cleanup() {
  [ -n "$viewer_pid" ] && kill "$viewer_pid" 2>/dev/null || true
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

# Waits (up to a minute) for a line starting with $2 in file $1 and prints it.
wait_for_line() {
  for _ in $(seq 600); do
    if line="$(grep -m1 "^$2" "$1")"; then
      echo "$line"
      return 0
    fi
    sleep 0.1
  done
  echo "make_viewer_screenshot: timed out waiting for '$2'" >&2
  cat "$1" "$tmp/viewer.err" >&2 || true
  return 1
}

# Xvfb picks a free display and writes its number to fd 3 when it is ready.
Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp 3>"$tmp/display" 2>"$tmp/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 600); do [ -s "$tmp/display" ] && break; sleep 0.1; done
export DISPLAY=":$(head -n1 "$tmp/display")" SDL_VIDEODRIVER=x11

cd "$tmp"
"$tessera" view ${model:+"$model"} -w 480 -h 360 -stats -axes >"$tmp/viewer.out" 2>"$tmp/viewer.err" &
viewer_pid=$!
wait_for_line "$tmp/viewer.out" "tessera view: showing" >/dev/null
window="$(xdotool search --onlyvisible --name '^tessera view' | head -n1)"
xdotool mousemove --window "$window" 240 180
sleep 1  # let the stats overlay measure a frame rate
xdotool key F12
shot="$(wait_for_line "$tmp/viewer.out" "saved " | cut -c7-)"
xdotool key Escape
wait "$viewer_pid"
viewer_pid=""
cp "$shot" "$out"
echo "wrote $out"
