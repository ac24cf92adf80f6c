#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan, tests/fuzz/configure.sh) and runs
# each for a bounded time, starting from the committed corpus. New inputs go to a scratch folder;
# a crash leaves its input as <build>/fuzz-<target>-crash-* and fails this script.
#   tests/fuzz/run.sh [SECONDS_PER_TARGET=30] [extra libFuzzer options...]
# Environment: PM_FUZZ_BUILD (default build-fuzz/ in the repository; configure.sh sets it up),
# PM_FUZZ_TARGETS (default: all six).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${1:-30}
shift || true
build=$("$root/tests/fuzz/configure.sh")
targets=${PM_FUZZ_TARGETS:-scene frame_spec gltf exr checkpoint texture}
cmake --build "$build" --target $(printf 'pm_fuzz_%s ' $targets)
# The scene fuzzer writes its inputs to files: on tmpfs it runs about 10x faster.
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
status=0
for target in $targets; do
  work=$(mktemp -d)
  dict=()
  [ -f "$root/tests/fuzz/$target.dict" ] && dict=(-dict="$root/tests/fuzz/$target.dict")
  echo "fuzzing $target for ${seconds} s"
  if ! "$build/tests/pm_fuzz_$target" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
       -print_final_stats=1 "${dict[@]}" -artifact_prefix="$build/fuzz-$target-" "$@" "$work" \
       "$root/tests/fuzz/corpus/$target"; then
    echo "fuzzer $target failed: see $build/fuzz-$target-*" >&2
    status=1
  fi
  rm -rf "$work"
done
exit $status
