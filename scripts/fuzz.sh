#!/usr/bin/env bash
# Fuzzes the environment loader, the glTF loader, the KTX readers (and the import of
# other tools' bakes) and bake.json's shading lights with libFuzzer (clang-14, ASan, UBSan),
# SECONDS each (default 60), starting from the committed corpus (tests/fuzz/corpus/) and the
# bundled models. It stops at the first failing input, saved in build-fuzz/crashes/: fix the
# bug, then commit the input under tests/fuzz/corpus/<target>/, where every test run
# replays it (tests/fuzz/replay_main.cpp).
#   scripts/fuzz.sh          # CI-sized: 60 s per target (.ci/run runs this)
#   scripts/fuzz.sh 3600     # a long run
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
if ! command -v clang++-14 >/dev/null || ! dpkg-query -W libclang-rt-14-dev >/dev/null 2>&1 || [ ! -x /usr/lib/llvm-14/bin/llvm-symbolizer ]; then
  echo "fuzz.sh: needs clang, libFuzzer and llvm-symbolizer: scripts/install-deps.sh (clang-14 libclang-rt-14-dev llvm-14)" >&2
  exit 2
fi
build_dir=${IBLAB_BUILD_DIR:-build-fuzz}
cmake -S . -B "$build_dir" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIBLAB_FUZZ=ON -DIBLAB_BUILD_TESTS=OFF
cmake --build "$build_dir" -j"$(nproc)" --target environment_fuzz gltf_fuzz ktx_fuzz lights_fuzz
mkdir -p "$build_dir/corpus/environment" "$build_dir/corpus/gltf" "$build_dir/corpus/ktx" "$build_dir/corpus/lights" "$build_dir/crashes"
cp tests/fuzz/corpus/environment/* "$build_dir/corpus/environment/"
cp tests/fuzz/corpus/gltf/* "$build_dir/corpus/gltf/"
cp tests/fuzz/corpus/ktx/* "$build_dir/corpus/ktx/"
cp tests/fuzz/corpus/lights/* "$build_dir/corpus/lights/"
# Seeds for the models: the bundled ones too. The bundled maps (100-500 KB) are left out:
# each run would parse half a megabyte, at a few runs a second; the committed seeds cover
# the same formats and compressions (scanline and tiled EXR, DWAB, PIZ, ZIP, RLE, B44, HDR,
# PNG) in about a kilobyte each.
cp assets/models/*.glb "$build_dir/corpus/gltf/"
# The suppressions name functions: leak stacks must be symbolized, by clang 14's own symbolizer.
export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
# A failing run can be silent: the loader sends stderr to a filter while libpng runs, so a
# report libFuzzer prints there just before exiting is lost. The exit code and the saved
# input say what happened; CI's root is deleted afterwards, so small inputs are printed.
explain() {
  case "$1" in
    70) echo "a run took longer than -timeout" ;;
    71) echo "out of memory: one allocation or the RSS went over -rss_limit_mb" ;;
    77) echo "a sanitizer or libFuzzer reported a bug" ;;
    *) echo "a crash or a trap (exit $1)" ;;
  esac
}
for target in environment gltf ktx lights; do
  status=0
  "$build_dir/tests/fuzz/${target}_fuzz" "$build_dir/corpus/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -seed=1 \
    -artifact_prefix="$build_dir/crashes/${target}-" -print_final_stats=1 || status=$?
  if [ "$status" -ne 0 ]; then
    echo "fuzz.sh: $target failed with exit $status: $(explain "$status")" >&2
    for input in "$build_dir/crashes/${target}-"*; do
      [ -f "$input" ] || continue
      echo "fuzz.sh: failing input $input ($(stat -c %s "$input") bytes)" >&2
      [ "$(stat -c %s "$input")" -le 4096 ] && { echo "fuzz.sh: base64 of it:" >&2; base64 "$input" >&2; }
    done
    exit "$status"
  fi
done
