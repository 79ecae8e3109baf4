"""Unit tests of experiments/analysis/resolution.py: the cheapest settings per
output size.

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
