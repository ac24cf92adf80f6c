#!/usr/bin/env bash
# Configures the one clang build that the fuzzers (tests/fuzz/run.sh) and the sanitizer test run
# (.ci/sanitizers.sh) share, and prints its folder: everything built with AddressSanitizer and
# UndefinedBehaviorSanitizer (any report fails), the parsers (pm_core) also with libFuzzer's
# coverage, no CUDA. Environment: PM_FUZZ_BUILD (default build-fuzz/ in the repository).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${PM_FUZZ_BUILD:-$root/build-fuzz}
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPMRENDER_CUDA=OFF \
      -DPMRENDER_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
echo "$build"
