#!/usr/bin/env bash
# The environment-switch numbers of docs/performance.md: what a GUI user waits for between clicking Load and
# the first frame drawn with the new environment's lighting, in the real GUI loop (offscreen,
# driven by a GUI script). Three cases, each the minimum of 3 runs:
#   - disk cache: a map baked in an earlier run, loaded and its bake read from the cache;
#   - kept: switching back to a map shown earlier in the session (its bake is kept);
#   - the frame alone: the render time of one frame at that size, for scale.
#   scripts/measure-switch.sh [WIDTHxHEIGHT]    # default 1280x720, the GUI's default window
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
size=${1:-1280x720}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_CACHE_HOME="$work/cache"
first="$PWD/assets/environments/courtyard.exr" second="$PWD/assets/environments/sunset.exr"
cat > "$work/switch.txt" <<SCRIPT
wait-idle
set "Environment/envpath" $first
click "Environment/Load"
wait-until /session/last_switch/environment == "$first"
wait-idle
set "Environment/envpath" $second
click "Environment/Load"
wait-until /session/last_switch/environment == "$second"
wait-idle
print /session/last_switch
set "Environment/envpath" $first
click "Environment/Load"
wait-until /session/last_switch/environment == "$first"
wait-idle
print /session/last_switch
print /renderer/render_ms
SCRIPT
"$iblab" --script "$work/switch.txt" --offscreen --window-size "$size" > /dev/null # fills the bake cache
for _ in 1 2 3; do "$iblab" --script "$work/switch.txt" --offscreen --window-size "$size" | grep '^/' ; done > "$work/runs.txt"
python3 - "$work/runs.txt" "$size" <<'PY'
import json, sys
disk, kept, frame = [], [], []
for line in open(sys.argv[1]):
    pointer, value = line.split(" = ", 1)
    if pointer == "/renderer/render_ms":
        frame.append(float(value))
        continue
    timing = json.loads(value)
    (kept if "courtyard" in timing["environment"] else disk).append(timing)
best = lambda runs: min(runs, key=lambda t: t["first_frame_ms"])
d, k = best(disk), best(kept)
print(f"environment switch at {sys.argv[2]}, minimum of {len(disk)} runs (ms from the click):")
print(f"  disk cache (sunset.exr): loaded {d['load_ms']:.0f}, bake read {d['bake_ms']:.0f}, first frame {d['first_frame_ms']:.0f}")
print(f"  kept in the session (back to courtyard.exr): shown {k['bake_ms']:.0f}, first frame {k['first_frame_ms']:.0f}")
print(f"  one frame's render alone: {min(frame):.0f}")
PY
