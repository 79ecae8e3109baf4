"""experiments/bench/scaling.py: the scaling table, the fitted slopes and the
log-log plot of `make bench-scaling` (experiments/bench/scaling.sh writes
the CSV it reads).

For each method and phase (trace, build, precompute, eye pass, total) it
fits log(seconds) = a + b log(emitted photons) by least squares over the
counts where the phase took any time; b is the phase's slope (1.0: linear
in the work; the build's n log n reads a little above 1 over 50k..20M),
with a 95% interval from the fit's residuals (Student's t, points - 2
degrees of freedom; none with fewer than 3 points). The peak bytes per
stored photon get a slope the same way (0: a constant cost per photon).
Every number in the Markdown is written here, from the CSV.

    python3 scaling.py SCALING_CSV --md OUT.md --png OUT.png [--load L]
                       [--commit C] [--threads T]
"""
import argparse
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402

PHASES = [("trace_s", "trace"), ("build_s", "build"), ("precompute_s", "precompute"),
          ("eye_s", "eye pass"), ("total_s", "total")]
METHODS = ["conventional", "precomputed"]
COLOURS = {"trace_s": "C0", "build_s": "C1", "precompute_s": "C2", "eye_s": "C3", "total_s": "C4"}


def read_rows(path):
    """The CSV's rows as dicts of floats (method kept as text), by column name."""
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            out = {"method": r["method"]}
            for k, v in r.items():
                if k != "method":
                    out[k] = float(v) if v not in ("", None) else math.nan
            rows.append(out)
    return rows


def fit_slope(x, y):
    """Slope of log(y) on log(x) over the points with y > 0: (slope, lo, hi,
    points); lo and hi are the 95% interval (nan below 3 points), slope nan
    below 2 points or with one distinct x."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = (x > 0) & (y > 0) & np.isfinite(y)
    lx, ly = np.log(x[keep]), np.log(y[keep])
    m = int(keep.sum())
    if m < 2 or np.ptp(lx) == 0:
        return math.nan, math.nan, math.nan, m
    res = stats.linregress(lx, ly)
    if m < 3:
        return float(res.slope), math.nan, math.nan, m
    t = stats.t.ppf(0.975, m - 2)
    return float(res.slope), float(res.slope - t * res.stderr), float(res.slope + t * res.stderr), m


def fmt_count(n):
    """N as '20M' or '50k' when it is a whole number of millions or thousands, else in digits."""
    n = int(n)
    if n >= 1000000 and n % 1000000 == 0:
        return "%dM" % (n // 1000000)
    if n >= 1000 and n % 1000 == 0:
        return "%dk" % (n // 1000)
    return str(n)


def fmt_slope(s, lo, hi):
    """'S [LO, HI]' to two decimals, 'S' without an interval (LO nan), '-' when S is nan."""
    if math.isnan(s):
        return "-"
    if math.isnan(lo):
        return "%.2f" % s
    return "%.2f [%.2f, %.2f]" % (s, lo, hi)


def repeats_text(rows):
    """How each count was timed, from the CSV's repeats column: 'one
    process per count, each phase the minimum over its R repeats', or 'one
    render per count' without the column."""
    reps = sorted({int(r["repeats"]) for r in rows if not math.isnan(r.get("repeats", math.nan))})
    if not reps:
        return "one render per count"
    return ("one process per count, each phase the minimum over its %s repeats"
            % ("-".join(str(x) for x in (reps[0], reps[-1])) if len(reps) > 1 else reps[0]))


