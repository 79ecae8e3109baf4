"""coverage.py: how often a few-seed percentile-bootstrap interval covers the truth.

Owns the simulation behind the findings' note on few-seed intervals: draw N
values from a normal distribution (mean 0), take the percentile bootstrap
interval of their mean (the quantiles stats.percentile_interval takes, over RESAMPLES resamples
of the N values, with replacement), and count how often it contains 0 over
TRIALS draws. With N = 3 a 95% interval covers about three times in four,
since the resampled means cannot spread wider than the three values do.
Random numbers come from a numpy Generator seeded here (SEED): the answer is
the same on every run.
"""

import numpy as np

from experiments.analysis import stats

# the simulation's defaults: small enough to run in well under a second
TRIALS = 2000
RESAMPLES = 1000
SEED = 1


def percentile_coverage(n=3, trials=TRIALS, resamples=RESAMPLES, level=stats.LEVEL, seed=SEED):
    """The share of TRIALS normal samples of size N whose percentile
    bootstrap interval of the mean at LEVEL contains the true mean."""
    if n < 2 or trials < 1 or resamples < 2:
        raise ValueError(f"coverage: n = {n}, trials = {trials}, resamples = {resamples}: too few")
    rng = np.random.default_rng(seed)
    data = rng.standard_normal((trials, n))
    idx = rng.integers(0, n, size=(trials, resamples, n))
    means = np.take_along_axis(data[:, None, :], idx, axis=2).mean(axis=2)
    a = (1.0 - level) / 2.0
    lo = np.quantile(means, a, axis=1)
    hi = np.quantile(means, 1.0 - a, axis=1)
    return float(np.mean((lo <= 0.0) & (0.0 <= hi)))
