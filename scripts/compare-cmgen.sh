#!/usr/bin/env bash
# Filament's cmgen and iblab bake the same maps; both bakes are measured against the exact
# references of the map (`iblab measure` for cmgen's _ibl.ktx, `iblab bake --json` for
# iblab's own: the same "errors" object) and timed process to process. Prints a Markdown
# table (the README's).
#   scripts/compare-cmgen.sh [MAP...]     # default: courtyard.exr and sunset.exr
# Each bake at its tool's defaults with a 256^2 face: cmgen --format=ktx --size=256 (1024
# samples, Filament's quadratic roughness-to-lod over mips down to 16^2, SH9 for diffuse);
# iblab's default preset. Times: wall clock of the whole process (start, read, bake, write,
# exit), the minimum of ROUNDS (default 3) interleaved runs; iblab's without its error
# report (--no-errors), its LUTs cached as after the first bake on a machine, its bake entry
# removed before each run so that every run bakes (as scripts/measure-bake.sh does).
# cmgen 1.9.25 reads no DWAB-compressed EXR (the bundled maps are): each map is first
# written as iblab loads it (`iblab measure --write-map`, float EXR with ZIP), and both
# tools bake that file.
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
rounds=${ROUNDS:-3}
command -v cmgen > /dev/null || { echo "compare-cmgen: cmgen is not installed (Debian: libfilament-tools, scripts/install-deps.sh)" >&2; exit 2; }
[ -x "$iblab" ] || { echo "compare-cmgen: $iblab is not built" >&2; exit 2; }
maps=("$@")
[ ${#maps[@]} -gt 0 ] || maps=(assets/environments/courtyard.exr assets/environments/sunset.exr)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
wall_ms() {
  local start end
  start=$(date +%s%N)
  "$@" > /dev/null 2>&1 || { echo "compare-cmgen: failed: $*" >&2; "$@" > /dev/null; exit 1; }
  end=$(date +%s%N)
  echo $(((end - start) / 1000000))
}
minimum() { tr ' ' '\n' | sort -n | head -1; }
rows=()
for map in "${maps[@]}"; do
  name=$(basename "${map%.*}")
  input="$work/$name.exr"
  "$iblab" measure --env "$map" --write-map "$input"
  "$iblab" bake --env "$input" --cache-dir "$work/cache" --no-errors > /dev/null # the LUTs, once
  theirs=() ours=()
  for _ in $(seq "$rounds"); do
    rm -rf "$work/cmgen-$name"
    theirs+=("$(cd "$work" && wall_ms cmgen --quiet --format=ktx --size=256 --deploy="cmgen-$name" "$name.exr")")
    rm -rf "$work/cache/bake"
    ours+=("$(wall_ms "$iblab" bake --env "$input" --cache-dir "$work/cache" --no-errors)")
  done
  "$iblab" measure --env "$input" --bake "$work/cmgen-$name/cmgen-${name}_ibl.ktx" --json --cache-dir "$work/cache" > "$work/$name-cmgen.json"
  rm -rf "$work/cache/bake"
  "$iblab" bake --env "$input" --json --cache-dir "$work/cache" > "$work/$name-iblab.json"
  rows+=("$name $(echo "${theirs[@]}" | minimum) $(echo "${ours[@]}" | minimum) $work/$name-cmgen.json $work/$name-iblab.json")
done
python3 - "${rows[@]}" <<'PY'
import json, sys
print("| map | bake | time (ms) | prefilter as shaded, RMS | worst mip | diffuse as shaded: SH mean / max | irradiance cube mean / max |")
print("|---|---|---|---|---|---|---|")
for row in sys.argv[1:]:
    name, cmgen_ms, iblab_ms, cmgen_json, iblab_json = row.split()
    for tool, ms, path in (("cmgen", cmgen_ms, cmgen_json), ("iblab", iblab_ms, iblab_json)):
        report = json.load(open(path))
        e = report["errors"]
        worst = max(e["prefilter"], key=lambda m: m["relative_rmse"])
        sh = e["irradiance_shaded"]["sh"]
        cube = next((v for k, v in e["irradiance_shaded"].items() if k.startswith("cube_")), None)
        layout = report.get("imported", {}).get("prefiltered") or report["textures"]["prefiltered"]
        levels = layout["levels"]
        bake = f"{tool} ({layout['size']}^2, {levels} mips)"
        cube_text = f"{cube['mean_relative']:.4f} / {cube['max_relative']:.4f}" if cube else "none (SH only)"
        print(f"| {name} | {bake} | {ms} | {e['prefilter_shaded_rms']:.4f} | {worst['relative_rmse']:.4f} (mip {worst['mip']}, r {worst['roughness']:.2f}) "
              f"| {sh['mean_relative']:.4f} / {sh['max_relative']:.4f} | {cube_text} |")
PY