def markdown(rows, load, commit, threads):
    """scaling.md's text from the CSV's ROWS: per method its table of phase times and memory per
    count of emitted photons, each phase's fitted slope, and the largest count's total and memory; LOAD
    (the load average) and COMMIT are quoted in its header, THREADS there and in the trace's CPU time per
    emitted photon."""
    out = ["# Scaling: each phase's cost against the work", ""]
    out.append("Written by `make bench-scaling` (experiments/bench/scaling.sh, scaling.py) from "
               "`results/bench/scaling.csv`: scenes/cornell.scene, n = 100, 512x384, %s threads, %s; "
               "times are the renderer's own phases (`time_s` in `--stats`), memory is "
               "the peak resident set (`/usr/bin/time -f %%M`) over the stored photons, of a second process of "
               "the same render with `--repeats 1` (repeats keep the memory they free for the next, so the timed "
               "process's peak is not what one render needs). Load average %s "
               "when it finished; commit `%s`." % (threads, repeats_text(rows), load, commit))
    out.append("")
    for method in METHODS:
        rs = sorted((r for r in rows if r["method"] == method), key=lambda r: r["photons_emitted"])
        if not rs:
            continue
        out.append("## %s" % method)
        out.append("")
        out.append("| emitted | stored | trace s | build s | precompute s | eye pass s | total s | "
                   "trace CPU us/emitted | peak B/stored |")
        out.append("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for r in rs:
            out.append("| %s | %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.1f |" % (
                fmt_count(r["photons_emitted"]), r["photons_stored"], r["trace_s"], r["build_s"],
                r["precompute_s"], r["eye_s"], r["total_s"],
                1e6 * r["trace_s"] * threads / r["photons_emitted"], r["bytes_per_stored"]))
        out.append("")
        out.append("Fitted slope of log(cost) on log(emitted photons), 95% interval (1.0: linear; 0: constant):")
        out.append("")
        out.append("| phase | slope | points |")
        out.append("|---|---:|---:|")
        x = [r["photons_emitted"] for r in rs]
        for key, name in PHASES:
            s, lo, hi, m = fit_slope(x, [r[key] for r in rs])
            if m == 0:
                continue
            out.append("| %s | %s | %d |" % (name, fmt_slope(s, lo, hi), m))
        s, lo, hi, m = fit_slope(x, [r["bytes_per_stored"] for r in rs])
        out.append("| peak bytes per stored photon | %s | %d |" % (fmt_slope(s, lo, hi), m))
        out.append("")
        big = rs[-1]
        out.append("At %s emitted photons (%d stored) the %s render took %.2f s in total, its peak memory "
                   "%.1f bytes per stored photon." % (fmt_count(big["photons_emitted"]), big["photons_stored"],
                                                      method, big["total_s"], big["bytes_per_stored"]))
        out.append("")
    out.append("![each phase against the emitted photons](../figures/bench-scaling.png)")
    out.append("")
    return "\n".join(out)


def plot(rows, path):
    """Writes the figure of ROWS to PATH (PNG): per method each phase's seconds against the emitted
    photons, log-log, with its fitted slope and a slope-1 guide, and both methods' peak bytes per stored
    photon."""
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for ax, method in zip(axes[:2], METHODS):
        rs = sorted((r for r in rows if r["method"] == method), key=lambda r: r["photons_emitted"])
        x = np.array([r["photons_emitted"] for r in rs])
        for key, name in PHASES:
            y = np.array([r[key] for r in rs])
            keep = y > 0
            if keep.sum() == 0:
                continue
            s, _, _, _ = fit_slope(x, y)
            label = name if math.isnan(s) else "%s (slope %.2f)" % (name, s)
            ax.loglog(x[keep], y[keep], "o-", color=COLOURS[key], label=label)
        if len(x):
            # a slope-1 guide through the smallest total
            ref = np.array([x.min(), x.max()])
            y0 = min(r["total_s"] for r in rs)
            ax.loglog(ref, y0 * ref / ref[0], "k:", lw=1, label="slope 1")
        ax.set_title("%s: seconds per phase" % method)
        ax.set_xlabel("emitted photons")
        ax.set_ylabel("seconds")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    ax = axes[2]
    for method in METHODS:
        rs = sorted((r for r in rows if r["method"] == method), key=lambda r: r["photons_emitted"])
        if rs:
            ax.semilogx([r["photons_emitted"] for r in rs], [r["bytes_per_stored"] for r in rs], "o-",
                        label=method)
    ax.axhline(48, color="k", ls=":", lw=1, label="48 B")
    ax.set_title("peak resident set per stored photon")
    ax.set_xlabel("emitted photons")
    ax.set_ylabel("bytes")
    ax.set_ylim(bottom=0)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110, format="png")


def main():
    """Command line: see the module docstring; writes --md and --png from the CSV, and exits 1 when
    the CSV has no rows."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--md", required=True)
    ap.add_argument("--png", required=True)
    ap.add_argument("--load", default="?")
    ap.add_argument("--commit", default="?")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    rows = read_rows(a.csv)
    if not rows:
        raise SystemExit("scaling.py: %s has no rows" % a.csv)
    with open(a.md, "w") as f:
        f.write(markdown(rows, a.load, a.commit, a.threads))
    plot(rows, a.png)


if __name__ == "__main__":
    main()
