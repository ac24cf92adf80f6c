#!/usr/bin/env python3
"""Where an image's indirect bias sits, by surface geometry (docs/accuracy.md, "Bias at bends").

Splits the indirect light of a test image against a reference by what each pixel sees, read from
a third image that holds the normal layer (`pmrender render ... --layers normal`, any method):

  - by orientation: surfaces facing up (n_y > 0.7), down (n_y < -0.7) and vertical;
  - by the largest angle between the pixel's normal and its four neighbours' (flat surfaces,
    tessellated curves, bends, creases).

  - where the third image also holds the position layer (`--layers normal,position`): bends and
    creases split into concave (the neighbour across rises in front of the pixel's tangent plane:
    a crease, a wall's foot) and convex (it falls behind: a rim, a silhouette), and the flat
    surfaces (under 2 degrees to every neighbour) by their distance in the scene to the nearest
    pixel that is not flat (a bend, crease or silhouette found in the image), in fractions of the
    scene's extent seen (the diagonal of the positions' box): is a flat surface's bias that of
    the edges near it, or of the surface itself?

For each class it prints the reference's share of the indirect light, the class's own bias and
its contribution to the whole image's bias. The indirect layer is `indirect` in all three files;
the images must have one size. Several TEST images may follow the reference: one report each.

    build/pyenv/bin/python bench/bias_by_geometry.py REF.exr NORMALS.exr TEST.exr [TEST.exr ...]
    build/pyenv/bin/python bench/bias_by_geometry.py REF.exr NORMALS.exr --mask classes.png

With --mask, a PNG shows where the edge classes lie: bends of 10-60 degrees concave in red and
convex in blue, creases of 60 degrees or more concave in yellow and convex in green, over the
reference's indirect light in grey.

Reads the EXR layers with the OpenEXR package where it is installed, else with Mitsuba 3's Bitmap
(the virtual environment of tests/mitsuba/install.sh).
"""
import argparse
import struct
import sys
import zlib

import numpy as np


def layers(path):
    """The image's layers by name ('' for R, G, B), each an H x W x C array."""
    try:
        import OpenEXR
    except ImportError:
        import mitsuba as mi
        mi.set_variant("scalar_rgb")
        return {name: np.array(bitmap, dtype=np.float64) for name, bitmap in mi.Bitmap(path).split()}
    groups = {}
    with OpenEXR.File(path, separate_channels=True) as exr:
        for name, channel in exr.channels().items():
            layer, _, component = name.rpartition(".")
            groups.setdefault(layer, {})[component] = channel.pixels
    out = {}
    for layer, components in groups.items():
        order = [c for c in ("R", "G", "B", "X", "Y", "Z") if c in components] or sorted(components)
        out[layer] = np.stack([components[c].astype(np.float64) for c in order], axis=2)
    return out


def nearest_marked(mask):
    """Per pixel the (row, column) of a nearby marked pixel: jump flooding, nearly the nearest."""
    h, w = mask.shape
    rows, cols = np.indices((h, w))
    best = np.where(mask, rows, -1), np.where(mask, cols, -1)
    step = 1 << int(np.ceil(np.log2(max(h, w))))
    while step >= 1:
        for dy in (-step, 0, step):
            for dx in (-step, 0, step):
                sy = np.clip(rows + dy, 0, h - 1)
                sx = np.clip(cols + dx, 0, w - 1)
                cand_r, cand_c = best[0][sy, sx], best[1][sy, sx]
                have = cand_r >= 0
                d_cand = np.where(have, (cand_r - rows) ** 2 + (cand_c - cols) ** 2, np.iinfo(np.int64).max)
                d_best = np.where(best[0] >= 0, (best[0] - rows) ** 2 + (best[1] - cols) ** 2,
                                  np.iinfo(np.int64).max)
                better = d_cand < d_best
                best = np.where(better, cand_r, best[0]), np.where(better, cand_c, best[1])
        step //= 2
    return best


def neighbour_angle(normals):
    """Per pixel the largest angle, in degrees, between its normal and its four neighbours'."""
    least_cos = np.ones(normals.shape[:2])
    for axis in (0, 1):
        for step in (1, -1):
            least_cos = np.minimum(least_cos, (normals * np.roll(normals, step, axis=axis)).sum(axis=2))
    return np.degrees(np.arccos(np.clip(least_cos, -1.0, 1.0)))


