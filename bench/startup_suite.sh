#!/usr/bin/env bash
# Start-up to the first frame of `pmrender render` with the program cache cold and warm
# (docs/benchmarks.md, "Start-up"): the built-in Cornell box at 16x16 with 1000 photons, run
# --repeat times per case; prints per case the medians of pmrender's own report (`render -v`:
# "to the first frame", the program step, the device's other steps) and of the process's wall
# time measured from outside. Cases:
#   cold         program cache empty, and (PoCL) its kernel cache empty too: a new machine
#   program-cold program cache empty, the driver's own cache warm: the first run of a new build
#   warm         program cache holding this build's entry: every later run
#   driver-cold  program cache warm, the driver's cache empty: a new node sharing the program cache
#   off          PMRENDER_PROGRAM_CACHE=off, the driver's own cache warm
# The driver's cache is PoCL's (POCL_CACHE_DIR); NVIDIA's compute cache is left as it is.
#
#   bench/startup_suite.sh --backend opencl --repeat 5
#   bench/startup_suite.sh --backend cuda --repeat 5        # no program cache: one case
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
pmrender="" backend=opencl device=0 repeat=5 cases="cold program-cold warm driver-cold off"
while [ $# -gt 0 ]; do
  case $1 in
    --pmrender) pmrender=$2; shift 2 ;;
    --backend) backend=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --cases) cases=$2; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "startup_suite.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
case $repeat in ''|*[!0-9]*|0) echo "startup_suite.sh: --repeat: expected a positive whole number, got '$repeat'" >&2; exit 2 ;; esac
suite_name=startup_suite.sh suite_dir=$here
# shellcheck source=bench/suite_common.sh
source "$here/suite_common.sh"
suite_find_pmrender "$pmrender"
[ "$backend" = cuda ] && cases=warm

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="$work/pocl-warm"

now() { date +%s.%N; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

# One run; prints "to_first_frame_ms program_ms device_other_ms wall_ms".
run_once() {
  local t0 t1 report
  t0=$(now)
  report=$("$pmrender" render --backend "$backend" --device "$device" --resolution 16x16 --photons 1000 -v \
           -o "$work/frame.exr")
  t1=$(now)
  # The table's rows: the step's name in columns 3-36, its milliseconds in 38-47.
  awk -v wall="$(awk "BEGIN { print ($t1 - $t0) * 1000 }")" '
    { name = substr($0, 3, 34); sub(/ +$/, "", name); ms = substr($0, 38, 10) + 0 }
    name == "to the first frame" { first = ms }
    name ~ /^(opencl|cuda) [0-9]+: / { if (name ~ /: program$/) program += ms; else other += ms }
    END { printf "%s %s %s %s\n", first, program + 0, other + 0, wall }' <<<"$report"
}

"$pmrender" --version
echo "backend $backend, device $device, $repeat runs per case, $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
PMRENDER_CACHE_DIR="$work/warm" run_once >/dev/null  # fills both caches for the warm cases
printf '%-13s %18s %12s %18s %14s\n' case to_first_frame_ms program_ms other_device_ms process_wall_ms
for case in $cases; do
  rows=()
  for i in $(seq "$repeat"); do
    case $case in
      cold) rows+=("$(POCL_CACHE_DIR="$work/pocl-$i" PMRENDER_CACHE_DIR="$work/cold-$i" run_once)") ;;
      program-cold) rows+=("$(PMRENDER_CACHE_DIR="$work/program-cold-$i" run_once)") ;;
      warm) rows+=("$(PMRENDER_CACHE_DIR="$work/warm" run_once)") ;;
      driver-cold) rows+=("$(POCL_CACHE_DIR="$work/pocl-driver-cold-$i" PMRENDER_CACHE_DIR="$work/warm" run_once)") ;;
      off) rows+=("$(PMRENDER_PROGRAM_CACHE=off run_once)") ;;
      *) echo "startup_suite.sh: unknown case $case" >&2; exit 2 ;;
    esac
  done
  column() { printf '%s\n' "${rows[@]}" | awk -v c="$1" '{ print $c }' | median; }
  printf '%-13s %18.1f %12.1f %18.1f %14.1f\n' "$case" "$(column 1)" "$(column 2)" "$(column 3)" "$(column 4)"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
