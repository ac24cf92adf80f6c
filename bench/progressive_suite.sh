#!/usr/bin/env bash
# Progressive rendering against the clock (docs/progressive.md): per scene, a reference rendered
# under a time budget (Sponza: the path tracer; the Cornell box: the fixed-radius estimator shrunk
# over many passes, because the box's light hangs under the ceiling, where the path tracer is at its
# noisiest (docs/tradeoff.md), while the radius estimator is nearly unbiased there), then per backend and per time budget T one frame of
# photon passes rendered with `--time T`, and its passes per second and error against the reference:
# relMAE, HDR-FLIP, the bias of the image mean and of the indirect light (everything but the
# direct layer, which the camera pass makes the same in both), beside the frame's own error
# estimate (the even/odd passes). Writes OUT/summary.md and the logs; the images stay in
# OUT/images.
#
#   bench/progressive_suite.sh --backend cuda,opencl --out results/progressive-h200
#
# Works from the repository (build/pmrender) and from the GPU bundle (bench/pack_for_gpu.sh).
set -euo pipefail

usage() {
  cat <<'USAGE'
usage: progressive_suite.sh [options]
  --backend LIST        cuda, opencl or a comma list (default: cuda)
  --out DIR             output folder (default: bench-results/progressive-<UTC date and time>)
  --scenes LIST         sponza, cornell-box (the built-in one) or a comma list (default: both)
  --times LIST          time budgets of the photon frames, seconds (default: 1,10,60)
  --reference-time LIST seconds of each scene's reference, in --scenes order (default: 20,40: the
                        whole suite then fits a 10-minute call on the GPU machine, 393 s on an H200)
  --resolution WxH      image size (default: 1920x1080)
  --photons N           photons per pass (default: 1048576)
  --reference-photons N photons per pass of the Cornell box's reference (default: 4194304; fewer
                        where a pass takes long, as on a CPU, so that its time holds many passes)
  --estimator E         pd, knn or radius (default: pd)
  --progressive MODE    average or shrink (default: shrink)
  --pmrender PATH       the pmrender binary (default: build/pmrender, or the bundle's bin/pmrender)
  -h, --help            this text
USAGE
}

suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
backends=cuda out="" scenes="sponza cornell-box" times="1 10 60" reference_times="20 40" resolution=1920x1080
photons=1048576 reference_photons=4194304 estimator=pd mode=shrink pmrender=""
while [ $# -gt 0 ]; do
  case $1 in
    --backend) backends=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --scenes) scenes=${2//,/ }; shift 2 ;;
    --times) times=${2//,/ }; shift 2 ;;
    --reference-time) reference_times=${2//,/ }; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --photons) photons=$2; shift 2 ;;
    --reference-photons) reference_photons=$2; shift 2 ;;
    --estimator) estimator=$2; shift 2 ;;
    --progressive) mode=$2; shift 2 ;;
    --pmrender) pmrender=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "progressive_suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for option in photons reference_photons; do
  [[ ${!option} =~ ^[1-9][0-9]*$ ]] ||
    { echo "progressive_suite.sh: --${option//_/-}: expected a positive number, got '${!option}'" >&2; exit 2; }
done
for t in $times $reference_times; do
  [[ $t =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "progressive_suite.sh: expected seconds, got '$t'" >&2; exit 2; }
done
read -r -a scene_list <<<"$scenes"
read -r -a reference_list <<<"$reference_times"
[ "${#reference_list[@]}" -eq "${#scene_list[@]}" ] ||
  { echo "progressive_suite.sh: --reference-time: one time per scene (${#scene_list[@]})" >&2; exit 2; }

suite_name=progressive_suite.sh
# shellcheck source=bench/suite_common.sh
source "$suite_dir/suite_common.sh"
suite_find_pmrender "$pmrender"

# The scene argument (empty: the built-in Cornell box) and the suite's per-scene settings, as
# bench/run_suite.sh's production profile has them.
scene_args() {
  case $1 in
    sponza) echo "$suite_dir/scenes/sponza.json --smoothing 40" ;;
    cornell-box) echo "--smoothing 6" ;;
    *) return 1 ;;
  esac
}
# The reference's method per scene: unbiased where it converges fast enough (scene_args come first).
reference_args() {
  case $1 in
    sponza) echo "--method path --spp 4" ;;
    cornell-box) echo "--method photon --estimator radius --radius 0.02 --progressive shrink --alpha 0.5 --photons $reference_photons" ;;
  esac
}
for s in "${scene_list[@]}"; do
  scene_args "$s" >/dev/null || { echo "progressive_suite.sh: --scenes: unknown scene '$s'" >&2; exit 2; }
done

[ -n "$out" ] || out=bench-results/progressive-$(date -u +%Y%m%d-%H%M%S)
mkdir -p "$out/images"
suite_environment "$out" "backend=$backends scenes='$scenes' times='$times' reference-time='$reference_times' \
resolution=$resolution photons=$photons estimator=$estimator progressive=$mode"

