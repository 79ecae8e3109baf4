#!/usr/bin/python3
"""report.py: the tables of `make bench` that are computed from files.

  report.py icount CALLGRIND_OUT_PREFIX BEFORE_CSV   instructions per query, before and after
  report.py heavy ROWS_FILE                          medians of the heavy cells

icount: every callgrind dump of `bench --icount` (its description is
"ours|nano P_e k order queries") gives instructions per query; the table puts
ours beside nanoflann and beside the kd-tree of before (BEFORE_CSV).
heavy: ROWS_FILE has one line per run "method render_s precompute_s total_s
rss_kib"; prints one Markdown row per method: the median of each time over
the runs and the largest RSS.
"""
import glob
import sys

import pandas as pd


def icount(prefix, before_csv):
    rows = []
    for path in glob.glob(prefix + ".*"):
        desc = total = None
        with open(path) as f:
            for line in f:
                if line.startswith("desc: Trigger: Client Request: "):
                    desc = line.split(": ", 3)[3].split()
                elif line.startswith(("totals:", "summary:")) and total is None:
                    total = int(line.split()[1])
        if desc and total is not None:
            who, photons, k, order, queries = desc
            rows.append({"who": who, "photons": int(photons), "k": int(k), "order": order,
                         "instr": total / int(queries)})
    if not rows:
        sys.exit("report.py icount: no callgrind dumps at " + prefix + ".*")
    d = pd.DataFrame(rows).pivot_table(index=["photons", "k", "order"], columns="who", values="instr").reset_index()
    before = pd.read_csv(before_csv, comment="#")
    d = d.merge(before, on=["photons", "k", "order"], how="left")
    d = d.sort_values(["photons", "k", "order"], ascending=[True, True, False])
    print("| P_e | k | order | before (instr/query) | ours now | nanoflann | now / before | nanoflann / ours |")
    print("|---:|---:|---|---:|---:|---:|---:|---:|")
    for _, r in d.iterrows():
        b = r["ours_instr_per_query"]
        bs = "n/a" if pd.isna(b) else f"{b:.0f}"
        ratio = "n/a" if pd.isna(b) else f"{r['ours'] / b:.2f}"
        print(f"| {r['photons']} | {r['k']} | {r['order']} | {bs} | {r['ours']:.0f} | {r['nano']:.0f} | {ratio} | "
              f"{r['nano'] / r['ours']:.2f} |")


def heavy(rows_file):
    d = pd.read_csv(rows_file, sep=" ", names=["method", "render_s", "precompute_s", "total_s", "rss_kib"])
    for method, g in d.groupby("method", sort=False):
        print(f"| {method} | {g['render_s'].median():.2f} | {g['precompute_s'].median():.2f} | "
              f"{g['total_s'].median():.2f} | {g['rss_kib'].max()} |")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "icount":
        icount(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1] == "heavy":
        heavy(sys.argv[2])
    else:
        sys.exit(__doc__)
