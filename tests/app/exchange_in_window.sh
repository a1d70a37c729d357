#!/bin/sh
# Runs `serosa run SCENE` on the current X display and, three times, presses X (the active hand
# puts its instrument in its port and takes the next one waiting, which slides in through its
# own port) and then drags the mouse with the left button held (xdotool): the trainee bringing in
# and moving three instruments in turn. Then it ends the session with Escape and leaves its
# summary with Space. Keys and drags are read once a frame, so each is held over two frames.
# Usage: exchange_in_window.sh SEROSA SCENE REPORT RECORDING
set -eu
serosa=$1 scene=$2 report=$3 recording=$4
"$serosa" run "$scene" --seconds 1200 --report "$report" --record "$recording" &
pid=$!
window=$(timeout 60 xdotool search --sync --name '^Serosa' | head -n 1)
[ -n "$window" ] || { echo "exchange_in_window.sh: no Serosa window" >&2; kill $pid; exit 1; }

. "$(dirname "$0")/window_frames.sh"

frames 3
xdotool windowfocus --sync "$window"
round=0
while [ $round -lt 3 ]; do
  xdotool keydown x
  frames 2
  xdotool keyup x
  # The new instrument slides in at 0.15 m/s: about a second of simulated time.
  sleep 1.5
  frames 2
  xdotool mousemove --window "$window" 640 360
  xdotool mousedown 1
  i=0
  while [ $i -lt 4 ]; do  # 160 px right and 80 px down, between two frames
    xdotool mousemove_relative -- 40 20
    i=$((i + 1))
  done
  frames 2
  xdotool mouseup 1
  frames 2
  round=$((round + 1))
done
xdotool keydown Escape
timeout 120 xdotool search --sync --name 'session summary' >/dev/null ||
  { echo "exchange_in_window.sh: no session summary" >&2; kill $pid; exit 1; }
xdotool keyup Escape
xdotool keydown space
wait $pid
xdotool keyup space
