"""The cost model's ratio beside the measured one (experiments/calibrate.py:
model files, model_ratio, explain; experiments/analysis/table.py: the
model columns of Table 1).

A synthetic model and renders whose times are the model's predictions with
0.5% noise: the model's ratio equals the measured one and nothing is
flagged. In one cell the precomputed eye pass takes 3x its prediction:
that cell is flagged, with the eye pass as the phase and its dominant
counter as the counter. Without a model file the table says "no model"."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from experiments import calibrate
from experiments.analysis import table

PIXELS = 10000


def synthetic_model():
    """Seconds per unit of each part's counters (calibrate.FEATURES order)."""
    per = {"trace": {"rays": 2e-7, "shape_tests": 3e-8},
           "build": {"tree_points": 1.5e-7},
           "precompute": {"knn_queries": 4e-7, "map_points": 2e-8},
           "render": {"rays": 3e-7, "map_points": 2e-8, "rep_points": 1e-8},
           "other": {}}
    return {p: np.array([0.0] + [per[p].get(f, 0.0) for f in calibrate.FEATURES[p]]) for p in calibrate.PARTS}


def work_of(method, photons, nn):
    zero = {f: 0 for f in ("traced_photons", "stored_photons", "rays", "shape_tests", "tree_points", "knn_queries",
                           "map_nodes", "map_points", "rep_lookups", "rep_nodes", "rep_points", "rep_evaluations")}
    w = {p: dict(zero) for p in calibrate.PHASES}
    w["trace"].update(traced_photons=photons, stored_photons=2 * photons, rays=3 * photons, shape_tests=20 * photons)
    w["build"]["tree_points"] = 2 * photons
    w["render"].update(rays=PIXELS, shape_tests=9 * PIXELS)
    if method == "precomputed":
        q = photons // 2
        w["precompute"].update(knn_queries=q, map_points=q * nn, tree_points=q)
        w["render"].update(rep_lookups=PIXELS, rep_points=PIXELS * 50)
    else:
        w["render"].update(knn_queries=PIXELS, map_points=PIXELS * nn * 3)
    return w


def make_runs(tmp_path, model, slow_cell=None, slow=("render", 3.0), seeds=3):
    """runs.csv rows of two cells (both methods, paper estimate), each
    render's stats file (its work) in TMP_PATH; times = the model's
    prediction x (1 + 0.5% noise); in SLOW_CELL (photons, nn) the
    precomputed render's phase SLOW[0] takes SLOW[1] x its prediction."""
    rng = np.random.default_rng(3)
    rows = []
    for photons, nn in ((50000, 10), (50000, 100)):
        for s in range(1, seeds + 1):
            for method in ("conventional", "precomputed"):
                work = work_of(method, photons, nn)
                q = calibrate.predict(model, {"work": work})
                t = {p: q[p] * (1 + 0.005 * rng.standard_normal()) for p in calibrate.PHASES}
                if (photons, nn) == slow_cell and method == "precomputed":
                    t[slow[0]] *= slow[1]
                base = str(tmp_path / f"{method}-p{photons}-n{nn}-seed{s}")
                with open(base + ".stats.json", "w") as f:
                    json.dump({"work": work}, f)
                rows.append({"method": method, "estimate": "paper", "photons": photons, "nn": nn, "seed": s,
                             "status": "ok", "role": "grid", "message": "", "width": 100, "height": 100,
                             "subpixels": 1, "tag": "", "threads": 1, "run": base,
                             **{f"{p}_s": t[p] for p in calibrate.PHASES}, "total_s": sum(t.values()),
                             "cpu_s": sum(t.values()), "relmse_ref": 0.1, "relmse_conv": 0.0,
                             "photons_stored": 2 * photons, "representatives": 100, "empty_estimates": 0})
    cells = pd.DataFrame([{"method": m, "estimate": "paper", "photons": 50000, "nn": n, "bias_ref": 0.1,
                           "variance_ref": 0.0, "relmse_ref_floor": math.nan, "ref": "", "ref_fast": ""}
                          for m in ("conventional", "precomputed") for n in (10, 100)])
    paper = pd.DataFrame([{"emitted_kphotons": 50, "nn": n, "conventional_s": 1.0, "proposed_s": 0.7,
                           "ratio_percent": 70.0} for n in (10, 100)])
    return pd.DataFrame(rows), cells, paper


VALIDATION = {"median": 0.03, "largest": 0.08}


def prec(t, nn):
    return t[(t["method"] == "precomputed") & (t["nn"] == nn)].iloc[0]


def test_model_ratio_beside_measured(tmp_path):
    model = synthetic_model()
    runs, cells, paper = make_runs(tmp_path, model)
    t, _ = table.summarize(runs, cells, paper, (model, VALIDATION))
    for nn in (10, 100):
        r = prec(t, nn)
        assert abs(r["model_ratio_percent"] / r["paired_ratio_percent"] - 1) < 0.01, r
        assert not r["model_differs"] and r["model_phase"] == ""
    # the model's ratio is the paired ratio of its predicted totals, computed directly
    a = [calibrate.predict(model, {"work": work_of("precomputed", 50000, 10)})["total"]]
    b = [calibrate.predict(model, {"work": work_of("conventional", 50000, 10)})["total"]]
    assert abs(prec(t, 10)["model_ratio_percent"] - 100 * a[0] / b[0]) < 1e-9
    assert (t.loc[t["method"] == "conventional", "model_ratio_percent"] == 100).all()


