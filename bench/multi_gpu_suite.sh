#!/usr/bin/env bash
# Several GPUs of one machine (`--devices`, docs/progressive.md "Several devices"): per backend and
# scene, the wall time of
#   frame     one 1920x1080 frame of P passes of 1M photons (by default), on device 0 and on devices 0,1 (the
#             passes are shared), median of R processes, and the two images' difference
#   sequence  24 frames of the scene with its light moving every frame (nothing is reused), one
#             pass each, on device 0 and on devices 0,1 (each device a contiguous run of frames)
# and the speed-up of two devices over one. Writes OUT/summary.md and the logs.
#
#   bench/multi_gpu_suite.sh --backend cuda,opencl --out results/two-h200
#
# Works from the repository (build/pmrender) and from the GPU bundle (bench/pack_for_gpu.sh).
set -euo pipefail

usage() {
  cat <<'USAGE'
usage: multi_gpu_suite.sh [options]
  --backend LIST     cuda, opencl or a comma list (default: cuda)
  --devices LIST     the several devices (default: 0,1)
  --out DIR          output folder (default: bench-results/multi-gpu-<UTC date and time>)
  --scenes LIST      space- or comma-separated bench scenes (default: sponza conference)
  --passes P         passes of the single frame (default: 32)
  --repeat R         processes per measurement, median (default: 3)
  --resolution WxH   image size (default: 1920x1080)
  --photons N        photons per pass (default: 1048576)
  --pmrender PATH    the pmrender binary (default: build/pmrender, or the bundle's bin/pmrender)
  -h, --help         this text
USAGE
}

suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
backends=cuda devices=0,1 out="" scenes="sponza conference" passes=32 repeat=3 pmrender="" resolution=1920x1080 photons=1048576
while [ $# -gt 0 ]; do
  case $1 in
    --backend) backends=$2; shift 2 ;;
    --devices) devices=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --scenes) scenes=${2//,/ }; shift 2 ;;
    --passes) passes=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --photons) photons=$2; shift 2 ;;
    --pmrender) pmrender=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "multi_gpu_suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for n in passes repeat photons; do
  [[ ${!n} =~ ^[1-9][0-9]*$ ]] || { echo "multi_gpu_suite.sh: --$n: expected a positive number, got '${!n}'" >&2; exit 2; }
done

suite_name=multi_gpu_suite.sh
# shellcheck source=bench/suite_common.sh
source "$suite_dir/suite_common.sh"
suite_find_pmrender "$pmrender"
for s in $scenes; do
  suite_light_motion "$s" >/dev/null || { echo "multi_gpu_suite.sh: --scenes: unknown scene '$s'" >&2; exit 2; }
done

[ -n "$out" ] || out=bench-results/multi-gpu-$(date -u +%Y%m%d-%H%M%S)
mkdir -p "$out/scenes" "$out/images"
suite_environment "$out" "backend=$backends devices=$devices scenes='$scenes' passes=$passes repeat=$repeat resolution=$resolution photons=$photons"

failed=0
# seconds NAME ARGS...: median wall time of R `pmrender render` processes, in seconds (3 decimals).
seconds() {
  local name=$1; shift
  local times=() i start end
  for ((i = 0; i < repeat; ++i)); do
    start=$(date +%s.%N)
    if ! "$pmrender" render "$@" --quiet >>"$out/$name.log" 2>&1; then
      echo "FAILED: $name (see $name.log)" >&2; failed=$((failed + 1)); echo nan; return
    fi
    end=$(date +%s.%N)
    times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')")
  done
  printf '%s\n' "${times[@]}" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "nan" }'; }

rows=()
for backend in ${backends//,/ }; do
  for s in $scenes; do
    scene=$suite_dir/scenes/$s.json
    lit=$(suite_animated_scene "$s" light "$out/scenes")
    common=(--backend "$backend" --resolution "$resolution" --photons "$photons")
    one=$(seconds "$backend-$s-frame-1" "$scene" "${common[@]}" --passes "$passes" --devices 0 \
      -o "$out/images/$backend-$s-1.exr")
    two=$(seconds "$backend-$s-frame-2" "$scene" "${common[@]}" --passes "$passes" --devices "$devices" \
      -o "$out/images/$backend-$s-2.exr")
    diff=$("$pmrender" compare --metric relmse --threshold 1 "$out/images/$backend-$s-1.exr" \
      "$out/images/$backend-$s-2.exr" 2>/dev/null | awk '$1 == "relmse" { print $2; exit }')
    seq_one=$(seconds "$backend-$s-sequence-1" "$lit" "${common[@]}" --frames 0-23 --devices 0 \
      -o "$out/images/$backend-$s-seq1-####.exr")
    seq_two=$(seconds "$backend-$s-sequence-2" "$lit" "${common[@]}" --frames 0-23 --devices "$devices" \
      -o "$out/images/$backend-$s-seq2-####.exr")
    rows+=("| $backend | $s | $one | $two | $(ratio "$one" "$two") | ${diff:-?} | $seq_one | $seq_two | $(ratio "$seq_one" "$seq_two") |")
    echo "${rows[-1]}"
  done
done

{
  echo "# pmrender on several GPUs"
  echo
  sed 's/^/    /' "$out/environment.txt"
  echo
  echo "Wall seconds per process (median of $repeat), start-up and scene loading included."
  echo
  echo "| backend | scene | frame ($passes passes), device 0 | devices $devices | speed-up | relmse of the two images | 24-frame sequence, device 0 | devices $devices | speed-up |"
  echo "|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$out/summary.md"
echo
echo "results in $out ($failed failed)"
[ "$failed" -eq 0 ]
