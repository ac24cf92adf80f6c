#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of the unit and OpenCL tests, in the clang build
# the fuzzers use (tests/fuzz/configure.sh: build-fuzz/, no CUDA), with leak checking. PoCL and its
# LLVM are not instrumented; what they allocate is left out of the leak check (.ci/lsan.supp: once,
# under load, their compiler state was reported at exit).
# Not run under ASan: MemoryLimits.* (ulimit -v cannot hold ASan's shadow memory) and
# SequenceMemory.* (its flat-memory bound cannot hold ASan's quarantine of freed memory).
# ASan does not track dynamically loaded libraries' thread-local blocks (intercept_tls_get_addr=0):
# after PoCL's compiler has run, one of the main thread's such blocks is left recorded at a bogus
# address, and LeakSanitizer's tracer crashed on it at exit (signal 11 at 0x1018, after every test
# had passed), depending on which tests the process ran.
#   .ci/sanitizers.sh [gtest filter, e.g. 'Cli*']
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$("$root/tests/fuzz/configure.sh")
cmake --build "$build" --target pmrender pm_unit_tests pm_opencl_tests
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$root/.ci/lsan.supp
filter=${1:-*}
"$build/tests/pm_unit_tests" --gtest_brief=1 --gtest_filter="$filter"
"$build/tests/pm_opencl_tests" --gtest_brief=1 --gtest_filter="$filter:-MemoryLimits.*:SequenceMemory.*"
