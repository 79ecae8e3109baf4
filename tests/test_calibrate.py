"""Tests of experiments/calibrate.py: a model fitted on renders whose times
are a known linear function of their counters (plus 2% noise) predicts
held-out renders within the goal; the negative control, the same model
fitted on the times shuffled among the renders, must fail the validation."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments import calibrate  # noqa: E402

# seconds per unit of the counters that drive each phase (the rest are 0)
TRUE = {"trace": {"rays": 2e-7, "shape_tests": 3e-8},
        "build": {"tree_points": 1.5e-7},
        "precompute": {"map_points": 2e-8, "knn_queries": 4e-7},
        "render": {"rays": 3e-7, "rep_points": 1e-8, "map_points": 2e-8}}


def synthetic(n, seed):
    """n renders of random size: counters, and times from TRUE with 2% noise."""
    rng = np.random.default_rng(seed)
    rows = []
    for _ in range(n):
        photons = int(rng.integers(10000, 200000))
        pixels = int(rng.integers(10000, 400000))
        method = rng.integers(2)
        work = {p: {f: 0 for f in calibrate.FEATURES["render"] + ("traced_photons", "stored_photons",
                                                                   "tree_points")} for p in calibrate.PHASES}
        work["trace"].update(traced_photons=photons, stored_photons=3 * photons, rays=4 * photons,
                             shape_tests=36 * photons)
        work["build"]["tree_points"] = 3 * photons
        q = (3 * photons) // 4 if method else 0
        work["precompute"].update(knn_queries=q, map_points=q * int(rng.integers(100, 400)), map_nodes=q * 25,
                                  tree_points=q, rep_evaluations=q)
        work["render"].update(rays=pixels, shape_tests=9 * pixels)
        if method:
            work["render"].update(rep_lookups=pixels, rep_points=pixels * int(rng.integers(5, 30)))
        else:
            work["render"].update(knn_queries=pixels, map_points=pixels * int(rng.integers(100, 400)))
        time = {p: sum(c * work[p][f] for f, c in TRUE[p].items()) * (1 + 0.02 * rng.standard_normal())
                for p in calibrate.PHASES}
        time["total"] = sum(time[p] for p in calibrate.PHASES)
        rows.append({"work": work, "time": time})
    return rows


def test_fit_validates():
    model = calibrate.fit(synthetic(40, 1))
    median, largest = calibrate.validate(model, synthetic(20, 2))
    assert median <= calibrate.GOAL_MEDIAN and largest < 0.15
    # the coefficients it finds are the true ones, within the noise
    assert abs(model["build"][1] / TRUE["build"]["tree_points"] - 1) < 0.05


def test_shuffled_times_fail():
    """Negative control: times no longer belong to their counters."""
    rows = synthetic(40, 1)
    rng = np.random.default_rng(3)
    times = [r["time"] for r in rows]
    for r, j in zip(rows, rng.permutation(len(rows))):
        r["time"] = times[j]
    median, _ = calibrate.validate(calibrate.fit(rows), synthetic(20, 2))
    assert median > calibrate.GOAL_MEDIAN
