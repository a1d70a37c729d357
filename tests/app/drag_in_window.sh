#!/bin/sh
# Runs `serosa run SCENE` for SECONDS on the current X display and, with DRAG=1, drags the mouse
# across its window with the left button held (xdotool): the trainee moving the active
# instrument; then pushes the endoscope in with the I key. Usage: drag_in_window.sh SEROSA SCENE REPORT SECONDS DRAG
set -eu
serosa=$1 scene=$2 report=$3 seconds=$4 drag=$5
"$serosa" run "$scene" --seconds "$seconds" --report "$report" &
pid=$!
# The window's title starts "Serosa" (it then shows the state); give up after 30 s.
window=$(timeout 30 xdotool search --sync --name '^Serosa' | head -n 1)
[ -n "$window" ] || { echo "drag_in_window.sh: no Serosa window" >&2; kill $pid; exit 1; }
sleep 1
if [ "$drag" = 1 ]; then
  xdotool mousemove --window "$window" 640 360 mousedown 1
  i=0
  while [ $i -lt 40 ]; do  # 200 px right and 80 px down over about a second
    xdotool mousemove_relative -- 5 2
    sleep 0.02
    i=$((i + 1))
  done
  xdotool mouseup 1
  # Push the endoscope in 3 cm: I six times (held 0.2 s each: the window polls its keys once a
  # frame).
  xdotool windowfocus --sync "$window"
  i=0
  while [ $i -lt 6 ]; do
    xdotool keydown i
    sleep 0.2
    xdotool keyup i
    sleep 0.1
    i=$((i + 1))
  done
fi
wait $pid