def concave_pixels(normals, positions, seen):
    """Edges by their side: at a concave edge (a crease, a wall's foot) every neighbour lies on or
    in front of the pixel's tangent plane; at a convex one (a ledge's rim, a column's silhouette)
    some neighbour falls behind it, or lies far behind (a depth jump)."""
    rise = np.full(normals.shape[:2], np.inf)
    for axis in (0, 1):
        for step in (1, -1):
            rise = np.minimum(rise, ((np.roll(positions, step, axis=axis) - positions) * normals).sum(axis=2))
    scale = np.linalg.norm(positions[seen].max(axis=0) - positions[seen].min(axis=0)) if seen.any() else 1.0
    return rise > -1e-4 * scale


def report_one(ref, test, normals, positions):
    total = ref.sum()

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
    angle = neighbour_angle(normals)
    for low, high in ((0, 2), (2, 10), (10, 30), (30, 60), (60, 181)):
        report(f"neighbours' normals {low}-{min(high, 180)} degrees", (angle >= low) & (angle < high))
    if positions is None:
        return
    seen = np.abs(normals).sum(axis=2) > 0
    concave = concave_pixels(normals, positions, seen)
    for low, high in ((10, 60), (60, 181)):
        edge = (angle >= low) & (angle < high) & seen
        report(f"  {low}-{min(high, 180)} degrees, concave", edge & concave)
        report(f"  {low}-{min(high, 180)} degrees, convex", edge & ~concave)
    flat = (angle < 2) & seen
    near_r, near_c = nearest_marked(~flat & seen)
    if not (near_r >= 0).any():
        return
    distance = np.linalg.norm(positions - positions[np.maximum(near_r, 0), np.maximum(near_c, 0)], axis=2)
    extent = np.linalg.norm(positions[seen].max(axis=0) - positions[seen].min(axis=0))
    edges = [0, 0.0025, 0.005, 0.01, 0.02, 0.04, np.inf]
    print(f"flat surfaces by distance to the nearest pixel that is not flat (fractions of {extent:.3g}):")
    for low, high in zip(edges[:-1], edges[1:]):
        label = f"  flat, {low:g}-{high:g}" if np.isfinite(high) else f"  flat, over {low:g}"
        report(label, flat & (distance >= low * extent) & (distance < high * extent))


def write_mask(path, ref, normals, positions):
    """A PNG of where the edge classes lie over the reference's indirect light (grey): bends of
    10-60 degrees concave red and convex blue, creases of 60 degrees or more concave yellow and
    convex green. Written with zlib alone (no imaging package)."""
    seen = np.abs(normals).sum(axis=2) > 0
    angle = neighbour_angle(normals)
    concave = concave_pixels(normals, positions, seen)
    grey = np.clip(ref / max(np.percentile(ref[seen], 99), 1e-12), 0.0, 1.0) ** (1 / 2.2) * 160 if seen.any() else ref
    rgb = np.repeat(grey[:, :, None], 3, axis=2)
    bend, crease = (angle >= 10) & (angle < 60) & seen, (angle >= 60) & seen
    for mask, colour in ((bend & concave, (255, 40, 40)), (bend & ~concave, (40, 120, 255)),
                         (crease & concave, (240, 220, 40)), (crease & ~concave, (40, 220, 40))):
        rgb[mask] = colour
    rgb = rgb.astype(np.uint8)
    height, width = rgb.shape[:2]
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference")
    parser.add_argument("normals", help="an image of the same view with the N layer (--layers normal[,position])")
    parser.add_argument("tests", nargs="*")
    parser.add_argument("--mask", metavar="PNG", help="also write where the edge classes lie (needs the position layer)")
    args = parser.parse_args()
    ref_layers, normal_layers = layers(args.reference), layers(args.normals)
    if "indirect" not in ref_layers:
        sys.exit(f"{args.reference}: no 'indirect' layer")
    if "N" not in normal_layers:
        sys.exit(f"{args.normals}: no 'N' layer (render it with --layers normal)")
    ref = ref_layers["indirect"].mean(axis=2)
    normals = normal_layers["N"]
    positions = normal_layers.get("P")
    if ref.shape != normals.shape[:2]:
        sys.exit("the reference and the normals differ in size")
    if not ref.sum() > 0:
        sys.exit(f"{args.reference}: no indirect light")
    if args.mask:
        if positions is None:
            sys.exit(f"{args.normals}: no 'P' layer for --mask (render it with --layers normal,position)")
        write_mask(args.mask, ref, normals, positions)
    for path in args.tests:
        test_layers = layers(path)
        if "indirect" not in test_layers:
            sys.exit(f"{path}: no 'indirect' layer")
        test = test_layers["indirect"].mean(axis=2)
        if test.shape != ref.shape:
            sys.exit(f"{path}: another size than the reference")
        print(f"== {path}")
        report_one(ref, test, normals, positions)


if __name__ == "__main__":
    main()
