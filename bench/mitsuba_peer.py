#!/usr/bin/env python3
"""Mitsuba 3's path tracer as the peer of docs/tradeoff.md: renders a pmrender scene with
Mitsuba at increasing samples per pixel and reports, for each, the time and the error against a
reference image (normally the path-traced reference.exr of `pmrender tradeoff`), so its
time to reach 5 %, 2 %, 1 % and 0.5 % relative mean absolute error sits beside pmrender's.

    python3 bench/mitsuba_peer.py SCENE.json --reference OUT/sponza/reference.exr \
        --pmrender build/pmrender --variant cuda_ad_rgb --spp 1,2,4,...,1024 --json peer.json

SCENE is a pmrender scene file (or "cornell-box" for the built-in one); it goes through
`pmrender export-scene`, then tests/mitsuba/pm_mitsuba.py (the converter the Mitsuba test uses:
samples at pixel centres, modified Phong as a Mitsuba plugin, power / 4 pi as intensity).
Bounces: max_depth = --bounces + 2, exact on scenes without mirrors. Time: wall time of the
render with the device synchronised, after one untimed render that compiles Mitsuba's kernels;
renders above --chunk-spp samples run as several renders (their times summed), as pmrender's
passes do."""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "mitsuba"))

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402

import pm_mitsuba  # noqa: E402


def relative_errors(image, reference):
    """relMAE and relMSE as pmrender tradeoff computes them, and the bias of the image mean: the
    check that the two renderers converge to the same image, beyond noise."""
    diff = image - reference
    relmae = float(np.abs(diff).sum() / np.abs(reference).sum())
    relmse = float(np.mean(diff ** 2 / (reference ** 2 + 0.01)))
    mean = float(image.sum() / reference.sum() - 1.0)
    return relmae, relmse, mean


def timed_render(scene, spp, seed, chunk):
    """Mean image of spp samples per pixel, and the seconds the renders took."""
    total, seconds, done, k = None, 0.0, 0, 0
    while done < spp:
        n = min(chunk, spp - done)
        start = time.perf_counter()
        image = mi.render(scene, spp=n, seed=seed * 7919 + k)
        dr.eval(image)
        dr.sync_thread()
        seconds += time.perf_counter() - start
        part = np.array(image, dtype=np.float64) * n
        total = part if total is None else total + part
        done += n
        k += 1
    return total / spp, seconds


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene", help="pmrender scene file, or cornell-box")
    p.add_argument("--reference", required=True, help="reference EXR (combined layer), e.g. tradeoff's reference.exr")
    p.add_argument("--pmrender", default=os.path.join(HERE, "..", "build", "pmrender"))
    p.add_argument("--variant", default="cuda_ad_rgb", help="Mitsuba variant (cuda_ad_rgb, llvm_ad_rgb, scalar_rgb)")
    p.add_argument("--spp", default="1,2,4,8,16,32,64,128,256,512,1024")
    p.add_argument("--chunk-spp", type=int, default=64, help="most samples per pixel in one render")
    p.add_argument("--bounces", type=int, default=2)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--levels", default="0.05,0.02,0.01,0.005")
    p.add_argument("--json", help="write the results here too")
    args = p.parse_args()

    pm_mitsuba.set_variant(args.variant)
    reference = pm_mitsuba_layers(args.reference)
    height, width = reference.shape[:2]
    with tempfile.TemporaryDirectory() as work:
        exported = os.path.join(work, "scene.json")
        scene_args = [] if args.scene == "cornell-box" else [args.scene]
        subprocess.run([args.pmrender, "export-scene"] + scene_args + ["-o", exported], check=True,
                       stdout=subprocess.DEVNULL)
        with open(exported) as f:
            if any(max(m["mirror"]) > 0 for m in json.load(f)["materials"].values()):
                print("mitsuba_peer: warning: the scene has mirrors; Mitsuba counts mirror reflections as depth, "
                      "pmrender does not (tests/mitsuba/compare_with_mitsuba.py)", file=sys.stderr)
        scene = mi.load_dict(pm_mitsuba.scene_dict(exported, args.bounces + 2, width, height))

    timed_render(scene, 1, 0, args.chunk_spp)  # compiles the kernels; not timed
    rows = []
    print("Mitsuba %s (%s), %dx%d, max_depth %d, reference %s" % (mi.__version__, args.variant, width, height,
                                                                  args.bounces + 2, args.reference))
    print("%8s %12s %10s %10s %9s" % ("spp", "seconds", "relMAE", "relMSE", "mean"))
    for spp in [int(s) for s in args.spp.split(",")]:
        image, seconds = timed_render(scene, spp, args.seed, args.chunk_spp)
        relmae, relmse, mean = relative_errors(image, reference)
        rows.append({"spp": spp, "seconds": seconds, "relmae": relmae, "relmse": relmse, "mean": mean})
        print("%8d %12.4f %9.3f%% %10.4g %+8.2f%%" % (spp, seconds, 100 * relmae, relmse, 100 * mean))
        sys.stdout.flush()
    reach = []
    for level in [float(x) for x in args.levels.split(",")]:
        hits = [r for r in rows if r["relmae"] <= level]
        best = min(hits, key=lambda r: r["seconds"]) if hits else None
        reach.append({"relmae": level, "seconds": best["seconds"] if best else None, "spp": best["spp"] if best else None})
        print("time to reach %g%% relMAE: %s" % (100 * level, "%.4f s (%d spp)" % (best["seconds"], best["spp"])
                                                  if best else "not reached"))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"mitsuba": mi.__version__, "variant": args.variant, "width": width, "height": height,
                       "max_depth": args.bounces + 2, "reference": args.reference, "rows": rows, "reach": reach}, f,
                      indent=2)


def pm_mitsuba_layers(path):
    """The combined layer of an EXR written by pmrender, as float64 (height, width, 3)."""
    for name, layer in mi.Bitmap(path).split():
        if name == "<root>":
            return np.array(layer, dtype=np.float64)
    sys.exit("mitsuba_peer: %s has no combined layer" % path)


if __name__ == "__main__":
    main()
