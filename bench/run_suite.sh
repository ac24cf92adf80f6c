#!/usr/bin/env bash
# The pmrender benchmark suite: `pmrender bench` over the benchmark scenes at the paper's settings
# (Fabianowski & Dingliana 2009, Table 2: 512x512, two bounces, one mirror bounce, r_max 0.7) and at
# production settings (1920x1080, 1M photons), one JSON and one text report per run, and a summary
# table. See docs/benchmarks.md.
#
#   bench/run_suite.sh --backend cuda --out results/h200-cuda
#   bench/run_suite.sh --backend cuda,opencl --device 0 --out results/h200 --paper-tables --knn
#
# Works from the repository (uses build/pmrender) and from the GPU bundle made by
# bench/pack_for_gpu.sh (uses the bundle's bin/pmrender and env.sh).
set -euo pipefail

usage() {
  cat <<'EOF'
usage: run_suite.sh [options]
  --backend LIST        auto, cuda, opencl or a comma list, e.g. cuda,opencl (default: auto)
  --device N            device index within each backend (default: 0)
  --out DIR             output folder (default: bench-results/<UTC date and time>)
  --profile P           paper, production or all (default: all)
  --scenes LIST         space- or comma-separated, from: sponza conference sibenik cornell-box
                        conference-69k (default: sponza conference sibenik cornell-box)
  --warmup N            warmup frames per run (default: 2)
  --repeat N            measured frames per run (default: 10)
  --resolution WxH      override both profiles' resolution (reduced runs)
  --photon-divisor D    divide every photon count by D (reduced runs; default 1)
  --paper-tables        paper profile also runs --leaf-sweep 1,...,512 (Table 1) and
                        --radius-histogram (Table 3)
  --knn                 paper profile also runs --estimator knn with --k = k_PD of the pd run
                        (capped at 256, the largest --k)
  --unclipped           every pd run also runs with --footprint-clip off (the paper's whole
                        ellipses; run name suffix -unclipped)
  --pmrender PATH       the pmrender binary (default: build/pmrender, or the bundle's bin/pmrender)
  -h, --help            this text
EOF
}

suite_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
backends=auto device=0 out="" profile=all scenes="sponza conference sibenik cornell-box"
warmup=2 repeat=10 resolution="" divisor=1 paper_tables=0 knn=0 unclipped=0 pmrender=""
while [ $# -gt 0 ]; do
  case $1 in
    --backend) backends=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --profile) profile=$2; shift 2 ;;
    --scenes) scenes=${2//,/ }; shift 2 ;;
    --warmup) warmup=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --photon-divisor) divisor=$2; shift 2 ;;
    --paper-tables) paper_tables=1; shift ;;
    --knn) knn=1; shift ;;
    --unclipped) unclipped=1; shift ;;
    --pmrender) pmrender=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run_suite.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case $profile in paper) profiles=paper ;; production) profiles=production ;; all) profiles="paper production" ;;
  *) echo "run_suite.sh: --profile: expected paper, production or all, got '$profile'" >&2; exit 2 ;; esac
[[ $divisor =~ ^[1-9][0-9]*$ ]] || { echo "run_suite.sh: --photon-divisor: expected a positive integer, got '$divisor'" >&2; exit 2; }

# The binary: given, the repository's build, or the bundle's (with its libraries).
suite_name=run_suite.sh
# shellcheck source=bench/suite_common.sh
source "$suite_dir/suite_common.sh"
suite_find_pmrender "$pmrender"

# Per scene: the scene argument (empty: the built-in Cornell box), the paper's emitted photons
# (Table 2; k = 1024) and smoothing factor s.
scene_arg() { case $1 in cornell-box) echo "" ;; *) echo "$suite_dir/scenes/$1.json" ;; esac; }
paper_photons() {
  case $1 in sponza) echo 262144 ;; conference|conference-69k) echo 131072 ;; sibenik) echo 524288 ;;
    cornell-box) echo 131072 ;; *) return 1 ;; esac
}
smoothing() {
  case $1 in sponza) echo 40 ;; conference|conference-69k) echo 22.5 ;; sibenik) echo 60 ;;
    cornell-box) echo 6 ;; *) return 1 ;; esac
}
for s in $scenes; do
  paper_photons "$s" >/dev/null || { echo "run_suite.sh: --scenes: unknown scene '$s'" >&2; exit 2; }
  a=$(scene_arg "$s"); [ -z "$a" ] || [ -f "$a" ] || { echo "run_suite.sh: missing scene file $a" >&2; exit 2; }
