"""Tests of experiments/calibrate.py: a model fitted on renders whose times
are a known linear function of their counters (plus 2% noise) predicts
held-out renders within the goal; the negative control, the same model
fitted on the times shuffled among the renders, must fail the validation."""

import math
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


# ---- predict_seconds: a study's wall time from its render configurations

def per_unit_rows(scene, k):
    """Calibration-like renders of SCENE whose counters are exactly K x a
    fixed work per unit of their drivers (photons, eye samples, n)."""
    rows = []
    for method in ("conventional", "precomputed"):
        for photons, nn, w, h in ((20000, 20, 64, 48), (50000, 50, 128, 96)):
            samples = w * h * 4
            work = {p: {f: 0 for f in calibrate.FEATURES["render"] + ("traced_photons", "stored_photons",
                                                                       "tree_points")} for p in calibrate.PHASES}
            work["trace"].update(traced_photons=photons, stored_photons=3 * k * photons, rays=4 * k * photons,
                                 shape_tests=36 * k * photons)
            work["build"]["tree_points"] = 3 * k * photons
            if method == "precomputed":
                work["precompute"].update(knn_queries=k * photons, map_points=k * photons * nn)
                work["render"].update(rays=k * samples, rep_lookups=samples, rep_points=10 * k * samples)
            else:
                work["render"].update(rays=k * samples, knn_queries=samples, map_points=3 * k * samples * nn)
            rows.append({"scene": scene, "method": method, "photons": photons, "nn": nn, "samples": samples,
                         "work": work})
    return rows


def linear_model():
    return {p: np.array([0.0] + [TRUE.get(p, {}).get(f, 0.0) for f in calibrate.FEATURES[p]])
            for p in calibrate.PARTS}


def test_predict_seconds_scales_with_the_configuration():
    model = linear_model()
    per_unit = calibrate.work_per_unit(per_unit_rows("cornell", 1) + per_unit_rows("caustic", 3))
    rule = (3, 10, 2.0)
    conf = {"scene": "scenes/cornell.scene", "method": "precomputed", "photons": 100000, "nn": 100, "width": 256,
            "height": 192, "subpixels": 2}
    samples = 256 * 192 * 4
    # by hand from TRUE and the work per unit of per_unit_rows (k = 1)
    want = (2e-7 * 4 * 100000 + 3e-8 * 36 * 100000 + 1.5e-7 * 3 * 100000 + 2e-8 * 100000 * 100
            + 4e-7 * 100000 + 3e-7 * samples + 1e-8 * 10 * samples)
    one, = calibrate.predict_seconds(model, per_unit, [conf], repeats=1, rule=rule)
    assert abs(one / want - 1) < 1e-9, (one, want)
    # three repeats: three times; auto: as many as the renderer's rule runs
    three, = calibrate.predict_seconds(model, per_unit, [conf], repeats=3, rule=rule)
    assert abs(three - 3 * one) < 1e-9
    auto, = calibrate.predict_seconds(model, per_unit, [conf], repeats="auto", rule=rule)
    assert abs(auto - one * min(10, max(3, math.ceil(2.0 / one)))) < 1e-9
    # a scene with three times the work per unit costs more; an unknown scene: the calibrated scenes' mean
    caustic, = calibrate.predict_seconds(model, per_unit, [dict(conf, scene="caustic")], repeats=1, rule=rule)
    other, = calibrate.predict_seconds(model, per_unit, [dict(conf, scene="box")], repeats=1, rule=rule)
    assert caustic > 2 * one and abs(other - (one + caustic) / 2) < 1e-9 * caustic
    # a method not calibrated: nan, not a guess
    assert math.isnan(calibrate.predict_seconds(model, per_unit, [dict(conf, method="pathtrace")], 1, rule)[0])


def test_auto_repeats_rule_is_the_renderers():
    lo, hi, budget = calibrate.auto_repeats_rule()
    assert 1 <= lo <= hi and budget > 0
    assert calibrate.repeats_of("auto", budget / 1000, (lo, hi, budget)) == hi
    assert calibrate.repeats_of("auto", budget, (lo, hi, budget)) == lo


def test_written_files_name_the_commit():
    """calibrate.md names the commit that wrote it, as every results file
    must (regenerate.COMMIT_RE, what `make results-check` reads), and no
    temporary name is left behind; control: without its first sentence the
    file names no commit."""
    import glob
    import re
    import tempfile
    from experiments import regenerate
    prov = {"cpu": "test CPU", "commit": "abcdef0", "tree": "clean", "compiler": "gcc", "flags": "-O2",
            "loadavg": [0.5, 0.5, 0.5]}
    rows = []
    for i, r in enumerate(synthetic(30, 3)):
        r.update(scene="cornell", method="conventional", photons=1000 + i, nn=50, width=64, height=48, repeats=3, samples=64 * 48 * 4,
                 provenance=prov)
        rows.append(r)
    model = calibrate.fit(rows[:20])
    median, largest = calibrate.validate(model, rows[20:])
    with tempfile.TemporaryDirectory() as d:
        calibrate.write(d, model, rows[:20], rows[20:], median, largest)
        text = open(os.path.join(d, "calibrate.md"), encoding="utf-8").read()
        assert regenerate.COMMIT_RE.search(text), text[:300]
        assert sorted(os.listdir(d)) == ["calibrate.md", "coefficients.csv", "model.json", "renders.csv"]
        assert not glob.glob(os.path.join(d, "*.tmp*"))
        rest = re.sub(r"Generated by .*?(?=Each phase)", "", text, count=1, flags=re.S)
        assert not regenerate.COMMIT_RE.search(rest)
