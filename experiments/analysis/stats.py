"""Statistics over seeds: the one implementation the analysis layer uses.

Owns the summaries of per-seed values (t-interval of a mean, median with
min-max), bootstrap resampling over seeds (percentile intervals, the ratio of
two medians), the Pareto front of (time, error) cells, the log-log
interpolation of the time a front needs to reach an error, the
least-squares line with its standard errors (the cost model time = a + b n)
and Fieller's interval of the ratio of two independent estimates. Nothing here
reads files; random numbers come from a numpy Generator the caller passes.
"""

import math

import numpy as np
from scipy import stats as sps

LEVEL = 0.95


def t_interval(values, level=LEVEL):
    """(mean, half-width) of the Student-t interval of the mean of VALUES.

    Half-width = t_{(1+level)/2, n-1} * sd / sqrt(n), sd with ddof = 1;
    NaN values are dropped; the half-width is nan with fewer than two values
    (and the mean too with none)."""
    v = np.asarray(values, dtype=np.float64)
    v = v[~np.isnan(v)]
    if v.size == 0:
        return math.nan, math.nan
    mean = float(v.mean())
    if v.size < 2:
        return mean, math.nan
    half = float(sps.t.ppf(0.5 + level / 2, v.size - 1) * v.std(ddof=1) / math.sqrt(v.size))
    return mean, half


def median_range(values):
    """(median, min, max) of VALUES without NaN; all nan when none is left."""
    v = np.asarray(values, dtype=np.float64)
    v = v[~np.isnan(v)]
    if v.size == 0:
        return math.nan, math.nan, math.nan
    return float(np.median(v)), float(v.min()), float(v.max())


def intervals_overlap(a, b):
    """True when the closed intervals A = (lo, hi) and B = (lo, hi) overlap,
    or when either is unknown (a nan end): only disjoint intervals rank."""
    if any(math.isnan(x) for x in (*a, *b)):
        return True
    return a[0] <= b[1] and b[0] <= a[1]


def rank(a, b):
    """How interval A = (lo, hi) stands against B: "lower" or "higher" when
    they are disjoint, "overlap" when not (no ranking), "unknown" when
    either has a nan end. The one rule every sentence that ranks follows."""
    if any(math.isnan(x) for x in (*a, *b)):
        return "unknown"
    if intervals_overlap(a, b):
        return "overlap"
    return "higher" if a[0] > b[1] else "lower"


def resample_indices(rng, n, replicates):
    """A (replicates, n) array of indices drawn with replacement from 0..n-1:
    one bootstrap resample of n seeds per row."""
    return rng.integers(0, n, size=(replicates, n))


def percentile_interval(samples, level=LEVEL):
    """(lo, hi, defined) of a bootstrap distribution: the percentile interval
    over the finite SAMPLES and the fraction of samples that were finite."""
    s = np.asarray(samples, dtype=np.float64)
    ok = s[np.isfinite(s)]
    defined = ok.size / s.size if s.size else 0.0
    if ok.size == 0:
        return math.nan, math.nan, defined
    lo, hi = np.quantile(ok, [0.5 - level / 2, 0.5 + level / 2])
    return float(lo), float(hi), defined


