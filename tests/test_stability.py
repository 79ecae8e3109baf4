"""Unit tests of experiments/stability.py's verdicts that need no render
(the rendered cases run in tests/robustness.test.sh and `make stability`).

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test`).
"""

import numpy as np

from experiments import stability


def test_exact_single_render_within_tolerance():
    """One render: the mean within TOL of the value; control: just outside."""
    assert stability.exact_verdict([0.5000004], 0.5, tol=1e-6)[2]
    assert not stability.exact_verdict([0.500002], 0.5, tol=1e-6)[2]


def test_exact_over_seeds_needs_a_narrow_interval():
    """Over seeds: the value inside the 99.9% interval passes only when the
    interval's half-width is at most RESOLVE of the value; controls: a wide
    interval around the value fails (it could not see a 10% bias), and a
    narrow interval beside the value fails."""
    rng = np.random.default_rng(1)
    narrow = 1.0 + 0.01 * rng.standard_normal(20)
    assert stability.exact_verdict(narrow, 1.0)[2]
    wide = 1.0 + 0.5 * rng.standard_normal(20)
    exp, obs, ok = stability.exact_verdict(wide, 1.0)
    assert not ok and "too wide" in obs and "half-width at most 10%" in exp
    assert not stability.exact_verdict(narrow + 0.05, 1.0)[2]
