#!/usr/bin/python3
"""report.py: the tables of `make bench` that are computed from files.

  report.py icount CALLGRIND_OUT_PREFIX BEFORE_CSV   instructions per query, before and after
  report.py heavy ROWS_FILE                          medians of the heavy cells
  report.py peers CSV                                the kNN against FLANN, cKDTree, nanoflann

icount: every callgrind dump of `bench --icount` (its description is
"ours|nano|flann P_e k order queries") gives instructions per query; the
table puts ours beside nanoflann, FLANN (when present) and the kd-tree of
before (BEFORE_CSV).
heavy: ROWS_FILE has one line per run "method render_s precompute_s total_s
rss_kib"; prints one Markdown row per method: the median of each time over
the runs and the largest RSS.
peers: CSV is the output of `bench --peers` (one row per query stream and
build, per check and per timed run); prints the queries/s of each tree
(median over the runs) per stream ("tiles": pixel centres in tile order;
"subpixels": the eye pass's four samples per pixel), ours / each peer, and
what the neighbour-set checks found.
"""
import glob
import sys

import pandas as pd


def icount(prefix, before_csv):
    """Prints the Markdown table of instructions per query per (P_e, k, order) from the callgrind
    dumps PREFIX.*: ours now beside the kd-tree of before (BEFORE_CSV), nanoflann, FLANN when present and
    our other modes; exits 1 when there is no dump."""
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
    fl = "flann" in d.columns
    modes = [(w, n) for w, n in [("ourspacket", "ours, packets of 4"), ("oursstateless", "ours, stateless")]
             if w in d.columns]
    print("| P_e | k | order | before (instr/query) | ours now | nanoflann | now / before | nanoflann / ours |"
          + (" FLANN knnSearch | FLANN / ours |" if fl else "") + "".join(f" {n} |" for _, n in modes))
    print("|---:|---:|---|---:|---:|---:|---:|---:|" + ("---:|---:|" if fl else "") + "---:|" * len(modes))
    for _, r in d.iterrows():
        b = r["ours_instr_per_query"]
        bs = "n/a" if pd.isna(b) else f"{b:.0f}"
        ratio = "n/a" if pd.isna(b) else f"{r['ours'] / b:.2f}"
        print(f"| {r['photons']} | {r['k']} | {r['order']} | {bs} | {r['ours']:.0f} | {r['nano']:.0f} | {ratio} | "
              f"{r['nano'] / r['ours']:.2f} |" + (f" {r['flann']:.0f} | {r['flann'] / r['ours']:.2f} |" if fl else "")
              + "".join(" n/a |" if pd.isna(r[w]) else f" {r[w]:.0f} |" for w, _ in modes))


def heavy(rows_file):
    """Prints one Markdown row per method of ROWS_FILE: the median render, precompute and total seconds
    over its runs and the largest RSS (KiB)."""
    d = pd.read_csv(rows_file, sep=" ", names=["method", "render_s", "precompute_s", "total_s", "rss_kib"])
    for method, g in d.groupby("method", sort=False):
        print(f"| {method} | {g['render_s'].median():.2f} | {g['precompute_s'].median():.2f} | "
              f"{g['total_s'].median():.2f} | {g['rss_kib'].max()} |")


PEERS = [("flann-knn", "FLANN knnSearch"), ("flann-radius", "FLANN radiusSearch"), ("ckdtree", "cKDTree"),
         ("nanoflann", "nanoflann")]
# ours in other modes (bench --peers): packets of four consecutive queries
# (kd_query_knn_packet, state carried), and no state between queries (each
# search starts from the cap, as a peer's single query does)
OURS_MODES = [("ours-packets", "ours, packets of 4"), ("ours-stateless", "ours, stateless")]
NAMES = dict(PEERS + OURS_MODES + [("ours", "ours")])


def peer_medians(d):
    """Per cell of a peers CSV (bench --peers: columns who, order, pe, stored,
    k, queries, rep, seconds), in the file's order: (order, pe, stored, k,
    queries, {who: median seconds over the runs}); the build and check rows
    are not runs."""
    runs = d[~d["rep"].isin(["build", "check"])]
    return [(order, pe, stored, k, g["queries"].iloc[0], g.groupby("who")["seconds"].median().to_dict())
            for (order, pe, stored, k), g in runs.groupby(["order", "pe", "stored", "k"], sort=False)]


