#!/usr/bin/env bash
# One call on the GPU machine, from the repository root with the bundle of bench/pack_for_gpu.sh in
# .gpu/: runs the named steps and leaves their logs and results in OUT (one tarball per step keeps
# what comes back within the device tool's limits).
#
#   bench/gpu_check.sh OUT STEP...
#
# Steps:
#   tests       pm_gpu_tests (CUDA), pm_opencl_tests (first OpenCL device: NVIDIA's)
#   paper       the suite's paper profile, CUDA and OpenCL, with pd vs knn (--knn)
#   production  the suite's production profile (1920x1080, 1M photons), CUDA and OpenCL
#   ncu         Nsight Compute on Sponza's production frame: the hot kernels' SIMT efficiency,
#               occupancy, throughput (--clock-control none: the clocks stay as they are)
#   sanitizer   compute-sanitizer memcheck and racecheck over pm_gpu_tests
#   radiosity   vertex link radiosity: the paper's tables (nC 256, one-sided, 3 bounces, CUDA) and
#               bench/radiosity_suite.sh on CUDA and OpenCL (docs/radiosity.md)
#   tradeoff    bench/tradeoff_suite.sh --profile h200 on CUDA over $TRADEOFF_SCENES (default
#               sponza), with $TRADEOFF_ARGS added (docs/tradeoff.md)
#   multi       bench/multi_gpu_suite.sh on CUDA and OpenCL, devices 0,1 (a two-GPU machine)
#   progressive bench/progressive_suite.sh on CUDA and OpenCL: passes per second and error after
#               1, 10 and 60 s, Sponza and the Cornell box at 1920x1080 (docs/progressive.md)
#   accuracy    bench/accuracy_suite.sh on CUDA: the CI-size references (96x54, 65536 paths per
#               pixel, every benchmark and golden scene, 2 and 1 bounces) as accuracy-ci.tgz, then at
#               $ACCURACY_SIZE (default 960x540; 4096-path references) every method's defaults
#               and $ACCURACY_CONFIGS (extra "NAME|ARGS" rows, separated by ';') (docs/accuracy.md);
#               ACCURACY_CI=0 skips the CI-size references, ACCURACY_DEFAULTS=0 the default rows;
#               ACCURACY_SCENES and ACCURACY_BOUNCES pass --scenes and --bounces
#   mitsuba     per scene of $MITSUBA_SCENES (default sponza; conference, sibenik, cornell-mcguire) at
#               960x540: `pmrender tradeoff` (CUDA; a 16 x 256-path reference) and Mitsuba 3's
#               cuda_ad_rgb path tracer against the same reference (docs/tradeoff.md); needs the
#               bundle made with `bench/pack_for_gpu.sh .gpu --mitsuba`
set -uo pipefail
out=$1; shift
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bundle=$here/.gpu
# shellcheck disable=SC1091
source "$bundle/env.sh"
export PM_TEST_DATA_DIR=$bundle/data PM_PMRENDER_BINARY=$bundle/bin/pmrender
mkdir -p "$out"
log() { echo "[$(date -u +%H:%M:%S)] $*"; }
{ nvidia-smi; pmrender devices; cat "$bundle/COMMIT"; } >"$out/machine.txt" 2>&1

