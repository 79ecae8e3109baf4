"""Tests of experiments/analysis/repeats_cost.py on synthetic stats files: a
known answer (two run roots, repeats whose sums, factor and minima's
distance below the cold and median times are worked out by hand), negative
controls (renders timed once: factor exactly 1 and no noise removed; a
render not ok left out; a broken stats file refused with exit 2 naming it)
and the cost model's section with and without a model file."""

import json
import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments import calibrate  # noqa: E402
from experiments.analysis import repeats_cost  # noqa: E402

PH = ("trace", "build", "precompute", "render")


def stats(path, repeats, status="ok"):
    """A stats file at PATH whose repeats are REPEATS: a list of {phase: s}
    (the total: the phases' sum), written as the renderer writes them."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    reps = [dict(r, total=sum(r[p] for p in PH)) for r in repeats]
    keys = PH + ("total",)
    doc = {"status": status, "repeats": len(reps),
           "time_s": {k: min(r[k] for r in reps) for k in keys},
           "time_s_cold": dict(reps[0]),
           "time_s_median": {k: float(np.median([r[k] for r in reps])) for k in keys},
           "time_s_repeats": {k: [r[k] for r in reps] for k in keys}}
    with open(path, "w") as f:
        json.dump(doc, f)


def rep(trace, build, precompute, render):
    return {"trace": trace, "build": build, "precompute": precompute, "render": render}


@pytest.fixture
def results(tmp_path):
    runs = tmp_path / "runs"
    # study a: one render of three repeats, one of one repeat
    stats(str(runs / "a-32x24-s2-t1" / "precomputed-paper-p1000-n10" / "seed1.stats.json"),
          [rep(1.0, 0.5, 0.5, 2.0), rep(0.5, 0.5, 0.25, 1.0), rep(0.8, 0.4, 0.3, 1.5)])
    stats(str(runs / "a-32x24-s2-t1" / "conventional-paper-p1000-n10" / "seed1.stats.json"),
          [rep(1.0, 1.0, 0.0, 1.0)])
    # study b: two repeats; a refused render beside it; the pinned renderer's hidden directory
    stats(str(runs / "b-32x24-s2-t1" / "conventional-paper-p1000-n10" / "seed1.stats.json"),
          [rep(2.0, 1.0, 0.0, 1.0), rep(1.0, 1.0, 0.0, 2.0)])
    stats(str(runs / "b-32x24-s2-t1" / "conventional-paper-p1000-n10" / "seed2.stats.json"),
          [rep(9.0, 9.0, 0.0, 9.0)], status="refused")
    stats(str(runs / ".renderer" / "x.stats.json"), [rep(100.0, 0, 0, 0)])
    return tmp_path


def test_known_answer(results):
    rows = {r["study"]: r for r in repeats_cost.collect(str(results))}
    assert list(rows) == ["a-32x24-s2-t1", "b-32x24-s2-t1", repeats_cost.ALL]
    a, b, every = rows["a-32x24-s2-t1"], rows["b-32x24-s2-t1"], rows[repeats_cost.ALL]
    # a: totals 4, 2.25, 3 (cold 4) and 3: one run 7 s, with repeats 12.25 s
    assert (a["renders"], a["repeats_median"], a["repeats_min"], a["repeats_max"]) == (2, 2.0, 1, 3)
    assert a["single_s"] == pytest.approx(7.0) and a["repeats_s"] == pytest.approx(12.25)
    assert a["factor"] == pytest.approx(1.75) and a["extra_s"] == pytest.approx(5.25)
    # only the render of three repeats counts for the noise: trace min 0.5, cold 1, median 0.8
    assert a["renders_repeated"] == 1
    assert a["min_below_cold_trace_pct"] == pytest.approx(50.0)
    assert a["min_below_median_trace_pct"] == pytest.approx(37.5)
    assert a["min_below_cold_total_pct"] == pytest.approx(100 * (1 - 2.25 / 4))
    assert a["min_below_median_total_pct"] == pytest.approx(25.0)
    # b: totals 4 and 4; the minimum of the totals (4), not the phases' minima summed (3)
    assert (b["renders"], b["left_out"]) == (1, 1)
    assert b["factor"] == pytest.approx(2.0) and b["min_below_cold_total_pct"] == pytest.approx(0.0)
    assert math.isnan(b["min_below_cold_precompute_pct"])  # no precompute: undefined, not 0
    assert b["min_below_cold_render_pct"] == pytest.approx(0.0)
    assert b["min_below_median_render_pct"] == pytest.approx(100 * (1 - 1 / 1.5))
    assert every["renders"] == 3 and every["left_out"] == 1
    assert every["single_s"] == pytest.approx(11.0) and every["repeats_s"] == pytest.approx(20.25)
    assert every["min_below_cold_trace_pct"] == pytest.approx(50.0)  # the median of 50 and 50


def test_single_runs_cost_nothing(tmp_path):
    """Negative control: renders timed once take as long as one run, and
    the repeats remove no noise (undefined, printed as —)."""
    for s in (1, 2):
        stats(str(tmp_path / "runs" / "c-32x24-s2-t1" / "x" / f"seed{s}.stats.json"), [rep(1.0, 1.0, 1.0, s)])
    out = str(tmp_path / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(tmp_path), "--out", out]) == 0
    row = repeats_cost.collect(str(tmp_path))[-1]
    assert row["factor"] == 1.0 and row["extra_s"] == 0.0 and row["renders_repeated"] == 0
    assert all(math.isnan(row[f"min_below_cold_{p}_pct"]) for p in repeats_cost.PHASES)
    md = open(out + ".md").read()
    assert "x1.00" in md and "| 0.0 |" in md and "— / —" in md
    assert not os.path.exists(out + ".md.tmp") and not os.path.exists(out + ".csv.tmp")


def test_outputs_and_no_model(results):
    out = str(results / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(results), "--out", out]) == 0
    lines = open(out + ".csv").read().splitlines()
    assert lines[0].split(",") == repeats_cost.CSV_COLUMNS and len(lines) == 4
    md = open(out + ".md").read()
    assert "## The cost model, per unit of work" in md
    assert "Not measured: run make calibrate" in md
    assert "x1.84" in md  # 20.25 / 11
    # it names the commit that wrote it, as every results file must (make results-check)
    from experiments import regenerate
    assert regenerate.COMMIT_RE.search(md), md[:300]


def test_model_section(results):
    """The cost model's coefficients in ns per unit, its validation and date."""
    os.makedirs(results / "calibrate")
    model = {p: np.zeros(1 + len(calibrate.FEATURES[p])) for p in calibrate.PARTS}
    model["render"][1 + calibrate.FEATURES["render"].index("rays")] = 3.25e-7
    model["build"][0] = 2e-3
    calibrate.write_model(str(results / "calibrate" / "model.json"), model, 0.031, 0.084,
                          {p: 0.0 for p in calibrate.PHASES}, {"cpu": "Test CPU", "commit": "abc123"},
                          written="2026-01-02")
    out = str(results / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(results), "--out", out]) == 0
    md = open(out + ".md").read()
    assert "| render | rays | 325 |" in md
    assert "| build | (constant: ns per render) | 2e+06 |" in md
    assert "of 2026-01-02" in md and "median of 3.1% and at most 8.4%" in md and "Test CPU" in md
    assert "Not measured" not in md and "shape_tests" not in md  # a zero coefficient is left out