failed=0
first_backend=${backends%%,*}
# metric NAME FILE: the value of metric NAME in a `pmrender compare` report.
metric() { awk -v m="$1" '$1 == m { print $2; exit }' "$2"; }
# row NAME BACKEND SCENE BUDGET: the summary row of a finished render and its comparison.
row() {
  local name=$1 wrote ms passes estimate relmae flip mean_bias indirect_bias
  # "wrote FILE (frame 0, WxH, DEVICE, 1009.71 ms, 48 passes (time), error ~1.70%)"
  wrote=$(grep '^wrote ' "$out/$name.log" | tail -n 1)
  ms=$(echo "$wrote" | grep -o '[0-9.]* ms,' | tail -n 1 | cut -d' ' -f1)
  passes=$(echo "$wrote" | grep -o '[0-9]* passes' | cut -d' ' -f1)
  estimate=$(echo "$wrote" | grep -o 'error ~[0-9.]*%' | sed 's/error ~//')
  relmae=$(metric relmae "$out/$name.compare") flip=$(metric flip "$out/$name.compare")
  if [ -z "$relmae" ] || [ -z "$ms" ]; then
    echo "| $2 | $3 | $4 | failed: $(head -n 1 "$out/$name.compare" 2>/dev/null) |"
    return
  fi
  # "bias    -1.1472% image mean, -2.3607% indirect light with the direct light matched"
  mean_bias=$(awk '$1 == "bias" { print $2; exit }' "$out/$name.compare" | tr -d ',')
  indirect_bias=$(awk '$1 == "bias" { print $5; exit }' "$out/$name.compare" | tr -d ',')
  awk -v b="$2" -v s="$3" -v t="$4" -v ms="$ms" -v p="$passes" -v e="$estimate" -v r="$relmae" -v f="$flip" \
    -v mb="$mean_bias" -v ib="$indirect_bias" 'BEGIN {
      printf "| %s | %s | %s | %.2f | %d | %.1f | %.2f %% | %.4f | %s | %s | %s |\n", b, s, t, ms / 1000, p,
      p / (ms / 1000), 100 * r, f, mb, ib, e }'
}

# The comparisons (HDR-FLIP of a 1080p image takes seconds of CPU) run in the background while
# the GPU renders the next budget; the rows are made once all have finished.
finished=()
for i in "${!scene_list[@]}"; do
  s=${scene_list[$i]}
  read -r -a args <<<"$(scene_args "$s")"
  common=("${args[@]}" --resolution "$resolution" --rmax 0.7 --bounces 2 --mirror-depth 1)
  ref=$out/images/$s-reference.exr
  read -r -a ref_args <<<"$(reference_args "$s")"
  echo "== $s: reference, ${ref_args[*]} for ${reference_list[$i]} s ($first_backend)"
  if ! "$pmrender" render "${common[@]}" --backend "$first_backend" "${ref_args[@]}" --seed 7 \
       --time "${reference_list[$i]}" --float -o "$ref" >"$out/$s-reference.log" 2>&1; then
    echo "FAILED: $s reference (see $s-reference.log)"; failed=$((failed + 1)); continue
  fi
  cat "$out/$s-reference.log"
  for backend in ${backends//,/ }; do
    for t in $times; do
      name=$backend-$s-${t}s
      img=$out/images/$name.exr
      if ! "$pmrender" render "${common[@]}" --backend "$backend" --photons "$photons" --estimator "$estimator" \
           --progressive "$mode" --time "$t" --float -o "$img" >"$out/$name.log" 2>&1; then
        echo "FAILED: $name (see $name.log)"; failed=$((failed + 1)); continue
      fi
      grep '^wrote ' "$out/$name.log"
      "$pmrender" compare --metric relmae --threshold 1e9 "$ref" "$img" >"$out/$name.compare" 2>&1 &
      finished+=("$name $backend $s $t")
    done
  done
done
wait
rows=()
for f in ${finished[@]+"${finished[@]}"}; do
  read -r -a r <<<"$f"
  rows+=("$(row "${r[@]}")")
  case ${rows[-1]} in *"| failed: "*) failed=$((failed + 1)) ;; esac
  echo "${rows[-1]}"
done

{
  echo "# pmrender progressive rendering against the clock"
  echo
  sed 's/^/    /' "$out/environment.txt"
  echo
  echo "References:"
  for s in "${scene_list[@]}"; do echo "- $s: $(reference_args "$s"): $(grep -h '^wrote ' "$out/$s-reference.log")"; done
  echo
  echo "| backend | scene | budget s | render s | passes | passes per second | relMAE | HDR-FLIP | image mean bias | indirect bias | own estimate |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' ${rows[@]+"${rows[@]}"}
} >"$out/summary.md"
echo
echo "results in $out ($failed failed)"
[ "$failed" -eq 0 ]