def median_ratio(a, b, rng, replicates, level=LEVEL):
    """(ratio, lo, hi) of median(A) / median(B) with a bootstrap percentile
    interval: the seeds of A and of B are resampled independently. nan when
    either side has no value or median(B) is not positive; the interval is nan when either has only one."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    a = a[~np.isnan(a)]
    b = b[~np.isnan(b)]
    if a.size == 0 or b.size == 0:
        return math.nan, math.nan, math.nan
    if not np.median(b) > 0:
        return math.nan, math.nan, math.nan
    ratio = float(np.median(a) / np.median(b))
    if a.size < 2 or b.size < 2:
        return ratio, math.nan, math.nan
    ma = np.median(a[resample_indices(rng, a.size, replicates)], axis=1)
    mb = np.median(b[resample_indices(rng, b.size, replicates)], axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(mb > 0, ma / np.where(mb > 0, mb, 1.0), math.nan)
    lo, hi, _ = percentile_interval(r, level)
    return ratio, lo, hi


def pareto_front(times, errors):
    """Indices of the cells on the Pareto front, fastest first: a cell is on
    it when every faster cell has a larger error (ties in time: the smaller
    error). Along the front time rises and error falls strictly. Cells with
    a non-finite or non-positive time or error are left out."""
    t = np.asarray(times, dtype=np.float64)
    e = np.asarray(errors, dtype=np.float64)
    ok = np.flatnonzero(np.isfinite(t) & np.isfinite(e) & (t > 0) & (e > 0))
    order = ok[np.lexsort((e[ok], t[ok]))]
    front, best = [], math.inf
    for i in order:
        if e[i] < best:
            front.append(int(i))
            best = e[i]
    return front


def front_segment(front_errors, target):
    """(i, j): the indices of the two front cells whose errors bracket
    TARGET (i == j when a cell's error equals it), or None when TARGET lies
    outside the front's errors (FRONT_ERRORS fall, as pareto_front orders
    them)."""
    e = np.asarray(front_errors, dtype=np.float64)
    if e.size == 0 or not (target > 0) or target > e[0] or target < e[-1]:
        return None
    j = int(np.flatnonzero(e <= target)[0])
    return (j, j) if e[j] == target else (j - 1, j)


def time_at_error(front_times, front_errors, target):
    """The time a front needs to reach error TARGET, interpolated linearly in
    (log time, log error) between the two front cells around it.

    FRONT_TIMES rise and FRONT_ERRORS fall (as pareto_front orders them).
    Returns nan when TARGET lies outside the front's errors: below its
    smallest error (not reached in the grid) or above its largest (even the
    fastest cell is more accurate: the time is only bounded above)."""
    t = np.asarray(front_times, dtype=np.float64)
    e = np.asarray(front_errors, dtype=np.float64)
    seg = front_segment(e, target)
    if seg is None:
        return math.nan
    i, j = seg
    if i == j:
        return float(t[i])
    lt0, lt1 = math.log(t[i]), math.log(t[j])
    le0, le1 = math.log(e[i]), math.log(e[j])
    return math.exp(lt0 + (math.log(target) - le0) * (lt1 - lt0) / (le1 - le0))


def front_time_at_error(times, errors, target):
    """time_at_error along the Pareto front of the cells (TIMES, ERRORS)."""
    f = pareto_front(times, errors)
    t = np.asarray(times, dtype=np.float64)[f]
    e = np.asarray(errors, dtype=np.float64)[f]
    return time_at_error(t, e, target)


def linear_fit(x, y, level=LEVEL):
    """Least-squares line y = a + b x over the points (X, Y) (NaN pairs
    dropped), with the uncertainty of ordinary least squares.

    Returns a dict: a, b; se_a, se_b (standard errors from the residual
    variance s^2 = SSR / (N - 2)); dof = N - 2; half_a, half_b (half-widths
    of the Student-t intervals at LEVEL); r2 (coefficient of
    determination). With fewer than three points (or one distinct x) the
    uncertainties are nan; with fewer than two, everything is."""
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    ok = ~(np.isnan(x) | np.isnan(y))
    x, y = x[ok], y[ok]
    nan = math.nan
    out = {"a": nan, "b": nan, "se_a": nan, "se_b": nan, "dof": max(int(x.size) - 2, 0),
           "half_a": nan, "half_b": nan, "r2": nan, "points": int(x.size)}
    sxx = float(np.sum(np.square(x - x.mean()))) if x.size else 0.0
    if x.size < 2 or not sxx > 0:
        return out
    b = float(np.sum((x - x.mean()) * (y - y.mean())) / sxx)
    a = float(y.mean() - b * x.mean())
    out["a"], out["b"] = a, b
    ssr = float(np.sum(np.square(y - (a + b * x))))
    sst = float(np.sum(np.square(y - y.mean())))
    out["r2"] = 1.0 - ssr / sst if sst > 0 else nan
    if x.size < 3:
        return out
    s2 = ssr / (x.size - 2)
    out["se_b"] = math.sqrt(s2 / sxx)
    out["se_a"] = math.sqrt(s2 * (1.0 / x.size + x.mean() ** 2 / sxx))
    t = float(sps.t.ppf(0.5 + level / 2, x.size - 2))
    out["half_a"], out["half_b"] = t * out["se_a"], t * out["se_b"]
    return out


def ratio_se(num, se_num, den, se_den):
    """Standard error of NUM / DEN for two independent estimates by the
    delta method: |num/den| sqrt((se_num/num)^2 + (se_den/den)^2), written
    as sqrt(se_num^2 + (num/den)^2 se_den^2) / |den| so that num = 0 is
    fine; nan when DEN is 0 or an input is not a number."""
    vals = (num, se_num, den, se_den)
    if any(not math.isfinite(v) for v in vals) or den == 0:
        return math.nan
    q = num / den
    return math.sqrt(se_num * se_num + q * q * se_den * se_den) / abs(den)


def fieller_ratio(num, se_num, den, se_den, dof, level=LEVEL):
    """(ratio, lo, hi): NUM / DEN with Fieller's interval at LEVEL for two
    independent, normally distributed estimates with standard errors SE_NUM
    and SE_DEN and DOF degrees of freedom (Student-t quantile).

    The interval is the set of ratios q with (num - q den)^2 <= t^2 (se_num^2
    + q^2 se_den^2). When DEN is not significantly different from zero
    (t se_den >= |den|) the set is unbounded: lo and hi are nan. Also nan
    when an input is not a number or DOF < 1."""
    vals = (num, se_num, den, se_den)
    if any(not math.isfinite(v) for v in vals) or den == 0:
        return math.nan, math.nan, math.nan
    ratio = num / den
    if not dof >= 1:
        return ratio, math.nan, math.nan
    t = float(sps.t.ppf(0.5 + level / 2, dof))
    qa = den * den - t * t * se_den * se_den
    if not qa > 0:
        return ratio, math.nan, math.nan
    qb = -2.0 * num * den
    qc = num * num - t * t * se_num * se_num
    disc = qb * qb - 4.0 * qa * qc
    root = math.sqrt(max(disc, 0.0))
    return ratio, (-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa)


def paired_log_ratio(a, b, level=LEVEL):
    """(ratio, lo, hi, pairs) of A over B from paired samples: A[s] and B[s]
    are measured together (one seed, back to back), so the ratio is
    exp(mean_s log(A[s] / B[s])), the geometric mean of the per-pair ratios,
    with the Student-t interval of that mean over the pairs, exponentiated.
    A pair with a nan, or a non-positive value, is dropped; the interval is
    nan with fewer than two pairs, everything with none."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if a.shape != b.shape:
        raise ValueError(f"paired_log_ratio: {a.shape} against {b.shape} values: not pairs")
    ok = np.isfinite(a) & np.isfinite(b) & (a > 0) & (b > 0)
    d = np.log(a[ok] / b[ok])
    m, h = t_interval(d, level)
    if math.isnan(m):
        return math.nan, math.nan, math.nan, 0
    if math.isnan(h):
        return math.exp(m), math.nan, math.nan, int(d.size)
    return math.exp(m), math.exp(m - h), math.exp(m + h), int(d.size)


