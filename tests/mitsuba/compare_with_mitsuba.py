#!/usr/bin/env python3
"""pmrender's path tracer against Mitsuba 3 on every golden scene, the built-in Cornell box and
the light and texture cases of light_scenes.py (a spot light, an emitting panel, a textured
floor, an open corner under an environment map), where photon mapping (pd), radiosity and final
gathering over each of them are checked against the same reference too
(ctest `mitsuba`; tests/mitsuba/README.md says how to run it and why the tolerances are what
they are). Exit code 0 when every scene agrees within the noise of both renderers and every
injected bias is detected, 1 otherwise (also when Mitsuba is missing), 2 on bad arguments.

Per scene: `pmrender export-scene` writes what pmrender loaded; Mitsuba renders that (scalar_rgb,
samples at pixel centres, pm_mitsuba.py); pmrender renders the original scene with
`--method path`. Each renderer renders twice with different seeds, so the noise of each is
measured, not assumed. Compared: means over square regions of the combined image, and the image
mean.
  - regions: relative mean absolute difference of the region means (every channel) of the two
    averaged images must be <= 1.5 x what pure noise would give, sqrt(D_pm^2 + D_mi^2) / 2 with
    D the same difference between a renderer's two seeds, plus 0.2 % for rounding;
  - image mean: |difference| <= 4 standard errors (from the region differences of the seeds).
Bias must fail: the same test on pmrender's image x 1.05 (5 % too much light), and on scenes
without mirrors on pmrender with one bounce fewer, must report a difference (> 4 standard
errors), or the comparison is too weak to mean anything and the scene fails.

Scenes without mirrors compare exact bounce semantics: pmrender --bounces 2 is Mitsuba
max_depth 4. With mirrors the two count paths differently (Mitsuba counts mirror reflections as
depth, pmrender does not: eye mirrors up to --mirror-depth, then up to 8 more besides the
bounces), so both render to convergence instead: pmrender --bounces 16 --mirror-depth 8 against
Mitsuba max_depth -1 (Russian roulette, unbiased); what pmrender then leaves out is below
0.1 % here. Neither renderer samples light that leaves a point light through a perfect mirror
(docs/tradeoff.md), so the same light paths are compared.

Light and texture cases, besides the above: the bias of the indirect light with the direct light
matched (indirect_bias), of the path tracer (tolerance: 4 standard errors), of pd and of
radiosity at their defaults and of final gathering (64 rays over the pd map, fg, or over the
radiosity solution, radfg) (ctest accuracy's 1.5 % plus 4 standard errors)."""
import argparse
import glob
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
# Samples per pixel relative to --pm-spp and --mi-spp, by scene. The Cornell box's light hangs
# 1 cm under the ceiling: the bright spot it makes there reaches the rest of the room through few
# paths, so this scene needs the most samples for the same noise. The glossy scene's Mitsuba BSDF
# is Python (pm_mitsuba.py), the slowest per sample, and needs fewer for the noise wanted. The
# light and texture cases' Mitsuba samples (with its multijitter sampler, MI_SAMPLER) keep its
# noise in their indirect light at 0.17-0.27 % (standard error of the image mean), so that pd's
# and radiosity's 1.5 % target means something; area-box's 144 = 12 x 12 (multijitter rounds a
# count up to a product of two near-equal integers: 128 would be 132). On env-corner pmrender's
# path tracer takes 8 times its paths, cheaply (both seeds in 1.6 to 3.2 s; its indirect mean's
# standard error 0.08 %), to keep the path tracer's limit, 4 standard errors, small.
SAMPLE_SCALE = {"cornell-box": (4, 6), "glossy": (1, 0.5),
                "spot-box": (1, 2), "area-box": (1, 1.125), "textured-box": (1, 2), "env-corner": (8, 2)}
ROOT = os.path.dirname(os.path.dirname(HERE))
# The light and texture cases (light_scenes.py) also check photon mapping (pd) and radiosity at
# their defaults, and final gathering over a pd map (fg: 64 rays a pass; with 16 its standard
# error was 0.8-1.2 % and a 5 % error passed) and over the radiosity solution (radfg: 64 rays,
# the solution with one bounce fewer and 64 link directions, since it supplies only the light
# beyond the rays' hits: 1.5-2.9 s a case where 256 took 3.8-9.6 s, the same biases within
# 0.1 %), against Mitsuba: their indirect light's bias, the direct light matched, within
# ctest accuracy's 1.5 % target plus the noise of the comparison (indirect_bias). The error
# estimate's control paths are left out (they change the estimate, not the image).
METHODS = {"pd": ["--method", "photon", "--estimator", "pd", "--control-paths", "0"],
           "radiosity": ["--method", "radiosity", "--control-paths", "0"],
           "fg": ["--method", "photon", "--estimator", "pd", "--final-gather", "64", "--photons", "65536",
                  "--control-paths", "0"],
           "radfg": ["--method", "radiosity", "--final-gather", "64", "--directions", "64", "--control-paths", "0"]}