def test_broken_stats_refused(results, capsys):
    bad = results / "runs" / "a-32x24-s2-t1" / "bad" / "seed1.stats.json"
    os.makedirs(bad.parent)
    bad.write_text('{"status": "ok", "time_s": {"trace": 1}}')
    out = str(results / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(results), "--out", out]) == 2
    assert str(bad) in capsys.readouterr().err
    assert not os.path.exists(out + ".md")


def test_model_of_other_counters_named(results):
    """A model file of other counters (an older calibrate) is named with the
    reason in the section, and the rest is written (exit 0)."""
    os.makedirs(results / "calibrate")
    (results / "calibrate" / "model.json").write_text(json.dumps(
        {"parts": {p: {"counters": ["constant"], "seconds_per_unit": [0.0]} for p in calibrate.PARTS},
         "validation": {"median": 0.1, "largest": 0.2}}))
    out = str(results / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(results), "--out", out]) == 0
    md = open(out + ".md").read()
    assert "Not measured: " in md and "not this version's" in md


def merged(path, processes, faults=None, minima=None):
    """A stats file at PATH of one render timed in PROCESSES (a list of
    lists of repeats, as rep()), merged as launch.py's merge_stats merges
    them; FAULTS every repeat's page faults; MINIMA replaces
    time_s_processes (a split that does not check)."""
    stats(path, [r for p in processes for r in p])
    with open(path) as f:
        doc = json.load(f)
    keys = PH + ("total",)
    doc["processes"] = len(processes)
    doc["time_s_processes"] = minima or {k: [min(sum(r[q] for q in PH) if k == "total" else r[k] for r in p)
                                             for p in processes] for k in keys}
    if faults is not None:
        doc["minor_faults_repeats"] = faults
    with open(path, "w") as f:
        json.dump(doc, f)


