#!/usr/bin/env bash
# Builds the bundle for the GPU machine (default .gpu/, ignored by git): the binaries with their
# shared libraries (../shared/tools/device-bundle), the test data, the benchmark suite and the scene
# files it reads. Run from anywhere after `cmake --build build`.
#
#   bench/pack_for_gpu.sh [OUT_DIR] [--mitsuba]
#
# --mitsuba adds Mitsuba 3 for the GPU machine's Python (3.12): its wheels and drjit's, downloaded
# with pip and cut down to the cuda_ad_rgb and scalar_rgb variants and the plugins
# tests/mitsuba/pm_mitsuba.py's scenes load (the whole wheel, 62 MB, would not fit beside the rest),
# as OUT_DIR/mitsuba-site.tar.xz: a folder for PYTHONPATH (bench/gpu_check.sh's `mitsuba` step).
#
# Layout:
#   OUT_DIR/bin, lib, env.sh      device-bundle's output
#   OUT_DIR/data/                 tests/data (PM_TEST_DATA_DIR for the bundled test binaries)
#   OUT_DIR/bench/run_suite.sh    the suites (and radiosity_suite.sh, suite_common.sh); find ../bin/pmrender and ../env.sh
#   OUT_DIR/bench/tradeoff_suite.sh, mitsuba_peer.py, OUT_DIR/tests/mitsuba/pm_mitsuba.py:
#                                 the speed/accuracy suite and its Mitsuba peer (docs/tradeoff.md)
#   OUT_DIR/bench/accuracy_suite.sh, OUT_DIR/golden/scenes/: references and biases (docs/accuracy.md)
#   OUT_DIR/bench/startup_suite.sh: start-up to the first frame, program cache cold and warm
#   OUT_DIR/bench/scenes/*.json   the bench scene files, paths rewritten to ../../shared/scenes/
#   OUT_DIR/shared.tar.xz         the OBJ and MTL files they name and the images of the MTL files'
#                                 map_Kd and map_d statements, as shared/scenes/...; env.sh unpacks
#                                 it on first use
#   OUT_DIR/COMMIT                the commit the binaries were built from
#
# On the GPU machine, from the folder that holds OUT_DIR:
#   OUT_DIR/bench/run_suite.sh --backend cuda,opencl --out suite --paper-tables --knn
#   tar czf "$OUT/suite.tgz" suite
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "$repo/../shared" && pwd)
out=$repo/.gpu mitsuba=0
for arg in "$@"; do
  case $arg in --mitsuba) mitsuba=1 ;; -*) echo "pack_for_gpu.sh: unknown option '$arg'" >&2; exit 2 ;; *) out=$arg ;; esac
done
limit_mib=60
mitsuba_version=3.9.1 drjit_version=1.5.0

binaries=("$repo/build/pmrender" "$repo/build/tests/pm_gpu_tests" "$repo/build/tests/pm_opencl_tests")
for b in "${binaries[@]}"; do
  [ -x "$b" ] || { echo "pack_for_gpu.sh: $b is missing: build first (cmake --build build)" >&2; exit 2; }
done

"$shared/tools/device-bundle" "$out" "${binaries[@]}" >/dev/null
cp -r "$repo/tests/data" "$out/data"
mkdir -p "$out/bench/scenes" "$out/shared/scenes"
cp "$repo/bench/run_suite.sh" "$repo/bench/radiosity_suite.sh" "$repo/bench/multi_gpu_suite.sh" "$repo/bench/suite_common.sh" \
   "$repo/bench/tradeoff_suite.sh" "$repo/bench/progressive_suite.sh" "$repo/bench/mitsuba_peer.py" "$repo/bench/gpu_check.sh" \
   "$repo/bench/accuracy_suite.sh" "$repo/bench/startup_suite.sh" "$out/bench/"
# The golden scenes (small, with their meshes) for the accuracy suite's references.
mkdir -p "$out/golden"
cp -r "$repo/golden/scenes" "$out/golden/"
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
      [ -f "$objdir/$mtl" ] || continue
      cp "$objdir/$mtl" "$out/shared/scenes/$(dirname "$rel")/"
      # The images of its map_Kd and map_d statements (the last word: options come first),
      # relative to the MTL file's folder, to the same place beside the MTL in the bundle.
      mtldir=$(dirname "$objdir/$mtl")
      mapfile -t images < <(tr -d '\r' <"$objdir/$mtl" | awk '$1 == "map_Kd" || $1 == "map_d" { print $NF }' | sort -u)
      for image in ${images[@]+"${images[@]}"}; do
        [ -f "$mtldir/$image" ] || { echo "pack_for_gpu.sh: $objdir/$mtl: image '$image' does not exist" >&2; exit 2; }
        dest=$out/shared/scenes/$(dirname "$rel")/$image
        mkdir -p "$(dirname "$dest")"
        cp "$mtldir/$image" "$dest"
      done
    done
  done
done

# The scenes travel compressed (OBJ text: 28 MiB as files, a sixth of that as xz); the bundle's
# env.sh unpacks them beside itself the first time it is sourced.
tar cJf "$out/shared.tar.xz" -C "$out" shared
rm -rf "$out/shared"
cat >>"$out/env.sh" <<'UNPACK'
[ -d "$here/shared" ] || tar xJf "$here/shared.tar.xz" -C "$here"
UNPACK

if [ "$mitsuba" = 1 ]; then
  wheels=$(mktemp -d) site=$(mktemp -d)
  python3 -m pip download -q --no-deps --only-binary=:all: --python-version 3.12 --implementation cp \
    --platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 --platform manylinux_2_17_x86_64 \
    --platform manylinux2014_x86_64 -d "$wheels" "mitsuba==$mitsuba_version" "drjit==$drjit_version"
  for w in "$wheels"/*.whl; do (cd "$site" && python3 -m zipfile -e "$w" .); done
  # Variants: cuda_ad_rgb (the peer) and scalar_rgb; plugins: what pm_mitsuba.py's scene dictionaries
  # instantiate (an OBJ loaded through "merge", two-sided diffuse, conductor and blendbsdf for
  # mirrors, point lights, the path integrator, a perspective camera, an RGB film).
  for so in "$site"/mitsuba/*.cpython-*.so; do
    case $(basename "$so" | sed 's/\.cpython.*//') in mitsuba_ext|mitsuba_alias|cuda_ad_rgb|scalar_rgb) ;; *) rm -f "$so" ;; esac
  done
  for so in "$site"/mitsuba/plugins/*.so; do
    case $(basename "$so" .so) in
      path|perspective|hdrfilm|box|independent|obj|merge|point|diffuse|twosided|conductor|blendbsdf|srgb|d65|uniform|constant|bitmap) ;;
      *) rm -f "$so" ;;
    esac
  done
  rm -rf "$site"/mitsuba/{include,pkgconfig,cmake,mitsuba_stubs} "$site"/drjit/{include,cmake} \
    "$site"/mitsuba/data/srgb.coeff "$site"/mitsuba/data/sunsky
  find "$site" -name '*.pyi' -delete
  tar cJf "$out/mitsuba-site.tar.xz" -C "$site" .
  rm -rf "$wheels" "$site"
fi

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
