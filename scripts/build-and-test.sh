#!/usr/bin/env bash
# Builds iblab and runs every test suite (CPU and headless GL). The README's second command.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${IBLAB_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=${IBLAB_BUILD_TYPE:-RelWithDebInfo}
cmake --build "$build_dir" -j"$(nproc)"
# GL suites are RUN_SERIAL (llvmpipe already uses every core); CPU suites run in parallel.
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" --timeout 300