ncu_bin=$(command -v ncu || ls /opt/nvidia/nsight-compute/*/ncu 2>/dev/null | head -n 1)
sanitizer=$(command -v compute-sanitizer || ls /usr/local/cuda/bin/compute-sanitizer 2>/dev/null | head -n 1)

for step in "$@"; do
  log "step $step"
  case $step in
    tests)
      "$bundle/bin/pm_gpu_tests" >"$out/gpu_tests.txt" 2>&1; echo "pm_gpu_tests exit $?" | tee -a "$out/summary.txt"
      "$bundle/bin/pm_opencl_tests" >"$out/opencl_tests.txt" 2>&1; echo "pm_opencl_tests exit $?" | tee -a "$out/summary.txt"
      grep -E "^\[  (PASSED|FAILED)|tests? ran|SKIPPED \]" "$out"/gpu_tests.txt "$out"/opencl_tests.txt | tee -a "$out/summary.txt"
      ;;
    accuracy)
      suite=$bundle/bench/accuracy_suite.sh
      all="builtin cornell-mcguire sponza sibenik conference glossy mirror-box ring three-lights"
      if [ "${ACCURACY_CI:-1}" != 0 ]; then
        "$suite" --backend cuda --out "$out/accuracy-ci" --size 96x54 --ref-spp 65536 --scenes "$all" --only-references \
          >"$out/accuracy-ci.log" 2>&1
        "$suite" --backend cuda --out "$out/accuracy-ci" --size 96x54 --ref-spp 65536 --bounces 1 --only-references \
          >>"$out/accuracy-ci.log" 2>&1
        tar czf "$out/accuracy-ci.tgz" -C "$out" accuracy-ci && rm -rf "$out/accuracy-ci"
      fi
      extra=()
      IFS=';' read -r -a rows <<<"${ACCURACY_CONFIGS:-}"
      for r in ${rows[@]+"${rows[@]}"}; do extra+=(--config "$r"); done
      [ "${ACCURACY_DEFAULTS:-1}" = 0 ] && extra+=(--no-defaults)
      [ -n "${ACCURACY_SCENES:-}" ] && extra+=(--scenes "$ACCURACY_SCENES")
      "$suite" --backend cuda --out "$out/accuracy" --size "${ACCURACY_SIZE:-960x540}" --ref-spp 4096 \
        --bounces "${ACCURACY_BOUNCES:-2}" ${extra[@]+"${extra[@]}"} >"$out/accuracy.log" 2>&1
      echo "accuracy suite exit $?" | tee -a "$out/summary.txt"; cat "$out/accuracy/accuracy.tsv" >>"$out/summary.txt"
      cat "$out/accuracy/references.txt" >>"$out/summary.txt" 2>/dev/null
      rm -f "$out"/accuracy/*.exr
      ;;
    paper)
      "$bundle/bench/run_suite.sh" --backend cuda,opencl --profile paper --knn --unclipped --out "$out/paper" >"$out/paper.log" 2>&1
      echo "paper suite exit $?" | tee -a "$out/summary.txt"; cat "$out/paper/summary.md" >>"$out/summary.txt"
      ;;
    production)
      "$bundle/bench/run_suite.sh" --backend cuda,opencl --profile production --unclipped --out "$out/production" \
        >"$out/production.log" 2>&1
      echo "production suite exit $?" | tee -a "$out/summary.txt"; cat "$out/production/summary.md" >>"$out/summary.txt"
      ;;
    ncu)
      "$ncu_bin" --clock-control none \
        -k 'regex:pm_(gather|photon_trace|camera_pass|photon_map_bottom_up|photon_map_nodes|photon_footprint[a-z_]*|photon_morton|sort_scatter)$' \
        --launch-count 60 --section SpeedOfLight --section Occupancy --section LaunchStats \
        --section WarpStateStats --section MemoryWorkloadAnalysis \
        --metrics smsp__thread_inst_executed_per_inst_executed.ratio,l1tex__t_sector_hit_rate.pct,lts__t_sector_hit_rate.pct \
        pmrender bench "$bundle/bench/scenes/sponza.json" --backend cuda --resolution 1920x1080 --photons 1048576 \
        --smoothing 40 --rmax 0.7 --warmup 0 --repeat 2 >"$out/ncu.txt" 2>&1
      echo "ncu exit $?" | tee -a "$out/summary.txt"
      ;;
    sanitizer)
      for tool in memcheck racecheck; do
        "$sanitizer" --tool $tool --error-exitcode 99 pm_gpu_tests >"$out/sanitizer_$tool.txt" 2>&1
        echo "compute-sanitizer $tool exit $?: $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$out/sanitizer_$tool.txt" | tail -n 1)" \
          | tee -a "$out/summary.txt"
      done
      ;;
    radiosity)
      for s in conference conference-69k sponza sibenik; do
        pmrender bench "$bundle/bench/scenes/$s.json" --backend cuda --method radiosity --sides one --directions 256 \
          --bounces 3 --resolution 512x512 --warmup 0 --repeat 1 >"$out/radiosity-paper-$s.txt" 2>&1
        echo "radiosity paper $s exit $?" | tee -a "$out/summary.txt"
      done
      "$bundle/bench/radiosity_suite.sh" --backend cuda,opencl --out "$out/radiosity" >"$out/radiosity.log" 2>&1
      echo "radiosity suite exit $?" | tee -a "$out/summary.txt"; cat "$out/radiosity/summary.md" >>"$out/summary.txt"
      ;;
    tradeoff)
      # shellcheck disable=SC2086
      "$bundle/bench/tradeoff_suite.sh" --profile h200 --backend cuda --scenes "${TRADEOFF_SCENES:-sponza}" \
        ${TRADEOFF_ARGS:-} --out "$out/tradeoff" >"$out/tradeoff.log" 2>&1
      echo "tradeoff suite exit $?" | tee -a "$out/summary.txt"; cat "$out/tradeoff/summary.md" >>"$out/summary.txt"
      ;;
    multi)
      "$bundle/bench/multi_gpu_suite.sh" --backend cuda,opencl --out "$out/multi" >"$out/multi.log" 2>&1
      echo "multi-GPU suite exit $?" | tee -a "$out/summary.txt"; cat "$out/multi/summary.md" >>"$out/summary.txt"
      ;;
    progressive)
      "$bundle/bench/progressive_suite.sh" --backend cuda,opencl --out "$out/progressive" >"$out/progressive.log" 2>&1
      echo "progressive suite exit $?" | tee -a "$out/summary.txt"; cat "$out/progressive/summary.md" >>"$out/summary.txt"
      ;;
    mitsuba)
      site=$(mktemp -d) && tar xJf "$bundle/mitsuba-site.tar.xz" -C "$site"
      for scene in ${MITSUBA_SCENES:-sponza}; do
        # The suite's s per scene (bench/run_suite.sh); the box's own s keeps its gathers small.
        case $scene in sponza) s=40 ;; conference) s=22.5 ;; sibenik) s=60 ;; cornell-mcguire) s=6 ;;
          *) echo "mitsuba: unknown scene $scene" | tee -a "$out/summary.txt"; continue ;; esac
        dir=$out/mitsuba/$scene
        pmrender tradeoff "$bundle/bench/scenes/$scene.json" --backend cuda --resolution 960x540 \
          --reference-spp 256 --reference-passes 16 --bounces 2 --mirror-depth 1 --rmax 0.7 \
          --estimators pd,knn,path --photons 1048576 --passes 1,4,16,64 --progressive average,shrink \
          --smoothing "$s" --k 64 --spp 4,16 --warmup 1 --repeat 3 -q -o "$dir" >"$out/mitsuba-$scene-tradeoff.log" 2>&1
        echo "mitsuba $scene: pmrender tradeoff exit $?" | tee -a "$out/summary.txt"; cat "$dir/tradeoff.txt" >>"$out/summary.txt"
        PYTHONPATH=$site PYTHONUNBUFFERED=1 python3 "$bundle/bench/mitsuba_peer.py" "$bundle/bench/scenes/$scene.json" \
          --reference "$dir/reference.exr" --pmrender "$bundle/bin/pmrender" --variant cuda_ad_rgb \
          --json "$dir/mitsuba.json" >"$out/mitsuba-$scene-peer.log" 2>&1
        echo "mitsuba $scene: peer exit $?" | tee -a "$out/summary.txt"; cat "$out/mitsuba-$scene-peer.log" >>"$out/summary.txt"
      done
      ;;
    *) echo "unknown step $step" | tee -a "$out/summary.txt" ;;
  esac
done
log done
# Images stay behind (the device tool brings back at most 16 MiB a file); the numbers come back.
tar czf "$out.tgz" --exclude='*.exr' -C "$(dirname "$out")" "$(basename "$out")"