def test_warm_repeats_known_answer(tmp_path):
    """Per process: two processes of three repeats, the first cold in every
    phase, the second repeat warm in one process and 10% slow in the other's
    build; page faults per repeat; the medians and warm shares by hand."""
    root = tmp_path / "runs" / "w-32x24-s2-t1"
    cold, warm, slow = rep(2.0, 2.0, 2.0, 2.0), rep(1.0, 1.0, 1.0, 1.0), rep(1.0, 1.1, 1.0, 1.0)
    merged(str(root / "x" / "seed1.stats.json"), [[cold, warm, warm], [cold, slow, warm]],
           faults=[1000, 10, 0, 3000, 30, 0])
    # a render of two repeats per process: too few for the section
    merged(str(root / "x" / "seed2.stats.json"), [[cold, warm], [cold, warm]])
    rows, warmrows = repeats_cost.collect_all(str(tmp_path))
    every = [w for w in warmrows if w["study"] == repeats_cost.ALL]
    assert [w["repeat"] for w in every] == [1, 2, 3] and every[0]["processes"] == 2 and every[0]["unsplit"] == 0
    assert every[0]["build_over_least_median"] == pytest.approx(2.0) and every[0]["build_warm_share"] == 0.0
    assert every[1]["build_over_least_median"] == pytest.approx(1.05) and every[1]["build_warm_share"] == 0.5
    assert every[1]["trace_warm_share"] == 1.0 and every[2]["build_warm_share"] == 1.0
    assert every[0]["minor_faults_median"] == 2000 and every[1]["minor_faults_median"] == 20
    out = str(tmp_path / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(tmp_path), "--out", out]) == 0
    lines = open(out + "-warm.csv").read().splitlines()
    assert lines[0].split(",") == repeats_cost.WARM_COLUMNS and len(lines) == 1 + 2 * 3
    md = open(out + ".md").read()
    assert "| 2 | 1.000 (100.0%) | 1.050 (50.0%) |" in md
    assert "for the build in 50.0% of the processes" in md
    assert not os.path.exists(out + "-warm.csv.tmp")


def test_warm_split_that_does_not_check_is_left_out(tmp_path):
    """Negative control: a render whose processes' minima do not match the
    split (its repeats cannot be told apart) is counted, not guessed; one
    whose repeats do not divide among its processes likewise."""
    root = tmp_path / "runs" / "w-32x24-s2-t1"
    a, b = rep(2.0, 2.0, 2.0, 2.0), rep(1.0, 1.0, 1.0, 1.0)
    keys = PH + ("total",)
    merged(str(root / "x" / "seed1.stats.json"), [[a, b, b], [a, b, b]],
           minima={k: [9.0, 9.0] for k in keys})
    merged(str(root / "x" / "seed2.stats.json"), [[a, b, b], [a, b]])
    every = [w for w in repeats_cost.collect_all(str(tmp_path))[1] if w["study"] == repeats_cost.ALL]
    assert every[0]["processes"] == 0 and every[0]["unsplit"] == 2
    assert all(math.isnan(every[1][f"{p}_over_least_median"]) for p in repeats_cost.PHASES)
    out = str(tmp_path / "bench" / "repeats")
    assert repeats_cost.main(["--results", str(tmp_path), "--out", out]) == 0
    assert "No process of at least 3 repeats under runs/." in open(out + ".md").read()
