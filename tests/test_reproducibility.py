"""Unit tests of experiments/analysis/reproducibility.py: two runs of the
grid compared.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`); pytest rewrites
the asserts, so they check under `python3 -O` too. Every check compares
against a value computed another way (a closed form, a simulation with a
known answer, the definition computed directly), so each can fail. Random
numbers come from fixed seeds: the outcome is deterministic.
"""

import json
import os
import tempfile

import pandas as pd

from experiments.analysis import reproducibility
from helpers import table1_frame


def test_reproducibility_compare():
    """Deltas in pp, overlap flags and the goal: met for close runs, not met
    when one cell's intervals are disjoint (negative control) or the median
    |delta| exceeds the goal."""
    a = table1_frame([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.0, 0.02)] * 3)
    b = table1_frame([(81, 76, 86), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    f = reproducibility.compare(a, b)
    assert list(f["ratio_delta_pp"]) == [-1, -1, 2]
    s = reproducibility.summary(f, 3.0)
    assert s["ratio_median_abs_delta_pp"] == 1 and s["met"] and s["ratio_overlap_cells"] == 3
    c = table1_frame([(81, 76, 86), (50, 48, 52), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
    s = reproducibility.summary(reproducibility.compare(a, c), 3.0)
    assert s["ratio_overlap_cells"] == 2 and not s["met"]
    s = reproducibility.summary(reproducibility.compare(a, b), 0.5)
    assert not s["met"]


def test_reproducibility_prints_reference_error():
    """reproducibility.md names the reference with its measured noise and
    kernel bias from the JSON beside it (a converged reference); control: a
    reference without one is said to be unmeasured, and no number is made up."""
    a = table1_frame([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.0, 0.02)] * 3)
    b = table1_frame([(81, 76, 86), (41, 39, 43), (98, 93, 103)], [(0.01, 0.0, 0.02)] * 3)
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
