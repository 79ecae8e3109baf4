"""Unit tests of the experiment analysis layer (experiments/analysis/).

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test`: `python3 -m pytest tests/test_analysis.py`); pytest rewrites the
asserts, so they check under `python3 -O` too.
Every check compares against a value computed another way (a closed form, a
simulation with a known answer, the definition computed directly), so each can
fail. Random numbers come from fixed seeds: the outcome is deterministic.
"""

import json
import math
import os
import subprocess
import tempfile

import numpy as np
import pandas as pd

from experiments.analysis import equal_error, metrics, stats

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def close(a, b, tol, what=""):
    """Assert |a - b| <= tol."""
    assert abs(a - b) <= tol, f"{what}: {a} vs {b} (tolerance {tol})"


# ---- stats: intervals over seeds

def test_t_interval_coverage():
    """The 95% t-interval of 5 normal draws covers the true mean in about 95%
    of 4000 trials (a z-interval would cover about 88%: this fails then)."""
    rng = np.random.default_rng(7)
    hits = 0
    trials = 4000
    for _ in range(trials):
        m, h = stats.t_interval(rng.normal(3.0, 2.0, size=5))
        hits += (m - h) <= 3.0 <= (m + h)
    cover = hits / trials
    assert 0.935 <= cover <= 0.965, f"coverage {cover}"


def test_t_interval_edges():
    """One value: no half-width; NaN values are dropped; the known value for
    (1, 2, 3): mean 2, half-width t(0.975, 2) * 1 / sqrt(3) = 2.4841."""
    m, h = stats.t_interval([4.0])
    assert m == 4.0 and math.isnan(h)
    m, h = stats.t_interval([1.0, float("nan"), 2.0, 3.0])
    close(m, 2.0, 1e-12, "mean")
    close(h, 4.302652729911275 / math.sqrt(3), 1e-9, "half-width")
    assert all(math.isnan(x) for x in stats.t_interval([]))


def test_median_range_known():
    """Median with min and max, NaN ignored."""
    assert stats.median_range([3.0, 1.0, float("nan"), 2.0, 10.0]) == (2.5, 1.0, 10.0)


def test_percentile_interval_known():
    """The 2.5% and 97.5% quantiles of 0..1000 are 25 and 975; the share of
    finite samples is reported."""
    lo, hi, d = stats.percentile_interval(np.append(np.arange(1001.0), [np.nan] * 1001))
    close(lo, 25.0, 1e-9, "lo")
    close(hi, 975.0, 1e-9, "hi")
    close(d, 0.5, 1e-12, "defined")


def test_median_ratio_known():
    """median(a)/median(b) and an interval that contains it; constant
    samples give a degenerate interval at the ratio."""
    rng = np.random.default_rng(1)
    r, lo, hi = stats.median_ratio([2.0, 2.0, 2.0], [4.0, 4.0, 4.0], rng, 500)
    assert (r, lo, hi) == (0.5, 0.5, 0.5), (r, lo, hi)
    r, lo, hi = stats.median_ratio([1.0, 2.0, 9.0], [1.0, 1.0, 1.0], rng, 500)
    assert r == 2.0 and lo <= 2.0 <= hi and lo >= 1.0 and hi <= 9.0, (r, lo, hi)
    assert math.isnan(stats.median_ratio([1.0], [0.0], rng, 10)[0])


def test_intervals_overlap_known():
    """Disjoint intervals do not overlap; touching and unknown ones do."""
    assert not stats.intervals_overlap((1, 2), (3, 4))
    assert stats.intervals_overlap((1, 3), (3, 4))
    assert stats.intervals_overlap((1, float("nan")), (5, 6))


# ---- stats: fronts and interpolation

def test_pareto_front_known():
    """Dominated cells and cells with a tied time but a larger error are not
    on the front; the front is ordered by time."""
    t = [1.0, 2.0, 2.0, 3.0, 4.0, 0.5]
    e = [0.5, 0.6, 0.3, 0.4, 0.1, float("nan")]
    assert stats.pareto_front(t, e) == [0, 2, 4], stats.pareto_front(t, e)


def test_interpolation_power_law():
    """Cells on a power law t = 3 e^-1.5 lie on a straight line in log-log,
    so the interpolated time at any error between them is the law's."""
    e = np.array([0.2, 0.1, 0.05, 0.01])
    t = 3.0 * e ** -1.5
    for target in (0.2, 0.15, 0.07, 0.05, 0.011, 0.01):
        close(stats.time_at_error(t, e, target), 3.0 * target ** -1.5, 1e-9 * 3.0 * target ** -1.5, f"at {target}")
    close(stats.front_time_at_error(list(t) + [1000.0], list(e) + [0.5], 0.07), 3.0 * 0.07 ** -1.5, 1e-6, "front")


def test_interpolation_outside_is_undefined():
    """A target below the front's smallest error or above its largest is
    not extrapolated."""
    e = np.array([0.2, 0.1])
    t = np.array([1.0, 2.0])
    assert math.isnan(stats.time_at_error(t, e, 0.05))
    assert math.isnan(stats.time_at_error(t, e, 0.3))
    assert math.isnan(stats.time_at_error([], [], 0.1))


# ---- metrics

