#!/usr/bin/env python3
"""Where an image's indirect bias sits, by surface geometry (docs/accuracy.md, "Bias at bends").

Splits the indirect light of a test image against a reference by what each pixel sees, read from
a third image that holds the normal layer (`pmrender render ... --layers normal`, any method):

  - by orientation: surfaces facing up (n_y > 0.7), down (n_y < -0.7) and vertical;
  - by the largest angle between the pixel's normal and its four neighbours' (flat surfaces,
    tessellated curves, bends, creases).

For each class it prints the reference's share of the indirect light, the class's own bias and
its contribution to the whole image's bias. The indirect layer is `indirect` in all three files;
the images must have one size.

    build/pyenv/bin/python bench/bias_by_geometry.py REF.exr TEST.exr NORMALS.exr

Reads the EXR layers with Mitsuba 3's Bitmap (the virtual environment of tests/mitsuba/install.sh).
"""
import argparse
import sys

import numpy as np


def layers(path):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    return {name: np.array(bitmap, dtype=np.float64) for name, bitmap in mi.Bitmap(path).split()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference")
    parser.add_argument("test")
    parser.add_argument("normals", help="an image of the same view with the N layer (--layers normal)")
    args = parser.parse_args()
    ref_layers, test_layers, normal_layers = layers(args.reference), layers(args.test), layers(args.normals)
    for path, found in ((args.reference, ref_layers), (args.test, test_layers)):
        if "indirect" not in found:
            sys.exit(f"{path}: no 'indirect' layer")
    if "N" not in normal_layers:
        sys.exit(f"{args.normals}: no 'N' layer (render it with --layers normal)")
    ref = ref_layers["indirect"].mean(axis=2)
    test = test_layers["indirect"].mean(axis=2)
    normals = normal_layers["N"]
    if ref.shape != test.shape or ref.shape != normals.shape[:2]:
        sys.exit("the three images differ in size")
    total = ref.sum()
    if not total > 0:
        sys.exit(f"{args.reference}: no indirect light")

    def report(name, mask):
        if not mask.any() or not ref[mask].sum() > 0:
            return
        share = ref[mask].sum() / total * 100
        bias = (test[mask].sum() / ref[mask].sum() - 1) * 100
        contribution = (test[mask].sum() - ref[mask].sum()) / total * 100
        print(f"{name:<34} share {share:5.1f} %  bias {bias:+6.2f} %  contribution {contribution:+5.2f} %")

    print(f"{'whole image':<34} bias {(test.sum() / total - 1) * 100:+.2f} %")
    up = normals[:, :, 1]
    report("facing up", up > 0.7)
    report("facing down", up < -0.7)
    report("vertical", np.abs(up) <= 0.7)
    least_cos = np.ones(ref.shape)
    for axis in (0, 1):
        for step in (1, -1):
            least_cos = np.minimum(least_cos, (normals * np.roll(normals, step, axis=axis)).sum(axis=2))
    angle = np.degrees(np.arccos(np.clip(least_cos, -1.0, 1.0)))
    for low, high in ((0, 2), (2, 10), (10, 30), (30, 60), (60, 181)):
        report(f"neighbours' normals {low}-{min(high, 180)} degrees", (angle >= low) & (angle < high))


if __name__ == "__main__":
    main()
