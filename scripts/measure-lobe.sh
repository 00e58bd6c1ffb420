#!/usr/bin/env bash
# Where the split sum reads the prefiltered cube, measured on the GPU (issue #14): the bench's
# specular-lobe family (split sum at R, Frostbite's and Filament's dominant directions, the
# fitted lobe; all on the bench's default bake) on every bundled map, for the sphere (the
# material sliders' copper at roughness 0.3, and at 0.6: the issue's two) and the 7x7 grid,
# each against the reference renderer's full integral over the pixels it resolves, with the
# reference 256 wide (resolving roughness >= 0.192) as `accuracy_study eval --bench-scenes`
# sums it, so that the two measures can be compared map by map. Prints one Markdown table: relative
# RMSE per map and scene, each read's ratio to the split sum's, and its frame time against
# the split sum's (bench frames, 128 x 128, median of 5: a few milliseconds of shading among
# tens of fixed cost, so noisy), then the frame time of a sphere filling a 1280 x 720 view
# with each method (the smallest of three interleaved medians of 10, so that a burst of load
# from another process does not land on one method only).
#   scripts/measure-lobe.sh [OUT_DIR]     (the bench's files stay in OUT_DIR, default a temporary one)
#   MAPS="city night" scripts/measure-lobe.sh    (only these bundled maps, for a quick look)
#   UNSEEN="../shared/assets/hdri/pmndrs/*.exr" scripts/measure-lobe.sh
#                                         (also these maps, which the fit never saw: their rows are
#                                          marked "unseen", benched apart so that a stem equal to a
#                                          bundled map's keeps its own row)
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
out=${1:-$(mktemp -d)}
mkdir -p "$out"
export IBLAB_CACHE_DIR="$out/cache"
envs=()
for f in assets/environments/*.exr; do
  name=$(basename "$f" .exr)
  if [ -z "${MAPS:-}" ] || [[ " $MAPS " == *" $name "* ]]; then envs+=(--env "$f"); fi
done
scenes=("sphere-0.3" "sphere-0.6" "grid")
for scene in "${scenes[@]}"; do
  case $scene in
    sphere-*) args=(--scene sphere --roughness "${scene#sphere-}") ;;
    *) args=(--scene "$scene") ;;
  esac
  "$iblab" bench --family specular-lobe "${args[@]}" --reference-width 256 "${envs[@]}" --out "$out/$scene" >/dev/null
  unseen=()
  for f in ${UNSEEN:-}; do unseen+=(--env "$f"); done
  if [ ${#unseen[@]} -gt 0 ]; then
    "$iblab" bench --family specular-lobe "${args[@]}" --reference-width 256 "${unseen[@]}" --out "$out/unseen-$scene" >/dev/null
  fi
done
renderer=$("$iblab" render --scene none --width 64 --height 64 --json -o "$out/probe.png" |
  python3 -c "import json,sys; print(json.load(sys.stdin)['renderer'].split(': ',1)[1].split(', OpenGL')[0])")
python3 - "$out" "$renderer" <<'EOF'
import csv, os, sys
out, renderer = sys.argv[1], sys.argv[2]
reads = ["split-sum", "split-sum, Frostbite direction", "split-sum, Filament direction", "fitted lobe"]
print(f"Relative RMSE against the reference (ratio to the split sum's; frame time ratio in brackets), {renderer}:\n")
print("| map | scene | " + " | ".join(reads) + " |")
print("|---|---|" + "---|" * len(reads))
worst = {r: 0.0 for r in reads}
frames = {r: [] for r in reads}
for scene in ["sphere-0.3", "sphere-0.6", "grid"]:
    rows = {}
    for prefix, path in [("", f"{out}/{scene}/bench.csv"), ("unseen ", f"{out}/unseen-{scene}/bench.csv")]:
        if os.path.exists(path):
            for row in csv.DictReader(open(path)):
                rows.setdefault(prefix + row["environment"], {})[row["series"]] = row
    for env, points in rows.items():
        base = points["split-sum"]
        e0, f0 = float(base["relative_rmse"]), float(base["frame_ms"])
        cells = []
        for r in reads:
            e, f = float(points[r]["relative_rmse"]), float(points[r]["frame_ms"])
            worst[r] = max(worst[r], e / e0)
            frames[r].append(f / f0)
            cells.append(f"{e:.3f}" if r == "split-sum" else f"{e:.3f} ({e / e0:.2f}; {f / f0:.2f}x)")
        print(f"| {env} | {scene} | " + " | ".join(cells) + " |")
median = lambda v: sorted(v)[len(v) // 2]
print("| **worst error ratio** (median, largest frame ratio) | | " +
      " | ".join("1" if r == "split-sum" else f"{worst[r]:.2f} (frame {median(frames[r]):.2f}x, {max(frames[r]):.2f}x)" for r in reads) + " |")
EOF
echo
echo "Sphere filling a 1280 x 720 view, courtyard.exr, copper, roughness 0.3 (frame time: the smallest of 3 medians of 10 frames, the methods' runs interleaved, shader cache warm; load average $(cut -d' ' -f1-3 /proc/loadavg)):"
echo
methods=("--method splitsum" "--method splitsum --specular-direction frostbite" "--method splitsum --specular-direction filament" "--method fitted-lobe")
declare -A best
for round in 1 2 3; do
  for args in "${methods[@]}"; do
    # shellcheck disable=SC2086
    ms=$("$iblab" render --scene sphere $args --width 1280 --height 720 --time 10 --json -o "$out/frame.png" |
      python3 -c "import json,sys; print('%.1f' % json.load(sys.stdin)['timings_ms']['frame_median'])")
    if [ -z "${best[$args]:-}" ] || python3 -c "import sys; sys.exit(0 if $ms < ${best[$args]} else 1)"; then best[$args]=$ms; fi
  done
done
echo "| method | frame ms | ratio to the split sum |"
echo "|---|---|---|"
for args in "${methods[@]}"; do
  echo "| $args | ${best[$args]} | $(python3 -c "print('%.2f' % (${best[$args]} / ${best[--method splitsum]}))")x |"
done

# The fitted lobe's shading lights cost per light (docs/accuracy-study.md, "Compact sources"):
# the same sphere on a map with none (courtyard) and two with the default bake's most, 4
# (sunrise: a sun across groups; interior: lamps).
echo
echo "The same sphere on maps without and with shading lights (same timing rule):"
echo
echo "| map | lights | split sum ms | fitted lobe without lights | with them (default) |"
echo "|---|---|---|---|---|"
for map in courtyard sunrise interior; do
  unset best
  declare -A best
  variants=("--method splitsum" "--method fitted-lobe --no-shading-lights" "--method fitted-lobe")
  for round in 1 2 3; do
    for args in "${variants[@]}"; do
      # shellcheck disable=SC2086
      json=$("$iblab" render --scene sphere --env "assets/environments/$map.exr" $args --width 1280 --height 720 --time 10 --json -o "$out/frame.png")
      ms=$(echo "$json" | python3 -c "import json,sys; print('%.1f' % json.load(sys.stdin)['timings_ms']['frame_median'])")
      lights=$(echo "$json" | python3 -c "import json,sys; print(json.load(sys.stdin)['shading_lights'])")
      if [ -z "${best[$args]:-}" ] || python3 -c "import sys; sys.exit(0 if $ms < ${best[$args]} else 1)"; then best[$args]=$ms; fi
    done
  done
  split=${best[--method splitsum]}
  echo "| $map | $lights | $split | $(python3 -c "print('%.2fx' % (${best[--method fitted-lobe --no-shading-lights]} / $split))") | $(python3 -c "print('%.2fx' % (${best[--method fitted-lobe]} / $split))") |"
done
