#!/usr/bin/env bash
# Runs a command with DISPLAY on a private Xvfb server, and stops the server however the
# command ends. The GUI tests use it to drive a real GLFW window (GLX on Mesa) on machines
# with no display.
# The display number is random (100-29999), not the lowest free one (-displayfd alone): two
# window tests of a fresh-root run, run in parallel, failed with "Failed to open display :0"
# after their server had accepted a client, most likely because a server stopping beside them
# had freed :0 and then removed the socket path of the server that took it. A random number is
# not one another test has just freed. A number in use makes Xvfb exit, and another is tried.
#   tests/gui/with-xvfb.sh [--size WxHxD] COMMAND [ARGS...]
# The command runs only once a client has connected to the server: a CI run in a fresh root
# once saw the first window test fail with "Failed to open display" right after Xvfb had
# reported its display. A server no client can reach is stopped and another started (five
# tries); its log is shown if all fail.
# -noreset: an X server resets itself when its last client disconnects, and the probe
# (xkbcomp) is that client: a fresh-root run saw the test's GLFW fail with "Failed to open
# display" after the probe had succeeded, most likely while the server was resetting (not
# reproduced in 70 tries, idle or with both cores busy; the option costs nothing).
set -euo pipefail
size=1920x1080x24
if [ "${1:-}" = "--size" ]; then size=$2; shift 2; fi
command -v Xvfb >/dev/null || { echo "with-xvfb: Xvfb is not installed (scripts/install-deps.sh installs xvfb)" >&2; exit 2; }
# xkbcomp comes with Xvfb (xserver-common depends on x11-xkb-utils); reading the server's
# keymap is a complete client connection, which is what the test's GLFW needs.
command -v xkbcomp >/dev/null || { echo "with-xvfb: xkbcomp is missing (Debian's x11-xkb-utils)" >&2; exit 2; }
work=$(mktemp -d)
server=
stop_server() {
  if [ -n "$server" ]; then kill "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true; fi
  server=
}
trap 'stop_server; rm -rf "$work"' EXIT
reachable() {
  local tries=50  # 10 s in steps of 0.2 s
  while [ $tries -gt 0 ]; do
    xkbcomp -w 0 ":$1" "$work/keymap.xkm" 2>/dev/null && return 0
    kill -0 "$server" 2>/dev/null || return 1
    sleep 0.2
    tries=$((tries - 1))
  done
  return 1
}
for attempt in 1 2 3 4 5; do
  mkfifo "$work/displayfd"
  # With a display given, -displayfd reports it once the server accepts clients.
  Xvfb ":$((100 + (RANDOM * 32768 + RANDOM) % 29900))" -displayfd 3 -screen 0 "$size" -nolisten tcp -noreset 3>"$work/displayfd" 2>"$work/xvfb.log" &
  server=$!
  display=
  read -r -t 30 display <"$work/displayfd" || true
  rm -f "$work/displayfd"
  if [ -n "$display" ] && reachable "$display"; then
    DISPLAY=":$display" "$@"
    exit $?
  fi
  echo "with-xvfb: Xvfb (try $attempt) did not accept a client on display '${display:-none}'" >&2
  stop_server
done
echo "with-xvfb: Xvfb's log of the last try:" >&2
cat "$work/xvfb.log" >&2
exit 2
