#!/bin/sh
# Runs `serosa replay RECORDING` on the current X display, waits until its metric timeline has
# been computed (the title then counts the errors: "errors N") and the replay has played to its
# end (where it pauses), and presses N twice, printing the window's title after each press (N jumps to a second before the
# next error; the title then says "error K/N"). Keys are tapped, not held (a held key repeats);
# the window counts a tap between two frames. Usage: jump_in_replay.sh SEROSA RECORDING
set -eu
serosa=$1 recording=$2
"$serosa" replay "$recording" --seconds 600 &
pid=$!
fail() { echo "jump_in_replay.sh: $1" >&2; kill $pid; exit 1; }
window=$(timeout 60 xdotool search --sync --name '^Serosa replay' | head -n 1)
[ -n "$window" ] || fail "no replay window"

# Waits until the window's title matches the pattern (grep -E), at most $2 seconds.
title_matches() {
  n=0
  while ! xdotool getwindowname "$window" | grep -Eq "$1"; do
    sleep 0.05
    n=$((n + 1))
    [ $n -lt $(($2 * 20)) ] || fail "the title never matched '$1': $(xdotool getwindowname "$window")"
  done
}
# Taps key $1, then waits until the title matches $2.
press() {
  xdotool key "$1"
  title_matches "$2" 60
}

# Focused once it draws (a window not yet mapped cannot take the focus).
title_matches 'errors [0-9]+' 300
xdotool windowfocus --sync "$window"
title_matches ' ([0-9.]+) / \1 s ' 300
press n 'error 1/'
xdotool getwindowname "$window"
press n 'error 2/'
xdotool getwindowname "$window"
xdotool key Escape
wait $pid
