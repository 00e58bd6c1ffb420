#!/usr/bin/env bash
# Times the bake and one frame per shading method on a hardware GPU with GL timer queries
# (GL_TIME_ELAPSED: `iblab bake --json --repeat N`'s gpu_total_ms, `iblab render --json --time N`'s
# frame_gpu_*), beside the steady-clock times that llvmpipe reports. Prints one JSON line per
# measurement into $1 (default timings.jsonl). IBLAB points at the binary; ROUNDS (default 3)
# is how many processes bake each map with each variant. IBLAB_BASELINE (an older build's
# binary, its shaders in IBLAB_BASELINE_ASSETS) bakes the default and sampled-only beside them,
# interleaved, so that both builds are compared on the same machine in the same minutes.
#   IBLAB=build/app/iblab scripts/device-timings.sh out.jsonl
set -euo pipefail
iblab=${IBLAB:-build/app/iblab}
out=${1:-timings.jsonl}
: >"$out"
tmp=$(mktemp -d)
maps=(assets/environments/*.exr)
rounds=${ROUNDS:-3}
# One JSON line for one bake: kind, map, round, and the report's times (gpu_total_ms: the warm
# repeat's GL_TIME_ELAPSED; timings_ms and part_timings_ms: its steady-clock steps).
bake_line() {
  local kind=$1 map=$2 round=$3 bin=("$iblab")
  shift 3
  # An older build reads its own shaders (IBLAB_BASELINE_ASSETS: a copy of its assets folder).
  if [[ $kind == baseline-* ]]; then bin=(env "IBLAB_ASSET_DIR=${IBLAB_BASELINE_ASSETS:-$PWD/assets}" "$IBLAB_BASELINE"); fi
  # The report is parsed once the bake has exited: python beside it would take a core from
  # its host work (scripts/measure-bake.sh's bake_report).
  "${bin[@]}" bake --env "$map" --no-cache --no-errors --repeat 3 --json "$@" > "$tmp/bake.json"
  python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({"kind":sys.argv[1],"map":sys.argv[2],"round":int(sys.argv[3]),"renderer":j.get("renderer"),"timings_ms":j.get("timings_ms"),"part_timings_ms":j.get("part_timings_ms"),"gpu_total_ms":j.get("gpu_total_ms")}))' "$kind" "$map" "$round" < "$tmp/bake.json" >>"$out"
}
# Three repeats of each bake in one process (the first compiles the shaders: a bare machine has
# no disk cache), ROUNDS processes of each, interleaved so that every variant sees the same
# machine: the default and tutorial presets, the default's sampled-only estimator
# (--prefilter-bright-texels 0: what the exact bright-texel sums cost on this GPU) and the
# default without its refinement of mips 1 and 2 (--prefilter-refine-factor 1), the default
# with its host work in steps of their own, as on llvmpipe (--host-work steps), and the default
# with its lights in blocks every texel sums instead of per tile (--prefilter-tile-lights 0).
for round in $(seq "$rounds"); do
  for map in "${maps[@]}"; do
    bake_line bake-default "$map" "$round"
    bake_line bake-tutorial "$map" "$round" --preset tutorial
    bake_line bake-sampled-only "$map" "$round" --prefilter-bright-texels 0
    bake_line bake-unrefined "$map" "$round" --prefilter-refine-factor 1
    bake_line bake-own-steps "$map" "$round" --host-work steps
    bake_line bake-blocks "$map" "$round" --prefilter-tile-lights 0
    if [ -n "${IBLAB_BASELINE:-}" ]; then
      bake_line baseline-default "$map" "$round"
      bake_line baseline-sampled-only "$map" "$round" --prefilter-bright-texels 0
    fi
  done
done
for method in splitsum fitted-lobe sampled reference; do
  for size in "1280 720" "1920 1080"; do
    set -- $size
    "$iblab" render --method "$method" --width "$1" --height "$2" --time 30 --json -o "$tmp/frame-$method.exr" > "$tmp/frame.json"
    python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({"kind":"frame","method":sys.argv[1],"size":sys.argv[2],"renderer":j.get("renderer"),"timings_ms":j.get("timings_ms"),"gpu_timing_method":j.get("gpu_timing_method")}))' "$method" "$1x$2" < "$tmp/frame.json" >>"$out"
  done
done
# The fitted lobe's shading lights on the GPU: a copper sphere filling 1280 x 720 (as
# scripts/measure-lobe.sh's last table) on a map without lights (courtyard) and two with the
# default's 4 (sunrise, interior), each method's GPU frame time.
for map in courtyard sunrise interior; do
  for variant in "splitsum" "fitted-lobe --no-shading-lights" "fitted-lobe"; do
    # shellcheck disable=SC2086
    "$iblab" render --scene sphere --env "assets/environments/$map.exr" --method $variant --width 1280 --height 720 --time 30 --json -o "$tmp/sphere.exr" > "$tmp/sphere.json"
    python3 -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({"kind":"sphere","map":sys.argv[1],"variant":sys.argv[2],"shading_lights":j.get("shading_lights"),"timings_ms":j.get("timings_ms")}))' "$map" "$variant" < "$tmp/sphere.json" >>"$out"
  done
done
# The tables of docs/gpu-timings.md: per map, the minimum over the rounds of each variant.
python3 - "$out" <<'PY'
import collections, json, statistics, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
bakes = collections.defaultdict(lambda: collections.defaultdict(list))
for r in rows:
    if r["kind"].startswith("bake") or r["kind"].startswith("baseline"):
        bakes[r["map"].rsplit("/", 1)[-1].removesuffix(".exr")][r["kind"]].append(r)
def least(runs, key):
    return min(key(r) for r in runs)
gpu = lambda r: r["gpu_total_ms"]
part = lambda name: (lambda r: (r.get("part_timings_ms") or {}).get(name, 0.0))
print("| map | default | sampled-only | default / sampled-only | without refinement | host work in own steps | lights in blocks | tutorial | default: split | mip 1 | mip 2 | own steps: shading lights | own steps: split |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
ratios = []
for m, k in sorted(bakes.items()):
    d, s = least(k["bake-default"], gpu), least(k["bake-sampled-only"], gpu)
    ratios.append(d / s)
    print(f"| {m} | {d:.1f} | {s:.1f} | {d / s:.2f}x | {least(k['bake-unrefined'], gpu):.1f} | {least(k['bake-own-steps'], gpu):.1f} | {least(k['bake-blocks'], gpu):.1f} | "
          f"{least(k['bake-tutorial'], gpu):.1f} | {least(k['bake-default'], part('prefilter.split')):.1f} | "
          f"{least(k['bake-default'], part('prefilter.mip1')):.2f} | {least(k['bake-default'], part('prefilter.mip2')):.2f} | "
          f"{least(k['bake-own-steps'], part('prefilter.shading_lights')):.1f} | {least(k['bake-own-steps'], part('prefilter.split')):.1f} |")
if ratios:
    print(f"default / sampled-only: {min(ratios):.2f}x .. {max(ratios):.2f}x, median {statistics.median(ratios):.2f}x")
if any("baseline-default" in k for k in bakes.values()):
    print("| map | baseline default | baseline sampled-only | baseline ratio | default | sampled-only | ratio |")
    print("|---|---|---|---|---|---|---|")
    for m, k in sorted(bakes.items()):
        bd, bs = least(k["baseline-default"], gpu), least(k["baseline-sampled-only"], gpu)
        d, s = least(k["bake-default"], gpu), least(k["bake-sampled-only"], gpu)
        print(f"| {m} | {bd:.1f} | {bs:.1f} | {bd / bs:.2f}x | {d:.1f} | {s:.1f} | {d / s:.2f}x |")
spheres = collections.defaultdict(dict)
for r in rows:
    if r["kind"] == "sphere":
        spheres[r["map"]][r["variant"]] = r
if spheres:
    print("| map | lights | split sum GPU ms | fitted lobe without lights | with them (default) |")
    print("|---|---|---|---|---|")
    for m, v in spheres.items():
        g = lambda name: v[name]["timings_ms"].get("frame_gpu_median", v[name]["timings_ms"]["frame_median"])
        print(f"| {m} | {v['fitted-lobe']['shading_lights']} | {g('splitsum'):.3f} | {g('fitted-lobe --no-shading-lights') / g('splitsum'):.3f}x | {g('fitted-lobe') / g('splitsum'):.3f}x |")
print("| method | size | GPU median | steady median | reference |")
print("|---|---|---|---|---|")
for r in rows:
    if r["kind"] == "frame":
        t = r["timings_ms"]
        print(f"| {r['method']} | {r['size']} | {t.get('frame_gpu_median', 0):.2f} | {t['frame_median']:.2f} | {t['reference']:.0f} |" if "reference" in t else
              f"| {r['method']} | {r['size']} | {t.get('frame_gpu_median', 0):.2f} | {t['frame_median']:.2f} | |")
PY
