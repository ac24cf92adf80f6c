#!/usr/bin/env bash
# Several GPUs of one machine (`--devices`, docs/progressive.md "Several devices"): per backend and
# scene,
#   frame     one 1920x1080 frame of 1M photons a pass (by default) under `--time T`: passes per
#             second of rendering on device 0 and on devices 0,1 (the passes are shared), median of
#             R processes; and the difference of the two devices' image from one device's over the
#             same P passes (float summation order only)
#   sequence  N frames (default 48) of the scene with its light moving every frame (nothing is
#             reused), one pass each, on device 0 and on devices 0,1 (runs of frames with work
#             stealing): wall seconds per process, start-up, loading and writing included, median
#             of R, and the frames each device rendered
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
  --time T           seconds of the single frame's budget (default: 10)
  --passes P         passes of the frame whose two images are compared (default: 8)
  --frames N         frames of the sequence (default: 48)
  --parts LIST       frame, sequence or both (default: frame,sequence)
  --repeat R         processes per measurement, median (default: 3)
  --resolution WxH   image size (default: 1920x1080)
  --photons N        photons per pass (default: 1048576)
  --pmrender PATH    the pmrender binary (default: build/pmrender, or the bundle's bin/pmrender)
  --render-args ARGS more options for every render (e.g. "--control-paths 0": the frame's work
                     then does not depend on its time, see docs/benchmarks.md "Several GPUs")
  -h, --help         this text
USAGE
}

suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
backends=cuda devices=0,1 out="" scenes="sponza conference" seconds=10 passes=8 frames=48 parts=frame,sequence repeat=3 pmrender="" resolution=1920x1080 photons=1048576
render_args=""
while [ $# -gt 0 ]; do
  case $1 in
    --backend) backends=$2; shift 2 ;;
    --devices) devices=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --scenes) scenes=${2//,/ }; shift 2 ;;
    --time) seconds=$2; shift 2 ;;
    --passes) passes=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --parts) parts=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --photons) photons=$2; shift 2 ;;
    --pmrender) pmrender=$2; shift 2 ;;
    --render-args) render_args=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "multi_gpu_suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for n in seconds passes frames repeat photons; do
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
suite_environment "$out" "backend=$backends devices=$devices scenes='$scenes' time=$seconds passes=$passes frames=$frames repeat=$repeat resolution=$resolution photons=$photons render_args='$render_args'"

failed=0
# run_median NAME WHAT ARGS...: the median over R `pmrender render` processes of WHAT: "wall" (the
# process's wall seconds) or "rate" (passes per second of rendering, from its "wrote" line).
run_median() {
  local name=$1 what=$2; shift 2
  local values=() i start end line
  for ((i = 0; i < repeat; ++i)); do
    start=$(date +%s.%N)
    if ! "$pmrender" render "$@" >"$out/$name.$i.log" 2>&1; then
      echo "FAILED: $name (see $name.$i.log)" >&2; failed=$((failed + 1)); echo nan; return
    fi
    end=$(date +%s.%N)
    if [ "$what" = wall ]; then
      values+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')")
    else
      # "wrote F (frame 0, WxH, DEVICES, 10012.34 ms, 412 passes (time), ...)"
      line=$(grep '^wrote ' "$out/$name.$i.log" | tail -n 1)
      values+=("$(echo "$line" | awk '{ for (i = 1; i <= NF; ++i) { if ($i == "ms,") ms = $(i - 1); if ($i == "passes") p = $(i - 1) } }
        END { if (ms > 0) printf "%.2f", p / (ms / 1000); else print "nan" }')")
    fi
  done
  printf '%s\n' "${values[@]}" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
ratio() { [ "$1" = - ] || [ "$2" = - ] && { echo -; return; }; awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "nan" }'; }

rows=()
for backend in ${backends//,/ }; do
  for s in $scenes; do
    scene=$suite_dir/scenes/$s.json
    lit=$(suite_animated_scene "$s" light "$out/scenes" "$frames")
    common=(--backend "$backend" --resolution "$resolution" --photons "$photons")
    # shellcheck disable=SC2206  # --render-args are words
    common+=($render_args)
    one=- two=- diff=- seq_one=- seq_two=- split=-
    if [[ ,$parts, == *,frame,* ]]; then
      one=$(run_median "$backend-$s-frame-1" rate "$scene" "${common[@]}" --time "$seconds" --devices 0 \
        -o "$out/images/$backend-$s-time-1.exr")
      two=$(run_median "$backend-$s-frame-2" rate "$scene" "${common[@]}" --time "$seconds" --devices "$devices" \
        -o "$out/images/$backend-$s-time-2.exr")
      # The same P passes on one device and on two: equal but for float summation order.
      "$pmrender" render "$scene" "${common[@]}" --passes "$passes" --devices 0 --quiet \
        -o "$out/images/$backend-$s-1.exr" >>"$out/$backend-$s-compare.log" 2>&1 || failed=$((failed + 1))
      "$pmrender" render "$scene" "${common[@]}" --passes "$passes" --devices "$devices" --quiet \
        -o "$out/images/$backend-$s-2.exr" >>"$out/$backend-$s-compare.log" 2>&1 || failed=$((failed + 1))
      diff=$("$pmrender" compare --metric relmse --threshold 1 "$out/images/$backend-$s-1.exr" \
        "$out/images/$backend-$s-2.exr" 2>/dev/null | awk '$1 == "relmse" { print $2; exit }')
    fi
    if [[ ,$parts, == *,sequence,* ]]; then
      last=$((frames - 1))
      seq_one=$(run_median "$backend-$s-sequence-1" wall "$lit" "${common[@]}" --frames "0-$last" --devices 0 \
        -o "$out/images/$backend-$s-seq1-####.exr")
      seq_two=$(run_median "$backend-$s-sequence-2" wall "$lit" "${common[@]}" --frames "0-$last" --devices "$devices" \
        -o "$out/images/$backend-$s-seq2-####.exr")
      split=$(grep -ho 'frames per device: [0-9, ]*' "$out/$backend-$s-sequence-2.0.log" | sed 's/frames per device: //')
    fi
    rows+=("| $backend | $s | $one | $two | $(ratio "$two" "$one") | ${diff:-?} | $seq_one | $seq_two | $(ratio "$seq_one" "$seq_two") | ${split:-?} |")
    echo "${rows[-1]}"
  done
done

{
  echo "# pmrender on several GPUs"
  echo
  sed 's/^/    /' "$out/environment.txt"
  echo
  echo "Frame: passes per second of rendering under --time $seconds (median of $repeat processes). Sequence:"
  echo "wall seconds per process (median of $repeat), start-up, scene loading and EXR writing included."
  [ -z "$render_args" ] || echo "Every render also had: $render_args"
  echo
  echo "| backend | scene | frame, passes/s, device 0 | devices $devices | speed-up | relmse of the two devices' image ($passes passes) | $frames-frame sequence, s, device 0 | devices $devices | speed-up | frames per device |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$out/summary.md"
echo
echo "results in $out ($failed failed)"
[ "$failed" -eq 0 ]
