"""Tests of experiments/calibrate.py: a model fitted on renders whose times
are a known linear function of their counters (plus 2% noise) predicts
held-out renders within the goal; the negative control, the same model
fitted on the times shuffled among the renders, must fail the validation."""

import json
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
        calibrate.write(d, model, rows[:20], rows[20:], median, largest, calibrate.timing_knobs({}), prov)
        text = open(os.path.join(d, "calibrate.md"), encoding="utf-8").read()
        assert regenerate.COMMIT_RE.search(text), text[:300]
        assert sorted(os.listdir(d)) == ["calibrate.md", "coefficients.csv", "model.json", "renders.csv"]
        assert not glob.glob(os.path.join(d, "*.tmp*"))
        rest = re.sub(r"Generated by .*?(?=Each phase)", "", text, count=1, flags=re.S)
        assert not regenerate.COMMIT_RE.search(rest)


# ---- the factors of the derived counters, and the renders themselves

def test_derived_counters_by_hand():
    """C*log2_map is C x log2 of the map's points; an unknown factor is an error."""
    work = {p: {"map_nodes": 0, "tree_points": 0} for p in calibrate.PHASES}
    work["build"]["tree_points"] = 1024
    row = {"work": work}
    assert calibrate.counter(row, "build", "tree_points*log2_map") == 1024 * 10
    assert calibrate.counter(row, "build", "tree_points") == 1024
    import pytest
    with pytest.raises(KeyError):
        calibrate.counter(row, "build", "tree_points*nothing")


def test_log2_map_carries_the_build_across_map_sizes():
    """Build times of N log N (a k-d tree's sort): fitted on maps of 10^4
    and 10^7 points, the model predicts 10^5 and 10^6 within the goal;
    control: without the N log N counter (its coefficient left out and the
    rest refitted) it misses by more than the goal."""
    def rows(ns):
        out = []
        for n in ns:
            work = {p: {f.split("*")[0]: 0 for fs in calibrate.FEATURES.values() for f in fs} for p in calibrate.PHASES}
            work["build"]["tree_points"] = n
            t = {p: 0.0 for p in calibrate.PHASES}
            t["build"] = 8e-9 * n * math.log2(n) + 1e-3
            t["total"] = t["build"]
            out.append({"work": work, "time": t})
        return out
    fit_rows, held = rows([10 ** 4, 2 * 10 ** 4, 10 ** 7, 2 * 10 ** 7]), rows([10 ** 5, 10 ** 6])
    assert calibrate.validate(calibrate.fit(fit_rows), held)[0] <= calibrate.GOAL_MEDIAN
    saved = dict(calibrate.FEATURES)
    try:
        calibrate.FEATURES["build"] = ("tree_points",)
        assert calibrate.validate(calibrate.fit(fit_rows), held)[0] > calibrate.GOAL_MEDIAN
    finally:
        calibrate.FEATURES.clear()
        calibrate.FEATURES.update(saved)


PM = os.path.join(os.path.dirname(__file__), "..", "build", "photonmap")


