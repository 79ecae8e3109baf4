"""Time ratios as paired per-seed log ratios with t intervals over seeds
(experiments/analysis/stats.py, table.py).

The coverage check is a simulation with a known answer: renders whose times
are a true ratio apart, each with log-normal machine noise. The 95% t
interval of the mean per-seed log ratio covers the true ratio in about 95%
of trials at 3 and at 5 seeds; a percentile bootstrap of the same mean (the
negative control) covers far less, which is why no time ratio uses one.
Random numbers come from fixed seeds: the outcome is deterministic."""

import math

import numpy as np
import pandas as pd
import pytest

from experiments.analysis import stats, table

TRUE = 0.7    # precomputed / conventional
SIGMA = 0.1   # log-normal noise of one render's time
TRIALS = 2000


def simulate(seeds, rng):
    """One trial: (precomputed, conventional) times of SEEDS seeds."""
    return TRUE * np.exp(rng.normal(0, SIGMA, seeds)), np.exp(rng.normal(0, SIGMA, seeds))


def coverage(seeds, interval, seed):
    rng = np.random.default_rng(seed)
    hits = 0
    for _ in range(TRIALS):
        a, b = simulate(seeds, rng)
        lo, hi = interval(a, b, rng)
        hits += lo <= TRUE <= hi
    return hits / TRIALS


def t_interval(a, b, rng):
    return stats.paired_log_ratio(a, b)[1:3]


def percentile_bootstrap(a, b, rng):
    """The percentile bootstrap of the same geometric-mean ratio: seeds
    resampled with replacement, 500 resamples."""
    d = np.log(a / b)
    lo, hi, _ = stats.percentile_interval(np.exp(d[stats.resample_indices(rng, d.size, 500)].mean(axis=1)))
    return lo, hi


@pytest.mark.parametrize("seeds", [3, 5])
def test_t_interval_covers_95(seeds):
    c = coverage(seeds, t_interval, 20 + seeds)
    assert 0.93 <= c <= 0.97, f"{seeds} seeds: t interval covers {c}"


@pytest.mark.parametrize("seeds,below", [(3, 0.85), (5, 0.90)])
def test_percentile_bootstrap_undercovers(seeds, below):
    """Negative control: the percentile bootstrap at few seeds misses the
    true ratio far more often than 5% (about 26% at 3 seeds, 16% at 5)."""
    c = coverage(seeds, percentile_bootstrap, 40 + seeds)
    assert c < below, f"{seeds} seeds: percentile bootstrap covers {c}"


def grid_runs(seeds=3, seed=5):
    """A runs frame of one cell (both methods, paper estimate) whose
    precomputed renders take TRUE x the conventional one's time, noisy."""
    rng = np.random.default_rng(seed)
    rows = []
    for s in range(1, seeds + 1):
        base = math.exp(rng.normal(0, SIGMA))
        for method, t in (("conventional", base), ("precomputed", TRUE * base * math.exp(rng.normal(0, SIGMA)))):
            rows.append({"method": method, "estimate": "paper", "photons": 50000, "nn": 10, "seed": s,
                         "status": "ok", "role": "grid", "message": "", "width": 64, "height": 48, "subpixels": 2,
                         "tag": "", "threads": 1, "total_s": t, "cpu_s": 1.1 * t, "trace_s": 0.2 * base,
                         "build_s": 0.01, "precompute_s": 0.1 if method == "precomputed" else 0.0,
                         "render_s": 0.5 * t, "relmse_ref": 0.1 + 0.01 * s, "relmse_conv": 0.0 if
                         method == "conventional" else 0.02, "photons_stored": 1000, "representatives": 100,
                         "empty_estimates": 0})
    return pd.DataFrame(rows)


def test_table_ratio_is_the_paired_t_ratio():
    """table.py's ratio_percent (the Markdown's "our ratio %") is the paired
    per-seed log ratio with its t interval, not a ratio of medians."""
    runs = grid_runs()
    cells = pd.DataFrame([{"method": m, "estimate": "paper", "photons": 50000, "nn": 10, "bias_ref": 0.1,
                           "variance_ref": 0.01, "relmse_ref_floor": math.nan, "ref": "", "ref_fast": ""}
                          for m in ("conventional", "precomputed")])
    paper = pd.DataFrame([{"emitted_kphotons": 50, "nn": 10, "conventional_s": 10.0, "proposed_s": 7.0,
                           "ratio_percent": 70.0}])
    t, _ = table.summarize(runs, cells, paper)
    p = t[t["method"] == "precomputed"].iloc[0]
    a = runs.loc[runs["method"] == "precomputed", "total_s"].to_numpy()
    b = runs.loc[runs["method"] == "conventional", "total_s"].to_numpy()
    d = np.log(a / b)
    half = 4.302652729911275 * d.std(ddof=1) / math.sqrt(3)   # t(0.975, 2)
    for col in ("ratio", "paired_ratio"):
        assert abs(p[f"{col}_percent"] - 100 * math.exp(d.mean())) < 1e-9
        assert abs(p[f"{col}_ci95_lo"] - 100 * math.exp(d.mean() - half)) < 1e-9
        assert abs(p[f"{col}_ci95_hi"] - 100 * math.exp(d.mean() + half)) < 1e-9
    # not the ratio of medians (which differs for this draw)
    assert abs(p["ratio_percent"] - 100 * np.median(a) / np.median(b)) > 1e-6
    c = t[t["method"] == "conventional"].iloc[0]
    assert c["ratio_percent"] == 100 and c["ratio_ci95_lo"] == 100 and c["ratio_ci95_hi"] == 100
