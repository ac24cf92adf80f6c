#!/usr/bin/env bash
# Builds the bundle for the GPU machine (default .gpu/, ignored by git): the binaries with their
# shared libraries (../shared/tools/device-bundle), the test data, the benchmark suite and the scene
# files it reads. Run from anywhere after `cmake --build build`.
#
#   bench/pack_for_gpu.sh [OUT_DIR]
#
# Layout:
#   OUT_DIR/bin, lib, env.sh      device-bundle's output
#   OUT_DIR/data/                 tests/data (PM_TEST_DATA_DIR for the bundled test binaries)
#   OUT_DIR/bench/run_suite.sh    the suites (and radiosity_suite.sh, suite_common.sh); find ../bin/pmrender and ../env.sh
#   OUT_DIR/bench/tradeoff_suite.sh, mitsuba_peer.py, OUT_DIR/tests/mitsuba/pm_mitsuba.py:
#                                 the speed/accuracy suite and its Mitsuba peer (docs/tradeoff.md)
#   OUT_DIR/bench/scenes/*.json   the bench scene files, paths rewritten to ../../shared/scenes/
#   OUT_DIR/shared/scenes/...     the OBJ and MTL files they name (no textures: nothing reads them)
#   OUT_DIR/COMMIT                the commit the binaries were built from
#
# On the GPU machine, from the folder that holds OUT_DIR:
#   OUT_DIR/bench/run_suite.sh --backend cuda,opencl --out suite --paper-tables --knn
#   tar czf "$OUT/suite.tgz" suite
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "$repo/../shared" && pwd)
out=${1:-$repo/.gpu}
limit_mib=60

binaries=("$repo/build/pmrender" "$repo/build/tests/pm_gpu_tests" "$repo/build/tests/pm_opencl_tests")
for b in "${binaries[@]}"; do
  [ -x "$b" ] || { echo "pack_for_gpu.sh: $b is missing: build first (cmake --build build)" >&2; exit 2; }
done

"$shared/tools/device-bundle" "$out" "${binaries[@]}" >/dev/null
cp -r "$repo/tests/data" "$out/data"
mkdir -p "$out/bench/scenes" "$out/shared/scenes"
cp "$repo/bench/run_suite.sh" "$repo/bench/radiosity_suite.sh" "$repo/bench/multi_gpu_suite.sh" "$repo/bench/suite_common.sh" \
   "$repo/bench/tradeoff_suite.sh" "$repo/bench/mitsuba_peer.py" "$repo/bench/gpu_check.sh" "$out/bench/"
# The Mitsuba converter mitsuba_peer.py imports (docs/tradeoff.md, "H200 (CUDA)").
mkdir -p "$out/tests/mitsuba"
cp "$repo/tests/mitsuba/pm_mitsuba.py" "$repo/tests/mitsuba/requirements.txt" "$out/tests/mitsuba/"

# The scene JSONs name their meshes as ../../../shared/scenes/<path> (relative to bench/scenes/ in
# the repository); in the bundle, bench/scenes/ is two levels below the bundle's shared/.
prefix='../../../shared/scenes/'
for json in "$repo"/bench/scenes/*.json; do
  sed "s#\"$prefix#\"../../shared/scenes/#g" "$json" >"$out/bench/scenes/$(basename "$json")"
  grep -o "\"file\": *\"[^\"]*\"" "$json" | sed 's/^"file": *"//; s/"$//' | while read -r file; do
    case $file in "$prefix"*) ;; *) echo "pack_for_gpu.sh: $json: mesh '$file' is not under $prefix" >&2; exit 2 ;; esac
    rel=${file#"$prefix"}
    src=$shared/scenes/$rel
    [ -f "$src" ] || { echo "pack_for_gpu.sh: $json: $src does not exist" >&2; exit 2; }
    mkdir -p "$out/shared/scenes/$(dirname "$rel")"
    cp "$src" "$out/shared/scenes/$rel"
    # MTL files the OBJ names, from the OBJ's folder (CRLF tolerated).
    objdir=$(dirname "$src")
    mapfile -t mtls < <(tr -d '\r' <"$src" | awk '$1 == "mtllib" { for (i = 2; i <= NF; ++i) print $i }')
    for mtl in ${mtls[@]+"${mtls[@]}"}; do
      if [ -f "$objdir/$mtl" ]; then cp "$objdir/$mtl" "$out/shared/scenes/$(dirname "$rel")/"; fi
    done
  done
done

commit=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)
git -C "$repo" diff --quiet HEAD -- 2>/dev/null || commit="$commit (with uncommitted changes)"
echo "$commit" >"$out/COMMIT"

size_kib=$(du -sk "$out" | cut -f1)
echo "bundle $out: $((size_kib / 1024)) MiB (commit $commit)"
du -sh "$out"/* | sed 's/^/  /'
if [ "$size_kib" -ge $((limit_mib * 1024)) ]; then
  echo "pack_for_gpu.sh: the bundle is $((size_kib / 1024)) MiB, over the ${limit_mib} MiB limit" >&2
  exit 1
fi
