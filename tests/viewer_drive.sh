# Sourced by the window tests' driver scripts (tests/gpu/viewer_gpu_test.cpp), which run
# `amrvk view --state-file "$STATE"` in the background (its pid in VIEWER) on an Xvfb display of
# their own and drive it with xdotool. Every wait here is on the state the viewer reports
# (docs/viewer.md, --state-file: rewritten after every frame, one member a line), polled and
# bounded by a deadline, never a fixed pause: on a loaded machine a frame may take seconds.
# Pointer positions: the window sits at the screen's origin (no window manager) and its
# framebuffer is its window coordinates (scale 1), so screen, window and layout pixels agree.

# state KEY [FIELD]: the value on the state file's line for KEY (compact JSON; keys are unique in
# the file), or the value of FIELD in it; fails while the file does not exist yet.
state() {
  local line
  line=$(grep -m1 -F "\"$1\": " "$STATE" 2>/dev/null) || return 1
  line=${line#*\": }
  line=${line%,}
  if [ $# -ge 2 ]; then line=$(printf '%s\n' "$line" | sed -n "s/.*\"$2\":\([^,}]*\).*/\1/p"); fi
  [ -n "$line" ] && printf '%s\n' "$line"
}

# wait_until WHAT COMMAND...: runs COMMAND every 0.05 s until it succeeds. When the viewer ends
# first, or WAIT_SECONDS (default 120) pass, prints WHAT and the last state, ends the viewer and
# exits 1: a lost event fails the test, it does not hang it.
wait_until() {
  local what=$1 deadline=$((SECONDS + ${WAIT_SECONDS:-120}))
  shift
  until "$@"; do
    if ! kill -0 "$VIEWER" 2>/dev/null; then
      echo "drive: the viewer ended while waiting for $what; last state:" >&2
      cat "$STATE" >&2 2>/dev/null
      exit 1
    fi
    if [ "$SECONDS" -ge "$deadline" ]; then
      echo "drive: no $what after ${WAIT_SECONDS:-120} s; last state:" >&2
      cat "$STATE" >&2 2>/dev/null
      kill "$VIEWER" 2>/dev/null
      exit 1
    fi
    sleep 0.05
  done
}

frames_at_least() { local f; f=$(state frame) && [ "$f" -ge "$1" ]; }
pointer_at() { [ "$(state pointer x)" = "$1" ] && [ "$(state pointer y)" = "$2" ]; }
held_is() { [ "$(state pointer held)" = "$1" ]; }
scrolls_at_least() { local n; n=$(state events scroll) && [ "$n" -ge "$1" ]; }
has() { state "$1" >/dev/null; }

# The viewer's first frame presented (its pipelines built, the panel laid out): before any input.
wait_first_frame() { wait_until "first frame" frames_at_least 1; }

# settle: waits for two more frames than the state shows now. The second of them began after the
# state was read, so it took every event sent before this call (and laid out what they changed).
settle() {
  local f
  f=$(state frame) || f=0
  wait_until "frame $((f + 2))" frames_at_least $((f + 2))
}

# move X Y: the pointer to X, Y, then waits until the viewer has taken it there.
move() {
  xdotool mousemove "$1" "$2"
  wait_until "the pointer at $1,$2" pointer_at "$1" "$2"
}

# press / release: the left button (GLFW button 0), then waits until the viewer has taken it.
press() {
  xdotool mousedown 1
  wait_until "the left button held" held_is 1
}
release() {
  xdotool mouseup 1
  wait_until "the left button released" held_is 0
}

# wheel_up N: N wheel steps up, then waits until the viewer has taken them.
wheel_up() {
  local before
  before=$(state events scroll)
  xdotool click --repeat "$1" 4
  wait_until "$1 wheel steps" scrolls_at_least $((before + $1))
}

# centre NAME: "X Y", the centre of the rectangle the state reports as NAME (a layout rectangle or
# a widget of the panel).
centre() {
  echo "$(($(state "$1" x) + $(state "$1" width) / 2)) $(($(state "$1" y) + $(state "$1" height) / 2))"
}

# click NAME: a left click at the centre of the widget NAME, once the viewer reports it on screen;
# the pointer rests there a frame first (ImGui hovers, then presses).
click() {
  wait_until "the widget '$1' on screen" has "$1"
  move $(centre "$1")
  settle
  press
  release
  settle
}

# to_window U V: "X Y", the window pixel showing pixel (U, V) of the image (the picture
# rectangle and the image size the state reports; U, V may be fractional).
to_window() {
  awk -v u="$1" -v v="$2" -v px="$(state picture x)" -v py="$(state picture y)" -v pw="$(state picture width)" \
    -v ph="$(state picture height)" -v iw="$(state image width)" -v ih="$(state image height)" \
    'BEGIN { printf "%d %d\n", int(px + u * pw / iw + 0.5), int(py + v * ph / ih + 0.5) }'
}

# quit: the q key, then exits with the viewer's status (started under `timeout`, a viewer that
# misses the key is ended: the test fails, it does not hang).
quit() {
  xdotool key q
  wait "$VIEWER"
  exit $?
}
