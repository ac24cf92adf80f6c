#!/usr/bin/env bash
# Vertex link radiosity against photon mapping over the benchmark scenes (docs/radiosity.md):
# per backend and scene, `pmrender bench` of
#   full        a fresh renderer's first frame: refinement, links, light links, gathering,
#               smoothing, camera pass and interpolation (the paper's t_full, Table 2)
#   light-only  a sequence whose light moves every frame (camera still): light links + gathering
#               + smoothing + interpolation per frame; photon mapping traces every frame
#   camera-only a sequence whose camera moves every frame (light still): camera pass +
#               interpolation; photon mapping reuses its photon map and gathers again
#   static      the still scene, frames after the first: the same work as camera-only
# for both methods, plus the images: radiosity against a photon-mapping reference of many photons
# (accuracy), and CUDA against OpenCL when both backends run. The animated scenes are written
# into OUT/scenes from bench/scenes/*.json. One JSON and one text report per run, summary.md.
#
#   bench/radiosity_suite.sh --backend cuda,opencl --out results/radiosity-h200
#   bench/radiosity_suite.sh --backend opencl --scenes cornell-mcguire --resolution 128x128 \
#       --directions 16 --photons 65536 --reference-passes 2 --frames 3 --out /tmp/rs
#
# Works from the repository (build/pmrender) and from the GPU bundle (bench/pack_for_gpu.sh).
set -euo pipefail

usage() {
  cat <<'EOF'
usage: radiosity_suite.sh [options]
  --backend LIST          auto, cuda, opencl or a comma list, e.g. cuda,opencl (default: auto)
  --device N              device index within each backend (default: 0)
  --out DIR               output folder (default: bench-results/radiosity-<UTC date and time>)
  --scenes LIST           space- or comma-separated, from: cornell-mcguire sponza conference
                          conference-69k sibenik (default: cornell-mcguire sponza conference sibenik)
  --resolution WxH        image size (default: 512x512)
  --directions N          radiosity nC (default: 256)
  --bounces N             diffuse bounces, both methods (default: 2)
  --photons N             photon mapping: photons per frame (default: 262144)
  --frames N              measured frames per sequence (default: 10)
  --full-runs N           fresh processes timing the full solution (default: 3)
  --reference-passes N    accuracy reference: photon mapping with N passes of 1048576 photons
                          (default: 8; 0: no accuracy comparison)
  --radiosity-args "..."  more options for every radiosity run, e.g. "--sides one"
  --pmrender PATH         the pmrender binary (default: build/pmrender, or the bundle's bin/pmrender)
  -h, --help              this text
EOF
}

suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
backends=auto device=0 out="" scenes="cornell-mcguire sponza conference sibenik" resolution=512x512
directions=256 bounces=2 photons=262144 frames=10 full_runs=3 reference_passes=8 radiosity_args="" pmrender=""
while [ $# -gt 0 ]; do
  case $1 in
    --backend) backends=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --scenes) scenes=${2//,/ }; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --directions) directions=$2; shift 2 ;;
    --bounces) bounces=$2; shift 2 ;;
    --photons) photons=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --full-runs) full_runs=$2; shift 2 ;;
    --reference-passes) reference_passes=$2; shift 2 ;;
    --radiosity-args) radiosity_args=$2; shift 2 ;;
    --pmrender) pmrender=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "radiosity_suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for n in device directions bounces photons frames full_runs reference_passes; do
  [[ ${!n} =~ ^[0-9]+$ ]] || { echo "radiosity_suite.sh: --${n//_/-}: expected a number, got '${!n}'" >&2; exit 2; }
done
[ "$frames" -ge 1 ] || { echo "radiosity_suite.sh: --frames: expected at least 1" >&2; exit 2; }

suite_name=radiosity_suite.sh
# shellcheck source=bench/suite_common.sh
source "$suite_dir/suite_common.sh"
suite_find_pmrender "$pmrender"

for s in $scenes; do
  suite_light_motion "$s" >/dev/null || { echo "radiosity_suite.sh: --scenes: unknown scene '$s'" >&2; exit 2; }
  [ -f "$suite_dir/scenes/$s.json" ] || { echo "radiosity_suite.sh: missing $suite_dir/scenes/$s.json" >&2; exit 2; }
done

[ -n "$out" ] || out=bench-results/radiosity-$(date -u +%Y%m%d-%H%M%S)
mkdir -p "$out/scenes" "$out/images"

suite_environment "$out" "backend=$backends device=$device scenes='$scenes' resolution=$resolution \
directions=$directions bounces=$bounces photons=$photons frames=$frames full-runs=$full_runs \
reference-passes=$reference_passes radiosity-args='$radiosity_args'"

