#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of the unit and OpenCL tests: clang build in
# build-asan/ (no CUDA), then both test binaries with leak checking (PoCL and its LLVM are not
# instrumented; no leak report comes from them, so no suppressions are needed).
# Not run under ASan: MemoryLimits.* (ulimit -v cannot hold ASan's shadow memory) and
# SequenceMemory.* (its flat-memory bound cannot hold ASan's quarantine of freed memory).
#   .ci/sanitizers.sh [extra gtest filter, e.g. 'Cli*']
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${PM_ASAN_BUILD:-$root/build-asan}
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPMRENDER_CUDA=OFF \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$build" --target pmrender pm_unit_tests pm_opencl_tests
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
filter=${1:-*}
"$build/tests/pm_unit_tests" --gtest_brief=1 --gtest_filter="$filter"
"$build/tests/pm_opencl_tests" --gtest_brief=1 --gtest_filter="$filter:-MemoryLimits.*:SequenceMemory.*"