def test_relmse_known():
    """relMSE of identical images is 0 and PSNR inf; x = 2, r = 1 gives
    relMSE 1/1.01, RMSE 1, PSNR 0 dB; a size mismatch is an error."""
    r = np.full((4, 5, 3), 1.0)
    assert metrics.relmse(r, r) == 0.0 and metrics.psnr(r, r) == math.inf and metrics.rmse(r, r) == 0.0
    x = np.full((4, 5, 3), 2.0)
    close(metrics.relmse(x, r), 1 / 1.01, 1e-15, "relmse")
    close(metrics.rmse(x, r), 1.0, 1e-15, "rmse")
    close(metrics.psnr(x, r), 0.0, 1e-12, "psnr")
    try:
        metrics.relmse(x, np.zeros((5, 4, 3)))
    except ValueError:
        return
    raise AssertionError("size mismatch accepted")


def synthetic_truth(rng, bias_scale, sigma_scale, shape=(12, 16, 3)):
    """A reference r, a per-value bias b and noise sigma; returns (r, b,
    sigma, true bias term, true variance term) in the relMSE weighting."""
    r = rng.uniform(0.05, 1.0, size=shape)
    b = bias_scale * rng.uniform(-1.0, 1.0, size=shape)
    sigma = sigma_scale * rng.uniform(0.5, 1.5, size=shape)
    w = metrics.rel_weight(r)
    return r, b, sigma, float(np.mean(w * b * b)), float(np.mean(w * sigma * sigma))


def synthetic_cell(rng, seeds, bias_scale, sigma_scale):
    """SEEDS images x_s = r + b + sigma * N(0, 1) of one synthetic truth;
    returns (images, r)."""
    r, b, sigma, _, _ = synthetic_truth(rng, bias_scale, sigma_scale)
    return [r + b + sigma * rng.standard_normal(r.shape) for _ in range(seeds)], r


def test_bias_variance_recovers_truth():
    """Over 400 synthetic cells of 4 seeds whose noise is far larger than
    their bias (fresh noise, the same truth), the mean bias and variance
    estimates match the true terms within 4 standard errors; the plain
    squared error of the mean image (without the s^2/S correction) misses
    the bias by far (this would fail with that estimator)."""
    r, b, sigma, true_b, true_v = synthetic_truth(np.random.default_rng(11), 0.02, 0.1)
    rng = np.random.default_rng(3)
    est_b, est_v, naive = [], [], []
    for _ in range(400):
        imgs = [r + b + sigma * rng.standard_normal(r.shape) for _ in range(4)]
        bias, variance = metrics.bias_variance(imgs, r)
        est_b.append(bias)
        est_v.append(variance)
        naive.append(float(np.mean(metrics.rel_weight(r) * (np.mean(imgs, axis=0) - r) ** 2)))
    se_b = np.std(est_b, ddof=1) / math.sqrt(len(est_b))
    se_v = np.std(est_v, ddof=1) / math.sqrt(len(est_v))
    close(np.mean(est_b), true_b, 4 * se_b, "bias")
    close(np.mean(est_v), true_v, 4 * se_v, "variance")
    assert abs(np.mean(naive) - true_b) > 20 * se_b, "the uncorrected estimator should be far off"


def test_bias_variance_identity_and_definition():
    """bias + variance equals the mean over seeds of relMSE, and both equal
    the per-pixel definition written out here (mean image, ddof-1 variance)."""
    imgs, r = synthetic_cell(np.random.default_rng(5), 5, 0.05, 0.05)
    b, v = metrics.bias_variance(imgs, r)
    close(b + v, np.mean([metrics.relmse(x, r) for x in imgs]), 1e-12, "identity")
    w = 1.0 / (r * r + 0.01)
    stack = np.stack(imgs)
    s2 = stack.var(axis=0, ddof=1)
    close(v, float(np.mean(w * s2)), 1e-12, "variance definition")
    close(b, float(np.mean(w * ((stack.mean(axis=0) - r) ** 2 - s2 / 5))), 1e-12, "bias definition")
    assert all(math.isnan(x) for x in metrics.bias_variance(imgs[:1], r))


def test_bias_variance_counts_are_repeats():
    """Weighting seeds by bootstrap counts equals repeating the images."""
    imgs, r = synthetic_cell(np.random.default_rng(6), 3, 0.05, 0.05)
    g = metrics.weighted_gram(imgs, r)
    got = metrics.bias_variance_from_gram(g, [2, 0, 1])
    want = metrics.bias_variance([imgs[0], imgs[0], imgs[2]], r)
    close(got[0], want[0], 1e-12, "bias")
    close(got[1], want[1], 1e-12, "variance")


def test_metrics_command_line_matches_functions():
    """On a real pair of renders, the command line the shell tools call
    (python3 -m experiments.analysis.metrics) prints metrics.py's relMSE,
    RMSE and PSNR, and these equal a direct numpy computation of the
    definition; read_exr gives H x W x 3."""
    pm = os.environ.get("PM", os.path.join(ROOT, "build", "photonmap"))
    scene = os.path.join(ROOT, "scenes", "cornell.scene")
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "a.exr"), os.path.join(d, "b.exr")
        for path, method in ((a, "conventional"), (b, "precomputed")):
            subprocess.run([pm, "render", scene, "--width", "32", "--height", "24", "--photons", "3000", "--nn", "10",
                            "--method", method, "-o", path, "--quiet"], check=True)
        out = subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.metrics", b, a, "--csv"], check=True,
                             capture_output=True, text=True, cwd=ROOT).stdout.strip()
        c_rel, c_rmse, c_psnr = (float(v) for v in out.split(",")[:3])
        x, r = metrics.read_exr(b), metrics.read_exr(a)
        assert x.shape == (24, 32, 3), x.shape
        got = (metrics.relmse(x, r), metrics.rmse(x, r), metrics.psnr(x, r))
        d2 = (x - r) ** 2
        direct = (float((d2 / (r * r + 0.01)).sum() / d2.size), math.sqrt(d2.sum() / d2.size),
                  10 * math.log10(1.0 / (d2.sum() / d2.size)))
        for name, g, c, e in zip(("relMSE", "RMSE", "PSNR"), got, (c_rel, c_rmse, c_psnr), direct):
            assert abs(g - c) <= 1e-5 * abs(g), f"{name}: function {g} vs command line {c}"
            assert abs(g - e) <= 1e-9 * abs(e), f"{name}: function {g} vs the definition {e}"
        same = subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.metrics", a, a], check=True,
                              capture_output=True, text=True, cwd=ROOT).stdout.strip()
        assert same == "relmse=0 rmse=0 psnr=inf pixels=768 peak=1", same


