#!/usr/bin/env bash
# The accuracy suite (docs/accuracy.md): per scene a path-traced reference, then each method at
# its defaults (and any extra settings), compared with it: the signed bias of the indirect light
# with the direct light matched, the indirect layer's relMAE, and the frame's own error estimate
# (pmrender/error_estimate) beside them, so that how well the estimate tracks the true error is
# read off the same table.
#
#   bench/accuracy_suite.sh [--out DIR] [--size WxH] [--ref-spp N] [--backend B] [--pmrender BIN]
#                           [--scenes "sponza sibenik ..."] [--only-references]
#                           [--config "NAME|ARGS"]... [--no-defaults] [--bounces N]
#
# Scenes are bench/scenes/NAME.json, golden/scenes/NAME.json, or `builtin` (the built-in Cornell
# box). References are kept: an existing DIR/ref_SCENE_bB.exr is reused (so references made once,
# on a GPU, serve every later run). --config adds a row per scene (e.g. "pd-s16|--smoothing 16");
# --no-defaults leaves only those. The table goes to stdout and DIR/accuracy.tsv.
set -euo pipefail
suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
suite_name=accuracy_suite.sh
# shellcheck source=bench/suite_common.sh
source "$suite_dir/suite_common.sh"

out=accuracy size=96x54 ref_spp=8192 backend=auto given_pmrender="" only_refs=0 defaults=1 bounces=2
scenes="builtin cornell-mcguire sponza sibenik conference"
configs=()
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --backend) backend=$2; shift 2 ;;
    --pmrender) given_pmrender=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --config) configs+=("$2"); shift 2 ;;
    --only-references) only_refs=1; shift ;;
    --no-defaults) defaults=0; shift ;;
    --bounces) bounces=$2; shift 2 ;;
    *) echo "$suite_name: unknown option '$1'" >&2; exit 2 ;;
  esac
done
case $size in *x*) ;; *) echo "$suite_name: --size expects WxH, got '$size'" >&2; exit 2 ;; esac
case $ref_spp in '' | *[!0-9]*) echo "$suite_name: --ref-spp expects a number, got '$ref_spp'" >&2; exit 2 ;; esac
case $bounces in '' | *[!0-9]*) echo "$suite_name: --bounces expects a number, got '$bounces'" >&2; exit 2 ;; esac
suite_find_pmrender "$given_pmrender"
if [ "$defaults" = 1 ]; then
  configs=("pd|" "pd-shrink16|--progressive shrink --passes 16" "pd-shrink64|--progressive shrink --passes 64"
           "knn|--estimator knn" "radius|--estimator radius" "radiosity|--method radiosity" "${configs[@]}")
fi

scene_file() {
  local name=$1
  [ "$name" = builtin ] && return 0
  for f in "$suite_dir/scenes/$name.json" "$suite_dir/../golden/scenes/$name.json"; do
    [ -f "$f" ] && { echo "$f"; return 0; }
  done
  echo "$suite_name: no scene '$name' in bench/scenes or golden/scenes" >&2
  exit 2
}
for s in $scenes; do scene_file "$s" >/dev/null; done
mkdir -p "$out"

# One render; prints "milliseconds estimate" (estimate "-" when the frame has none).
render() {
  local log=$1; shift
  "$pmrender" render "$@" --backend "$backend" --resolution "$size" --bounces "$bounces" --float >"$log" 2>&1 ||
    { echo "$suite_name: render failed: $(tail -n 1 "$log")" >&2; return 1; }
  local line ms estimate
  line=$(grep '^wrote ' "$log" | tail -n 1)
  ms=$(sed -n 's/.*, \([0-9.]*\) ms.*/\1/p' <<<"$line")
  estimate=$(sed -n 's/.*error ~\([0-9.]*\)%.*/\1/p' <<<"$line")
  echo "${ms:-?} ${estimate:--}"
}

printf '%-16s %-14s %9s %9s %9s %9s %10s\n' scene config "bias_ind%" "bias_img%" "relMAE%" "estimate%" "ms" | tee "$out/accuracy.tsv"
failed=0
for s in $scenes; do
  file=$(scene_file "$s")
  ref=$out/ref_${s}_b${bounces}.exr
  if [ ! -f "$ref" ]; then
    passes=$(( (ref_spp + 255) / 256 ))
    spp=$(( ref_spp < 256 ? ref_spp : 256 ))
    if ! timing=$(render "$out/ref_${s}.log" ${file:+"$file"} --method path --spp "$spp" --passes "$passes" -o "$ref"); then
      failed=$((failed + 1)); continue
    fi
    echo "# reference $s: $((spp * passes)) paths per pixel, ${timing% *} ms, its own error estimate ${timing#* }%" |
      tee -a "$out/references.txt"
  fi
  [ "$only_refs" = 1 ] && continue
  for c in "${configs[@]}"; do
    name=${c%%|*} args=${c#*|}
    test=$out/${s}_${name}_b${bounces}.exr
    # shellcheck disable=SC2086  # ARGS are words
    if ! timing=$(render "$out/${s}_${name}.log" ${file:+"$file"} $args -o "$test"); then
      failed=$((failed + 1)); continue
    fi
    cmp=$("$pmrender" compare "$ref" "$test" --metric relmae 2>&1 || true)  # the bias line
    relmae=$("$pmrender" compare "$ref" "$test" --metric relmae --layer indirect 2>&1 |
             sed -n 's/^relmae *\([0-9.e+-]*\) *(sum.*/\1/p' || true)
    bias_img=$(sed -n 's/^bias *\([-+0-9.]*\)% image mean.*/\1/p' <<<"$cmp")
    bias_ind=$(sed -n 's/.*, \([-+0-9.]*\)% indirect light.*/\1/p' <<<"$cmp")
    printf '%-16s %-14s %9s %9s %9s %9s %10s\n' "$s" "$name" "${bias_ind:-?}" "${bias_img:-?}" \
      "$(awk -v v="${relmae:-nan}" 'BEGIN { printf "%.2f", 100 * v }')" "${timing#* }" "${timing% *}" |
      tee -a "$out/accuracy.tsv"
  done
done
[ "$failed" -eq 0 ] || { echo "$suite_name: $failed runs failed" >&2; exit 1; }
