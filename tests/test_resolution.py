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


def test_cheapest_names_the_cells_it_is_not_told_from():
    """A cell is cheapest outright only when every other cell's range of
    times over seeds lies above its own; the cells whose range overlaps it
    are named beside it (control: disjoint ranges name none)."""
    from experiments.analysis import resolution

    def c(nn, t, lo, hi):
        return {"method": "precomputed", "estimate": "paper", "photons": 50000, "nn": nn, "time": t, "mean": 0.01,
                "half": 0.001, "tmin": lo, "tmax": hi}
    a, b, far = c(10, 1.0, 0.9, 1.2), c(20, 1.1, 1.05, 1.3), c(50, 2.0, 1.8, 2.2)
    best, ties = resolution.cheapest([far, b, a])
    assert best is a and ties == [b]
    text = resolution.cheapest_text([far, b, a])
    assert text.startswith("prec./paper, P_e=50k, n=10: 1 s") and "not told apart from 1 other cell" in text
    assert "n=20" in text and "n=50" not in text
    assert resolution.cheapest([far, a]) == (a, []) and "not told apart" not in resolution.cheapest_text([far, a])
    assert resolution.cheapest_text([]) == "none in grid"
    # the table's min and max columns give the range; without them the median alone
    table = pd.DataFrame([{"method": "precomputed", "photons": 50000, "nn": 10, "total_median_s": 1.0,
                           "total_min_s": 0.8, "total_max_s": 1.4, "relmse_ref_mean": 0.01, "relmse_ref_ci95": 0.001}])
    (cand,) = resolution.candidates(table, "total_s")
    assert (cand["tmin"], cand["tmax"]) == (0.8, 1.4)
    (cand,) = resolution.candidates(table.drop(columns=["total_min_s", "total_max_s"]), "total_s")
    assert (cand["tmin"], cand["tmax"]) == (1.0, 1.0)