def test_read_exr_missing_file():
    """A missing file is a ValueError that names it."""
    try:
        metrics.read_exr("/nonexistent/x.exr")
    except ValueError as e:
        assert "/nonexistent/x.exr" in str(e), str(e)
        return
    raise AssertionError("no error")


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


# ---- stats: the cost model's fit and the ratio of two slopes

def test_linear_fit_known():
    """An exact line gives its coefficients and zero standard errors; the
    standard errors of a noisy line agree with the closed form (numpy's
    polyfit covariance with the N-2 scaling)."""
    fit = stats.linear_fit([10, 20, 50, 100], [3.0 + 0.5 * n for n in (10, 20, 50, 100)])
    close(fit["a"], 3.0, 1e-12, "a")
    close(fit["b"], 0.5, 1e-12, "b")
    close(fit["se_b"], 0.0, 1e-12, "se_b")
    close(fit["r2"], 1.0, 1e-12, "r2")
    rng = np.random.default_rng(3)
    x = np.repeat([10.0, 20.0, 50.0, 100.0], 3)
    y = 2.0 + 0.1 * x + rng.normal(0, 0.3, x.size)
    fit = stats.linear_fit(x, y)
    coef, cov = np.polyfit(x, y, 1, cov="unscaled")
    s2 = np.sum(np.square(y - np.polyval(coef, x))) / (x.size - 2)
    close(fit["b"], coef[0], 1e-10, "b")
    close(fit["a"], coef[1], 1e-10, "a")
    close(fit["se_b"], math.sqrt(s2 * cov[0, 0]), 1e-10, "se_b")
    close(fit["se_a"], math.sqrt(s2 * cov[1, 1]), 1e-10, "se_a")
    close(fit["half_b"], 2.2281388519649385 * fit["se_b"], 1e-9, "t_{0.975,10}")
    assert fit["dof"] == 10 and fit["points"] == 12
    two = stats.linear_fit([1, 2], [1, 3])
    assert two["b"] == 2 and math.isnan(two["se_b"])
    assert math.isnan(stats.linear_fit([1, 1, 1], [1, 2, 3])["b"])


def test_linear_fit_coverage():
    """The 95% interval of the slope covers the true slope in about 95% of
    2000 noisy lines of 4 points (the paper's fits: 2 degrees of freedom)."""
    rng = np.random.default_rng(11)
    x = np.array([10.0, 20.0, 50.0, 100.0])
    hits = 0
    for _ in range(2000):
        fit = stats.linear_fit(x, 5.0 + 0.4 * x + rng.normal(0, 4.0, x.size))
        hits += abs(fit["b"] - 0.4) <= fit["half_b"]
    close(hits / 2000, 0.95, 0.015, "coverage")


def test_fieller_known():
    """Fieller's interval: exact without noise in the denominator (num/den
    +- t se_num/den); covers the true ratio of two noisy independent
    estimates in about 95% of trials; unbounded (nan) when the denominator
    is not significant."""
    r, lo, hi = stats.fieller_ratio(2.0, 0.5, 4.0, 0.0, 10)
    t = 2.2281388519649385
    close(r, 0.5, 1e-12, "ratio")
    close(lo, (2.0 - t * 0.5) / 4.0, 1e-12, "lo")
    close(hi, (2.0 + t * 0.5) / 4.0, 1e-12, "hi")
    rng = np.random.default_rng(5)
    hits = 0
    for _ in range(4000):
        num, den = rng.normal(1.0, 0.2), rng.normal(4.0, 0.8)
        _, lo, hi = stats.fieller_ratio(num, 0.2, den, 0.8, 1000)
        hits += lo <= 0.25 <= hi
    close(hits / 4000, 0.95, 0.012, "coverage")
    r, lo, hi = stats.fieller_ratio(1.0, 0.1, 0.1, 0.1, 10)
    assert r == 10.0 and math.isnan(lo) and math.isnan(hi)
    # the delta method's standard error against a simulation of the ratio
    sims = rng.normal(1.0, 0.02, 200000) / rng.normal(4.0, 0.08, 200000)
    close(stats.ratio_se(1.0, 0.02, 4.0, 0.08), float(np.std(sims)), 0.02 * float(np.std(sims)), "delta se")
    close(stats.ratio_se(0.0, 0.5, 2.0, 1.0), 0.25, 1e-12, "num 0")


