#!/usr/bin/env bash
# The fitted lobe's refit and how it holds on maps it was not fitted on (issue #29, item 3;
# docs/accuracy-study.md, "Leave one out"). Runs `accuracy_study fit` once on the 8 bundled
# maps (the full fit) and once per bundled map with that map left out (--leave-out), all with
# the same options; then measures, as scripts/measure-lobe.sh measures on the GPU (copper
# spheres, metallic 1, 128 x 128, at roughness 0.3 and 0.6, and the grid; reference 256 wide;
# `accuracy_study eval --bench-scenes`, which agrees with it within 3% on the spheres), each
# leave-one-out table on the map it left out, and the full fit on maps no fit has seen: the
# unseen pmndrs maps (../shared/assets/hdri/pmndrs) and the synthetic ones of
# scripts/heldout-maps.py (texel noise too). The committed table (what the build shades with) is measured beside
# each. Prints Markdown tables, worst case first: per map and scene the split sum's relative RMSE, each table's,
# its ratio to the split sum's, then the worst and median ratio of (i) the leave-one-out tables
# on their left-out maps and (ii) the full fit on the unseen maps.
#   scripts/fit-lobe-loo.sh [OUT_DIR]        (default build/lobe-loo; a rerun keeps the tables,
#                                            bakes and maps already in OUT_DIR: empty it to refit)
#   FIT="--frames 48 --smooth 1 --smooth-passes 4" scripts/fit-lobe-loo.sh   (the fits' options
#                                            beyond the fixed ones below; this is the default)
#   TAPS=3 scripts/fit-lobe-loo.sh OUT_DIR   (the table's layout, `accuracy_study fit --taps`: 4 by
#                                            default, the committed table's)
#   ONLY_FULL=1 scripts/fit-lobe-loo.sh      (the full fit and the unseen maps only)
#   BAKE_ARGS="--prefilter-shading-lights 4" scripts/fit-lobe-loo.sh OUT_DIR   (options added to every
#                                            bake, passed to scripts/accuracy-bakes.sh)
#   LIGHTS=0 scripts/fit-lobe-loo.sh         (fit and measure the table on the plain cube; by default
#                                            as the renderer shades it: the bake's shading lights summed
#                                            exactly, the table reading the cube without them, --lights)
# The full fit's table is OUT_DIR/full.inc; to commit it: cp OUT_DIR/full.inc
# renderer/ibl/specular_lobe_fit.inc (its header names the command). The committed table is
# this script's full fit at its defaults (--smooth 1: at 0.5, with 4 or 8 passes, one step
# between neighbouring cells stays at 0.52, over lobe_table_smoothness_test's bound of 0.5). The integrals are cached
# in build/accuracy_cache, so the leave-one-out fits reuse the full fit's.
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
study=${STUDY:-build/renderer/lab/accuracy_study}
out=${1:-build/lobe-loo}
fit_options=${FIT:---frames 48 --smooth 1 --smooth-passes 4}
lights=(--lights)
suffix=+lights
if [ "${LIGHTS:-1}" = 0 ]; then lights=(); suffix=; fi
mkdir -p "$out"
bakes="$out/bakes"
start=$(date +%s)
log() { echo "[$(($(date +%s) - start)) s] $*" >&2; }