def test_calibrate_renders_then_refits(tmp_path, monkeypatch):
    """make calibrate's path on a tiny design: both methods of each group
    rendered by the launcher, every file written, the knobs recorded; the
    model refitted from renders.csv (--refit) is the same to the last digit;
    control: a renders.csv without a counter's column is refused, and a
    failing renderer writes nothing."""
    if not os.access(PM, os.X_OK):
        import pytest
        pytest.skip("build/photonmap is not built")
    for k, v in (("TIME_REPEATS", "1"), ("TIME_PROCESSES", "1"), ("TIME_GAUGE", "0"), ("TIME_CPU", "none")):
        monkeypatch.setenv(k, v)
    monkeypatch.setattr(calibrate, "FIT", [("cornell", 2000, 10, 32, 24), ("cornell", 4000, 20, 48, 36),
                                           ("caustic", 3000, 10, 32, 24)])
    monkeypatch.setattr(calibrate, "HELD_OUT", [("cornell", 3000, 15, 40, 30)])
    out, again = tmp_path / "cal", tmp_path / "refit"
    assert calibrate.main(["--pm", PM, "--out", str(out)]) == 0
    assert sorted(os.listdir(out)) == ["calibrate.md", "coefficients.csv", "model.json", "renders.csv"]
    doc = json.load(open(out / "model.json"))
    assert doc["timing"]["TIME_PROCESSES"] == "1" and doc["timing"]["TIME_CPU"] == "none"
    assert calibrate.main(["--refit", str(out), "--out", str(again)]) == 0
    assert (out / "coefficients.csv").read_text() == (again / "coefficients.csv").read_text()
    assert (out / "renders.csv").read_text() == (again / "renders.csv").read_text()
    text = (out / "renders.csv").read_text().splitlines()
    assert len(text) == 1 + 2 * 4 and text[0].count("render.map_nodes") == 1
    broken = tmp_path / "broken"
    broken.mkdir()
    cols = text[0].split(",")
    drop = cols.index("render.map_nodes")
    (broken / "renders.csv").write_text("\n".join(",".join(c for i, c in enumerate(l.split(",")) if i != drop)
                                                  for l in text) + "\n")
    (broken / "model.json").write_text((out / "model.json").read_text())
    assert calibrate.main(["--refit", str(broken), "--out", str(tmp_path / "x")]) == 1
    assert not (tmp_path / "x" / "model.json").exists()
    fail = tmp_path / "failpm"
    fail.write_text("#!/bin/sh\nexit 1\n")
    fail.chmod(0o755)
    assert calibrate.main(["--pm", str(fail), "--out", str(tmp_path / "y")]) == 1
    assert not (tmp_path / "y" / "model.json").exists()


def test_slow_spell_groups_are_rendered_again(monkeypatch):
    """A group whose photon pass per stored photon lies 30% over its scene's
    others is rendered again, and keeps the faster rendering; a group within
    SPELL_PCT is not. Control: a group that stays slow is tried REDO_MAX
    times, then kept as it is."""
    calls = []

    def fake_group(pm, group, root, k, of, knobs):
        calls.append(group)
        scene, photons = group[0], group[1]
        slow = {"a": 1.3, "b": 1.3 if stubborn else (1.3 if calls.count(group) == 1 else 1.0)}.get(group[5], 1.0)
        return [{"scene": scene, "method": m, "time": {"trace": 1e-7 * 3 * photons * slow},
                 "work": {"trace": {"stored_photons": 3 * photons}}} for m in calibrate.METHODS]

    monkeypatch.setattr(calibrate, "render_group", fake_group)
    groups = [("cornell", 1000 * (i + 1), 10, 32, 24, "b" if i == 3 else "-") for i in range(10)]
    stubborn = False
    rows, redone = calibrate.render_all("pm", groups, "root", {})
    assert redone == 1 and calls.count(groups[3]) == 2 and len(calls) == 11
    assert abs(rows[6]["time"]["trace"] / (3e-7 * 4000) - 1) < 1e-12  # the faster rendering kept
    calls.clear()
    stubborn = True
    rows, redone = calibrate.render_all("pm", groups, "root", {})
    assert redone == 1 and calls.count(groups[3]) == 1 + calibrate.REDO_MAX
    assert abs(rows[6]["time"]["trace"] / (3e-7 * 4000 * 1.3) - 1) < 1e-12
    # within SPELL_PCT of the others: nothing rendered again
    assert calibrate.slow_pairs([fake_group(None, ("cornell", 1000, 10, 32, 24, "-"), 0, 0, 0, 0)] * 9
                                + [[dict(r, time={"trace": r["time"]["trace"] * 1.05}) for r in
                                    fake_group(None, ("cornell", 1000, 10, 32, 24, "-"), 0, 0, 0, 0)]]) == []


def test_calm_errors_leave_out_the_slow_spell():
    """Held-out renders whose photon pass ran 20% slow (a slow spell, the
    totals slowed alike) are counted and left out of the diagnostic, whose
    median is then the validation of the others; control: with no spell
    nothing is left out and the median is validate's."""
    model = calibrate.fit(synthetic(40, 1))
    held = synthetic(20, 2)
    assert calibrate.calm_errors(model, held)[:2] == (0, calibrate.validate(model, held)[0])
    slowed = [dict(r, time={k: v * 1.2 for k, v in r["time"].items()}) for r in held[:5]] + held[5:]
    slow, median, largest = calibrate.calm_errors(model, slowed)
    assert slow == 5
    assert (median, largest) == calibrate.validate(model, held[5:])
    assert calibrate.validate(model, slowed)[0] > median