def test_window_scaling():
    """The caustic window 24x20+52+76 at 128x96 is 96x80+208+304 at 512x384
    and the same pixels at 128x96; a window that leaves the image, or a
    malformed one, is an error."""
    assert metrics.scale_window("24x20+52+76", "128x96", "512x384") == (96, 80, 208, 304)
    assert metrics.scale_window("24x20+52+76", "128x96", (128, 96)) == (24, 20, 52, 76)
    img = np.arange(96 * 128 * 3, dtype=float).reshape(96, 128, 3)
    win = metrics.window(img, "24x20+52+76", "128x96")
    assert win.shape == (20, 24, 3) and win[0, 0, 0] == img[76, 52, 0] and win[-1, -1, 2] == img[95, 75, 2]
    for bad in ("24x20+110+0", "24x20", "0x5+1+1"):
        try:
            metrics.scale_window(bad, "128x96", "128x96")
        except ValueError:
            continue
        raise AssertionError(f"{bad} accepted")


def test_peak_ratio_known():
    """A copy keeps its peak (1); a box-blurred spot keeps less (about the
    blurred mean over the spot); a uniform scale is the scale."""
    r = np.full((20, 24, 3), 0.1)
    r[8:12, 10:14] = 2.0
    close(metrics.peak_ratio(r, r), 1.0, 1e-12, "copy")
    close(metrics.peak_ratio(0.5 * r, r), 0.5, 1e-12, "scale")
    from scipy.ndimage import uniform_filter
    blurred = uniform_filter(r, size=(5, 5, 1), mode="nearest")
    pr = metrics.peak_ratio(blurred, r, top=16 / 480)
    close(pr, float(blurred[8:12, 10:14, 1].mean()) / 2.0, 1e-9, "blur")
    assert pr < 0.7


def test_rank_known():
    """stats.rank: disjoint intervals rank, touching or overlapping ones do
    not, a nan end is unknown."""
    assert stats.rank((1, 2), (3, 4)) == "lower"
    assert stats.rank((3, 4), (1, 2)) == "higher"
    assert stats.rank((1, 3), (3, 4)) == "overlap"  # closed intervals: touching is overlapping
    assert stats.rank((1, 5), (2, 3)) == "overlap"
    assert stats.rank((math.nan, 2), (3, 4)) == "unknown"


# ---- stats: paired comparisons (timing pairs, error differences, Holm)

def correlated_pairs(rng, seeds, ratio, common_sd, own_sd):
    """(a, b): B = exp(common + own noise) and A = RATIO x exp(the same
    common + its own noise): a machine state shared by the two renders of a
    pair (COMMON_SD in log) and each render's own noise (OWN_SD)."""
    common = rng.normal(0.0, common_sd, size=seeds)
    b = np.exp(1.0 + common + rng.normal(0.0, own_sd, size=seeds))
    a = ratio * np.exp(1.0 + common + rng.normal(0.0, own_sd, size=seeds))
    return a, b


def test_paired_log_ratio_known():
    """Per-pair ratios 2, 2, 2 give exactly 2 with a zero-width interval;
    ratios 1.9, 2, 2.1 give their geometric mean with the t-interval of the
    logs computed directly."""
    r, lo, hi, n = stats.paired_log_ratio([2.0, 4.0, 6.0], [1.0, 2.0, 3.0])
    close(r, 2.0, 1e-12, "ratio")
    close(lo, 2.0, 1e-12, "lo")
    close(hi, 2.0, 1e-12, "hi")
    assert n == 3
    d = np.log([1.9, 2.0, 2.1])
    half = 4.302652729911275 * d.std(ddof=1) / math.sqrt(3)
    r, lo, hi, n = stats.paired_log_ratio([1.9, 4.0, 6.3], [1.0, 2.0, 3.0])
    close(r, math.exp(d.mean()), 1e-12, "geometric mean")
    close(lo, math.exp(d.mean() - half), 1e-12, "lo")
    close(hi, math.exp(d.mean() + half), 1e-12, "hi")
    r, lo, hi, n = stats.paired_log_ratio([2.0, math.nan, 0.0], [1.0, 1.0, 1.0])
    assert r == 2.0 and math.isnan(lo) and n == 1


def test_paired_log_ratio_coverage():
    """On correlated pairs with a true ratio 0.7 the paired 95% interval
    covers 0.7 in about 95% of 2000 trials of 5 seeds."""
    rng = np.random.default_rng(11)
    hits = 0
    for _ in range(2000):
        a, b = correlated_pairs(rng, 5, 0.7, 0.3, 0.02)
        _, lo, hi, _ = stats.paired_log_ratio(a, b)
        hits += lo <= 0.7 <= hi
    assert 0.93 <= hits / 2000 <= 0.97, hits / 2000


def test_paired_interval_narrower_than_unpaired():
    """A machine state shared by a pair (log sd 0.2) against each render's
    own noise (0.01): the paired interval is much narrower than the
    unpaired bootstrap interval of the ratio of medians on the same data;
    negative control: shuffling the pairing (seed s's A with another seed's
    B) widens the paired interval to about the unpaired width."""
    rng = np.random.default_rng(5)
    paired, unpaired, shuffled = [], [], []
    for _ in range(50):
        a, b = correlated_pairs(rng, 8, 0.6, 0.2, 0.01)
        _, lo, hi, _ = stats.paired_log_ratio(a, b)
        paired.append(math.log(hi / lo))
        _, ulo, uhi = stats.median_ratio(a, b, rng, 400)
        unpaired.append(math.log(uhi / ulo))
        _, slo, shi, _ = stats.paired_log_ratio(a, np.roll(b, 3))
        shuffled.append(math.log(shi / slo))
    p, u, s = np.median(paired), np.median(unpaired), np.median(shuffled)
    assert p < 0.2 * u, (p, u)
    assert s > 5 * p and s > 0.5 * u, (p, s, u)


