"""Tests of experiments/analysis/evaluate.py's verdict sentence (verdict_of):
the targets where the band lies above, below and across 1, worded only
where enough resamples reach both fronts. The final-gathering part:
tests/test_evaluate_gather.py; the whole study: tests/evaluate.test.sh.

Run by pytest from the repository root (`python3 -m pytest tests/`).
"""

import pandas as pd

from experiments.analysis import evaluate


def curve(rows):
    """An equal-error frame of the paper estimate: (target, speedup, lo, hi, defined_fraction) per row."""
    return pd.DataFrame([{"estimate": "paper", "kind": "curve", "target": t, "speedup": s, "lo": lo, "hi": hi,
                          "defined_fraction": d} for t, s, lo, hi, d in rows])


def test_verdict_words_each_band():
    """Above 1 at 0.03-0.04, below at 0.01, across at 0.02; a target few
    resamples reach (0.05, below 1) is not worded (the control)."""
    ee = curve([(0.01, 0.5, 0.4, 0.6, 1.0), (0.02, 1.0, 0.8, 1.2, 1.0), (0.03, 2.0, 1.5, 2.5, 1.0),
                (0.04, 2.2, 1.8, 2.6, 0.99), (0.05, 0.3, 0.2, 0.4, 0.5)])
    s = evaluate.verdict_of(ee, "paper")
    assert s.startswith("paper estimate: ")
    assert "the band lies above 1 for targets 0.03-0.04" in s
    assert "is slower (band below 1) for targets 0.01-0.01" in s
    assert "undetermined (band contains 1) for targets 0.02-0.02" in s
    assert "0.05" not in s
    assert evaluate.band_tail(ee.iloc[:0], ee.iloc[:0], "at relMSE") == []
