#!/usr/bin/env bash
# The speed/accuracy suite of docs/tradeoff.md: `pmrender tradeoff` over the benchmark scenes
# (Sponza, Conference, Sibenik, Cornell box), each against a path-traced reference, with the
# paper's smoothing and r_max per scene. Two profiles:
#   h200: 1920x1080, the full grid (the numbers of docs/tradeoff.md, "H200 (CUDA)")
#   pocl: reduced size and grid for a CPU through PoCL (docs/tradeoff.md, "PoCL")
#
#   bench/tradeoff_suite.sh --profile h200 --backend cuda --out results/tradeoff-h200
#   bench/tradeoff_suite.sh --profile pocl --backend opencl --out results/tradeoff-pocl
#
# Writes OUT/<scene>/{reference.exr,tradeoff.txt,tradeoff.json,tradeoff.svg}, OUT/<scene>.log and
# OUT/summary.md (every scene's time-to-error table). Works from the repository (build/pmrender)
# and from the GPU bundle of bench/pack_for_gpu.sh (bin/pmrender, env.sh).
set -euo pipefail

usage() {
  cat <<'EOF'
usage: tradeoff_suite.sh [options]
  --profile P           h200 or pocl (default: h200)
  --backend B           auto, cuda or opencl (default: auto)
  --device N            device index within the backend (default: 0)
  --out DIR             output folder (default: tradeoff-results/<profile>-<UTC date and time>)
  --scenes LIST         from: sponza conference sibenik cornell-box (default: all four)
  --resolution WxH      override the profile's resolution
  --reference-spp N     override the profile's reference paths per pixel and pass
  --reference-passes N  override the profile's reference passes
  --passes LIST         override the profile's passes per frame
  --progressive LIST    how photon passes combine: average, shrink or average,shrink (default: average)
  --pmrender PATH       the pmrender binary (default: build/pmrender, or the bundle's bin/pmrender)
  -h, --help            this text
EOF
}

suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
profile=h200 backend=auto device=0 out="" scenes="sponza conference sibenik cornell-box" pmrender=""
resolution="" reference_spp="" reference_passes="" passes_list="" progressive=average
while [ $# -gt 0 ]; do
  case $1 in
    --profile) profile=$2; shift 2 ;;
    --backend) backend=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --scenes) scenes=${2//,/ }; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --reference-spp) reference_spp=$2; shift 2 ;;
    --reference-passes) reference_passes=$2; shift 2 ;;
    --passes) passes_list=$2; shift 2 ;;
    --progressive) progressive=$2; shift 2 ;;
    --pmrender) pmrender=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "tradeoff_suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

# Per profile: resolution, reference (paths per pixel and pass x passes), the grid, frames.
case $profile in
  h200)
    res=1920x1080 ref_spp=256 ref_passes=64
    photons=262144,1048576,4194304 passes=1,4,16 spp=1,4,16,64 k=16,64,256 warmup=2 repeat=5 ;;
  pocl)
    res=96x54 ref_spp=512 ref_passes=4
    photons=16384,65536,262144 passes=1,4 spp=4,16,64 k=16,64 warmup=1 repeat=2 ;;
  *) echo "tradeoff_suite.sh: --profile: expected h200 or pocl, got '$profile'" >&2; exit 2 ;;
esac
[ -z "$resolution" ] || res=$resolution
[ -z "$reference_spp" ] || ref_spp=$reference_spp
[ -z "$reference_passes" ] || ref_passes=$reference_passes
[ -z "$passes_list" ] || passes=$passes_list

if [ -z "$pmrender" ]; then
  if [ -x "$suite_dir/../build/pmrender" ]; then
    pmrender=$suite_dir/../build/pmrender
  elif [ -x "$suite_dir/../bin/pmrender" ]; then
    pmrender=$suite_dir/../bin/pmrender
    # shellcheck disable=SC1091
    source "$suite_dir/../env.sh"
  else
    pmrender=$(command -v pmrender || true)
  fi
fi
[ -n "$pmrender" ] && [ -x "$pmrender" ] || { echo "tradeoff_suite.sh: no pmrender binary found (use --pmrender)" >&2; exit 2; }

# The paper's smoothing s (Table 2) per scene, as bench/run_suite.sh uses it, with r_max 0.7 m;
# pd also at half that s, the radius estimator at 5 % of the scene diagonal and half of it.
scene_arg() { case $1 in cornell-box) echo "" ;; *) echo "$suite_dir/scenes/$1.json" ;; esac; }
smoothing() {
  case $1 in sponza) echo 20,40 ;; conference) echo 11.25,22.5 ;; sibenik) echo 30,60 ;; cornell-box) echo 3,6 ;;
    *) return 1 ;; esac
}
for s in $scenes; do
  smoothing "$s" >/dev/null || { echo "tradeoff_suite.sh: --scenes: unknown scene '$s'" >&2; exit 2; }
done

[ -n "$out" ] || out=tradeoff-results/$profile-$(date -u +%Y%m%d-%H%M%S)
mkdir -p "$out"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host: $(uname -n) ($(nproc) cores)"
  echo "pmrender: $pmrender ($("$pmrender" --version))"
  echo "suite: profile=$profile backend=$backend resolution=$res reference=${ref_passes}x${ref_spp} spp passes=$passes progressive=$progressive"
  "$pmrender" devices || true
} >"$out/environment.txt"
cat "$out/environment.txt"

failed=0
for s in $scenes; do
  a=$(scene_arg "$s")
  echo
  echo "== $s"
  rc=0
  "$pmrender" tradeoff ${a:+"$a"} --backend "$backend" --device "$device" --resolution "$res" \
    --reference-spp "$ref_spp" --reference-passes "$ref_passes" --bounces 2 --mirror-depth 1 --rmax 0.7 \
    --estimators pd,knn,radius,path --photons "$photons" --passes "$passes" --progressive "$progressive" --smoothing "$(smoothing "$s")" \
    --k "$k" --radius 0 --spp "$spp" --warmup "$warmup" --repeat "$repeat" -o "$out/$s" 2>&1 | tee "$out/$s.log" ||
    rc=$?
  [ "$rc" -eq 0 ] || { echo "FAILED (exit $rc)"; failed=$((failed + 1)); }
done

{
  echo "# pmrender tradeoff suite ($profile)"
  echo
  sed 's/^/    /' "$out/environment.txt"
  for s in $scenes; do
    echo
    echo "## $s"
    echo
    if [ -f "$out/$s/tradeoff.txt" ]; then sed 's/^/    /' "$out/$s/tradeoff.txt"; else echo "failed: see $s.log"; fi
  done
} >"$out/summary.md"
echo
echo "results in $out ($failed failed)"
[ "$failed" -eq 0 ]
