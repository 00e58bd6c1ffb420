#!/usr/bin/env bash
# Start-up and frame costs at 1280x720, headless (EGL), printed as Markdown tables for
# docs/performance.md. GPU time: steady clock around glFinish (llvmpipe's timer queries are wrong at
# this size); medians of repeated frames in one process, after a warm-up frame.
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
out=$(mktemp -d)
export IBLAB_CACHE_DIR="$out/cache" # a private cache: the first run bakes, later runs load it
trap 'rm -rf "$out"' EXIT
run() { "$iblab" render --width 1280 --height 720 --json -o "$out/frame.png" "$@"; }
field() { python3 -c "import json,sys; print('%.1f' % json.load(sys.stdin)['timings_ms']['$1'])"; }
renderer=$(run --scene none --time 1 | python3 -c "import json,sys; print(json.load(sys.stdin)['renderer'].split(': ',1)[1].split(', OpenGL')[0])")

cold=$(MESA_SHADER_CACHE_DISABLE=true run --scene none --time 20)
warm=$(run --scene none --time 20)
echo "Sky + tone map ($renderer):"
echo
echo "| measurement | shader cache off (cold) | shader cache warm |"
echo "|---|---|---|"
echo "| process start to first frame finished, ms | $(echo "$cold" | field start_to_first_frame) | $(echo "$warm" | field start_to_first_frame) |"
echo "| of which environment load + bake (bake cached), ms | $(echo "$cold" | field environment_load) | $(echo "$warm" | field environment_load) |"
echo "| frame time, median of 20, ms | $(echo "$cold" | field frame_median) | $(echo "$warm" | field frame_median) |"
echo
echo "Lit sphere filling the view, courtyard.exr, metallic 1, roughness 0.3 (shader cache warm):"
echo
echo "| method | frame time, median of 10, ms |"
echo "|---|---|"
echo "| split-sum | $(run --scene sphere --method splitsum --time 10 | field frame_median) |"
for n in 1 8 64; do
  echo "| sampled, N = $n | $(run --scene sphere --method sampled --samples $n --time 10 | field frame_median) |"
done
echo "| split-sum, 7x7 grid | $(run --scene grid --method splitsum --time 10 | field frame_median) |"