failed=0
runs=()
# run NAME ARGS...: one pmrender bench; only its stage and frame rows are shown.
show_rows() { grep -E '^(radiosity: |camera |photon trace|gather |frame \(|frames per second)'; }
suite_show=show_rows
run() { suite_run "$@"; }
# image NAME ARGS...: one pmrender render of frame 0 into OUT/images/NAME.exr.
image() {
  local name=$1; shift
  "$pmrender" render "$@" --frame 0 --quiet -o "$out/images/$name.exr" 2>"$out/images/$name.err" ||
    { echo "FAILED: render $name: $(cat "$out/images/$name.err")"; failed=$((failed + 1)); }
  [ -s "$out/images/$name.err" ] || rm -f "$out/images/$name.err"
}
# compare REF TEST: the indirect layers' metrics, one line each into compare.txt.
compare() {
  local line=""
  for metric in mean relmse flip; do
    local v
    v=$("$pmrender" compare "$out/images/$1.exr" "$out/images/$2.exr" --layer indirect --metric "$metric" 2>/dev/null |
        awk -v m="$metric" '$1 == m { print $2; exit }') || true
    line="$line $metric=${v:-?}"
  done
  echo "$2 vs $1 (indirect):$line" | tee -a "$out/compare.txt"
}

radiosity=(--method radiosity --directions "$directions" --bounces "$bounces")
# shellcheck disable=SC2206
[ -z "$radiosity_args" ] || radiosity+=($radiosity_args)
photon=(--method photon --photons "$photons" --bounces "$bounces")
for s in $scenes; do
  still=$suite_dir/scenes/$s.json
  lit=$(suite_animated_scene "$s" light "$out/scenes")
  moved=$(suite_animated_scene "$s" camera "$out/scenes")
  for backend in ${backends//,/ }; do
    common=(--backend "$backend" --device "$device" --resolution "$resolution")
    for i in $(seq 1 "$full_runs"); do
      run "$backend-$s-radiosity-full-$i" "$still" "${common[@]}" "${radiosity[@]}" --warmup 0 --repeat 1
    done
    for method in radiosity photon; do
      if [ $method = radiosity ]; then args=("${radiosity[@]}"); else args=("${photon[@]}"); fi
      run "$backend-$s-$method-light-only" "$lit" "${common[@]}" "${args[@]}" --warmup 1 --repeat "$frames"
      run "$backend-$s-$method-camera-only" "$moved" "${common[@]}" "${args[@]}" --warmup 1 --repeat "$frames"
      run "$backend-$s-$method-static" "$still" "${common[@]}" "${args[@]}" --warmup 1 --repeat "$frames"
    done
    image "$backend-$s-radiosity" "$still" "${common[@]}" "${radiosity[@]}"
  done
  first=${backends%%,*}
  if [ "$reference_passes" -gt 0 ]; then
    image "$first-$s-reference" "$still" --backend "$first" --device "$device" --resolution "$resolution" \
      --method photon --photons 1048576 --passes "$reference_passes" --bounces "$bounces"
    image "$first-$s-photon" "$still" --backend "$first" --device "$device" --resolution "$resolution" "${photon[@]}"
    compare "$first-$s-reference" "$first-$s-radiosity"
    compare "$first-$s-reference" "$first-$s-photon"
  fi
  for backend in ${backends//,/ }; do
    [ "$backend" = "$first" ] || compare "$first-$s-radiosity" "$backend-$s-radiosity"
  done
done

# Summary: one row per run, from the text reports.
summary=$out/summary.md
{
  echo "# pmrender radiosity suite"
  echo
  sed 's/^/    /' "$out/environment.txt"
  echo
  echo "Medians over the measured frames (ms); a full run measures one first frame."
  echo
  echo "| run | wall | stages | camera | refine | links | light links | gather | smooth | interpolate | photon trace | photon gather | elements | links | link MB | peak MiB |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for name in "${runs[@]}"; do
    f=$out/$name.txt
    if suite_failed_row "$name" 15; then continue; fi
    awk -v name="$name" '
      /^camera / { camera = $2 }
      /^radiosity: refine / { refine = $3 } /^radiosity: links / { links_ms = $3 }
      /^radiosity: light links / { light = $4 } /^radiosity: gather / { rgather = $3 }
      /^radiosity: smooth / { smooth = $3 } /^radiosity: interpolate / { interp = $3 }
      /^photon trace / { trace = $3 } /^gather / { pgather = $2 }
      /^frame \(sum of stages\)/ { stages = $5 } /^frame \(host wall\)/ { wall = $4 }
      /^  elements / { elements = $2 } /^  links / { links = $2 } /^  link_bytes / { bytes = $2 / 1e6 }
      /^peak device memory:/ { peak = $4 }
      function v(x) { return x == "" ? "-" : x }
      END {
        printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", name, wall, stages,
               v(camera), v(refine), v(links_ms), v(light), v(rgather), v(smooth), v(interp), v(trace), v(pgather),
               v(elements), v(links), bytes == "" ? "-" : sprintf("%.1f", bytes), peak
      }' "$f"
  done
  if [ -s "$out/compare.txt" ]; then
    echo
    echo "Images (frame 0, indirect layer; reference: photon mapping, $reference_passes x 1048576 photons):"
    echo
    sed 's/^/    /' "$out/compare.txt"
  fi
} >"$summary"
echo
cat "$summary"
echo
echo "results in $out ($((${#runs[@]} - failed)) of ${#runs[@]} runs succeeded)"
[ "$failed" -eq 0 ]
