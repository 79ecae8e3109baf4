"""Unit tests of experiments/analysis/scenes.py: the kNN's share of the
conventional render and the speed-up of the total at one cell, the latter
the table's paired time ratio inverted (not a ratio of medians).

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`).
"""

import math

import pandas as pd

from experiments.analysis import scenes
from helpers import close


def table(ratio=(50.0, 40.0, 62.5)):
    """A table1.csv of one cell: conventional 4 s total, eye pass 3 s;
    precomputed eye pass 1 s, medians 2.5 s total (a ratio of medians of
    1.6); its paired ratio RATIO (percent, lo, hi)."""
    return pd.DataFrame([
        {"method": "conventional", "photons": 1000, "nn": 10, "render_median_s": 3.0, "total_median_s": 4.0,
         "paired_ratio_percent": math.nan, "paired_ratio_ci95_lo": math.nan, "paired_ratio_ci95_hi": math.nan},
        {"method": "precomputed", "photons": 1000, "nn": 10, "render_median_s": 1.0, "total_median_s": 2.5,
         "paired_ratio_percent": ratio[0], "paired_ratio_ci95_lo": ratio[1], "paired_ratio_ci95_hi": ratio[2]}])


def test_knn_share_and_paired_speedup():
    share, (speed, lo, hi) = scenes.knn_share(table(), 1000, 10)
    close(share, (3.0 - 1.0) / 4.0, 1e-12, "kNN share")
    # the paired ratio 50% [40, 62.5] inverted: 2 [1.6, 2.5], not 4 / 2.5 = 1.6
    close(speed, 2.0, 1e-12, "speed-up")
    close(lo, 1.6, 1e-12, "low end")
    close(hi, 2.5, 1e-12, "high end")
    # control: a cell the table lacks is nan, not a number
    share, sp = scenes.knn_share(table(), 1000, 20)
    assert math.isnan(share) and all(math.isnan(x) for x in sp)
    # control: no paired ratio (one seed) gives no speed-up
    _, sp = scenes.knn_share(table((math.nan,) * 3), 1000, 10)
    assert all(math.isnan(x) for x in sp)
