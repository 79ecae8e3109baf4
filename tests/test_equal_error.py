"""Unit tests of experiments/analysis/equal_error.py: the speed-up at equal
error, its curve and its tightest target.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`); pytest rewrites
the asserts, so they check under `python3 -O` too. Every check compares
against a value computed another way (a closed form, a simulation with a
known answer, the definition computed directly), so each can fail. Random
numbers come from fixed seeds: the outcome is deterministic.
"""

import math

import numpy as np
import pandas as pd

from experiments.analysis import equal_error
from helpers import close


# ---- equal error

def synthetic_runs(speedup, seeds=5, noise=0.02):
    """runs.csv rows of a grid where both methods follow error = 1/n and the
    precomputed method takes 1/SPEEDUP of the conventional time at every
    cell, with a little multiplicative noise per seed."""
    rng = np.random.default_rng(9)
    rows = []
    for method, scale in (("conventional", 1.0), ("precomputed", 1.0 / speedup)):
        for n in (10, 20, 50, 100):
            for s in range(1, seeds + 1):
                rows.append({"role": "grid", "status": "ok", "estimate": "paper", "method": method,
                             "photons": 1000, "nn": n, "seed": s,
                             "cpu_s": scale * n * math.exp(noise * rng.standard_normal()),
                             "relmse_ref": (1.0 / n) * math.exp(noise * rng.standard_normal())})
    return pd.DataFrame(rows)


def test_equal_error_recovers_speedup():
    """With precomputed exactly 3x faster at every error, the speed-up at
    each automatic target is 3 within 5%, its interval contains 3, and the
    targets lie inside both fronts' error range."""
    res = equal_error.analyse(synthetic_runs(3.0), "paper", "cpu_s", "auto", np.random.default_rng(2), 400)
    assert len(res["rows"]) == 5, res["targets"]
    for r in res["rows"]:
        assert 0.01 < r["target"] < 0.1, r["target"]
        close(r["speedup"], 3.0, 0.15, f"speed-up at {r['target']}")
        assert r["lo"] <= 3.0 <= r["hi"], r


def test_equal_error_curve_and_tightest_target():
    """The curve spans the whole common range of the fronts (errors 1/n,
    n = 10 ... 100, so about 0.01 to 0.1) with CURVE_POINTS targets; the
    speed-up is 3 all along it, inside its band wherever the band is
    defined in every resample; the tightest target is the larger of the
    fronts' smallest errors, computed directly."""
    runs = synthetic_runs(3.0)
    res = equal_error.analyse(runs, "paper", "cpu_s", "auto", np.random.default_rng(2), 400)
    c = res["curve"]
    assert len(c) == equal_error.CURVE_POINTS
    xs = [r["target"] for r in c]
    assert xs == sorted(xs)
    mins = [runs[runs.method == m].groupby("nn").relmse_ref.mean().min() for m in ("conventional", "precomputed")]
    maxs = [runs[runs.method == m].groupby("nn").relmse_ref.mean().max() for m in ("conventional", "precomputed")]
    close(res["tightest"]["target"], max(mins), 1e-12, "tightest target")
    close(xs[0], max(mins), 1e-12, "curve start")
    close(xs[-1], min(maxs), 1e-12, "curve end")
    assert res["tightest"]["kind"] == "tightest" and all(r["kind"] == "curve" for r in c)
    for r in c:
        close(r["speedup"], 3.0, 0.2, f"speed-up at {r['target']}")
        if r["defined_fraction"] == 1:
            assert r["lo"] <= 3.0 <= r["hi"], r


def test_equal_error_curve_shows_a_changing_speedup():
    """A speed-up that grows with the error (precomputed's time scale 1 at
    n = 100 up to 1/4 at n = 10): the curve rises from about 1 at the
    tightest target to about 4 at the loosest, so no single point stands for
    it; negative control: the constant case above stays flat."""
    runs = synthetic_runs(1.0, noise=0.01)
    sel = runs.method == "precomputed"
    runs.loc[sel, "cpu_s"] = runs.loc[sel, "cpu_s"] / (1 + 3 * (100 - runs.loc[sel, "nn"]) / 90)
    res = equal_error.analyse(runs, "paper", "cpu_s", "auto", np.random.default_rng(2), 200)
    sp = [r["speedup"] for r in res["curve"]]
    close(sp[0], 1.0, 0.1, "at the tightest target")
    close(sp[-1], 4.0, 0.3, "at the loosest target")
    flat = [r["speedup"] for r in equal_error.analyse(synthetic_runs(3.0, noise=0.01), "paper", "cpu_s", "auto",
                                                      np.random.default_rng(2), 200)["curve"]]
    assert max(flat) / min(flat) < 1.05 and sp[-1] / sp[0] > 3


