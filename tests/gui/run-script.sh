#!/usr/bin/env bash
# Runs one GUI script in a fresh working directory (captures, presets and exports land there),
# offscreen or in a real window on a private Xvfb, and keeps its control coverage.
#   tests/gui/run-script.sh offscreen|window WORKDIR COVERAGE_JSON IBLAB SCRIPT [IBLAB OPTIONS...]
set -euo pipefail
mode=$1 work=$2 coverage=$3 iblab=$4 script=$5
shift 5
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work" "$(dirname "$coverage")"
cd "$work"
# The GUI remembers its sections, paths and window size in $XDG_CONFIG_HOME, and saves
# screenshots and presets into the pictures and documents folders: all of them in the run's
# own folder, so that a run neither reads nor writes the user's.
export XDG_CONFIG_HOME="$work/config" XDG_PICTURES_DIR="$work" XDG_DOCUMENTS_DIR="$work"
case "$mode" in
  offscreen) exec "$iblab" --script "$script" --offscreen --coverage-out "$coverage" "$@" ;;
  window) exec "$here/with-xvfb.sh" "$iblab" --script "$script" --coverage-out "$coverage" "$@" ;;
  *) echo "run-script: mode is offscreen or window, got '$mode'" >&2; exit 2 ;;
esac
