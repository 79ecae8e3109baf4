"""experiments/bench/threads.py: the table of results/bench/threads.md from
results/bench/threads.csv (experiments/bench/threads.sh): per emitted photon
count and phase, the speed-up of 2 threads over 1 as the geometric mean of
the paired ratios t1/t2 (pairs ran back to back, order alternating), with its
95% t interval over the pairs (stats.paired_log_ratio, as every time ratio
of the project). Raises ValueError on a CSV without both thread counts."""
import subprocess
import sys

import numpy as np
import pandas as pd

from experiments.analysis import stats

PHASES = [("trace_s", "photon pass"), ("build_s", "kd-tree build"),
          ("eye_s", "eye pass"), ("total_s", "total")]


def speedup(g, col):
    """(speed-up, lo, hi, pairs) of column COL over the pairs of G (one
    emitted photon count's rows of threads.csv): the geometric mean of
    t(1 thread) / t(2 threads) with its 95% t interval over the pairs
    (stats.paired_log_ratio; nan interval under two pairs, None without a
    pair)."""
    one = g[g.threads == 1].set_index("pair")
    two = g[g.threads == 2].set_index("pair")
    pairs = one.index.intersection(two.index)
    if not len(pairs):
        return None
    return stats.paired_log_ratio(one.loc[pairs, col].to_numpy(np.float64), two.loc[pairs, col].to_numpy(np.float64))


def main(path):
    df = pd.read_csv(path)
    if set(df["threads"]) != {1, 2}:
        raise ValueError(f"{path}: needs renders on 1 and 2 threads, has {sorted(set(df['threads']))}")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    out = ["# Two threads against one", "",
           f"`make bench-threads` (experiments/bench/threads.sh), commit `{commit}`: cornell, "
           "conventional, n = 100, 512x384; each pair renders on 1 and 2 threads back to back "
           "(order alternating); the renderer's own phase timers. Speed-up = t(1 thread) / "
           "t(2 threads), the geometric mean over the pairs [95% t interval over the pairs].", "",
           "| emitted | stored | pairs | " + " | ".join(l for _, l in PHASES) + " | total, 2 threads (s) |",
           "|---:|---:|---:|" + "---:|" * len(PHASES) + "---:|"]
    for p, g in df.groupby("photons_emitted"):
        one = g[g.threads == 1].set_index("pair")
        two = g[g.threads == 2].set_index("pair")
        pairs = one.index.intersection(two.index)
        cells = []
        for col, _ in PHASES:
            r = speedup(g, col)
            cells.append("-" if r is None else f"{r[0]:.2f}x [{r[1]:.2f}, {r[2]:.2f}]")
        t2 = np.median(two.loc[pairs, "total_s"])
        out.append(f"| {p:,} | {int(g.photons_stored.iloc[0]):,} | {len(pairs)} | "
                   + " | ".join(cells) + f" | {t2:.2f} |")
    print("\n".join(out))


if __name__ == "__main__":
    main(sys.argv[1])
