#!/usr/bin/env bash
# Usage: tests/with_xvfb.sh WxHxDEPTH COMMAND [ARGS...]
# Runs COMMAND on an X display of its own: Xvfb chooses a free display number itself and reports
# it (-displayfd), so tests run in parallel (ctest -j) never share one. `xvfb-run -a` picks the
# number before starting the server and two concurrent runs can both take :99. The server is
# stopped when COMMAND ends; COMMAND's exit status is returned.
set -u
screen="$1"
shift
tmp="$(mktemp -d)"
trap 'kill "$xvfb" 2>/dev/null; wait "$xvfb" 2>/dev/null; rm -rf "$tmp"' EXIT
Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp -noreset 3>"$tmp/display" 2>"$tmp/xvfb.log" &
xvfb=$!
for _ in $(seq 200); do  # up to 20 s for the server to come up
  [ -s "$tmp/display" ] && break
  kill -0 "$xvfb" 2>/dev/null || { echo "with_xvfb.sh: Xvfb failed: $(tail -1 "$tmp/xvfb.log")" >&2; exit 1; }
  sleep 0.1
done
[ -s "$tmp/display" ] || { echo "with_xvfb.sh: Xvfb reported no display in 20 s" >&2; exit 1; }
DISPLAY=":$(head -1 "$tmp/display")" "$@"