def test_equal_error_no_common_range():
    """Fronts that reach no common error give no target; explicit targets
    outside a front give undefined times."""
    runs = synthetic_runs(2.0)
    runs.loc[runs["method"] == "precomputed", "relmse_ref"] *= 100
    res = equal_error.analyse(runs, "paper", "cpu_s", "auto", np.random.default_rng(2), 50)
    assert res["targets"] == [] and res["rows"] == []
    res = equal_error.analyse(runs, "paper", "cpu_s", "0.05", np.random.default_rng(2), 50)
    assert math.isnan(res["rows"][0]["precomputed_s"]) and math.isnan(res["rows"][0]["speedup"])


def test_headline_only_where_defined():
    """equal_error.headline: the tightest curve target with at least 95% of
    the resamples defined; a tightest target defined in 50% is never the
    headline, and with none at 95% there is none. evaluate.py's verdict
    words the headline, not the half-defined tightest target."""
    from experiments.analysis import evaluate
    rows = [{"estimate": "paper", "kind": "curve", "target": 0.01, "speedup": 1.8, "lo": 0.9, "hi": 7.0,
             "defined_fraction": 0.5},
            {"estimate": "paper", "kind": "curve", "target": 0.02, "speedup": 1.5, "lo": 1.2, "hi": 1.9,
             "defined_fraction": 0.96},
            {"estimate": "paper", "kind": "curve", "target": 0.04, "speedup": 1.3, "lo": 1.1, "hi": 1.6,
             "defined_fraction": 1.0}]
    assert equal_error.headline(rows)["target"] == 0.02
    assert equal_error.headline([dict(r, defined_fraction=0.94) for r in rows]) is None
    ee = pd.DataFrame([dict(rows[0], kind="tightest")] + rows)
    text = evaluate.verdict_of(ee, "paper")
    assert "1.8x" not in text and "[0.9, 7]" not in text, text
    assert "(relMSE 0.02) the method pays: 1.5x [1.2, 1.9]" in text, text


def paired_runs(seeds=6, spread=0.3, drop=None):
    """A grid where each seed's photon map makes both methods' renders
    slower or faster together (a per-seed factor, spread SPREAD in log, the
    same for every cell and both methods) and the precomputed method is 2x
    faster: the per-seed ratio is exactly 2. DROP (method, n, seed) leaves
    one render out."""
    rng = np.random.default_rng(4)
    seed_factor = {s: math.exp(spread * rng.standard_normal()) for s in range(1, seeds + 1)}
    rows = []
    for method, scale in (("conventional", 1.0), ("precomputed", 0.5)):
        for n in (10, 20, 50, 100):
            for s in range(seeds, 0, -1):  # seeds out of order: the samples are sorted by seed
                if drop == (method, n, s):
                    continue
                rows.append({"role": "grid", "status": "ok", "estimate": "paper", "method": method,
                             "photons": 1000, "nn": n, "seed": s, "cpu_s": scale * n * seed_factor[s],
                             "relmse_ref": (1.0 / n) * seed_factor[s]})
    return pd.DataFrame(rows)


def test_bootstrap_is_paired_over_seeds():
    """A seed's renders move together in both methods (one photon map): the
    paired bootstrap draws each seed once for every cell of both methods,
    so the per-seed factor cancels and the speed-up's band is 2 within
    1e-9 however large the seeds' spread; a cell's seeds are sorted by seed.
    Negative control: one render missing, the cells' seeds differ, each
    cell is drawn on its own and the band widens well past that."""
    res = equal_error.analyse(paired_runs(), "paper", "cpu_s", "auto", np.random.default_rng(3), 400)
    assert res["paired"] and res["rows"]
    for r in res["rows"]:
        close(r["lo"], 2.0, 1e-9, "paired band, low end")
        close(r["hi"], 2.0, 1e-9, "paired band, high end")
    seeds = {}
    equal_error.cell_samples(paired_runs(), "paper", "conventional", "cpu_s", seeds)
    assert seeds[(1000, 10)] == (1, 2, 3, 4, 5, 6)
    ctl = equal_error.analyse(paired_runs(drop=("precomputed", 50, 3)), "paper", "cpu_s", "auto",
                              np.random.default_rng(3), 400)
    assert not ctl["paired"]
    widths = [r["hi"] / r["lo"] for r in ctl["rows"] if math.isfinite(r["lo"])]
    assert widths and max(widths) > 1.2, widths
    assert "once for every cell of both methods" in equal_error.paired_text([res])
    assert "on their own" in equal_error.paired_text([ctl])


def test_shared_indices():
    """One draw for every cell when all share their seeds; None when one
    cell's seeds differ."""
    rng = np.random.default_rng(1)
    same = {"a": {(1, 1): (1, 2, 3), (1, 2): (1, 2, 3)}, "b": {(1, 1): (1, 2, 3)}}
    idx = equal_error.shared_indices(same, rng, 50)
    assert idx.shape == (50, 3) and idx.min() >= 0 and idx.max() <= 2
    assert equal_error.shared_indices({"a": {(1, 1): (1, 2, 3)}, "b": {(1, 1): (1, 2)}}, rng, 50) is None