done

[ -n "$out" ] || out=bench-results/$(date -u +%Y%m%d-%H%M%S)
mkdir -p "$out"

suite_environment "$out" "backend=$backends device=$device profile=$profile scenes='$scenes' warmup=$warmup \
repeat=$repeat resolution=${resolution:-profile} photon-divisor=$divisor paper-tables=$paper_tables knn=$knn unclipped=$unclipped"

failed=0
runs=()
run() { suite_run "$@"; }

for backend in ${backends//,/ }; do
  for p in $profiles; do
    for s in $scenes; do
      if [ "$p" = paper ]; then res=512x512 photons=$(paper_photons "$s"); else res=1920x1080 photons=1048576; fi
      [ -z "$resolution" ] || res=$resolution
      photons=$((photons / divisor))
      a=$(scene_arg "$s")
      common=(${a:+"$a"} --backend "$backend" --device "$device" --resolution "$res" --photons "$photons"
              --smoothing "$(smoothing "$s")" --rmax 0.7 --bounces 2 --mirror-depth 1
              --warmup "$warmup" --repeat "$repeat")
      extra=()
      [ "$p" = paper ] && [ "$paper_tables" = 1 ] &&
        extra=(--leaf-sweep "1,2,4,8,16,32,64,128,256,512" --radius-histogram)
      run "$backend-$p-$s" "${common[@]}" ${extra[@]+"${extra[@]}"}
      [ "$unclipped" = 0 ] || run "$backend-$p-$s-unclipped" "${common[@]}" --footprint-clip off
      if [ "$p" = paper ] && [ "$knn" = 1 ] && [ -s "$out/$backend-$p-$s.txt" ]; then
        k=$(awk '/^counted in frame/ { for (i = 1; i <= NF; ++i) if ($i ~ /^photons_per_gather=/) {
                   split($i, kv, "="); printf "%d", kv[2] + 0.5 } }' "$out/$backend-$p-$s.txt")
        if [ -n "$k" ] && [ "$k" -ge 1 ]; then
          [ "$k" -le 256 ] || k=256
          run "$backend-$p-$s-knn" "${common[@]}" --estimator knn --k "$k"
        fi
      fi
    done
  done
done

# Summary: one row per run, read back from the text reports.
summary=$out/summary.md
{
  echo "# pmrender benchmark suite"
  echo
  sed 's/^/    /' "$out/environment.txt"
  echo
  echo "| run | resolution | photons | fps (wall) | frame ms wall | frame ms stages | camera ms | trace ms | map ms | gather ms | hits | k_PD | peak MiB | bytes/photon |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for name in "${runs[@]}"; do
    f=$out/$name.txt
    if suite_failed_row "$name" 13; then continue; fi
    awk -v name="$name" '
      /^settings: / { res = $2; for (i = 3; i <= NF; ++i) if ($i ~ /^photons=/) { split($i, kv, "="); photons = kv[2] } }
      /^camera / { camera = $2 }
      /^photon trace / { trace = $3 }
      /^map: (morton|sort|tree) / { map += $3 }
      /^gather / { gather = $2 }
      /^frame \(sum of stages\)/ { stages = $5 }
      /^frame \(host wall\)/ { wall = $4 }
      /^frames per second:/ { fps = $4 }
      /^  hits / { hits = $2 }
      /^counted in frame/ { for (i = 1; i <= NF; ++i) if ($i ~ /^photons_per_gather=/) { split($i, kv, "="); kpd = kv[2] } }
      /^peak device memory:/ { peak = $4; bpp = ($6 ~ /^[0-9]/) ? $6 : "-" }
      END {
        printf "| %s | %s | %s | %s | %s | %s | %s | %s | %.3f | %s | %s | %s | %s | %s |\n", name, res, photons, fps,
               wall, stages, camera, trace, map, gather, hits == "" ? "-" : hits, kpd == "" ? "-" : kpd, peak, bpp
      }' "$f"
  done
} >"$summary"
echo
cat "$summary"
echo
echo "results in $out ($((${#runs[@]} - failed)) of ${#runs[@]} runs succeeded)"
[ "$failed" -eq 0 ]