# pmrender options of a case, by method. env-corner: 256 environment samples per pixel in the
# direct light (the camera pass), not 16, for the path tracer and pd: at 16 the standard error of
# pmrender's direct image mean (0.44 % per seed) alone kept pd's indirect light 5 % too high or
# too low from being caught. Radiosity keeps its default 16: the option also sets its light
# links' environment samples per element, and at 256 its two renders took 17.9 s. pd averages
# two of its default passes (262,144 photons each) per seed: with one, the standard error of its
# indirect mean was 0.44 % against 0.28 % with two, and its limit 3.56 % against 3.04 %, close
# to where an indirect light 5 % off would pass. fg (64 gather rays over 65,536 photons a pass)
# averages four passes there: with one its standard error was 0.63 % and a 5 % error passed.
CASE_OPTIONS = {"env-corner": {"path": ["--area-light-samples", "256"],
                              "pd": ["--area-light-samples", "256", "--passes", "2"],
                              "fg": ["--area-light-samples", "256", "--passes", "4"],
                              "radfg": ["--passes", "4"]}}
# Mitsuba's sampler by case (default `independent`). A light case's indirect light is the
# difference of Mitsuba's full render and its max_depth 2 render with the same seed, but
# `independent` draws one sequential stream per pixel, so the two renders share no random numbers
# after a pixel's first sample and the difference carries the direct light's noise: on env-corner
# (256 samples per seed) the standard error of Mitsuba's indirect image mean was 0.98 %, as much
# in absolute terms as that of its direct light alone. `multijitter` (stratified, a permutation
# per dimension keyed by the sample index) gave 0.21 % at the same samples, and its means matched
# `independent`'s at 4096 samples (direct -0.1 %, indirect -0.06 %). On the other light cases it
# gave lower standard errors at half the samples or fewer (tests/mitsuba/README.md).
MI_SAMPLER = {"spot-box": "multijitter", "area-box": "multijitter", "textured-box": "multijitter",
              "env-corner": "multijitter"}
# The bias allowed beyond the noise: ctest accuracy's target for pd and radiosity; none for the
# path tracer, which is unbiased.
INDIRECT_TOLERANCE = {"path": 0.0, "pd": 0.015, "radiosity": 0.015, "fg": 0.015, "radfg": 0.015}


def fail(message):
    print("compare_with_mitsuba: " + message, file=sys.stderr)
    sys.exit(1)


try:
    import numpy as np
    import mitsuba  # noqa: F401  (checked here so a missing install fails with this message)
except ImportError as e:
    fail("%s: Mitsuba 3 and numpy are needed (tests/mitsuba/install.sh creates the virtual "
         "environment; cmake -DPMRENDER_TEST_PYTHON=... points the test at it)" % e)

sys.path.insert(0, HERE)
import light_scenes  # noqa: E402
import pm_mitsuba  # noqa: E402

LIGHT_CASES = ("spot-box", "area-box", "textured-box", "env-corner")
# The cases lit by an environment.
ENVIRONMENT_CASES = ("env-corner",)


def read_exr_layers(path):
    bitmap = mitsuba.Bitmap(path)
    return {("combined" if name == "<root>" else name): np.array(b, dtype=np.float64) for name, b in bitmap.split()}