def test_holm_known():
    """Holm's adjusted p-values for a known family: (0.01, 0.04, 0.03) ->
    (0.03, 0.06, 0.06) (3 x 0.01; max(0.03, 2 x 0.03); max(0.06, 0.04)),
    nan left out of the count."""
    adj = stats.holm([0.01, 0.04, 0.03, math.nan])
    assert np.allclose(adj[:3], [0.03, 0.06, 0.06], rtol=0, atol=1e-12), adj
    assert math.isnan(adj[3])
    assert np.allclose(stats.holm([0.5, 0.9]), [1.0, 1.0])


def test_holm_controls_family_error():
    """Twelve null cells (no difference) of 5 pairs each, 1000 tables: an
    uncorrected test ranks some cell in about 1 - 0.95^12 = 46% of the
    tables, Holm in at most about 5% (the family-wise error it controls)."""
    rng = np.random.default_rng(3)
    raw_any = holm_any = 0
    for _ in range(1000):
        comps = [stats.paired_difference(rng.normal(1.0, 0.1, 5) + (c := rng.normal(0, 1, 5)), 1.0 + c)
                 for _ in range(12)]
        raw_any += any(c["p"] < 0.05 for c in comps)
        holm_any += any(c["verdict"] in ("higher", "lower") for c in stats.compare_family(comps))
    assert 0.38 <= raw_any / 1000 <= 0.54, raw_any
    assert holm_any / 1000 <= 0.07, holm_any


def test_holm_does_not_rank_what_uncorrected_ranks():
    """Negative control: in a family of four, a cell with p = 0.02 is
    ranked by the uncorrected test but not after Holm (4 x 0.02 = 0.08);
    a cell with p = 0.001 is ranked by both."""
    fam = [{"p": 0.02, "mean": 0.1, "equivalent": False}, {"p": 0.001, "mean": -0.1, "equivalent": False},
           {"p": 0.5, "mean": 0.0, "equivalent": True}, {"p": 0.7, "mean": 0.01, "equivalent": False}]
    out = stats.compare_family(fam)
    assert [c["verdict"] for c in out] == ["undetermined", "lower", "equivalent", "undetermined"], out
    close(out[0]["p_holm"], 0.06, 1e-12, "p_holm of 0.02 (rank 2 of 4: 3 x 0.02)")


def test_paired_difference_known_and_equivalence():
    """The paired difference of A = B + 0.01 (B's mean 1) is 0.01 with a
    tiny interval: ranked "higher", and at margin 0.02 (delta = 0.02) also
    inside +-delta; at margin 0.005 not equivalent. A pure-noise
    difference with sd 0.05 over 5 seeds: neither ranked nor equivalent at
    margin 0.02 ("undetermined": overlapping intervals never say "no
    difference")."""
    rng = np.random.default_rng(2)
    b = 1.0 + rng.normal(0, 0.3, 6)
    a = b + 0.01 + rng.normal(0, 1e-4, 6)
    d = stats.paired_difference(a, b, margin=0.02)
    close(d["mean"], 0.01, 2e-4, "mean")
    assert d["lo"] < 0.01 < d["hi"] and d["p"] < 1e-6
    close(d["delta"], 0.02 * abs(b.mean()), 1e-12, "delta")
    assert d["equivalent"] == (d["hi"] < d["delta"])
    assert stats.compare_family([d])[0]["verdict"] == "higher"
    assert not stats.paired_difference(a, b, margin=0.005)["equivalent"]
    b = np.ones(5)
    a = b + np.array([0.05, -0.04, 0.06, -0.05, 0.01])
    d = stats.compare_family([stats.paired_difference(a, b, margin=0.02)])[0]
    assert d["verdict"] == "undetermined" and not d["equivalent"], d
    b = np.ones(8)
    a = b + np.array([1, -1, 2, -2, 1, -1, 0.5, -0.5]) * 1e-3
    d = stats.compare_family([stats.paired_difference(a, b, margin=0.02)])[0]
    assert d["verdict"] == "equivalent", d


def test_paired_difference_uses_the_pairing():
    """Errors of one seed correlate (the same photon map): a difference of
    1% on errors that vary 30% between seeds is found paired (p < 0.01)
    and missed unpaired (Welch's test on the same numbers, p > 0.5);
    negative control: a shuffled pairing loses it too."""
    from scipy import stats as sps
    rng = np.random.default_rng(9)
    b = 0.02 * np.exp(rng.normal(0, 0.3, 5))
    a = b * (1.01 + rng.normal(0, 0.001, 5))
    assert stats.paired_difference(a, b)["p"] < 0.01
    assert sps.ttest_ind(a, b, equal_var=False).pvalue > 0.5
    assert stats.paired_difference(a, np.roll(b, 2))["p"] > 0.05


# ---- metrics: the relative error that stays relative

