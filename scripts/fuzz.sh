#!/usr/bin/env bash
# Fuzzes the environment loader and the glTF loader with libFuzzer (clang-14, ASan, UBSan),
# SECONDS each (default 60), starting from the bundled files. New crashes land in
# build-fuzz/crashes/; add each, once fixed, to the test corpus.
#   scripts/fuzz.sh          # CI-sized: 60 s per target
#   scripts/fuzz.sh 3600     # a long run
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
if ! command -v clang++ >/dev/null || ! dpkg-query -W libclang-rt-14-dev >/dev/null 2>&1; then
  echo "fuzz.sh: needs clang and libFuzzer: apt-get install clang-14 libclang-rt-14-dev" >&2
  exit 2
fi
build_dir=${IBLAB_BUILD_DIR:-build-fuzz}
cmake -S . -B "$build_dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIBLAB_FUZZ=ON -DIBLAB_BUILD_TESTS=OFF
cmake --build "$build_dir" -j"$(nproc)" --target environment_fuzz gltf_fuzz
mkdir -p "$build_dir/corpus/environment" "$build_dir/corpus/gltf" "$build_dir/crashes"
# Seeds: the bundled maps (prefixed with the extension byte the target reads) and models.
i=0
for f in assets/environments/*.exr; do { printf '\x00'; cat "$f"; } > "$build_dir/corpus/environment/seed$i"; i=$((i + 1)); done
cp assets/models/*.glb "$build_dir/corpus/gltf/"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="halt_on_error=1"
for target in environment gltf; do
  "$build_dir/tests/fuzz/${target}_fuzz" "$build_dir/corpus/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$build_dir/crashes/${target}-" -print_final_stats=1
done
