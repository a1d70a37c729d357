#!/bin/sh
# Runs `serosa replay RECORDING` on the current X display until its timeline has assessed the
# recording (the title then counts the errors: "errors N"), lets a few frames draw, and closes it
# with Escape: the window writes its last picture to PNG and its overlay's layout to JSON.
# Usage: debrief_in_replay.sh SEROSA RECORDING PNG JSON
set -eu
serosa=$1 recording=$2 png=$3 json=$4
"$serosa" replay "$recording" --seconds 600 --snapshot "$png" --layout-log "$json" &
pid=$!
fail() { echo "debrief_in_replay.sh: $1" >&2; kill $pid; exit 1; }
window=$(timeout 60 xdotool search --sync --name '^Serosa replay' | head -n 1)
[ -n "$window" ] || fail "no replay window"
n=0
while ! xdotool getwindowname "$window" | grep -Eq 'errors [0-9]+'; do
  sleep 0.1
  n=$((n + 1))
  [ $n -lt 3000 ] || fail "the timeline never assessed the recording"
done
sleep 1
xdotool windowfocus --sync "$window"
xdotool key Escape
wait $pid
