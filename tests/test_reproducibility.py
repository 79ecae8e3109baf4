"""Unit tests of experiments/analysis/reproducibility.py: two runs of the
grid compared.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`); pytest rewrites
the asserts, so they check under `python3 -O` too. Every check compares
against a value computed another way (a closed form, a simulation with a
known answer, the definition computed directly), so each can fail. Random
numbers come from fixed seeds: the outcome is deterministic.
"""

import json
import os
import tempfile

import numpy as np
import pandas as pd

from experiments.analysis import reproducibility
from helpers import table1_frame


def test_reproducibility_compare():
    """Deltas in pp, overlap flags and the goal: met for close runs, not met
    when one cell's intervals are disjoint (negative control) or the median
    |delta| exceeds the goal."""
    a = table1_frame([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.0, 0.02)] * 3)
    b = table1_frame([(81, 76, 86), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    f = reproducibility.compare(a, b)
    assert list(f["ratio_delta_pp"]) == [-1, -1, 2]
    s = reproducibility.summary(f, 3.0)
    assert s["ratio_median_abs_delta_pp"] == 1 and s["met"] and s["ratio_overlap_cells"] == 3
    c = table1_frame([(81, 76, 86), (50, 48, 52), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    s = reproducibility.summary(reproducibility.compare(a, c), 3.0)
    assert s["ratio_overlap_cells"] == 2 and not s["met"]
    s = reproducibility.summary(reproducibility.compare(a, b), 0.5)
    assert not s["met"]
    # the largest |delta| (2 pp) above its bound; the drift control (the
    # trace ratios 80/81, 40/41, 100/98) outside [97, 103] in two cells
    s = reproducibility.summary(f, 3.0, max_pp=1.5)
    assert s["ratio_max_abs_delta_pp"] == 2 and not s["met"]
    s = reproducibility.summary(f, 3.0, drift=(97, 103))
    assert s["drift_inside_cells"] == 1 and (s["drift_min"], s["drift_max"]) == (40, 100) and not s["met"]
    assert reproducibility.summary(f, 3.0, max_pp=2, drift=(39, 101))["met"]


def test_reproducibility_phase_load():
    """Each phase's ratio busy / A over the renders both runs made: the
    medians of known ratios and of their distance from 1; a render only one
    run made is left out."""
    def runs(scale, seeds):
        return pd.DataFrame([{"method": m, "estimate": "paper", "photons": 50000, "nn": 10, "seed": k, "status": "ok",
                              "trace_s": 0.1 * scale[k - 1], "build_s": 0.05, "precompute_s": 0.0,
                              "render_s": 1.0 * scale[k - 1], "total_s": 1.15 * scale[k - 1]}
                             for m in ("conventional", "precomputed") for k in seeds])
    rows = reproducibility.phase_load(runs([1, 1, 1, 1], (1, 2, 3)), runs([1.1, 1.3, 1.2, 9.0], (1, 2, 3, 4)))
    by = {(r["method"], r["phase"]): r for r in rows}
    assert by[("precomputed", "trace")]["renders"] == 3
    assert abs(by[("precomputed", "trace")]["median_ratio"] - 1.2) < 1e-12
    assert abs(by[("precomputed", "trace")]["median_abs_change"] - 0.2) < 1e-12  # |1.1, 1.3, 1.2 - 1|
    assert abs(by[("conventional", "render")]["max_ratio"] - 1.3) < 1e-12
    assert by[("conventional", "build")]["median_ratio"] == 1.0
    assert by[("conventional", "precompute")]["renders"] == 0  # 0 s: no ratio


def test_reproducibility_prints_reference_error():
    """reproducibility.md names the reference with its measured noise and
    kernel bias from the JSON beside it (a converged reference); control: a
    reference without one is said to be unmeasured, and no number is made up."""
    a = table1_frame([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.0, 0.02)] * 3)
    b = table1_frame([(81, 76, 86), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    runs = pd.DataFrame([{"scene": "scenes/cornell.scene", "width": 64, "height": 48, "subpixels": 2, "threads": 1,
                          "method": m, "estimate": "paper", "photons": 50000, "nn": 10, "seed": k, "status": "ok",
                          "relmse_ref": 0.01 * k, "loadavg_1min": 0.5} for m in ("conventional", "precomputed")
                         for k in (1, 2)])
    with tempfile.TemporaryDirectory() as d:
        paths = {}
        for name, frame in (("ta", a), ("tb", b), ("ra", runs), ("rb", runs)):
            paths[name] = os.path.join(d, name + ".csv")
            frame.to_csv(paths[name], index=False)
        pd.DataFrame([{"kind": "curve", "target": 0.02}, {"kind": "tightest", "target": 0.015}]).to_csv(
            os.path.join(d, "ee.csv"), index=False)
        ref = os.path.join(d, "ref.exr")
        info = {"noise": 0.000367, "bias": 1.9e-05, "bias_raw": 1.9e-05, "metric": "relmse",
                "settings": {"method": "conventional", "direct": "shadow-rays", "photons": 10000000, "nn": 200,
                             "seeds": [1000001, 1000002]}}
        with open(os.path.join(d, "ref.json"), "w") as f:
            json.dump(info, f)
        args = ["--table-a", paths["ta"], "--table-b", paths["tb"], "--runs-a", paths["ra"], "--runs-b", paths["rb"],
                "--equal-error-a", os.path.join(d, "ee.csv")]
        reproducibility.main(args + ["--ref", ref, "--out", os.path.join(d, "r1")])
        with open(os.path.join(d, "r1.md")) as f:
            text = f.read()
        assert f"Reference `{ref}`" in text and "noise 0.000367" in text and "kernel bias 1.9e-05" in text
        assert "0.015" in text  # checked against run A's tightest target
        bare = os.path.join(d, "pov.exr")
        reproducibility.main(args + ["--ref", bare, "--out", os.path.join(d, "r2")])
        with open(os.path.join(d, "r2.md")) as f:
            text = f.read()
        assert "its own error is not measured here" in text and "noise 0.000367" not in text
        assert "busy loop" not in text
        # a third run with a busy loop: its section, judged by its own goal
        c = table1_frame([(85, 80, 90), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
        c.to_csv(os.path.join(d, "tc.csv"), index=False)
        reproducibility.main(args + ["--table-busy", os.path.join(d, "tc.csv"), "--runs-busy", paths["rb"],
                                     "--busy-goal-pp", "3", "--out", os.path.join(d, "r3")])
        with open(os.path.join(d, "r3.md")) as f:
            text = f.read()
        assert "busy loop on the other core" in text and "median |delta| 2.00 pp" in text
        assert list(pd.read_csv(os.path.join(d, "r3.csv"))["runs"]) == ["a-b"] * 3 + ["a-busy"] * 3


def test_reproducibility_pooled_drift():
    """The drift control with each render's time the minimum over several
    runs' processes, against the geometric mean computed by hand: one slow
    precomputed trace in A (1.2x) puts the cell outside [97, 103] alone and
    inside once B's process is pooled; control: a pool whose other run is
    slow too stays outside."""
    def runs(prec_trace):
        return pd.DataFrame([{"method": m, "estimate": "paper", "photons": 50000, "nn": 10, "seed": k,
                              "status": "ok", "trace_s": (prec_trace[k - 1] if m == "precomputed" else 0.1)}
                             for m in ("conventional", "precomputed") for k in (1, 2)])
    a, b, slow = runs([0.12, 0.1]), runs([0.1, 0.1]), runs([0.13, 0.1])
    one = reproducibility.pooled_drift([a], (97, 103))
    assert one["cells"] == 1 and one["inside"] == 0
    assert abs(one["min"] - 100 * (1.2 ** 0.5)) < 1e-9  # exp(mean(log 1.2, log 1))
    two = reproducibility.pooled_drift([a, b], (97, 103))
    assert two["inside"] == 1 and abs(two["max"] - 100) < 1e-9
    assert reproducibility.pooled_drift([a, slow], (97, 103))["inside"] == 0
    # a render one run lacks is left out of the pool
    assert reproducibility.pooled_drift([a, b.iloc[:3]], (97, 103))["cells"] == 1


def test_rounds_only_leaves_out_the_gauges_processes(tmp_path):
    """A render the gauge gave a third process (trace 0.10 there, 0.12 in
    the rounds' two): the rounds alone time it 0.12, so its cell's drift
    control leaves [97, 103]; renders without an added process keep their
    time. Controls: no gauge_added column, or none added, gives None; a
    missing stats file gives None."""
    import json
    base = tmp_path / "precomputed-paper-p50000-n10" / "seed1"
    base.parent.mkdir()
    (tmp_path / "precomputed-paper-p50000-n10" / "seed1.stats.json").write_text(
        json.dumps({"time_s_processes": {"trace": [0.12, 0.125, 0.10]}}))
    runs = pd.DataFrame([{"method": m, "estimate": "paper", "photons": 50000, "nn": 10, "seed": 1, "status": "ok",
                          "trace_s": 0.10, "processes": 3 if m == "precomputed" else 2,
                          "gauge_added": 1 if m == "precomputed" else 0,
                          "run": str(base) if m == "precomputed" else str(tmp_path / "none")}
                         for m in ("conventional", "precomputed")])
    r = reproducibility.rounds_only(runs)
    assert list(r["trace_s"]) == [0.10, 0.12]
    assert reproducibility.pooled_drift([runs], (97, 103))["inside"] == 1
    assert reproducibility.pooled_drift([r], (97, 103))["inside"] == 0
    assert reproducibility.rounds_only(runs.drop(columns="gauge_added")) is None
    assert reproducibility.rounds_only(runs.assign(gauge_added=0)) is None
    assert reproducibility.rounds_only(runs.assign(run=str(tmp_path / "missing"))) is None


def test_reproducibility_process_change():
    """How far the same render's time moves between two processes: the
    median and 90th percentile of |B / A - 1| against numpy on known ratios
    (both methods pooled); a render one run lacks is left out."""
    def runs(totals):
        return pd.DataFrame([{"method": m, "estimate": "paper", "photons": 50000, "nn": 10, "seed": k + 1,
                              "status": "ok", "total_s": t} for m in ("conventional", "precomputed")
                             for k, t in enumerate(totals)])
    a, b = runs([1.0, 1.0, 1.0, 1.0, 1.0]), runs([1.1, 0.8, 1.0, 1.3, 1.05])
    med, p90 = reproducibility.process_change(a, b)
    d = np.abs(np.array([1.1, 0.8, 1.0, 1.3, 1.05] * 2) - 1)
    assert abs(med - np.median(d)) < 1e-12 and abs(p90 - np.percentile(d, 90)) < 1e-12
    med, _ = reproducibility.process_change(a, b.iloc[:1])  # one render in common: |1.1 - 1|
    assert abs(med - 0.1) < 1e-12


def test_pinning_text():
    """The runs' CPU column worded: one CPU for every render; none (records
    before pinning, or --cpu none); a mixture says some were not pinned."""
    import pandas as pd
    from experiments.analysis import reproducibility as rp
    assert rp.pinning_text(pd.DataFrame({"cpu": [0, 0, 0]})).startswith("every render pinned to CPU 0")
    assert rp.pinning_text(pd.DataFrame({"cpu": [float("nan")] * 2})) == "not pinned"
    assert rp.pinning_text(pd.DataFrame({"x": [1]})) == "not pinned"
    assert rp.pinning_text(pd.DataFrame({"cpu": [0, float("nan")]})) == "pinned to CPUs 0 (some renders not pinned)"


def test_processes_text():
    """The runs' processes column worded: two processes said; one, or no
    column (records before TIME_PROCESSES), says nothing."""
    import pandas as pd
    from experiments.analysis import reproducibility as rp
    assert rp.processes_text(pd.DataFrame({"processes": [2, 2]})).startswith("; each render timed in 2 processes")
    assert "1-2 processes" in rp.processes_text(pd.DataFrame({"processes": [1, 2]}))
    assert rp.processes_text(pd.DataFrame({"processes": [1, 1]})) == ""
    assert rp.processes_text(pd.DataFrame({"x": [1]})) == ""
    text = rp.processes_text(pd.DataFrame({"processes": [2, 3, 4, 2], "gauge_added": [0, 1, 2, 0]}))
    assert "2-4 processes" in text and "gauge (TIME_GAUGE) added 3 processes to 2 of 4 renders" in text
    assert "gauge" not in rp.processes_text(pd.DataFrame({"processes": [2, 2], "gauge_added": [0, 0]}))


def spell_runs(tmp_path, conv2):
    """Two groups' renders with their stats and records: seed 1 fast in both
    members; seed 2's conventional processes timed CONV2 (the gauge gave
    it four), its precomputed ones 0.100 and 0.101."""
    procs = {("conventional", 1): ([0.100, 0.101], [1, 2]), ("precomputed", 1): ([0.100, 0.102], [2, 1]),
             ("conventional", 2): (conv2, [2, 1, 2, 1]), ("precomputed", 2): ([0.100, 0.101], [1, 2])}
    rows = []
    for (m, seed), (t, pos) in procs.items():
        base = tmp_path / f"{m}-paper-p50000-n10" / f"seed{seed}"
        base.parent.mkdir(exist_ok=True)
        (tmp_path / f"{m}-paper-p50000-n10" / f"seed{seed}.stats.json").write_text(
            json.dumps({"time_s": {"trace": min(t)}, "time_s_processes": {"trace": t}}))
        (tmp_path / f"{m}-paper-p50000-n10" / f"seed{seed}.run.json").write_text(
            json.dumps({"pair_pos_processes": pos}))
        rows.append({"method": m, "estimate": "paper", "photons": 50000, "nn": 10, "seed": seed, "status": "ok",
                     "run": str(base)})
    return pd.DataFrame(rows)


def test_slow_spells_by_hand(tmp_path):
    """Seed 2's conventional member ran all four processes 10-12% slow: the
    run's 10th percentile is 0.100, so four of ten processes are slow; in
    the order they ran (prec .100, conv .110, conv .111, prec .101, conv
    .112, conv .111) a slow one follows a slow one in 2 of 3 cases; the
    group is uneven by 10%. Control: the same member at the others' speed
    leaves nothing slow and nothing uneven; a missing record gives None."""
    sp = reproducibility.slow_spells(spell_runs(tmp_path, [0.110, 0.111, 0.112, 0.111]), 4.0)
    assert sp["processes"] == 10 and abs(sp["slow"] - 0.4) < 1e-12 and abs(sp["after_slow"] - 2 / 3) < 1e-12
    assert [u[:4] for u in sp["uneven"]] == [("paper", 50000, 10, 2)] and abs(sp["uneven"][0][4] - 10.0) < 1e-9
    text = "\n".join(reproducibility.spell_lines([("A", spell_runs(tmp_path, [0.110, 0.111, 0.112, 0.111]))], 4.0))
    assert "| A | 10 | 40 | 67 | 1 |" in text and "A: paper P_e=50000 n=10 seed 2 (10.0%)" in text
    calm = reproducibility.slow_spells(spell_runs(tmp_path, [0.100, 0.101, 0.100, 0.101]), 4.0)
    assert calm["slow"] == 0 and calm["uneven"] == [] and np.isnan(calm["after_slow"])
    runs = spell_runs(tmp_path, [0.1, 0.1, 0.1, 0.1])
    os.remove(tmp_path / "conventional-paper-p50000-n10" / "seed2.run.json")
    assert reproducibility.slow_spells(runs, 4.0) is None
    assert reproducibility.spell_lines([("A", runs)], 4.0) == []
