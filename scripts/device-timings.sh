#!/usr/bin/env bash
# Times the bake and one frame per shading method on a hardware GPU with GL timer queries
# (GL_TIME_ELAPSED: `iblab bake --json --repeat N`'s gpu_total_ms, `iblab render --json --time N`'s
# frame_gpu_*), beside the steady-clock times that llvmpipe reports. Prints one JSON line per
# measurement into $1 (default timings.jsonl). IBLAB points at the binary.
#   IBLAB=build/app/iblab scripts/device-timings.sh out.jsonl
set -euo pipefail
iblab=${IBLAB:-build/app/iblab}
out=${1:-timings.jsonl}
: >"$out"
tmp=$(mktemp -d)
maps=(assets/environments/*.exr)
# Three repeats of each bake: the first compiles the shaders (no disk cache on a bare machine).
for map in "${maps[@]}"; do
  for preset in default tutorial; do
    "$iblab" bake --env "$map" --preset "$preset" --no-cache --no-errors --repeat 3 --json \
      | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({"kind":"bake","map":sys.argv[1],"preset":sys.argv[2],"renderer":j.get("renderer"),"timings_ms":j.get("timings_ms"),"gpu_total_ms":j.get("gpu_total_ms"),"repeat_totals_ms":j.get("repeat_totals_ms")}))' "$map" "$preset" >>"$out"
  done
done
# The default's prefilter against the sampled-only estimator (--prefilter-bright-texels 0),
# same maps, same process shape: what the exact bright-texel sum costs on this GPU.
for map in "${maps[@]}"; do
  "$iblab" bake --env "$map" --no-cache --no-errors --repeat 3 --json --prefilter-bright-texels 0 \
    | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({"kind":"bake-sampled-only","map":sys.argv[1],"timings_ms":j.get("timings_ms"),"gpu_total_ms":j.get("gpu_total_ms")}))' "$map" >>"$out"
done
for method in splitsum fitted-lobe sampled reference; do
  for size in "1280 720" "1920 1080"; do
    set -- $size
    "$iblab" render --method "$method" --width "$1" --height "$2" --time 30 --json -o "$tmp/frame-$method.exr" \
      | python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({"kind":"frame","method":sys.argv[1],"size":sys.argv[2],"renderer":j.get("renderer"),"timings_ms":j.get("timings_ms"),"gpu_timing_method":j.get("gpu_timing_method")}))' "$method" "$1x$2" >>"$out"
  done
done
cat "$out"