def test_nmse_known_and_scale_invariant():
    """NMSE = mean((x-r)^2) / mean(r^2) on a known pair (r = 1, 2; x = 1.1,
    1.8: (0.01 + 0.04) / 2 / 2.5 = 0.01); scaling both images by 0.01 leaves
    it unchanged, while relMSE (its absolute offset 0.01) falls by far more
    than rounding: the negative control that shows why NMSE is added."""
    r = np.array([[[1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]])
    x = np.array([[[1.1, 1.1, 1.1], [1.8, 1.8, 1.8]]])
    close(metrics.nmse(x, r), 0.01, 1e-12, "nmse")
    close(metrics.nmse(0.01 * x, 0.01 * r), metrics.nmse(x, r), 1e-12, "nmse scaled")
    assert metrics.relmse(0.01 * x, 0.01 * r) < 0.05 * metrics.relmse(x, r)
    assert math.isnan(metrics.nmse(x, 0 * r))
    assert metrics.PRIMARY in ("relmse", "nmse")


# ---- findings: README's summary backed by the results files
from experiments.analysis import findings, reproducibility  # noqa: E402


def test_readme_numbers_backed():
    """Every number of README's findings section is a number token of some
    results file (the committed README against the committed results/)."""
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        section = findings.findings_section(f.read())
    assert section.strip(), "README.md has no findings section"
    assert findings.unbacked_numbers(section, findings.results_text(os.path.join(ROOT, "results"))) == []


def test_readme_numbers_negative_control():
    """A made-up number fails the check, a digit run inside a longer number
    does not count as present, and a thousands separator is looked through."""
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "a.md"), "w", encoding="utf-8") as f:
            f.write("ratio 85.6% at n = 10; 1800 shapes; 2.4117\n")
        readme = "# x\n\n## What it found, in short\n\n- 85.6% at n = 10, 1,800 shapes\n\n## Next\n\n- 99.9\n"
        sec = findings.findings_section(readme)
        assert "99.9" not in sec
        hay = findings.results_text(d)
        assert findings.unbacked_numbers(sec, hay) == []
        bad = readme.replace("85.6%", "85.7%")
        assert findings.unbacked_numbers(findings.findings_section(bad), hay) == ["85.7"]
        inner = readme.replace("85.6%", "2.41x")  # 2.41 is only a prefix of 2.4117
        assert findings.unbacked_numbers(findings.findings_section(inner), hay) == ["2.41"]
        # the command line exits 1 on the bad README (markers and an empty
        # block given, so that the number check is what fails)
        path = os.path.join(d, "README.md")
        with open(path, "w", encoding="utf-8") as f:
            f.write(bad.replace("## Next", findings.SUMMARY_BEGIN + "\n" + findings.SUMMARY_END + "\n\n## Next"))
        rc = subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.findings", "--results", d,
                             "--check-readme", path], cwd=ROOT, capture_output=True, check=False).returncode
        assert rc == 1


def test_readme_summary_current(monkeypatch):
    """README's summary block is the one findings.summary writes from the
    committed results/ now (as `make findings` runs it, from the top
    directory): a number left behind by a rerun fails here."""
    monkeypatch.chdir(ROOT)
    with open("README.md", encoding="utf-8") as f:
        text = f.read()
    at = findings.readme_block(text)
    assert at is not None, "README.md has no findings summary block"
    assert text[at[0]:at[1]] == findings.summary(findings.paths("results"))


