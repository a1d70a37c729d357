#!/bin/sh
# Runs `serosa run SCENE` on the current X display and, with DRAG=1, drags the mouse across its
# window with the left button held (xdotool): the trainee moving the active instrument; then
# pushes the endoscope in with two presses of I. Without DRAG it waits as long, counted in the
# window's frames, and sends nothing; either way it then ends the session with Escape and leaves
# its summary with Space. The window gathers the drag event by event between frames, so the drag
# goes in one go; each press of I is held over two frames, since the endoscope's keys are read
# once a frame (a sanitizer build draws a frame every few seconds). The session's own limit is
# far beyond what the script needs, so only Escape ends it.
# Usage: drag_in_window.sh SEROSA SCENE REPORT DRAG
set -eu
serosa=$1 scene=$2 report=$3 drag=$4
"$serosa" run "$scene" --seconds 1200 --report "$report" &
pid=$!
# The window's title starts "Serosa" (then it shows the simulated time); give up after 60 s.
window=$(timeout 60 xdotool search --sync --name '^Serosa' | head -n 1)
[ -n "$window" ] || { echo "drag_in_window.sh: no Serosa window" >&2; kill $pid; exit 1; }

. "$(dirname "$0")/window_frames.sh"
act() { if [ "$drag" = 1 ]; then xdotool "$@"; fi; }

frames 3
act mousemove --window "$window" 640 360
act mousedown 1
i=0
while [ $i -lt 4 ]; do  # 200 px right and 80 px down in four moves, between two frames
  act mousemove_relative -- 50 20
  i=$((i + 1))
done
act mouseup 1
frames 2
xdotool windowfocus --sync "$window"
i=0
while [ $i -lt 2 ]; do
  act keydown i
  frames 2
  act keyup i
  frames 2
  i=$((i + 1))
done
# Escape ends the session; the scene scores it, so its summary follows (the title says so), and
# Space leaves it (Escape, still held, would need a release first).
xdotool keydown Escape
timeout 120 xdotool search --sync --name 'session summary' >/dev/null ||
  { echo "drag_in_window.sh: no session summary" >&2; kill $pid; exit 1; }
xdotool keyup Escape
xdotool keydown space  # held until the window has closed
wait $pid
xdotool keyup space
