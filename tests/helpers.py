"""Helpers shared by the pytest files of tests/ (imported as `helpers`:
pytest puts tests/ on sys.path)."""

import pandas as pd


def close(a, b, tol, what=""):
    """Assert |a - b| <= tol."""
    assert abs(a - b) <= tol, f"{what}: {a} vs {b} (tolerance {tol})"


def table1_frame(ratios, diffs):
    """A minimal table1.csv frame: one precomputed row per (photons, nn) with
    paired ratios (r, lo, hi) and relMSE differences (m, lo, hi)."""
    rows = []
    for (p, n), (r, lo, hi), (m, dlo, dhi) in zip([(50000, 10), (50000, 100), (500000, 10)], ratios, diffs):
        row = {"photons": p, "nn": n, "method": "precomputed", "pairs": 5, "paper_ratio_percent": 70.0}
        for stem in ("paired_ratio", "paired_cpu_ratio", "trace_ratio"):
            row.update({f"{stem}_percent": r, f"{stem}_ci95_lo": lo, f"{stem}_ci95_hi": hi})
        row.update(relmse_diff_mean=m, relmse_diff_lo=dlo, relmse_diff_hi=dhi, relmse_diff_verdict="higher")
        rows.append(row)
        rows.append({"photons": p, "nn": n, "method": "conventional"})
    return pd.DataFrame(rows)


def write_reference_json(exr, noise, bias, metric="relmse"):
    """The JSON reference.py writes beside a converged reference EXR, with
    the given NOISE and BIAS (the EXR itself is not written)."""
    import json
    from experiments.analysis import reference
    with open(reference.sidecar(exr), "w") as f:
        json.dump({"noise": noise, "bias": bias, "bias_raw": bias, "metric": metric,
                   "settings": {"method": "conventional", "direct": "shadow-rays", "photons": 10 ** 6, "nn": 50,
                                "seeds": [101, 102]}}, f)
