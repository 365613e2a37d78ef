#!/usr/bin/env bash
# Runs a command on a private Xvfb display and returns the command's exit status:
#   with-xvfb.sh CMD [ARGS...]
# Xvfb picks a free display number itself (-displayfd), atomically. `xvfb-run -a` instead guesses
# one from the lock files and then starts the server, so parallel runs (ctest -j) can pick the same
# number: one of them then fails to start, or runs its command on the other's server.
# The server listens on its local socket only and is stopped when the command ends.
set -uo pipefail
[ $# -ge 1 ] || { echo "usage: with-xvfb.sh CMD [ARGS...]" >&2; exit 2; }
command -v Xvfb >/dev/null 2>&1 || { echo "with-xvfb: Xvfb is not installed (apt-get install xvfb)" >&2; exit 1; }
dir="$(mktemp -d -t with-xvfb.XXXXXX)" || exit 1
xvfb=""
stop() {
  if [ -n "$xvfb" ]; then kill "$xvfb" 2>/dev/null; wait "$xvfb" 2>/dev/null; fi
  rm -rf "$dir"
}
trap stop EXIT
trap 'exit 143' TERM INT HUP
Xvfb -displayfd 3 -nolisten tcp -screen 0 1280x1024x24 3>"$dir/display" >"$dir/xvfb.log" 2>&1 &
xvfb=$!
# Xvfb writes the number and a newline once it accepts connections.
reported() { [ "$(wc -l <"$dir/display")" -ge 1 ]; }
for _ in $(seq 200); do
  reported && break
  kill -0 "$xvfb" 2>/dev/null || { echo "with-xvfb: Xvfb failed to start: $(tail -n 1 "$dir/xvfb.log")" >&2; exit 1; }
  sleep 0.05
done
reported || { echo "with-xvfb: Xvfb did not report a display within 10 s" >&2; exit 1; }
DISPLAY=":$(head -n 1 "$dir/display")" "$@"
