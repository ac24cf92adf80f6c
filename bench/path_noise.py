#!/usr/bin/env python3
"""The path tracer's noise per path against Mitsuba 3's (docs/tradeoff.md, "Noise per path").

Renders a scene twice (seeds 1 and 2) with `pmrender render --method path --spp N` and twice with
Mitsuba 3's own `path` integrator (the converter of tests/mitsuba/pm_mitsuba.py: the same
triangles, materials, lights and pixel-centre camera), and prints for each renderer the variance
of one path's estimate relative to the image's light, mean over pixels of (a - b)^2 / 2 times the
samples per pixel over the squared image mean, and the two renderers' ratio. Both images hold
direct and indirect light; with one point or spot light, the direct light at a pixel centre is the
same in every render of both renderers, so the variance is the indirect light's alone (the script
refuses scenes with emitting triangles, an environment or several lights, whose direct light
Mitsuba samples).

  build/pyenv/bin/python bench/path_noise.py --pmrender build/pmrender [SCENE] [--size 64]
      [--pm-spp 256] [--mi-spp 256] [--bounces 2] [--backend auto]

SCENE is a pmrender scene file (none: the built-in Cornell box)."""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "mitsuba"))
import mitsuba  # noqa: E402
import pm_mitsuba  # noqa: E402


def relative_variance_per_sample(a, b, spp):
    """One sample's variance at a pixel, over pixels and channels, relative to the squared mean."""
    return float(((a - b) ** 2).mean() / 2.0 * spp / (0.5 * (a + b)).mean() ** 2)


def pmrender_image(args, work, seed):
    out = os.path.join(work, "pm%d.exr" % seed)
    cmd = [args.pmrender, "render"] + ([args.scene] if args.scene else []) + [
        "--method", "path", "--spp", str(args.pm_spp), "--bounces", str(args.bounces), "--mirror-depth", "1",
        "--backend", args.backend, "--resolution", "%dx%d" % (args.size, args.size), "--seed", str(seed),
        "--float", "-q", "-o", out]
    subprocess.run(cmd, check=True)
    layers = dict(mitsuba.Bitmap(out).split())
    return np.array(layers["<root>"], dtype=np.float64)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default="")
    parser.add_argument("--pmrender", required=True)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--pm-spp", type=int, default=256)
    parser.add_argument("--mi-spp", type=int, default=256)
    parser.add_argument("--bounces", type=int, default=2)
    parser.add_argument("--backend", default="auto")
    parser.add_argument("--variant", default="scalar_rgb", help="Mitsuba variant (llvm_ad_rgb, cuda_ad_rgb: faster)")
    args = parser.parse_args()
    pm_mitsuba.set_variant(args.variant)
    with tempfile.TemporaryDirectory() as work:
        exported = os.path.join(work, "scene.json")
        subprocess.run([args.pmrender, "export-scene"] + ([args.scene] if args.scene else []) + ["-o", exported],
                       check=True, stdout=subprocess.DEVNULL)
        with open(exported) as f:
            scene = json.load(f)
        if any(max(m.get("emission", [0])) > 0 for m in scene["materials"].values()) or scene.get("environment"):
            sys.exit("path_noise.py: %s has sampled direct light (emitting triangles or an environment); "
                     "use a scene lit by point and spot lights" % (args.scene or "the built-in box"))
        if len(scene.get("lights", [])) != 1:
            sys.exit("path_noise.py: %s has %d lights; Mitsuba samples one light per vertex, so its direct "
                     "light would carry noise of its own: use a scene with one point or spot light"
                     % (args.scene or "the built-in box", len(scene.get("lights", []))))
        if any(max(m["mirror"]) > 0 for m in scene["materials"].values()):
            sys.exit("path_noise.py: %s has mirrors, whose paths the two renderers count differently "
                     "(tests/mitsuba/README.md)" % (args.scene or "the built-in box"))
        start = time.time()
        pm = [pmrender_image(args, work, seed) for seed in (1, 2)]
        pm_seconds = (time.time() - start) / 2
        mi_scene = mitsuba.load_dict(pm_mitsuba.scene_dict(exported, args.bounces + 2, args.size, args.size))
        start = time.time()
        mi = [pm_mitsuba.render(mi_scene, args.mi_spp, seed=seed) for seed in (1, 2)]
        mi_seconds = (time.time() - start) / 2
    pm_var = relative_variance_per_sample(pm[0][..., :3], pm[1][..., :3], args.pm_spp)
    mi_var = relative_variance_per_sample(mi[0][..., :3], mi[1][..., :3], args.mi_spp)
    print("%-10s %6s %12s %10s" % ("renderer", "spp", "var/path", "s/render"))
    print("%-10s %6d %12.5f %10.2f" % ("pmrender", args.pm_spp, pm_var, pm_seconds))
    print("%-10s %6d %12.5f %10.2f" % ("mitsuba", args.mi_spp, mi_var, mi_seconds))
    print("ratio pmrender / mitsuba: %.3f (image means %.5g / %.5g)" %
          (pm_var / mi_var, float(np.mean(pm)), float(np.mean(mi))))


if __name__ == "__main__":
    main()
