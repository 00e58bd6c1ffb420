#!/usr/bin/env bash
# Builds iblab with AddressSanitizer + UndefinedBehaviorSanitizer and runs the whole test
# suite under them (CPU, headless GL and CLI tests). Any report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${IBLAB_BUILD_DIR:-build-asan}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIBLAB_SANITIZE=ON
cmake --build "$build_dir" -j"$(nproc)"
# Mesa's llvmpipe and LLVM keep process-lifetime allocations (JIT caches, the driver's
# screen) that LeakSanitizer reports at exit: suppressed by library, never our code.
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" --timeout 900
