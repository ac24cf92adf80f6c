#!/usr/bin/env bash
# What each farm task pays before its first frame (docs/farm.md, "Scaling"): process start and
# scene load, then device open (OpenCL program build, from the driver's kernel cache when warm) and
# scene BVH build and upload, measured per scene from the outside with plain pmrender runs:
#
#   load   = wall time of `render --resume` over a frame that is already complete (process start,
#            scene load, one completeness check; the device is never opened)
#   start  = wall time of a tiny frame (16x16, no photons) minus its render ms (the "wrote" line):
#            load + device open + scene BVH build and upload + writing a tiny EXR
#   device = start - load of the built-in Cornell box (32 triangles: no BVH to speak of)
#   bvh    = start - load - device, per scene
#
# Medians of --repeat runs. --cold also times one start with an empty kernel cache (PoCL only:
# POCL_CACHE_DIR), what the first task on a node without a shared cache pays.
#
#   bench/farm_startup.sh --backend opencl --repeat 5 --cold
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
pmrender="$here/../build/pmrender" backend=opencl repeat=5 cold=0
scenes=("builtin" "$here/scenes/conference-69k.json" "$here/scenes/sibenik.json" "$here/scenes/sponza.json"
        "$here/scenes/conference.json")
while [ $# -gt 0 ]; do
  case $1 in
    --pmrender) pmrender=$2; shift 2 ;;
    --backend) backend=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --cold) cold=1; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "farm_startup.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
calc() { awk "BEGIN { print $* }"; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
scene_args() { [ "$1" = builtin ] || printf '%s' "$1"; }

# One tiny frame; prints "wall_ms render_ms".
tiny_frame() {
  local scene=$1 out=$2
  rm -f "$out"
  local t0 t1 line
  t0=$(now)
  line=$("$pmrender" render $(scene_args "$scene") --backend "$backend" --resolution 16x16 --photons 0 --frames 0 -o "$out" 2>/dev/null)
  t1=$(now)
  echo "$(calc "($t1 - $t0) * 1000") $(sed -n 's/.*, \([0-9.]*\) ms.*/\1/p' <<<"$line")"
}

printf '%-16s %10s %8s %12s %12s %12s' scene triangles load_ms start_ms device_ms bvh_ms
[ $cold = 1 ] && printf ' %14s' cold_start_ms
printf '\n'
device_ms=""
for scene in "${scenes[@]}"; do
  name=$([ "$scene" = builtin ] && echo cornell-box || basename "$scene" .json)
  out="$work/$name.exr"
  tiny_frame "$scene" "$out" >/dev/null  # warms the kernel and file caches
  loads=() starts=()
  for _ in $(seq "$repeat"); do
    read -r wall render < <(tiny_frame "$scene" "$out")
    starts+=("$(calc "$wall - $render")")
    t0=$(now)
    "$pmrender" render $(scene_args "$scene") --backend "$backend" --frames 0 --resume -o "$out" -q
    t1=$(now)
    loads+=("$(calc "($t1 - $t0) * 1000")")
  done
  load=$(printf '%s\n' "${loads[@]}" | median)
  start=$(printf '%s\n' "${starts[@]}" | median)
  [ -z "$device_ms" ] && device_ms=$(calc "$start - $load")
  bvh=$(calc "$start - $load - $device_ms")
  [ "$scene" = builtin ] && bvh=0  # the baseline that defines device_ms
  triangles=$("$pmrender" bench $(scene_args "$scene") --backend "$backend" --resolution 16x16 --photons 0 --warmup 0 \
              --repeat 1 2>/dev/null | sed -n 's/.*[^0-9]\([0-9][0-9]*\) triangles.*/\1/p' | head -n 1)
  printf '%-16s %10s %8.0f %12.0f %12.0f %12.0f' "$name" "${triangles:-?}" "$load" "$start" "$device_ms" "$bvh"
  if [ $cold = 1 ]; then
    cache="$work/pocl-cache"
    rm -rf "$cache"
    read -r wall render < <(POCL_CACHE_DIR="$cache" tiny_frame "$scene" "$out")
    printf ' %14.0f' "$(calc "$wall - $render")"
  fi
  printf '\n'
done
