# Sourced by the window scripts: waiting for the Serosa window's frames ($window: its id).
# Waits until the window has drawn another frame (its title changes with the time), at most 30 s.
frame() {
  before=$(xdotool getwindowname "$window")
  n=0
  while [ "$(xdotool getwindowname "$window")" = "$before" ] && [ $n -lt 600 ]; do
    sleep 0.05
    n=$((n + 1))
  done
}
frames() { k=0; while [ $k -lt "$1" ]; do frame; k=$((k + 1)); done; }