def test_readme_summary_negative_control():
    """--write-readme fills the block from the files, --check-readme then
    passes; a number changed by hand in the block, a results file changed
    under it, and a README without the markers each fail it (exit 1)."""
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "table1"))
        _table([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(
            os.path.join(d, "table1", "table1.csv"), index=False)
        path = os.path.join(d, "README.md")
        base = ("# x\n\n## What it found, in short\n\nIn short:\n\n" + findings.SUMMARY_BEGIN + "\n"
                + findings.SUMMARY_END + "\n\n## Next\n")
        with open(path, "w", encoding="utf-8") as f:
            f.write(base)

        def run(*args):
            return subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.findings", "--results", d, *args],
                                  cwd=ROOT, capture_output=True, text=True, check=False)
        assert run("--check-readme", path).returncode == 1  # the empty block is stale
        assert run("--write-readme", path).returncode == 0
        with open(path, encoding="utf-8") as f:
            good = f.read()
        assert "falls from 80.0% [75.0, 85.0] at n = 10 to 40.0% [38.0, 42.0] at n = 100" in good
        assert "Not answered here" in good  # the files this directory lacks say so
        r = run("--check-readme", path)
        assert r.returncode == 0, r.stderr
        with open(path, "w", encoding="utf-8") as f:
            f.write(good.replace("40.0% [38.0, 42.0]", "41.0% [38.0, 42.0]"))
        r = run("--check-readme", path)
        assert r.returncode == 1 and "README.md:8: the findings summary is not the one" in r.stderr, r.stderr
        with open(path, "w", encoding="utf-8") as f:
            f.write(good)
        _table([(80, 75, 85), (45, 43, 47), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(
            os.path.join(d, "table1", "table1.csv"), index=False)
        assert run("--check-readme", path).returncode == 1  # the files moved on
        with open(path, "w", encoding="utf-8") as f:
            f.write(good.replace(findings.SUMMARY_END, ""))
        r = run("--check-readme", path)
        assert r.returncode == 1 and "no summary block" in r.stderr


def test_summary_wording_from_tests():
    """The summary's words follow its tests: the ratio 'falls' over n only
    when the two intervals are disjoint, and the shape 'reproduces' only when
    it falls at every photon count."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table1.csv")
        _table([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(path, index=False)
        line = findings.summary_table({"table": path})
        assert "P_e = 50k falls from" in line and "holds at 1 of 2 photon counts" in line
        _table([(80, 75, 85), (78, 70, 82), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(path, index=False)
        line = findings.summary_table({"table": path})
        assert "P_e = 50k goes from" in line and "holds at 0 of 2 photon counts" in line


def _table(ratios, diffs):
    """A minimal table1.csv frame: one precomputed row per (photons, nn) with
    paired ratios (r, lo, hi) and relMSE differences (m, lo, hi)."""
    rows = []
    for (p, n), (r, lo, hi), (m, dlo, dhi) in zip([(50000, 10), (50000, 100), (500000, 10)], ratios, diffs):
        row = {"photons": p, "nn": n, "method": "precomputed", "pairs": 5, "paper_ratio_percent": 70.0}
        for stem in ("paired_ratio", "paired_cpu_ratio", "trace_ratio"):
            row.update({f"{stem}_percent": r, f"{stem}_ci95_lo": lo, f"{stem}_ci95_hi": hi})
        row.update(relmse_diff_mean=m, relmse_diff_lo=dlo, relmse_diff_hi=dhi, relmse_diff_verdict="higher")
        rows.append(row)
        rows.append({"photons": p, "nn": n, "method": "conventional"})
    return pd.DataFrame(rows)


def test_reproducibility_compare():
    """Deltas in pp, overlap flags and the goal: met for close runs, not met
    when one cell's intervals are disjoint (negative control) or the median
    |delta| exceeds the goal."""
    a = _table([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.0, 0.02)] * 3)
    b = _table([(81, 76, 86), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    f = reproducibility.compare(a, b)
    assert list(f["ratio_delta_pp"]) == [-1, -1, 2]
    s = reproducibility.summary(f, 3.0)
    assert s["ratio_median_abs_delta_pp"] == 1 and s["met"] and s["ratio_overlap_cells"] == 3
    c = _table([(81, 76, 86), (50, 48, 52), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    s = reproducibility.summary(reproducibility.compare(a, c), 3.0)
    assert s["ratio_overlap_cells"] == 2 and not s["met"]
    s = reproducibility.summary(reproducibility.compare(a, b), 0.5)
    assert not s["met"]


def test_reproducibility_prints_reference_error():
    """reproducibility.md names the reference with its measured noise and
    kernel bias from the JSON beside it (a converged reference); control: a
    reference without one is said to be unmeasured, and no number is made up."""
    a = _table([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.0, 0.02)] * 3)
    b = _table([(81, 76, 86), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
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


def test_findings_wording_from_tests():
    """Finding 1 ranks only disjoint intervals: n = 100 below n = 10 at 50k
    (disjoint), P_e undetermined at n = 10 (overlapping); the paper's value
    inside our interval is counted."""
    t = _table([(80, 75, 85), (40, 38, 42), (82, 70, 95)], [(0.01, 0.0, 0.02)] * 3)
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table1.csv")
        t.to_csv(path, index=False)
        _, lines = findings.finding1({"table": path})
        text = "\n".join(lines)
        assert "at P_e = 50000: the ratio at n = 100 is ranked below the one at n = 10" in text
        assert "Over P_e at n = 10: the ratio at P_e = 500000 against the one at P_e = 50000: undetermined" in text
        assert "1 of 1 cells at P_e = 500000" in text and "0 of 2 cells at P_e = 50000" in text
        # a table without the paired columns: the finding says so, no number
        t.drop(columns=["paired_ratio_percent"]).to_csv(path, index=False)
        try:
            findings.finding1({"table": path})
            assert False, "finding1 answered without its column"
        except findings.Missing as e:
            assert "paired_ratio_percent" in str(e)


def test_resolution_prints_reference_error():
    """resolution.md names each size's converged reference with its measured
    noise and kernel bias (the JSON beside the EXR, given by --ref-exr) and
    checks them against the tightest target it judges; control: a size
    without --ref-exr, or whose reference has no JSON, gets no made-up number."""
    from experiments.analysis import resolution

    table = pd.DataFrame([{"method": m, "photons": 50000, "nn": 10, "total_median_s": t, "relmse_ref_mean": e,
                           "relmse_ref_ci95": 0.001} for m, t, e in (("conventional", 2.0, 0.02),
                                                                    ("precomputed", 1.0, 0.03))])
    with tempfile.TemporaryDirectory() as d:
        tpath = os.path.join(d, "table.csv")
        table.to_csv(tpath, index=False)
        ref = os.path.join(d, "ref.exr")
        with open(os.path.join(d, "ref.json"), "w") as f:
            json.dump({"noise": 0.000512, "bias": 3.1e-05, "bias_raw": 3.1e-05, "metric": "relmse",
                       "settings": {"method": "conventional", "direct": "shadow-rays", "photons": 10000000,
                                    "nn": 200, "seeds": [1000001, 1000002]}}, f)
        out = os.path.join(d, "resolution.md")
        resolution.main(["--size", "64x48", tpath, "ours", "--size", "32x24", tpath, "pov",
                         "--ref-exr", "64x48", ref, os.path.join(d, "none.csv"),
                         "--targets", "0.05 0.025", "--time", "total_s", "--out", out])
        with open(out) as f:
            text = f.read()
        line64 = next(x for x in text.splitlines() if x.startswith("- 64x48: ours"))
        assert "noise 0.000512" in line64 and "kernel bias 3.1e-05" in line64 and "0.025" in line64
        line32 = next(x for x in text.splitlines() if x.startswith("- 32x24: pov"))
        assert "noise" not in line32
        resolution.main(["--size", "64x48", tpath, "ours", "--ref-exr", "64x48", os.path.join(d, "bare.exr"), "",
                         "--targets", "0.05", "--time", "total_s", "--out", out])
        with open(out) as f:
            text = f.read()
        assert "its own error is not measured here" in text and "0.000512" not in text


def test_findings_resolution_per_size():
    """Finding 7 gives one block per output size, in size order, from each
    equal-error-WxH.csv; a CSV without the curve's columns is named, not
    read (negative control)."""
    rows = lambda s: pd.DataFrame([  # noqa: E731
        {"estimate": "paper", "kind": "tightest", "target": 0.02, "speedup": s, "lo": s - 0.1, "hi": s + 0.1,
         "defined_fraction": 1.0},
        {"estimate": "paper", "kind": "curve", "target": 0.03, "speedup": s + 0.2, "lo": s + 0.1, "hi": s + 0.3,
         "defined_fraction": 1.0}])
    with tempfile.TemporaryDirectory() as d:
        rows(0.75).to_csv(os.path.join(d, "equal-error-1024x768.csv"), index=False)
        rows(1.25).to_csv(os.path.join(d, "equal-error-256x192.csv"), index=False)
        _, lines = findings.finding7({"root": d, "resolution": d})
        text = "\n".join(lines)
        assert text.index("- 256x192:") < text.index("- 1024x768:")
        assert "1.25 [1.15, 1.35]x" in text and "0.75 [0.65, 0.85]x" in text
        rows(1.0).drop(columns=["kind"]).to_csv(os.path.join(d, "equal-error-512x384.csv"), index=False)
        try:
            findings.finding7({"root": d, "resolution": d})
            assert False, "finding7 read a CSV without its columns"
        except findings.Missing as e:
            assert "kind" in str(e)


def test_findings_beyond():
    """Finding B quotes each case's paper rule and best variant with their
    intervals and counts the cases where the goal holds; a case with fewer
    than MIN_SEEDS_QUOTED seeds is named without its intervals (negative
    control), and a table without the seeds column names the target."""
    def row(case, variant, sp, lo, hi, best, above, vs, met, seeds):
        return {"case": case, "variant": variant, "estimate": "paper", "target": 0.02, "speedup": sp, "lo": lo,
                "hi": hi, "fallback_rate": 0.125, "evaluated_share": 0.5, "seeds": seeds, "best": best,
                "above_one": above, "vs_paper": vs, "goal_met": met}
    rows = [row("a-64x48", "paper", 0.9, 0.8, 1.0, False, False, "", False, 5),
            row("a-64x48", "lazy", 1.3, 1.2, 1.4, True, True, "higher", True, 5),
            row("b-64x48", "paper", 1.1, 1.05, 1.2, False, True, "", False, 5),
            row("b-64x48", "gated0.1", 0.97, 0.9, 1.02, True, False, "lower", False, 5),
            row("c-64x48", "paper", 2.0, 1.9, 2.1, False, True, "", False, 3),
            row("c-64x48", "lazy", 2.5, 2.4, 2.6, True, True, "higher", True, 3),
            row("d-64x48", "paper", 1.0, 0.9, 1.1, False, False, "", False, 5),
            row("d-64x48", "lazy", 1.2, 1.004, 1.5, True, True, "overlap", True, 5)]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "beyond.csv")
        pd.DataFrame(rows).to_csv(path, index=False)
        _, lines = findings.finding_beyond({"beyond": path})
        text = "\n".join(lines)
        assert "a-64x48 (relMSE 0.02, 5 seeds): the paper's rule 0.900 [0.800, 1.000]x; the best variant, lazy, 1.300 [1.200, 1.400]x" in text
        assert "12.5% of its eye samples fell back, 50.0% of the representatives" in text
        assert "against the paper's rule's interval: above it" in text
        assert "b-64x48" in text and "interval: below it" in text and "the goal does not hold" in text
        assert "c-64x48: 3 seeds" in text and "[2.4, 2.6]" not in text
        assert "1.200 [1.004, 1.500]x, its interval above 1.0 only by less than the 2% margin" in text
        assert "holds as worded, by a margin too thin to rely on" in text
        assert "holds in 2 of 3 cases, 1 of them with the interval's lower end within the margin" in text
        pd.DataFrame(rows).drop(columns=["seeds"]).to_csv(path, index=False)
        try:
            findings.finding_beyond({"beyond": path})
            assert False, "finding_beyond answered without the seeds column"
        except findings.Missing as e:
            assert "make beyond" in str(e)


def test_findings_scale():
    """Finding P quotes the largest map's row of each method and the median
    paired two-thread speed-up (t1 / t2 per pair); without threads.csv it
    names the target instead of a number (negative control)."""
    sc = pd.DataFrame([{"method": "conventional", "photons_emitted": p, "photons_stored": 4 * p, "threads": 2,
                        "trace_s": p / 1e6, "build_s": 0.5, "precompute_s": 0.0, "eye_s": 0.25,
                        "total_s": p / 1e6 + 0.75, "bytes_per_stored": b} for p, b in ((1000, 90.0), (8000, 44.5))])
    th = pd.DataFrame([{"photons_emitted": 8000, "pair": k, "threads": t, "trace_s": 4.0 / t ** e,
                        "build_s": 2.0 / t, "total_s": 6.0 / t} for k, e in ((1, 1.0), (2, 0.5), (3, 0.0))
                       for t in (1, 2)])
    with tempfile.TemporaryDirectory() as d:
        sp, tp = os.path.join(d, "scaling.csv"), os.path.join(d, "threads.csv")
        sc.to_csv(sp, index=False)
        th.to_csv(tp, index=False)
        _, lines = findings.finding_scale({"scaling": sp, "threads": tp})
        text = "\n".join(lines)
        assert "8,000 emitted photons (32,000 stored): 0.758 s in total" in text and "44.5 bytes" in text
        assert "90" not in text.split("8,000 emitted")[0]
        assert "photon pass 1.41x [1, 2]" in text and "kd-tree build 2x [2, 2]" in text
        os.remove(tp)
        try:
            findings.finding_scale({"scaling": sp, "threads": tp})
            assert False, "finding_scale answered without threads.csv"
        except findings.Missing as e:
            assert "make bench-threads" in str(e)
