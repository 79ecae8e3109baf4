"""Unit tests of experiments/analysis/coverage.py: the simulated coverage of
a few-seed percentile-bootstrap interval of a mean.

Run by pytest from the repository root (`python3 -m pytest tests/`). The
simulation's seed is fixed, so each answer is deterministic; the checks
compare against what the percentile bootstrap is known to do (it covers far
less than its nominal level with 3 values, close to it with 30).
"""

import pytest

from experiments.analysis import coverage


def test_three_seeds_cover_about_three_in_four():
    """A nominal 95% interval of a mean of 3 normal values covers the truth
    about 75% of the time (the resampled means cannot spread wider than the
    three values), far below 95%."""
    c = coverage.percentile_coverage(3)
    assert 0.70 <= c <= 0.80, c
    assert c == coverage.percentile_coverage(3)  # the fixed seed: the same answer


def test_many_seeds_near_nominal_negative_control():
    """With 30 values the same procedure comes close to 95%: the function
    tells a few-seed interval from an adequate one."""
    c = coverage.percentile_coverage(30, trials=500, resamples=400)
    assert 0.90 <= c <= 0.99, c
    assert c > coverage.percentile_coverage(3) + 0.1
    # a nominal 50% interval covers about half as often as a 95% one at 30 values
    assert coverage.percentile_coverage(30, trials=500, resamples=400, level=0.5) < 0.65


def test_too_few_refused():
    """One value has no spread to resample: refused, not a coverage of 0."""
    with pytest.raises(ValueError):
        coverage.percentile_coverage(1)
