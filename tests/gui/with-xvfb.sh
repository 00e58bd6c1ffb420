#!/usr/bin/env bash
# Runs a command with DISPLAY on a private Xvfb server (a free display number chosen by
# Xvfb itself), and stops the server however the command ends. The GUI tests use it to drive
# a real GLFW window (GLX on Mesa) on machines with no display.
#   tests/gui/with-xvfb.sh [--size WxHxD] COMMAND [ARGS...]
set -euo pipefail
size=1920x1080x24
if [ "${1:-}" = "--size" ]; then size=$2; shift 2; fi
command -v Xvfb >/dev/null || { echo "with-xvfb: Xvfb is not installed (scripts/install-deps.sh installs xvfb)" >&2; exit 2; }
fifo=$(mktemp -u)
mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 "$size" -nolisten tcp 3>"$fifo" 2>/dev/null &
server=$!
trap 'kill "$server" 2>/dev/null; wait "$server" 2>/dev/null; rm -f "$fifo"' EXIT
read -r -t 30 display <"$fifo" || { echo "with-xvfb: Xvfb did not start" >&2; exit 2; }
DISPLAY=":$display" "$@"