def region_means(image, block):
    h, w, c = image.shape
    return image[: h - h % block, : w - w % block].reshape(h // block, block, w // block, block, c).mean(axis=(1, 3))


def rel_mad(a, b):
    """Relative mean absolute difference of two arrays of region means."""
    return float(np.abs(a - b).sum() / np.abs(b).sum())


def mean_variance(r1, r2):
    """Variance of the mean of the averaged image, from the region differences of two seeds."""
    d = (r1 - r2).sum(axis=2)  # channels of a region are not independent: one value per region
    n = d.size
    return float((d ** 2).sum() / (4.0 * n * n)) / 9.0  # per channel of the image mean


class Verdict:
    def __init__(self, pm1, pm2, mi1, mi2, block):
        self.r_pm1, self.r_pm2 = region_means(pm1, block), region_means(pm2, block)
        self.r_mi1, self.r_mi2 = region_means(mi1, block), region_means(mi2, block)
        self.noise_pm = rel_mad(self.r_pm1, self.r_pm2)
        self.noise_mi = rel_mad(self.r_mi1, self.r_mi2)
        self.var_pm = mean_variance(self.r_pm1, self.r_pm2)
        self.var_mi = mean_variance(self.r_mi1, self.r_mi2)
        self.mi = 0.5 * (self.r_mi1 + self.r_mi2)
        self.bound = 1.5 * math.sqrt(self.noise_pm ** 2 + self.noise_mi ** 2) / 2.0 + 0.002

    def judge(self, pm_regions):
        """(z of the image means, relative region difference, pass)"""
        diff = pm_regions.mean() - self.mi.mean()
        z = diff / math.sqrt(self.var_pm + self.var_mi)
        mad = rel_mad(pm_regions, self.mi)
        return float(z), mad, bool(abs(z) <= 4.0 and mad <= self.bound)


def pmrender_render(args, scene, out, seed, bounces, mirror_depth, method, options=()):
    """pmrender's layers (combined, direct, ...) of the scene rendered with the method's options
    and the case's (CASE_OPTIONS)."""
    cmd = [args.pmrender, "render"] + ([scene] if scene else []) + [
        "--backend", args.backend, "--bounces", str(bounces), "--mirror-depth", str(mirror_depth),
        "--resolution", "%dx%d" % (args.size, args.size), "--seed", str(seed), "--float", "-q", "-o", out] + method
    subprocess.run(cmd + list(options), check=True)
    return read_exr_layers(out)


def pmrender_path(args, scene, out, seed, bounces, mirror_depth, spp, layers=False, options=()):
    image = pmrender_render(args, scene, out, seed, bounces, mirror_depth, ["--method", "path", "--spp", str(spp)],
                            options)
    return image if layers else image["combined"]


def indirect_bias(pm, mi_full, mi_direct, block, tolerance):
    """pmrender's indirect light (two seeds' layers) against Mitsuba's: its bias with the direct
    light matched (render/image_metrics.h light_bias, what ctest accuracy checks): the ratio of
    indirect to direct light in pmrender's image over the same ratio in Mitsuba's, minus 1.
    Mitsuba's direct light is its max_depth 2 render (with the seeds of its full render; their
    difference is its indirect light). Standard errors from the region differences between the
    two seeds of each renderer (mean_variance), of the indirect and the direct light of both;
    pass when |bias| <= tolerance + 4 standard errors, and an indirect light 5 % too high and one
    5 % too low must both fail."""
    pm_dir = [region_means(p["direct"], block) for p in pm]
    pm_ind = [region_means(p["combined"], block) - d for p, d in zip(pm, pm_dir)]
    mi_dir = [region_means(d, block) for d in mi_direct]
    mi_ind = [region_means(f, block) - d for f, d in zip(mi_full, mi_dir)]

    def mean_and_rel_var(pair):
        m = float(0.5 * (pair[0] + pair[1]).mean())
        return m, mean_variance(pair[0], pair[1]) / (m * m)

    (pi_, vpi), (pd_, vpd) = mean_and_rel_var(pm_ind), mean_and_rel_var(pm_dir)
    (mi_, vmi), (md_, vmd) = mean_and_rel_var(mi_ind), mean_and_rel_var(mi_dir)
    ratio = (pi_ / pd_) / (mi_ / md_)
    se = ratio * math.sqrt(vpi + vpd + vmi + vmd)
    limit = tolerance + 4.0 * se

    def fails(scale):
        return abs(ratio * scale - 1.0) > limit

    return {"bias": ratio - 1.0, "se": se, "limit": limit, "rel_se": [math.sqrt(x) for x in (vpi, vpd, vmi, vmd)],
            "pass": bool(abs(ratio - 1.0) <= limit), "bias_detected": bool(fails(1.05) and fails(0.95)),
            "region_diff": rel_mad(0.5 * (pm_ind[0] + pm_ind[1]), 0.5 * (mi_ind[0] + mi_ind[1]))}


def compare_scene(args, name, scene, export_from=None, textures=None, methods=()):
    work = os.path.join(args.work, name)
    os.makedirs(work, exist_ok=True)
    exported = os.path.join(work, name + ".json")
    export_from = export_from or scene
    subprocess.run([args.pmrender, "export-scene"] + ([export_from] if export_from else []) + ["-o", exported],
                   check=True, stdout=subprocess.DEVNULL)
    with open(exported) as f:
        mirrors = any(max(m["mirror"]) > 0 for m in json.load(f)["materials"].values())
    bounces, mirror_depth, max_depth = (16, 8, -1) if mirrors else (args.bounces, 1, args.bounces + 2)

    pm_scale, mi_scale = SAMPLE_SCALE.get(name, (1, 1))
    pm_spp, mi_spp = int(args.pm_spp * pm_scale), int(args.mi_spp * mi_scale)
    start = time.time()
    options = CASE_OPTIONS.get(name, {}).get("path", ())
    pm_layers = [pmrender_path(args, scene, os.path.join(work, "pm%d.exr" % s), s, bounces, mirror_depth, pm_spp,
                               layers=True, options=options) for s in (1, 2)]
    pm = [p["combined"] for p in pm_layers]
    pm_seconds = time.time() - start
    start = time.time()
    sampler = MI_SAMPLER.get(name, "independent")
    mi_scene = mitsuba.load_dict(pm_mitsuba.scene_dict(exported, max_depth, args.size, args.size, textures, sampler))
    mi = [pm_mitsuba.render(mi_scene, mi_spp, seed=s) for s in (1, 2)]
    mi_seconds = time.time() - start

    v = Verdict(pm[0], pm[1], mi[0], mi[1], args.block)
    pm_regions = 0.5 * (v.r_pm1 + v.r_pm2)
    z, mad, ok = v.judge(pm_regions)
    row = {"scene": name, "mirrors": mirrors, "bounces": bounces, "max_depth": max_depth, "pm_spp": pm_spp,
           "mi_spp": mi_spp,
           "pm_mean": float(pm_regions.mean()), "mi_mean": float(v.mi.mean()), "z": z, "region_diff": mad,
           "bound": v.bound, "noise_pm": v.noise_pm, "noise_mi": v.noise_mi,
           "pm_seconds": pm_seconds, "mi_seconds": mi_seconds, "pass": ok}
    # Bias must fail.
    z_flux, _, ok_flux = v.judge(pm_regions * 1.05)
    row["z_flux"] = z_flux
    detected = not ok_flux
    if not mirrors:
        fewer = pmrender_path(args, scene, os.path.join(work, "pm_fewer.exr"), 3, bounces - 1, mirror_depth,
                              2 * pm_spp, options=options)
        z_fewer, _, ok_fewer = v.judge(region_means(fewer, args.block))
        row["z_fewer"] = z_fewer
        detected = detected and not ok_fewer
    row["bias_detected"] = detected
    row["pass"] = ok and detected
    if methods:
        start = time.time()
        mi_direct_scene = mitsuba.load_dict(pm_mitsuba.scene_dict(exported, 2, args.size, args.size, textures,
                                                                  sampler))
        mi_direct = [pm_mitsuba.render(mi_direct_scene, mi_spp, seed=s) for s in (1, 2)]
        row["mi_seconds"] += time.time() - start
        row["path"] = indirect_bias(pm_layers, mi, mi_direct, args.block, INDIRECT_TOLERANCE["path"])
        row["path"]["seconds"] = pm_seconds
        for method in methods:
            start = time.time()
            # Radiosity renders once: with point and spot lights its image does not depend on the
            # seed, and on area-box three seeds' indirect and direct means were within 0.06 % of
            # each other, far below Mitsuba's noise (its variance is taken as none). Under the
            # environment it renders twice: there its direct light (the camera pass's environment
            # samples) and its light links' environment samples follow the seed.
            seeds = (1,) if method == "radiosity" and name not in ENVIRONMENT_CASES else (1, 2)
            layers = [pmrender_render(args, scene, os.path.join(work, "%s%d.exr" % (method, s)), s, bounces, 1,
                                      METHODS[method], CASE_OPTIONS.get(name, {}).get(method, ())) for s in seeds]
            if len(layers) == 1:
                layers = layers * 2  # one render: no noise of its own in the standard error
            r = indirect_bias(layers, mi, mi_direct, args.block, INDIRECT_TOLERANCE[method])
            r["seconds"] = time.time() - start
            row[method] = r
    return row


def case_passes(r):
    return r["pass"] and all(r[m]["pass"] and r[m]["bias_detected"] for m in ("path",) + tuple(METHODS) if m in r)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pmrender", required=True)
    parser.add_argument("--work", required=True, help="folder for exported scenes and renders")
    parser.add_argument("--backend", default="opencl")
    parser.add_argument("--scenes", nargs="*", help="scene files (default: the built-in Cornell box and "
                        "golden/scenes/*.json; none: --scenes)")
    parser.add_argument("--size", type=int, default=32, help="image side, pixels")
    parser.add_argument("--block", type=int, default=4, help="region side, pixels")
    parser.add_argument("--bounces", type=int, default=2)
    parser.add_argument("--pm-spp", type=int, default=512, help="pmrender paths per pixel, each seed")
    parser.add_argument("--mi-spp", type=int, default=128, help="Mitsuba samples per pixel, each seed")
    parser.add_argument("--light-cases", nargs="*", default=list(LIGHT_CASES), choices=LIGHT_CASES,
                        help="the spot, area-light and texture cases to run (default: all; none: --light-cases)")
    parser.add_argument("--json", help="also write the table as JSON here")
    args = parser.parse_args()
    if args.size % args.block:
        parser.error("--size must be a multiple of --block")
    pm_mitsuba.set_variant("scalar_rgb")
    scenes = [("cornell-box", None)]
    for path in args.scenes if args.scenes is not None else sorted(glob.glob(os.path.join(ROOT, "golden/scenes/*.json"))):
        scenes.append((os.path.splitext(os.path.basename(path))[0], path))
    scenes = [(name, scene, None, None, ()) for name, scene in scenes]
    if args.scenes is not None:
        scenes = scenes[1:]
    if args.light_cases:
        for name, scene, export_from, textures in light_scenes.make_cases(args.pmrender, args.work):
            if name in args.light_cases:
                scenes.append((name, scene, export_from, textures, tuple(METHODS)))

    rows = []
    print("%-13s %-8s %9s %9s %7s %6s %8s %8s %8s %8s %6s %6s %6s %6s  %s" % (
        "scene", "paths", "pmrender", "mitsuba", "diff", "z", "regions", "bound", "x1.05 z", "B-1 z", "pm s", "mi s",
        "all s", "cpu s", "result"))
    for name, scene, export_from, textures, methods in scenes:
        start, cpu = time.time(), sum(os.times()[:4])
        r = compare_scene(args, name, scene, export_from, textures, methods)
        r["seconds"] = time.time() - start
        r["cpu_seconds"] = sum(os.times()[:4]) - cpu  # this process's threads and pmrender's
        rows.append(r)
        paths = "conv." if r["mirrors"] else "B=%d" % r["bounces"]
        print("%-13s %-8s %9.5f %9.5f %+6.2f%% %+6.2f %7.3f%% %7.3f%% %+8.1f %8s %6.1f %6.1f %6.1f %6.1f  %s" % (
            name, paths, r["pm_mean"], r["mi_mean"], 100 * (r["pm_mean"] / r["mi_mean"] - 1), r["z"],
            100 * r["region_diff"], 100 * r["bound"], r["z_flux"],
            "%+8.1f" % r["z_fewer"] if "z_fewer" in r else "n/a", r["pm_seconds"], r["mi_seconds"], r["seconds"],
            r["cpu_seconds"],
            "pass" if r["pass"] else ("FAIL" if r["bias_detected"] else "FAIL (bias not detectable)")))
        for m in ("path",) + tuple(METHODS):
            if m in r:
                x = r[m]
                print("  %-11s indirect bias %+6.2f%% +- %.2f%% (limit %.2f%%), x1.05 / x0.95 %s, regions %6.2f%%, "
                      "%5.1f s  %s" % (m, 100 * x["bias"], 100 * x["se"], 100 * x["limit"],
                                       "caught" if x["bias_detected"] else "NOT caught", 100 * x["region_diff"],
                                       x["seconds"], "pass" if x["pass"] and x["bias_detected"] else "FAIL"))
        sys.stdout.flush()
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=2)
    failed = [r["scene"] for r in rows if not case_passes(r)]
    if failed:
        fail("pmrender and Mitsuba 3 disagree on: " + ", ".join(failed))
    print("pmrender agrees with Mitsuba 3 on %d scenes" % len(rows))


if __name__ == "__main__":
    main()
