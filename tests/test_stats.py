"""Unit tests of experiments/analysis/stats.py: intervals over seeds, fronts and
interpolation, the cost model's fit and the ratio of two slopes, ranks,
paired comparisons and Holm.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`); pytest rewrites
the asserts, so they check under `python3 -O` too. Every check compares
against a value computed another way (a closed form, a simulation with a
known answer, the definition computed directly), so each can fail. Random
numbers come from fixed seeds: the outcome is deterministic.
"""

import math

import numpy as np

from experiments.analysis import stats
from helpers import close


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


def test_paired_family_is_holm_over_its_cells():
    """paired_family gives each cell's paired_difference, Holm over the
    cells, in the cells' order: a clear difference is ranked with p_holm =
    its p times the family's size (3 cells); control: alone, the same cell
    keeps its own p."""
    a = np.array([1.0, 1.1, 0.9, 1.05, 0.95])
    clear = (a + 1.0, a + np.array([0.0, 0.01, -0.01, 0.02, -0.02]))
    flat = (a, a[::-1].copy())
    labels, comps = stats.paired_family([("x", *clear), ("y", *flat), ("z", *flat)])
    assert labels == ["x", "y", "z"]
    p = stats.paired_difference(*clear)["p"]
    close(comps[0]["p_holm"], min(1.0, 3 * p), 1e-15, "Holm over 3 cells")
    assert comps[0]["verdict"] == "higher" and p < 0.01
    (_,), (alone,) = stats.paired_family([("x", *clear)])
    close(alone["p_holm"], p, 1e-15, "a family of one")
