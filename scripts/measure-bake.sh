#!/usr/bin/env bash
# The bake numbers of docs/performance.md, docs/bake.md and the README's headline numbers.
#   scripts/measure-bake.sh [ENV...]        # tutorial against default preset, one table (default: every bundled map;
#                                           # DEFAULT_ARGS=... are added to the default's bakes):
#       the default's LUTs cached, as they are after the first bake on a machine, 3 interleaved
#       runs each so both see the same machine load, the minimum reported, and the errors of
#       each against the exact references (deterministic: one run)
#   scripts/measure-bake.sh batch           # 4 maps in one process against one map per process (ROUNDS=N, default 5)
#   scripts/measure-bake.sh cmgen           # iblab against Filament's cmgen, process to process, 7 interleaved
#                                           # rounds (ROUNDS=N); IBLAB_BASELINE=an older build's iblab: interleaved too, --no-errors
#   scripts/measure-bake.sh writes          # the cache's EXR writes against the bake, per compression
#   scripts/measure-bake.sh hugepages       # the bake with and without malloc's huge pages (app/main.cpp)
#   scripts/measure-bake.sh unseen [DIR...] # the default prefilter's per-mip errors on maps that chose none of its
#                                           # settings (CC0 maps in ../shared/assets, builtin suns 1e2 .. 1e6 and at the
#                                           # poles of 256- and 512-wide maps, builtin slits) and every map in each DIR (scripts/probe-maps.py DIR,
#                                           # scripts/heldout-maps.py DIR make them)
#   scripts/measure-bake.sh instructions [ENV] # the instructions one bake executes (valgrind's callgrind, llvmpipe on
#                                           # the calling thread: LP_NUM_THREADS=0), the whole process; IBLAB_BASELINE=an older
#                                           # build: both, and their ratio; BAKE_ARGS="..." bakes with those options (--preset
#                                           # tutorial). The same count on any load, where wall-clock
#                                           # ratios on a shared 2-core VM move by tenths between runs
#   scripts/measure-bake.sh phases [ENV]    # each phase of the bake (timings_ms) and part of one (part_timings_ms), minimum and median of ROUNDS
#                                           # (default 8) processes; IBLAB_BASELINE=an older build: interleaved;
#                                           # BASELINE_ARGS="..." bakes the baseline (or this build) with those options
# Every time is the minimum of 3 interleaved runs (cmgen: of ROUNDS, default 7, since the
# processes differ by less than a shared machine's noise in 3); process times are wall clock around the
# whole process (start, context, load, bake, errors, cache writes, exit).
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
mode=tutorial
case "${1:-}" in batch | cmgen | writes | hugepages | phases | unseen | instructions) mode=$1; shift ;; esac
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
# Wall time of one process in ms (stdout and stderr discarded; a failure stops the script).
wall_ms() {
  local start end
  start=$(date +%s%N)
  "$@" > /dev/null 2>&1 || { echo "measure-bake: failed: $*" >&2; "$@" > /dev/null; exit 1; }
  end=$(date +%s%N)
  echo $(((end - start) / 1000000))
}
minimum() { tr ' ' '\n' | sort -n | head -1; }
# CPU time (user + system, ms) of one process and its threads; its output is discarded.
cpu_ms() {
  python3 - "$@" <<'PY'
import resource, subprocess, sys
subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(round((r.ru_utime + r.ru_stime) * 1000))
PY
}
# A bake's --json report, read only once the bake has exited: python's start-up in a pipeline
# beside the bake takes a core the bake's GL threads use (on a 2-core machine with a pyenv shim
# for python3 it added about 100 ms to a 150 ms bake, and its scatter).
bake_report() {
  local report
  report=$(mktemp -p "$cache")
  "$@" > "$report"
  cat "$report"
  rm -f "$report"
}
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
measure_tutorial() {
  [ $# -gt 0 ] || set -- assets/environments/*.exr
  local rows=()
  for env in "$@"; do
    [ -f "$env" ] || { echo "measure-bake: $env: no such file" >&2; exit 2; }
    "$iblab" bake --env "$env" --cache-dir "$cache" --no-errors --json > /dev/null # the LUTs, once
    tutorial=() default=()
    for _ in 1 2 3; do
      tutorial+=("$(bake_report "$iblab" bake --env "$env" --preset tutorial --no-cache --no-errors --json | total)")
      rm -rf "$cache/bake"
      # shellcheck disable=SC2086
      default+=("$(bake_report "$iblab" bake --env "$env" --cache-dir "$cache" --no-errors --json ${DEFAULT_ARGS:-} | total)")
    done
    local t d
    t=$(minimum <<< "${tutorial[*]}")
    d=$(minimum <<< "${default[*]}")
    rows+=("$(basename "$env") tutorial $t $("$iblab" bake --env "$env" --preset tutorial --no-cache --json | errors_row)")
    # shellcheck disable=SC2086
    rows+=("$(basename "$env") default $d $("$iblab" bake --env "$env" --no-cache --json ${DEFAULT_ARGS:-} | errors_row)")
  done
  echo "| map | preset | bake, ms (min of 3) | per mip (roughness > 0) | worst mip | as shaded, roughness 0, 0.1 .. 1: RMS / max |"
  echo "|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}" | python3 -c '
import sys
rows = [line.split(" ", 3) for line in sys.stdin.read().splitlines()]
tutorial = {r[0]: float(r[2]) for r in rows if r[1] == "tutorial"}
for name, preset, ms, rest in rows:
    ratio = "" if preset == "tutorial" else " (%.1fx faster)" % (tutorial[name] / float(ms))
    print("| %s | %s | %.0f%s | %s |" % (name, preset, float(ms), ratio, rest))'
}

# One table row's error cells from a bake report: per-mip relative RMSE of the mips with
# roughness > 0, the worst of them, and the as-shaded RMS and max over roughness 0, 0.1 .. 1.
errors_row() {
  python3 -c '
import json, sys
e = json.load(sys.stdin)["errors"]
mips = [m["relative_rmse"] for m in e["prefilter"] if m["roughness"] > 0]
shaded = [m["relative_rmse"] for m in e["prefilter_shaded"]]
print("%s | %.3f | %.3f / %.3f" % (" ".join("%.3f" % x for x in mips), max(mips), e["prefilter_shaded_rms"], max(shaded)))'
}

# 4 maps in one process (one context, its programs, the LUTs) against one map per process:
# default preset, LUTs cached, no bake cached, --no-errors (the errors against the exact
# references are computed per map on the CPU, the same work batched or not).
measure_batch() {
  local maps=(assets/environments/courtyard.exr assets/environments/sunset.exr assets/environments/forest.exr
    assets/environments/city.exr)
  "$iblab" bake --env "${maps[0]}" --cache-dir "$cache" --no-errors > /dev/null # the LUTs, once
  local one=() four=() separate=() one_cpu=() four_cpu=() rounds=${ROUNDS:-5}
  for _ in $(seq "$rounds"); do
    rm -rf "$cache/bake"
    one+=("$(wall_ms "$iblab" bake --env "${maps[0]}" --cache-dir "$cache" --no-errors --json)")
    rm -rf "$cache/bake"
    four+=("$(wall_ms "$iblab" bake "${maps[@]/#/--env=}" --cache-dir "$cache" --no-errors --json)")
    rm -rf "$cache/bake"
    local sum=0
    for map in "${maps[@]}"; do sum=$((sum + $(wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors --json))); done
    separate+=("$sum")
    rm -rf "$cache/bake"
    one_cpu+=("$(cpu_ms "$iblab" bake --env "${maps[0]}" --cache-dir "$cache" --no-errors --json)")
    rm -rf "$cache/bake"
    four_cpu+=("$(cpu_ms "$iblab" bake "${maps[@]/#/--env=}" --cache-dir "$cache" --no-errors --json)")
  done
  python3 - "${one[*]}" "${four[*]}" "${separate[*]}" "${one_cpu[*]}" "${four_cpu[*]}" <<'PY'
import statistics, sys
one, four, separate, one_cpu, four_cpu = ([float(x) for x in a.split()] for a in sys.argv[1:])
m = statistics.median
print(f"{len(one)} rounds, minimum (median): one map (courtyard.exr) {min(one):.0f} ms ({m(one):.0f}); 4 maps in one process "
      f"{min(four):.0f} ms ({m(four):.0f}) = {min(four) / min(one):.2f}x ({m(four) / m(one):.2f}x) one map, "
      f"{4 * min(four) / min(separate):.2f}x ({4 * m(four) / m(separate):.2f}x) the mean of the four maps alone; "
      f"the same 4 maps in 4 processes {min(separate):.0f} ms ({m(separate):.0f})")
print(f"  CPU time (user + system, median): one map {m(one_cpu):.0f} ms, 4 maps in one process {m(four_cpu):.0f} ms: "
      f"{(m(four_cpu) - m(one_cpu)) / 3:.0f} ms per map after the first")
PY
}

# iblab against Filament's cmgen on courtyard at 1024x512 as .hdr (oiiotool converts it; without
# it both read the .exr): cmgen --size=128 --ibl-samples=64 --ibl-ld (a fast cmgen: its defaults
# are a 256 face and 1024 samples, which scripts/compare-cmgen.sh times), iblab bake at its
# default preset (prefilter 256, more samples, the moment irradiance cube, SH9), LUTs cached,
# with and without the errors against the exact references. The one-run line's "programs compiled meanwhile": while the map decoded, so
# outside the bake's own total (0 for builds before that overlap).
measure_cmgen() {
  local map=assets/environments/courtyard.exr
  if command -v oiiotool > /dev/null; then
    oiiotool "$map" --resize 1024x512 -o "$cache/courtyard.hdr"
    map=$cache/courtyard.hdr
  else
    # Debian's cmgen (Filament 1.9.25) cannot decode the bundled maps' EXR compression
    # ("Unknown compression type"), so it needs the .hdr copy.
    echo "measure-bake: cmgen needs oiiotool to convert $map (Debian: apt install openimageio-tools)" >&2
    exit 2
  fi
  "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors > /dev/null # the LUTs, once
  local have_cmgen=1
  command -v cmgen > /dev/null || { have_cmgen=0; echo "measure-bake: cmgen is not installed (Debian: libfilament-tools): iblab alone"; }
  local baseline=${IBLAB_BASELINE:-}
  # Its own cache directory: an older build may key and lay out its entries differently.
  [ -n "$baseline" ] && "$baseline" bake --env "$map" --cache-dir "$cache/baseline" --no-errors > /dev/null
  # With the errors, two cases: the map's exact references computed (its first bake on a
  # machine), and read from the cache's reference/ directory (every later bake of the map,
  # whatever the settings: they depend only on its pixels and on what is measured).
  local ours=() ours_cold=() ours_no_errors=() theirs=() older=() rounds=${ROUNDS:-7}
  for _ in $(seq "$rounds"); do
    if [ $have_cmgen = 1 ]; then
      rm -rf "$cache/cmgen"
      theirs+=("$(wall_ms cmgen --size=128 --ibl-samples=64 --ibl-ld="$cache/cmgen" "$map")")
    fi
    rm -rf "$cache/bake" "$cache/reference"
    ours_cold+=("$(wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --json)")
    rm -rf "$cache/bake"
    ours+=("$(wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --json)")
    rm -rf "$cache/bake"
    ours_no_errors+=("$(wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors --json)")
    if [ -n "$baseline" ]; then
      rm -rf "$cache/baseline/bake"
      older+=("$(wall_ms "$baseline" bake --env "$map" --cache-dir "$cache/baseline" --no-errors --json)")
    fi
  done
  python3 - "${ours[*]}" "${ours_no_errors[*]}" "${theirs[*]:-}" "${older[*]:-}" "$baseline" "${ours_cold[*]}" <<'PY'
import statistics, sys
def times(arg): return [float(x) for x in arg.split()]
with_errors, without, cmgen, older, baseline, cold = times(sys.argv[1]), times(sys.argv[2]), times(sys.argv[3]), times(sys.argv[4]), sys.argv[5], times(sys.argv[6])
def ms(t): return f"{min(t):.0f} ms (median {statistics.median(t):.0f})"
line = (f"courtyard 1024x512, minimum of {len(without)} rounds: iblab bake {ms(with_errors)} with the errors against the exact references "
        f"(cached), {ms(cold)} with them computed (the map's first bake), {ms(without)} with --no-errors")
if cmgen:
    line += f"; cmgen {ms(cmgen)}: iblab takes " + ", ".join(
        f"{min(t) / min(cmgen):.2f}x (median {statistics.median(t) / statistics.median(cmgen):.2f}x) cmgen's time {what}"
        for t, what in ((with_errors, "with errors (cached)"), (cold, "with them computed"), (without, "without")))
print(line)
if older:
    line = f"  baseline {baseline}: {ms(older)} with --no-errors"
    if cmgen:
        line += f", {min(older) / min(cmgen):.2f}x cmgen's time"
    print(line)
PY
  if [ -n "$baseline" ]; then
    # The map's decode (other_ms.environment_load, on its thread while the context is made),
    # both builds, 8 interleaved runs, no cache.
    local load=() older_load=()
    for _ in 1 2 3 4 5 6 7 8; do
      load+=("$(bake_report "$iblab" bake --env "$map" --no-cache --no-errors --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["other_ms"]["environment_load"])')")
      older_load+=("$(bake_report "$baseline" bake --env "$map" --no-cache --no-errors --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["other_ms"]["environment_load"])')")
    done
    python3 - "${load[*]}" "${older_load[*]}" <<'PY'
import statistics, sys
ours, older = ([float(x) for x in a.split()] for a in sys.argv[1:])
print(f"  decode of the map (environment_load), minimum / median of {len(ours)}: {min(ours):.0f} / {statistics.median(ours):.0f} ms, "
      f"baseline {min(older):.0f} / {statistics.median(older):.0f} ms")
PY
  fi
  rm -rf "$cache/bake"
  bake_report "$iblab" bake --env "$map" --cache-dir "$cache" --json | python3 -c '
import json, sys
j = json.load(sys.stdin)
t, o = j["timings_ms"], j["other_ms"]
print("  iblab, one run: bake %.0f ms (of which shaders %.0f), environment load %.0f, context %.0f, programs compiled meanwhile %.0f, "
      "cache write wait %.0f, process until the report %.0f" % (t["total"], t["shaders"], o["environment_load"], o["context"],
      o.get("programs_while_loading", 0), o["cache_write_wait"], o["process"]))'
  echo "  iblab errors against the exact references:"
  "$iblab" bake --env "$map" --no-cache --json | errors
}

# The cache's EXR writes against the bake, per OpenEXR compression: the bake's own time, the
# writes' time on their thread, how long the process then waited for them (after the errors
# and the report, which the writes overlap; --no-errors here, so the wait is the longest it
# can be), and the size of the entry. Default preset, courtyard.exr, LUTs cached.
measure_writes() {
  local map=assets/environments/courtyard.exr
  "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors > /dev/null # the LUTs, once
  echo "| compression | bake, ms | cache write (its thread), ms | process waited for it, ms | entry size, KiB |"
  echo "|---|---|---|---|---|"
  for compression in zip none rle zips piz pxr24 b44 dwaa; do
    local rows=()
    for _ in 1 2 3; do
      rm -rf "$cache/bake"
      rows+=("$(IBLAB_CACHE_EXR_COMPRESSION=$compression "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors --json |
        python3 -c 'import json,sys; j=json.load(sys.stdin); o=j["other_ms"]; print("%.0f,%.0f,%.0f" % (j["timings_ms"]["total"], o["cache_write"], o["cache_write_wait"]))')")
    done
    local size
    size=$(du -sk "$cache/bake" | cut -f1)
    python3 - "$compression" "$size" "${rows[@]}" <<'PY'
import sys
name, size, rows = sys.argv[1], sys.argv[2], [list(map(float, r.split(","))) for r in sys.argv[3:]]
print("| %s | %s |  %s |" % (name, " | ".join("%.0f" % min(r[i] for r in rows) for i in range(3)), size))
PY
  done
}

# iblab bake restarts itself with glibc.malloc.hugetlb=1 (app/main.cpp); a GLIBC_TUNABLES that
# names the tunable is kept, so =0 runs the same build without. Process wall times, default
# preset, courtyard.exr, LUTs cached, no bake cached, with the errors (references cached) and
# without, 8 interleaved runs each: minimum and median.
measure_hugepages() {
  local map=assets/environments/courtyard.exr
  "$iblab" bake --env "$map" --cache-dir "$cache" > /dev/null # the LUTs and the references, once
  local on=() off=() on_errors=() off_errors=()
  for _ in 1 2 3 4 5 6 7 8; do
    rm -rf "$cache/bake"
    on+=("$(wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors --json)")
    rm -rf "$cache/bake"
    off+=("$(GLIBC_TUNABLES=glibc.malloc.hugetlb=0 wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --no-errors --json)")
    rm -rf "$cache/bake"
    on_errors+=("$(wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --json)")
    rm -rf "$cache/bake"
    off_errors+=("$(GLIBC_TUNABLES=glibc.malloc.hugetlb=0 wall_ms "$iblab" bake --env "$map" --cache-dir "$cache" --json)")
  done
  # A batch restarts the same way.
  local maps=(assets/environments/courtyard.exr assets/environments/sunset.exr assets/environments/forest.exr
    assets/environments/city.exr)
  local batch_on=() batch_off=()
  for _ in 1 2 3 4 5 6 7 8; do
    rm -rf "$cache/bake"
    batch_on+=("$(wall_ms "$iblab" bake "${maps[@]/#/--env=}" --cache-dir "$cache" --no-errors --json)")
    rm -rf "$cache/bake"
    batch_off+=("$(GLIBC_TUNABLES=glibc.malloc.hugetlb=0 wall_ms "$iblab" bake "${maps[@]/#/--env=}" --cache-dir "$cache" --no-errors --json)")
  done
  echo "transparent huge pages: $(cat /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || echo unknown)"
  python3 - "${on[*]}" "${off[*]}" "${on_errors[*]}" "${off_errors[*]}" "${batch_on[*]}" "${batch_off[*]}" <<'PY'
import statistics, sys
on, off, on_e, off_e, batch_on, batch_off = ([float(x) for x in a.split()] for a in sys.argv[1:])
for name, a, b in (("--no-errors", on, off), ("with errors", on_e, off_e), ("4-map batch", batch_on, batch_off)):
    print(f"{name}: huge pages min {min(a):.0f} / median {statistics.median(a):.0f} ms, without {min(b):.0f} / {statistics.median(b):.0f} ms: "
          f"{min(a) / min(b):.2f}x / {statistics.median(a) / statistics.median(b):.2f}x")
PY
}

# Each phase of one map's bake as the report's timings_ms gives it (steady clock from a step's
# submission to its fence), default preset, LUTs cached, no bake cached, --no-errors; ROUNDS
# processes (default 8), minimum and median per phase: the phases are tens of milliseconds, in
# which a shared machine's noise is large, so a change is compared on the minimum, with the
# older build interleaved run for run.
measure_phases() {
  local map=${1:-assets/environments/courtyard.exr}
  local baseline=${IBLAB_BASELINE:-} rounds=${ROUNDS:-8}
  # BASELINE_ARGS: options the baseline bakes with (the same build with another setting when
  # IBLAB_BASELINE is unset: BASELINE_ARGS="--prefilter-bright-texels 0" times the sampled-only
  # prefilter against the default in one run).
  local baseline_args=${BASELINE_ARGS:-}
  [ -z "$baseline" ] && [ -n "$baseline_args" ] && baseline=$iblab
  local builds=("$iblab") options=("")
  [ -n "$baseline" ] && builds+=("$baseline") && options+=("$baseline_args")
  local reports=() names=()
  for i in "${!builds[@]}"; do
    names+=("${builds[$i]}${options[$i]:+ ${options[$i]}}")
    # shellcheck disable=SC2086
    "${builds[$i]}" bake --env "$map" --cache-dir "$cache/$(echo "${names[$i]}" | md5sum | cut -c1-8)" --no-errors ${options[$i]} > /dev/null # the LUTs, once
    reports+=("$(mktemp -p "$cache")")
  done
  for _ in $(seq "$rounds"); do
    for i in "${!builds[@]}"; do
      local dir="$cache/$(echo "${names[$i]}" | md5sum | cut -c1-8)"
      rm -rf "$dir/bake"
      # shellcheck disable=SC2086
      bake_report "${builds[$i]}" bake --env "$map" --cache-dir "$dir" --no-errors --json ${options[$i]} | python3 -c 'import json,sys; j=json.load(sys.stdin); t=j["timings_ms"]; t.update(j.get("part_timings_ms", {})); print(json.dumps(t))' >> "${reports[$i]}"
    done
  done
  python3 - "$map" "$rounds" "${names[@]}" -- "${reports[@]}" <<'PY'
import json, statistics, sys
args = sys.argv[1:]
map_name, rounds = args[0], args[1]
split = args.index("--")
builds, reports = args[2:split], args[split + 1:]
runs = [[json.loads(line) for line in open(r)] for r in reports]
print(f"{map_name}, {rounds} processes per build, ms per phase, minimum (median):")
# Phases, then their parts (prefilter.split, prefilter.mip1, ...), in the order they ran, from
# every build: a baseline may have parts the other lacks.
phases = []
for r in runs:
    phases += [k for k in r[0] if k != "total" and k not in phases]
phases = [k for k in phases if "." not in k] + [k for k in phases if "." in k] + ["total"]
print("| phase | " + " | ".join(builds) + (" | ratio of minima |" if len(builds) > 1 else " |"))
print("|---" * (len(builds) + 1 + (len(builds) > 1)) + "|")
for phase in phases:
    cells = []
    for r in runs:
        values = [run[phase] for run in r if phase in run]
        cells.append(f"{min(values):.1f} ({statistics.median(values):.1f})" if values else "-")
    row = f"| {phase} | " + " | ".join(cells)
    if len(builds) > 1:
        a = min((run[phase] for run in runs[0] if phase in run), default=0.0)
        b = min((run[phase] for run in runs[1] if phase in run), default=0.0)
        row += f" | {a / b:.2f}x" if b >= 1.0 and a > 0.0 else " | -"
    print(row + " |")
PY
}

# The default prefilter's per-mip errors on maps that chose none of its settings: the CC0 maps
# in ../shared/assets/hdri/pmndrs (512x256, where present) and builtin suns of 0.5 degrees at
# 1e2 .. 1e6 over a sky of 1 and of 0.05, at 1024x512, each at three places (on a cube edge,
# off every axis, near a corner). One line per map: per-mip relative RMSE (roughness > 0),
# the worst, and the as-shaded RMS / max; EXTRA_ARGS are added to every bake (e.g.
# "--prefilter-bright-texels 0" for the estimator without the split).
measure_unseen() {
  local maps=()
  for f in ../shared/assets/hdri/pmndrs/*.exr; do [ -f "$f" ] && maps+=("$f"); done
  maps+=("builtin:slits" "builtin:slits?width=1024")
  local dir
  for dir in "$@"; do
    [ -d "$dir" ] || { echo "measure-bake: unseen: $dir is not a directory" >&2; exit 1; }
    for f in "$dir"/*.pfm "$dir"/*.hdr "$dir"/*.exr; do [ -f "$f" ] && maps+=("$f"); done
  done
  for sky in 1 0.05; do
    for intensity in 1e2 1e3 1e4 1e5 1e6; do
      for place in "elevation=45&azimuth=0" "elevation=23&azimuth=37" "elevation=35&azimuth=44"; do
        maps+=("builtin:sun?width=1024&size=0.5&intensity=$intensity&sky=$sky&$place")
      done
    done
  done
  # Suns at the poles of maps coarse enough to be upsampled, whose first rows the upsample
  # must not brighten (fluxConservingRowBlends).
  for width in 256 512; do
    for place in "elevation=90" "elevation=-90" "elevation=88&azimuth=10"; do
      maps+=("builtin:sun?width=$width&size=0.5&intensity=1e5&$place")
    done
  done
  for map in "${maps[@]}"; do
    # shellcheck disable=SC2086
    line=$("$iblab" bake --env "$map" --no-cache --json ${EXTRA_ARGS:-} | errors_row)
    echo "| $map | $line |"
  done | tee "$cache/unseen.txt"
  python3 - "$cache/unseen.txt" <<'PY'
import sys
rows = [l.split("|") for l in open(sys.argv[1]) if l.startswith("|")]
worst = max(rows, key=lambda r: float(r[3]))
print(f"worst mip over {len(rows)} maps: {float(worst[3]):.3f} ({worst[1].strip()})")
PY
}

# Instructions of one bake with the LUTs cached, the whole process (start, load, context, bake,
# exit): callgrind counts what runs, not how long it waits, so it is the same on any load.
# llvmpipe's threads off (LP_NUM_THREADS=0): its shaders run on the calling thread, each once.
# GLIBC_TUNABLES set beforehand, so that the bake does not restart itself under valgrind.
measure_instructions() {
  local map=${1:-assets/environments/courtyard.exr}
  command -v valgrind > /dev/null || { echo "measure-bake: instructions needs valgrind" >&2; exit 2; }
  local builds=("$iblab") counts=()
  [ -n "${IBLAB_BASELINE:-}" ] && builds+=("$IBLAB_BASELINE")
  for i in "${!builds[@]}"; do
    local dir="$cache/instructions$i"
    # shellcheck disable=SC2086
    GLIBC_TUNABLES=glibc.malloc.hugetlb=1 "${builds[$i]}" bake --env "$map" --cache-dir "$dir" --no-errors ${BAKE_ARGS:-} > /dev/null # the LUTs, once
    rm -rf "$dir/bake"
    # shellcheck disable=SC2086
    LP_NUM_THREADS=0 GLIBC_TUNABLES=glibc.malloc.hugetlb=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null --smc-check=all \
      "${builds[$i]}" bake --env "$map" --cache-dir "$dir" --no-errors ${BAKE_ARGS:-} > /dev/null 2> "$cache/callgrind$i.txt"
    counts+=("$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$cache/callgrind$i.txt")")
    echo "${builds[$i]}: ${counts[$i]} instructions ($map)"
  done
  [ ${#counts[@]} -gt 1 ] && python3 -c "import sys; print('ratio %.3fx' % (int(sys.argv[1]) / int(sys.argv[2])))" "${counts[0]}" "${counts[1]}"
  return 0
}

case $mode in
  instructions) measure_instructions "$@" ;;
  phases) measure_phases "$@" ;;
  unseen) measure_unseen "$@" ;;
  tutorial) measure_tutorial "$@" ;;
  hugepages) measure_hugepages ;;
  batch) measure_batch ;;
  cmgen) measure_cmgen ;;
  writes) measure_writes ;;
esac
