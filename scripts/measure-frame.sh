#!/usr/bin/env bash
# Start-up and frame cost of the sky + tone-map pass at 1280x720, headless (EGL), with
# and without Mesa's on-disk shader cache. Prints a Markdown table for the README.
# Timing: steady clock around glFinish (llvmpipe's timer queries are wrong at this size).
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { "$iblab" render --width 1280 --height 720 --time 20 --json -o "$out/frame.png" "$@"; }
field() { python3 -c "import json,sys; print('%.1f' % json.load(sys.stdin)['timings_ms']['$1'])"; }
cold=$(MESA_SHADER_CACHE_DISABLE=true run)
warm=$(run)
echo "| measurement (1280x720, sky + tone map, $(echo "$warm" | python3 -c "import json,sys; print(json.load(sys.stdin)['renderer'].split(',')[0].split(': ')[1])")) | shader cache off (cold) | shader cache warm |"
echo "|---|---|---|"
echo "| process start to first frame finished, ms | $(echo "$cold" | field start_to_first_frame) | $(echo "$warm" | field start_to_first_frame) |"
echo "| of which environment load (courtyard.exr), ms | $(echo "$cold" | field environment_load) | $(echo "$warm" | field environment_load) |"
echo "| frame time, median of 20, ms | $(echo "$cold" | field frame_median) | $(echo "$warm" | field frame_median) |"
