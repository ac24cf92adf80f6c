#!/usr/bin/env python3
"""The paper's claim checked at equal error (docs/tradeoff.md): Fabianowski & Dingliana 2009
report photon differentials (pd) at the quality of k-nearest-neighbour gathering (knn) with
k_PM ~ k_PD, many times faster. Compared here at equal error instead of equal k: for every pd
setting on pd's own Pareto front, the fastest knn setting at least as accurate, and the ratio of
their device times (> 1: pd is faster). Reads the tradeoff.json files `pmrender tradeoff` writes.

    python3 bench/tradeoff_equal_error.py OUT/sponza/tradeoff.json OUT/conference/tradeoff.json ...
"""
import json
import sys


def front(points):
    """The points no other point beats in both time and error (time, error, label)."""
    return [p for p in points
            if not any(q[0] <= p[0] and q[1] <= p[1] and (q[0] < p[0] or q[1] < p[1]) for q in points)]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for path in sys.argv[1:]:
        with open(path) as f:
            j = json.load(f)
        metric = j["metric"]
        rows = [(s["device_ms"]["median"], s[metric], s["label"], s["estimator"]) for s in j["settings"]]
        pd = sorted(front([r for r in rows if r[3] == "pd"]))
        knn = [r for r in rows if r[3] == "knn"]
        noise = j.get("reference_noise_relmae")
        print("%s (%s, %dx%d; reference noise %s)" % (j["scene"]["name"], j["device"]["name"], j["resolution"][0],
                                                     j["resolution"][1], "%.2f%%" % (100 * noise) if noise else "?"))
        print("  %-26s %10s %8s   %-26s %10s %8s %10s" % ("pd setting", "ms", metric, "fastest knn as accurate",
                                                          "ms", metric, "knn / pd"))
        for t, e, label, _ in pd:
            better = [r for r in knn if r[1] <= e]
            if better:
                k = min(better)
                print("  %-26s %10.3f %7.2f%%   %-26s %10.3f %7.2f%% %10.2f" % (label, t, 100 * e, k[2], k[0],
                                                                          100 * k[1], k[0] / t))
            else:
                print("  %-26s %10.3f %7.2f%%   %-26s" % (label, t, 100 * e, "(no knn setting this accurate)"))


if __name__ == "__main__":
    main()
