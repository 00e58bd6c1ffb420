#!/usr/bin/env bash
# The bake numbers of the README and docs/bake.md: for each environment, the tutorial preset
# against the default one (its LUTs cached, as they are after the first bake on a machine),
# 3 interleaved runs each so both see the same machine load, the minimum reported, and the
# errors of each against the exact references (deterministic: one run).
#   scripts/measure-bake.sh [ENV...]    # default: courtyard.exr and sunset.exr
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
[ $# -gt 0 ] || set -- assets/environments/courtyard.exr assets/environments/sunset.exr
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
total() { python3 -c 'import json,sys; print(json.load(sys.stdin)["timings_ms"]["total"])'; }
errors() {
  python3 -c '
import json, sys
e = json.load(sys.stdin)["errors"]
mips = " ".join("%.3g (r %.2f)" % (m["relative_rmse"], m["roughness"]) for m in e["prefilter"])
shaded = [m["relative_rmse"] for m in e["prefilter_shaded"]]
irr = "; ".join("%s %.2g / %.2g" % (k, v["mean_relative"], v["max_relative"]) for k, v in e["irradiance"].items() if isinstance(v, dict))
shaded_irr = "; ".join("%s %.2g / %.2g" % (k, v["mean_relative"], v["max_relative"]) for k, v in e["irradiance_shaded"].items())
lut = "; ".join("%s %.2g" % (k, v) for k, v in e["lut_max_abs"].items())
print("    per mip: %s" % mips)
print("    as shaded, roughness 0, 0.1 .. 1: %s | RMS %.3g, max %.3g" % (" ".join("%.3f" % x for x in shaded), e["prefilter_shaded_rms"], max(shaded)))
print("    diffuse mean / max at texel centres: %s" % irr)
print("    diffuse mean / max as shaded: %s | LUT max abs: %s" % (shaded_irr, lut))'
}
for env in "$@"; do
  [ -f "$env" ] || { echo "measure-bake: $env: no such file" >&2; exit 2; }
  "$iblab" bake --env "$env" --cache-dir "$cache" --no-errors --json > /dev/null # the LUTs, once
  tutorial=() default=()
  for _ in 1 2 3; do
    tutorial+=("$("$iblab" bake --env "$env" --preset tutorial --no-cache --no-errors --json | total)")
    rm -rf "$cache/bake"
    default+=("$("$iblab" bake --env "$env" --cache-dir "$cache" --no-errors --json | total)")
  done
  python3 - "$env" "${tutorial[*]}" "${default[*]}" <<'PY'
import sys
env, t, d = sys.argv[1], min(map(float, sys.argv[2].split())), min(map(float, sys.argv[3].split()))
print(f"{env}: tutorial {t:.0f} ms, default (LUTs cached) {d:.0f} ms: {t / d:.1f}x")
PY
  echo "  tutorial:"; "$iblab" bake --env "$env" --preset tutorial --no-cache --json | errors
  echo "  default:"; "$iblab" bake --env "$env" --no-cache --json | errors
done