# The default bake of every map the study reads, and the synthetic maps.
scripts/accuracy-bakes.sh "$bakes" >/dev/null
missing=()
for n in twosuns strip corner edge1e6 pole lamps tubes neon frames arcs citylights noise sparks; do [ -f "$out/synthetic/$n.hdr" ] || missing+=("$n"); done
if [ ${#missing[@]} -gt 0 ]; then python3 scripts/heldout-maps.py "$out/synthetic" "${missing[@]}" >/dev/null; fi
synthetic=()
for f in "$out"/synthetic/*.hdr; do
  name=$(basename "$f" .hdr)
  # shellcheck disable=SC2086
  [ -f "$bakes/$name/bake.json" ] || "$iblab" bake --env "$f" --no-errors ${BAKE_ARGS:-} --out "$bakes/$name" >/dev/null
  synthetic+=(--env "$f")
done
log "bakes in $bakes"

# shellcheck disable=SC2086
fit() { # OUT.inc [--leave-out MAP]
  [ -f "$1" ] && return
  local t
  t=$(date +%s)
  "$study" fit --taps "${TAPS:-4}" --width 256 --size 16 --min-roughness 0.15 --mixed-objective --per-map-ratio --bakes "$bakes" "${lights[@]}" \
    $fit_options "${@:2}" --out "$1.tmp" 2>"$1.log"
  mv "$1.tmp" "$1"
  log "$(basename "$1"): $(($(date +%s) - t)) s"
}
maps=()
for f in assets/environments/*.exr; do maps+=("$(basename "$f" .exr)"); done
fit "$out/full.inc"
if [ -z "${ONLY_FULL:-}" ]; then
  for m in "${maps[@]}"; do fit "$out/loo-$m.inc" --leave-out "$m"; done
fi

cp renderer/ibl/specular_lobe_fit.inc "$out/committed.inc"
evaluate() { # CSV eval-args...
  "$study" eval --bench-scenes --bakes "$bakes" "${lights[@]}" --table "$out/committed.inc" --table "$out/full.inc" --csv "$1" "${@:2}" >/dev/null 2>"$1.log"
}
if [ -z "${ONLY_FULL:-}" ]; then
  for m in "${maps[@]}"; do evaluate "$out/loo-$m.csv" --set none --env "assets/environments/$m.exr" --table "$out/loo-$m.inc"; done
fi
evaluate "$out/unseen.csv" --set unseen "${synthetic[@]}"
log "measured"

python3 - "$out" "$suffix" "${maps[@]}" <<'EOF'
import csv, os, sys
out, suffix, maps = sys.argv[1], sys.argv[2], sys.argv[3:]
scenes = ["0.3", "0.6", "grid"]
def read(path):
    rows = {}
    for r in csv.DictReader(open(path)):
        scene = "grid" if r["scene"] == "grid" else "%g" % float(r["roughness"])
        # The tables as shaded: with --lights their "+lights" rows (the split sum stays plain).
        method = r["method"]
        if suffix and method != "split-sum":
            if not method.endswith(suffix) or method.startswith("split-sum"):
                continue
            method = method[: -len(suffix)]
        rows.setdefault((r["environment"], scene), {})[method] = float(r["relative_rmse"])
    return rows
def summary(ratios):
    v = sorted(ratios)
    return "worst %.2f, median %.2f, %d of %d at most 0.5" % (v[-1], v[len(v) // 2] if len(v) % 2 else 0.5 * (v[len(v) // 2 - 1] + v[len(v) // 2]),
                                                             sum(x <= 0.5 for x in v), len(v))
scene_name = {"0.3": "sphere 0.3", "0.6": "sphere 0.6", "grid": "grid"}
if all(os.path.exists(f"{out}/loo-{m}.csv") for m in maps):
    print("Leave one out: each table fitted on the 7 other bundled maps, measured on the map it left out;\n"
          "beside it the full fit (all 8 maps, this one included) and the committed table. Relative RMSE (ratio to the split sum's):\n")
    print("| map | scene | split sum | left out (fitted without it) | full fit | committed |")
    print("|---|---|---|---|---|---|")
    loo, full, committed, lines = [], [], [], []
    for m in maps:
        rows = read(f"{out}/loo-{m}.csv")
        for s in scenes:
            p = rows[(m, s)]
            e0 = p["split-sum"]
            cells = []
            for name, acc in [(f"loo-{m}", loo), ("full", full), ("committed", committed)]:
                acc.append(p[name] / e0)
                cells.append(f"{p[name]:.3f} ({p[name] / e0:.2f})")
            lines.append((p[f"loo-{m}"] / e0, f"| {m} | {scene_name[s]} | {e0:.3f} | " + " | ".join(cells) + " |"))
    for _, line in sorted(lines, key=lambda l: -l[0]):  # worst case first
        print(line)
    print(f"| **ratio** | | | {summary(loo)} | {summary(full)} | {summary(committed)} |\n")
rows = read(f"{out}/unseen.csv")
print("Maps no fit has seen (pmndrs, synthetic): the full fit and the committed table. Relative RMSE (ratio to the split sum's):\n")
print("| map | scene | split sum | full fit | committed |")
print("|---|---|---|---|---|")
full, committed = [], []
for (env, s), p in sorted(rows.items(), key=lambda kv: -kv[1]["full"] / kv[1]["split-sum"]):  # worst case first
    e0 = p["split-sum"]
    full.append(p["full"] / e0)
    committed.append(p["committed"] / e0)
    print(f"| {env} | {scene_name[s]} | {e0:.3f} | {p['full']:.3f} ({p['full'] / e0:.2f}) | {p['committed']:.3f} ({p['committed'] / e0:.2f}) |")
print(f"| **ratio** | | | {summary(full)} | {summary(committed)} |")
EOF
log "done"
