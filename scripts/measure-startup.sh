#!/usr/bin/env bash
# Start-up numbers of docs/performance.md: process wall time of `iblab --help`
# and `iblab bake --help` (minimum of RUNS), the shared libraries loaded at start, and, when
# DISPLAY names a usable X server (e.g. Xvfb), the GUI to its first presented frame:
# process wall time of `iblab --quit-after-frames 1` (start, window, context, environment
# load and cached bake, first frame, exit) and the time the GUI itself prints (from its own
# construction to the frame), minimum of RUNS each, with a warm bake cache.
#   scripts/measure-startup.sh [RUNS]     # default 20 for --help, 5 for the GUI
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
runs=${1:-20}
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
export IBLAB_CACHE_DIR=$cache

# Minimum wall time in ms of RUNS runs of the command.
min_wall_ms() {
  local n=$1 best=""
  shift
  for _ in $(seq "$n"); do
    local start end
    start=$(date +%s%N)
    "$@" > /dev/null 2>&1 || true
    end=$(date +%s%N)
    local ms=$(((end - start) / 1000))
    if [ -z "$best" ] || [ "$ms" -lt "$best" ]; then best=$ms; fi
  done
  python3 -c "print('%.1f' % ($best / 1000))"
}

echo "| measurement | value |"
echo "|---|---|"
echo "| shared libraries the executable needs (ldd) | $(ldd "$iblab" | wc -l) |"
echo "| \`iblab --help\`, min of $runs, ms | $(min_wall_ms "$runs" "$iblab" --help) |"
echo "| \`iblab bake --help\`, min of $runs, ms | $(min_wall_ms "$runs" "$iblab" bake --help) |"

if [ -z "${DISPLAY:-}" ]; then
  echo "measure-startup: DISPLAY unset: no GUI first-frame numbers (run under Xvfb)" >&2
  exit 0
fi
gui_runs=$(( runs < 5 ? runs : 5 ))
# The default window, whatever size this user's GUI remembers (and nothing saved over it).
gui_config=$(mktemp -d)
trap 'rm -rf "$cache" "$gui_config"' EXIT
export XDG_CONFIG_HOME="$gui_config"
"$iblab" bake --env assets/environments/courtyard.exr --no-errors > /dev/null # the bake cache the GUI loads
best_wall="" best_own=""
for _ in $(seq "$gui_runs"); do
  start=$(date +%s%N)
  line=$("$iblab" --quit-after-frames 1 2>&1 | grep 'first frame' || true)
  end=$(date +%s%N)
  [ -n "$line" ] || { echo "measure-startup: no window this run (glfwInit failed?), not counted" >&2; continue; }
  wall=$(((end - start) / 1000000))
  own=$(echo "$line" | sed -E 's/.*first frame ([0-9]+) ms.*/\1/')
  if [ -z "$best_wall" ] || [ "$wall" -lt "$best_wall" ]; then best_wall=$wall; fi
  if [ -z "$best_own" ] || [ "$own" -lt "$best_own" ]; then best_own=$own; fi
done
echo "| GUI process start to exit after the first frame, min of $gui_runs, ms | ${best_wall:-none} |"
echo "| GUI's own first-frame time (from its construction), min of $gui_runs, ms | ${best_own:-none} |"
