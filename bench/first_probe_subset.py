#!/usr/bin/env python3
"""How the coverage probes' first pattern was chosen (kernels/common/footprint_coverage.h).

A footprint traces 16 probes first; where they find the surface ending inside it, all 64 of the
whole pattern (a Vogel spiral) measure the covered share. Taking the 16 from the 64 spares a
footprint at an edge 16 rays, if those 16 still tell an edge. This searches 16-subsets of the 64
by local search (swap one probe while it helps) from several random starts, for the least worst
ratio over four kinds of region about a covered centre (straight rims, convex and concave
corners, holes) of the kernel mass left uncovered in the footprints whose 16 probes are all
covered, against a 16-point spiral of its own; then checks the best on regions drawn afresh.
tests/unit/footprint_first_pattern_test.cpp checks the chosen subset in C++.

    python3 -m pip install numpy
    python3 bench/first_probe_subset.py [--starts 8] [--draws 20000]
"""
import argparse

import numpy as np

GOLDEN_ANGLE = np.pi * (3 - np.sqrt(5))


def spiral(count):
    j = np.arange(count)
    r = np.sqrt((j + 0.5) / count)
    return np.c_[r * np.cos(GOLDEN_ANGLE * j), r * np.sin(GOLDEN_ANGLE * j)]


def unit(angle):
    return np.c_[np.cos(angle), np.sin(angle)]


def region_kinds(rng, draws):
    """Per kind, a function of points (n x 2) giving covered flags (n x draws)."""
    a = rng.uniform(0, 2 * np.pi, draws)
    d = rng.uniform(0, 1, draws)
    rim = unit(a)
    b = a + rng.uniform(0.3 * np.pi, np.pi, draws)
    e = rng.uniform(0, 1, draws)
    second = unit(b)
    radius = rng.uniform(0.05, 0.5, draws)
    hole = unit(rng.uniform(0, 2 * np.pi, draws)) * (radius + rng.uniform(0, 1, draws))[:, None]
    return {
        "straight rim": lambda p: p @ rim.T <= d,
        "convex corner": lambda p: (p @ rim.T <= d) & (p @ second.T <= e),
        "concave corner": lambda p: (p @ rim.T <= d) | (p @ second.T <= e),
        "hole": lambda p: (p[:, None, 0] - hole[None, :, 0]) ** 2 + (p[:, None, 1] - hole[None, :, 1]) ** 2
        > radius ** 2,
    }


class Measure:
    """Uncovered kernel mass missed by a pattern, per kind of region."""

    def __init__(self, rng, draws, epanechnikov):
        fine = spiral(4000)
        weight = 2 * (1 - (fine ** 2).sum(1)) if epanechnikov else np.ones(len(fine))
        weight /= weight.sum()
        self.kinds = region_kinds(rng, draws)
        self.open_mass = {k: (~f(fine) * weight[:, None]).sum(0) for k, f in self.kinds.items()}
        self.whole = {k: f(spiral(64)) for k, f in self.kinds.items()}

    def missed(self, kind, covered):
        return (self.open_mass[kind] * covered.all(0)).mean()

    def ratios(self, subset, reference):
        return {k: self.missed(k, self.whole[k][subset]) / self.missed(k, self.kinds[k](reference))
                for k in self.kinds}


def search(measure, rng, starts):
    reference = spiral(16)
    best = None
    for _ in range(starts):
        subset = list(rng.choice(64, 16, replace=False))
        worst = max(measure.ratios(subset, reference).values())
        improved = True
        while improved:
            improved = False
            for slot in range(16):
                for probe in set(range(64)) - set(subset):
                    trial = subset.copy()
                    trial[slot] = probe
                    value = max(measure.ratios(trial, reference).values())
                    if value < worst - 1e-12:
                        subset, worst, improved = trial, value, True
        print(f"start: worst ratio {worst:.3f}, probes {sorted(int(q) for q in subset)}", flush=True)
        if best is None or worst < best[0]:
            best = (worst, sorted(int(q) for q in subset))
    return best[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=8)
    parser.add_argument("--draws", type=int, default=20000)
    parser.add_argument("--check", help="check this subset only (comma-separated probes)")
    args = parser.parse_args()
    if args.check:
        subset = [int(q) for q in args.check.split(",")]
    else:
        subset = search(Measure(np.random.default_rng(7), args.draws, True), np.random.default_rng(100), args.starts)
    for epanechnikov in (False, True):
        fresh = Measure(np.random.default_rng(12345), 2 * args.draws, epanechnikov)
        ratios = fresh.ratios(subset, spiral(16))
        print(f"{'Epanechnikov' if epanechnikov else 'constant'} kernel, fresh regions: " +
              ", ".join(f"{k} {v:.3f}" for k, v in ratios.items()))
    print("first pattern:", subset)


if __name__ == "__main__":
    main()