def strongest_peer(med):
    """The peer (a PEERS key) with the smallest median time in MED."""
    return min((w for w, _ in PEERS), key=lambda w: med[w])


def peers(csv):
    """Prints the peers tables of CSV (bench --peers): per cell each tree's queries/s (median over the
    runs) and ours against each peer and the strongest, the builds' times, and the neighbour-set checks;
    exits 1 naming how many sets did not check."""
    d = pd.read_csv(csv)
    runs = d[~d["rep"].isin(["build", "check"])].copy()
    checks = d[d["rep"] == "check"]
    builds = d[(d["rep"] == "build") & (d["order"] == d["order"].iloc[0])].set_index("who")["seconds"]
    reps = runs["rep"].nunique()
    modes = [(w, n) for w, n in OURS_MODES if w in set(runs["who"])]
    print("| P_e | stored | queries | k | ours (Mq/s) | " + " | ".join(f"{n} (Mq/s)" for _, n in PEERS) + " | "
          + " | ".join(f"ours / {n}" for _, n in PEERS) + " | ours / strongest peer |"
          + "".join(f" {n} / strongest peer |" for _, n in modes))
    print("|---:|---:|---|---:|---:|" + "---:|" * (2 * len(PEERS)) + "---:|" + "---:|" * len(modes))
    for order, pe, stored, k, nq, med in peer_medians(d):
        rate = {w: nq / med[w] * 1e-6 for w in med}
        best = strongest_peer(med)
        print(f"| {pe} | {stored} | {order} | {k} | {rate['ours']:.3f} | "
              + " | ".join(f"{rate[w]:.3f}" for w, _ in PEERS) + " | "
              + " | ".join(f"{med[w] / med['ours']:.2f}" for w, _ in PEERS) + " | "
              + f"{med[best] / med['ours']:.2f} ({dict(PEERS)[best]}) |"
              + "".join(f" {med[best] / med[w]:.2f} |" for w, _ in modes))
    print()
    print("Asymmetry: ours (the first ratio) keeps state between coherent queries (the last query's radius starts "
          "the next search) and uses AVX2; FLANN's knnSearch and radiusSearch get the whole query matrix in one "
          "call and cKDTree.query the whole array (workers=1), nanoflann single queries; none gets the previous "
          "radius as a bound. \"ours, packets of 4\" serves four consecutive queries with one traversal; "
          "\"ours, stateless\" starts every search from the cap, like a peer's single query.")
    print()
    print(f"Median of {reps} runs per cell; in each run all of them answer the same queries one after another "
          "(cKDTree timed by its own process around its one query call). Builds over the same points "
          "(one run, seconds): "
          + ", ".join(f"{n} {builds[w]:.3f}" for w, n in [("ours", "ours"), ("flann-knn", "FLANN"), ("ckdtree", "cKDTree"),
                                                         ("nanoflann", "nanoflann")]) + ".")
    print()
    print("Neighbour sets, checked before the timed runs (ours against brute force on a sample of the queries; "
          "every peer against ours on all of them):")
    print()
    print("| queries | k | answer | checked against | queries checked | neighbours found (all queries) | same set | differ by ties only | wrong |")
    print("|---|---:|---|---|---:|---:|---:|---:|---:|")
    bad = 0
    for _, r in checks.sort_values(["order", "k"], ascending=[False, True], kind="stable").iterrows():
        name = NAMES[r["who"]]
        against = "brute force" if r["who"] == "ours" else "ours"
        bad += int(r["mismatches"])
        print(f"| {r['order']} | {int(r['k'])} | {name} | {against} | {int(r['queries'])} | {int(r['found'])} | {int(r['exact'])} | "
              f"{int(r['ties'])} | {int(r['mismatches'])} |")
    if bad:
        sys.exit(f"report.py peers: {bad} neighbour sets did not check")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "icount":
        icount(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1] == "heavy":
        heavy(sys.argv[2])
    elif len(sys.argv) == 3 and sys.argv[1] == "peers":
        peers(sys.argv[2])
    else:
        sys.exit(__doc__)