@pytest.mark.parametrize("phase,factor,name", [("render", 3.0, "rep_points"), ("precompute", 1.5, "map_points")])
def test_difference_names_phase_and_counter(tmp_path, phase, factor, name):
    model = synthetic_model()
    runs, cells, paper = make_runs(tmp_path, model, slow_cell=(50000, 100), slow=(phase, factor))
    t, _ = table.summarize(runs, cells, paper, (model, VALIDATION))
    slow, fine = prec(t, 100), prec(t, 10)
    assert slow["model_differs"] and slow["paired_ratio_percent"] > 1.1 * slow["model_ratio_percent"]
    assert (slow["model_phase"], slow["model_counter"]) == (phase, name)
    assert not fine["model_differs"]
    text = "\n".join(table.model_lines(t, (model, VALIDATION), ["paper"]))
    assert "(50k, 100)" in text and f"phase {phase}, counter {name}" in text and "(50k, 10)" not in text


def test_no_model(tmp_path):
    runs, cells, paper = make_runs(tmp_path, synthetic_model())
    t, _ = table.summarize(runs, cells, paper, None)
    assert t["model_ratio_percent"].isna().all() and not t["model_differs"].any()
    assert table.model_text(prec(t, 10), None) == "no model"
    assert "no model" in "\n".join(table.model_lines(t, None, ["paper"]))
    assert calibrate.load_model(str(tmp_path / "none.json")) is None


def test_model_file_round_trip_and_refusal(tmp_path):
    model = synthetic_model()
    path = str(tmp_path / "model.json")
    calibrate.write_model(path, model, 0.03, 0.08, {p: 0.02 for p in calibrate.PHASES}, {"cpu": "test"})
    back, validation = calibrate.load_model(path)
    assert validation == VALIDATION
    assert all(np.array_equal(back[p], model[p]) for p in calibrate.PARTS)
    with open(path, "w") as f:
        f.write('{"parts": {}}')
    with pytest.raises(calibrate.ModelError, match="not a cost model"):
        calibrate.load_model(path)


def test_runs_without_their_stats_files(tmp_path):
    """A runs.csv whose renders are not on this machine (committed results
    without the run directories): the model columns are empty, no failure."""
    model = synthetic_model()
    runs, cells, paper = make_runs(tmp_path, model)
    runs["run"] = [str(tmp_path / "gone" / f"r{i}") for i in range(len(runs))]
    t, _ = table.summarize(runs, cells, paper, (model, VALIDATION))
    assert t["model_ratio_percent"].isna().all() and not t["model_differs"].any()
    assert table.model_text(prec(t, 10), (model, VALIDATION)) == "n/a"


def test_a_model_of_other_counters_is_named_not_fatal(tmp_path):
    """A model file written for other counters (an older calibrate): load_model
    refuses it with the reason, and the table's model line says there is no
    model and why, instead of the table failing; control: no file, no reason."""
    path = str(tmp_path / "model.json")
    model = synthetic_model()
    calibrate.write_model(path, model, 0.03, 0.08, {p: 0.02 for p in calibrate.PHASES}, {"cpu": "test"})
    doc = json.load(open(path))
    doc["parts"]["build"]["counters"] = ["constant", "tree_points"]
    doc["parts"]["build"]["seconds_per_unit"] = [0.0, 1e-7]
    open(path, "w").write(json.dumps(doc))
    with pytest.raises(calibrate.ModelError, match="not this version's") as e:
        calibrate.load_model(path)
    line = table.model_lines(None, None, ["paper"], str(e.value))[1]
    assert line.startswith("Model ratio: no model (") and "not this version's" in line
    assert table.model_lines(None, None, ["paper"])[1].startswith("Model ratio: no model (`make calibrate`")


def test_model_disagrees_only_outside_both_bands():
    """A disagreement needs the model's band (its ratio give or take its
    error) wholly outside the measured 95% interval: 0.80 with 3% error
    (band [0.777, 0.824]) against [0.70, 0.76] disagrees; controls: against
    [0.70, 0.78] the band reaches the interval (no claim), a model below the
    interval the same way, and an undefined interval (one pair) claims
    nothing."""
    assert table.model_disagrees(0.70, 0.76, 0.80, 0.03)
    assert not table.model_disagrees(0.70, 0.78, 0.80, 0.03)
    assert table.model_disagrees(0.90, 0.95, 0.85, 0.03) and not table.model_disagrees(0.87, 0.95, 0.85, 0.03)
    assert not table.model_disagrees(math.nan, math.nan, 0.5, 0.03)
