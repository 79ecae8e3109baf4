#!/usr/bin/python3
"""resolution.py: per-size Table 1 CSVs -> resolution.md, the cheapest
settings per output size (`make resolution`, experiments/rules/resolution.smk).

Owns the choice, for each relMSE target and output size, of the cheapest
cell (method, estimate, P_e, n) whose error stays below the target: the
upper end of its 95% t-interval over seeds (mean + half-width) must be below
the target, so that "below" holds at 95% and not by a lucky seed; with a
single seed there is no interval and the mean is used (the table says so).
Cheapest: the smallest median time over seeds (CPU or wall, as chosen).
Each size's reference is named, and where it is our converged reference
(--ref-exr: its EXR, with the JSON beside it) with its measured error
(reference.describe: noise, kernel bias, checked against the tightest
target it judges: the smallest of --targets and of that size's equal-error
curve).
"""

import argparse
import math
import os


from experiments.analysis import reference
from experiments.analysis import report
from experiments.analysis.report import fmt, isnum

# the table1.csv column of each time of report.TIME_LABEL
TIME_COLUMN = {"cpu_s": "cpu_median_s", "total_s": "total_median_s"}


def candidates(table, time_col):
    """One dict per (method, estimate, P_e, n) of a table1.csv frame with a
    time and an error: method, estimate, photons, nn, time, mean, half."""
    out = []
    estimates = ["paper"] + sorted({c[len("relmse_ref_mean_"):] for c in table.columns
                                    if c.startswith("relmse_ref_mean_")})
    for est in estimates:
        sfx = "" if est == "paper" else f"_{est}"
        tcol, mcol, hcol = f"{TIME_COLUMN[time_col]}{sfx}", f"relmse_ref_mean{sfx}", f"relmse_ref_ci95{sfx}"
        if tcol not in table or mcol not in table:
            continue
        for _, r in table.iterrows():
            if isnum(r[tcol]) and isnum(r[mcol]):
                lo, hi = (r.get(tcol.replace("_median_s", f"_{k}_s")) for k in ("min", "max"))
                out.append({"method": r["method"], "estimate": est, "photons": int(r["photons"]), "nn": int(r["nn"]),
                            "time": float(r[tcol]), "mean": float(r[mcol]),
                            "half": float(r[hcol]) if hcol in table and isnum(r[hcol]) else math.nan,
                            "tmin": float(lo) if isnum(lo) else float(r[tcol]),
                            "tmax": float(hi) if isnum(hi) else float(r[tcol])})
    return out


def cheapest(cands):
    """(the candidate of CANDS with the smallest median time, the others
    not told apart from it: their range of times over seeds overlaps its
    own); (None, []) for none."""
    if not cands:
        return None, []
    best = min(cands, key=lambda c: c["time"])
    return best, [c for c in cands if c is not best and c["tmin"] <= best["tmax"] and best["tmin"] <= c["tmax"]]


def cheapest_text(cands):
    """The cell of the target table: the cheapest candidate, and how many
    others its time does not tell apart from it (named)."""
    best, ties = cheapest(cands)
    if best is None:
        return "none in grid"
    if not ties:
        return describe(best)
    return (describe(best) + f"; not told apart from {len(ties)} other cell{'s' if len(ties) > 1 else ''} (times "
            "over seeds overlap): " + "; ".join(label(c) for c in sorted(ties, key=lambda c: c["time"])))


def upper(c):
    """The error bound a candidate must keep under the target: mean +
    half-width, or the mean when there is no interval."""
    return c["mean"] + c["half"] if isnum(c["half"]) else c["mean"]


def label(c):
    """'prec./paper, P_e=50k, n=20' of a candidate."""
    p = f"{c['photons'] // 1000}k" if c["photons"] % 1000 == 0 else str(c["photons"])
    return f"{c['method'][:4]}./{c['estimate']}, P_e={p}, n={c['nn']}"


def describe(c):
    """'prec./paper, P_e=50k, n=20: 0.27 s (relMSE 0.0446 ± 0.003)'."""
    return (f"{label(c)}: {fmt(c['time'])} s "
            f"(relMSE {report.fmt_pm(c['mean'], c['half'])}{'' if isnum(c['half']) else ', 1 seed'})")