def holm(pvalues):
    """Holm's step-down adjusted p-values of PVALUES (family-wise error
    control over all of them): sorted ascending p_(1) <= ... <= p_(m),
    adjusted p_(i) = max_{j <= i} min(1, (m - j + 1) p_(j)); a hypothesis is
    rejected at level alpha when its adjusted p is below alpha. nan entries
    stay nan and do not count in m."""
    p = np.asarray(pvalues, dtype=np.float64)
    out = np.full(p.shape, math.nan)
    idx = np.flatnonzero(np.isfinite(p))
    m = idx.size
    running = 0.0
    for rank_i, i in enumerate(idx[np.argsort(p[idx], kind="stable")]):
        running = max(running, min(1.0, (m - rank_i) * p[i]))
        out[i] = running
    return out


# the default equivalence margin of a paired error comparison: a difference
# within 2% of the baseline's mean error is "no difference that matters"
EQUIVALENCE_MARGIN = 0.02


def paired_difference(a, b, margin=EQUIVALENCE_MARGIN, level=LEVEL):
    """The paired comparison of A against B (A[s], B[s] of one seed: the
    same photon map): a dict with
      pairs, mean (of d = A - B), lo, hi (its Student-t interval at LEVEL),
      p (two-sided paired t-test of mean d = 0), delta (the equivalence
      margin: MARGIN x |mean B|), equivalent (True when the interval at
      LEVEL lies inside (-delta, delta): |diff| < delta at LEVEL, the
      two one-sided tests at (1 - LEVEL) / 2 each, so conservative), and
      relative (mean / mean B).
    Pairs with a nan are dropped; with fewer than two pairs lo, hi, p are
    nan and equivalent is False. A zero spread of d gives p = 0 for a
    non-zero mean, 1 for a zero one."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if a.shape != b.shape:
        raise ValueError(f"paired_difference: {a.shape} against {b.shape} values: not pairs")
    ok = np.isfinite(a) & np.isfinite(b)
    d, base = a[ok] - b[ok], b[ok]
    out = {"pairs": int(d.size), "mean": math.nan, "lo": math.nan, "hi": math.nan, "p": math.nan,
           "delta": math.nan, "equivalent": False, "relative": math.nan}
    if d.size == 0:
        return out
    m, h = t_interval(d, level)
    bm = float(base.mean())
    out.update(mean=m, delta=margin * abs(bm), relative=m / bm if bm != 0 else math.nan)
    if d.size < 2:
        return out
    sd = float(d.std(ddof=1))
    if sd == 0:
        p = 0.0 if m != 0 else 1.0
    else:
        p = float(2 * sps.t.sf(abs(m) / (sd / math.sqrt(d.size)), d.size - 1))
    out.update(lo=m - h, hi=m + h, p=p, equivalent=bool(-out["delta"] < m - h and m + h < out["delta"]))
    return out


def compare_family(comparisons, alpha=1 - LEVEL):
    """The verdicts of a family of paired comparisons (paired_difference
    dicts, e.g. one per cell of a table), Holm-corrected over the family:
    adds to each dict p_holm and verdict, one of
      "higher" / "lower"  A is ranked above / below B (p_holm < ALPHA),
      "equivalent"        not ranked, and |diff| < delta at 95%,
      "undetermined"      neither (too few pairs or too wide an interval),
    and returns the list. The one rule every sentence that compares two
    methods' paired values follows: "no difference" only as "equivalent
    within delta", never from overlapping intervals."""
    adj = holm([c["p"] for c in comparisons])
    for c, q in zip(comparisons, adj):
        c["p_holm"] = float(q)
        if np.isfinite(q) and q < alpha:
            c["verdict"] = "higher" if c["mean"] > 0 else "lower"
        elif c["equivalent"]:
            c["verdict"] = "equivalent"
        else:
            c["verdict"] = "undetermined"
    return comparisons


def paired_family(cells):
    """(labels, comparisons) of CELLS, an iterable of (label, a, b): each
    cell's paired_difference of A against B (arrays paired by position),
    with compare_family's verdicts, Holm over the cells."""
    labels, comps = [], []
    for label, a, b in cells:
        labels.append(label)
        comps.append(paired_difference(a, b))
    return labels, compare_family(comps)
