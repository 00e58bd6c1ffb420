#!/usr/bin/env bash
# Regenerates docs/gui.png, the README's screenshot of the GUI at 1600x900, by running
# scripts/gui-screenshot.txt through the GUI offscreen (the same frame a window shows).
#   scripts/gui-screenshot.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
# A first run's panel (no remembered sections or paths), whatever this user's GUI remembers.
config=$(mktemp -d)
trap 'rm -rf "$config"' EXIT
export XDG_CONFIG_HOME="$config"
IBLAB_SCREENSHOT="$PWD/docs/gui.png" "$build/app/iblab" --script scripts/gui-screenshot.txt --offscreen --window-size 1600x900
echo "wrote docs/gui.png"