def ref_text(exr, equal_error_csv, targets):
    """reference.describe of the reference EXR of one size, checked against
    the tightest target it judges (the smallest of TARGETS and of the
    equal-error curve in EQUAL_ERROR_CSV, when it has one)."""
    judged = [t for t in [*targets, reference.tightest_of(equal_error_csv) if equal_error_csv else None]
              if t is not None and isnum(t)]
    return reference.describe(exr, min(judged) if judged else None)


def main(argv=None):
    """Command line: see the module docstring; exits 1 on a missing or
    malformed input."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", action="append", nargs=3, metavar=("WxH", "TABLE_CSV", "REFERENCE"), required=True,
                    help="an output size, its table1.csv and a description of its reference")
    ap.add_argument("--ref-exr", action="append", nargs=3, default=[], metavar=("WxH", "EXR", "EQUAL_ERROR_CSV"),
                    help="a size's reference EXR (its measured error is read from the JSON beside it) and the "
                         "equal-error CSV of that size")
    ap.add_argument("--targets", required=True)
    ap.add_argument("--time", default="cpu_s", choices=sorted(TIME_COLUMN))
    ap.add_argument("--grid", default="", help="the grid, as text for the header")
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    try:
        targets = [float(t) for t in args.targets.split()]
    except ValueError:
        report.die("resolution.py", f"--targets '{args.targets}': not numbers", report.EXIT_BAD_INPUT)
    sizes = []
    for size, path, refdesc in args.size:
        need = ["method", "photons", "nn", TIME_COLUMN[args.time], "relmse_ref_mean", "relmse_ref_ci95"]
        table = report.read_csv(path, need, "resolution.py")
        sizes.append((size, path, refdesc, candidates(table, args.time)))

    out = ["# Cheapest settings per output resolution", "",
           "The paper names \"methods tuned to each output resolution\" as future work. For each output size "
           f"this runs the Table 1 grid ({args.grid}) and picks the cheapest cell, by median "
           f"{'CPU time of the process' if args.time == 'cpu_s' else 'wall-clock total'} over seeds, whose relMSE "
           "against the reference at that size is below the target with 95% confidence: the upper end of the 95% "
           "t-interval over seeds (mean + half-width) must lie below the target. Cells of both estimates "
           "compete (prec./corrected = precomputed with `--bias-correction`). A cell is called cheapest only "
           "against the cells whose range of times over seeds lies wholly above its own; the others it is not "
           "told apart from are named beside it. "
           f"Generated by `make resolution` on {report.today()}; machine: {report.machine()}, load average "
           f"{report.loadavg_now()} when written; commit {report.commit()}.", "", "References:"]
    exrs = {size: (exr, ee) for size, exr, ee in args.ref_exr}
    out += [f"- {size}: {refdesc}" + (f" {ref_text(*exrs[size], targets)}" if size in exrs else "")
            for size, _, refdesc, _ in sizes]
    out += ["", "relMSE = mean((x-r)^2/(r^2+0.01)) over pixels and RGB channels (`experiments/analysis/metrics.py`). "
            "Per-size tables: " + ", ".join(f"[`{os.path.basename(p)}`]({os.path.relpath(p, os.path.dirname(args.out) or '.')})"
                                           for _, p, _, _ in sizes) + " (and their `.md`).", ""]
    rows = []
    for t in targets:
        row = [fmt(t)]
        for _, _, _, cands in sizes:
            row.append(cheapest_text([c for c in cands if upper(c) < t]))
        rows.append(row)
    out += report.md_table(["relMSE target"] + [s for s, _, _, _ in sizes], rows, ["r"] + ["l"] * len(sizes))
    out += ["", "The cell of each method and estimate with the smallest median time at each size, and the one with "
            "the lowest mean error in the grid (point estimates, not ranked by a test):", ""]
    rows = []
    for size, _, _, cands in sizes:
        keys = list(dict.fromkeys((c["method"], c["estimate"]) for c in cands))
        for m, e in keys:
            mine = [c for c in cands if c["method"] == m and c["estimate"] == e]
            fast = min(mine, key=lambda c: c["time"])
            best = min(mine, key=lambda c: c["mean"])
            rows.append([size, m, e, describe(fast), describe(best)])
    out += report.md_table(["size", "method", "estimate", "smallest median time", "lowest mean relMSE"], rows,
                           ["l"] * 5)
    report.write_atomic(args.out, "\n".join(out) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
