#!/usr/bin/python3
"""repeats_cost.py: the cost of timing renders with repeats, and the cost
model per unit of work (issue 35, goal 8) -> OUT.md, OUT.csv and
OUT-warm.csv.

    python3 -m experiments.analysis.repeats_cost --results DIR --out DIR/bench/repeats

Owns the summary of every render's stats file under DIR/runs/<root>/**/
*.stats.json (the renderer's keys: `repeats`, `time_s` (the minima per phase
and of the totals), `time_s_repeats` (every repeat's times), `time_s_cold`
(the first repeat), `time_s_median`), per study run root (the directory under
runs/) and over all of them:
    - renders, and the repeats per render (median, range);
    - single_s: what one timed run of each render takes (the sum of the
      renders' cold totals, the first repeat), against repeats_s: what the
      repeats took (the sum of every repeat's total); factor = repeats_s /
      single_s and extra_s = repeats_s - single_s, the time the study's timed
      renders spend on repeats (the untimed parts of a render, loading the
      scene and writing the image, are in neither);
    - per phase (trace, build, precompute, render, total), the median over
      the renders with at least two repeats of how far the minimum lies
      below the first run (100 x (1 - min / cold)) and below the median of
      the repeats (100 x (1 - min / median)): the noise the repeats remove
      (a phase that takes no time in a render, precompute in the
      conventional method, does not count there).
The second section of OUT.md, "which repeats are warm", and OUT-warm.csv:
per process of a render (a render timed in several processes, launch.py's
merge_stats, lists every process's repeats in the order run; the split is
recovered from `processes` and checked against `time_s_processes`, each
process's minima, and a render whose split does not check is counted, not
guessed), over the processes of at least WARM_REPEATS repeats, for each of
the first WARM_REPEATS repeats and each phase: the median of the repeat's
time over the process's least, the share of processes where it lies within
WARM_MARGIN of the least, and the median of the repeat's page faults
(`minor_faults_repeats`, where the stats have them). The first repeat is
cold by design; the section shows whether the second already is not.
The third section of OUT.md, "the cost model, per unit of work": the
coefficients of the cost model `make calibrate` writes (MODEL, default
DIR/calibrate/model.json; experiments/calibrate.py) in ns per unit of each
phase's work counters, with its held-out validation; "not measured: run
make calibrate" when there is none.

A stats file that is not JSON, or lacks the times, exits 2 naming it; a
render whose status is not "ok" is left out and counted.
"""

import argparse
import glob
import json
import math
import os
import sys

import numpy as np

from experiments import calibrate
from experiments.analysis import report

PHASES = ("trace", "build", "precompute", "render", "total")
ALL = "all studies"
# the repeats the warm section follows per process (--repeats auto's least),
# and the distance from the process's least repeat that counts as warm
WARM_REPEATS = 3
WARM_MARGIN = 0.03
WARM_COLUMNS = (["study", "repeat", "processes"] + [f"{p}_over_least_median" for p in PHASES]
                + [f"{p}_warm_share" for p in PHASES] + ["minor_faults_median"])
CSV_COLUMNS = (["study", "renders", "left_out", "repeats_median", "repeats_min", "repeats_max", "single_s",
                "repeats_s", "factor", "extra_s", "renders_repeated"]
               + [f"min_below_cold_{p}_pct" for p in PHASES] + [f"min_below_median_{p}_pct" for p in PHASES])


class StatsError(Exception):
    """A stats file that cannot be read as a render's times, with the reason."""


def stats_files(results):
    """Every render's stats file under RESULTS/runs, as (run root, path),
    sorted; the hidden directories (the pinned renderer) are not run roots."""
    out = []
    runs = os.path.join(results, "runs")
    for root in sorted(os.listdir(runs)) if os.path.isdir(runs) else []:
        if root.startswith(".") or not os.path.isdir(os.path.join(runs, root)):
            continue
        for path in sorted(glob.glob(os.path.join(runs, root, "**", "*.stats.json"), recursive=True)):
            out.append((root, path))
    return out


def render_times(path):
    """The times of one render's stats file PATH: {"repeats": R, "min",
    "cold", "median": {phase: s}, "totals": [each repeat's total]}, or None
    for a render whose status is not ok. StatsError when it is unreadable or
    lacks the times. A file without the repeats' keys is one run."""
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        raise StatsError(f"{path}: not a stats file ({e.__class__.__name__}: {e})")
    if not isinstance(doc, dict):
        raise StatsError(f"{path}: not a stats file (not a JSON object)")
    if doc.get("status", "ok") != "ok":
        return None
    try:
        mins = {p: float(doc["time_s"][p]) for p in PHASES}
        reps = doc.get("time_s_repeats") or {p: [mins[p]] for p in PHASES}
        totals = [float(t) for t in reps["total"]]
        cold = doc.get("time_s_cold") or {p: reps[p][0] for p in PHASES}
        median = doc.get("time_s_median") or {p: float(np.median(reps[p])) for p in PHASES}
        out = {"repeats": int(doc.get("repeats", len(totals))), "min": mins, "totals": totals,
               "cold": {p: float(cold[p]) for p in PHASES}, "median": {p: float(median[p]) for p in PHASES}}
    except (KeyError, TypeError, ValueError, IndexError) as e:
        raise StatsError(f"{path}: lacks the times ({e.__class__.__name__}: {e}); "
                         "a stats file of photonmap render --stats has time_s and time_s_repeats")
    if out["repeats"] != len(totals) or not totals:
        raise StatsError(f"{path}: repeats is {out['repeats']} but time_s_repeats.total has {len(totals)} values")
    out["processes"] = split_processes(doc, reps)
    return out


def split_processes(doc, reps):
    """The processes of one render's stats DOC, each as {"times": {phase:
    [its repeats' s]}, "faults": [its repeats' page faults] or None}, from
    REPS (every repeat in the order run); None when the split cannot be
    recovered: the repeats do not divide evenly among `processes`, or a
    process's least repeat is not its minimum in `time_s_processes`."""
    k = int(doc.get("processes", 1))
    n = len(reps["total"])
    if k < 1 or n % k:
        return None
    m = n // k
    faults = doc.get("minor_faults_repeats")
    if faults is not None and len(faults) != n:
        faults = None
    per_process = doc.get("time_s_processes")
    out = []
    for j in range(k):
        times = {p: [float(t) for t in reps[p][j * m:(j + 1) * m]] for p in PHASES}
        if k > 1 and (not per_process or any(min(times[p]) != float(per_process[p][j]) for p in PHASES)):
            return None
        out.append({"times": times, "faults": None if faults is None else [int(f) for f in faults[j * m:(j + 1) * m]]})
    return out


def below(minimum, other):
    """100 x (1 - MINIMUM / OTHER): how far the minimum lies below OTHER, in
    percent; nan where OTHER is not positive (the phase took no time)."""
    return 100.0 * (1.0 - minimum / other) if other > 0 else math.nan


def median_or_nan(values):
    """The median of VALUES without NaN; nan when none is left."""
    v = [x for x in values if not math.isnan(x)]
    return float(np.median(v)) if v else math.nan


def summarise(name, renders, left_out):
    """One row of OUT.csv: the study NAME's RENDERS (render_times), LEFT_OUT
    renders not ok."""
    reps = [r["repeats"] for r in renders]
    single = sum(r["cold"]["total"] for r in renders)
    repeated = sum(sum(r["totals"]) for r in renders)
    multi = [r for r in renders if r["repeats"] >= 2]
    row = {"study": name, "renders": len(renders), "left_out": left_out,
           "repeats_median": float(np.median(reps)) if reps else math.nan,
           "repeats_min": min(reps) if reps else math.nan, "repeats_max": max(reps) if reps else math.nan,
           "single_s": single, "repeats_s": repeated,
           "factor": repeated / single if single > 0 else math.nan, "extra_s": repeated - single,
           "renders_repeated": len(multi)}
    for p in PHASES:
        row[f"min_below_cold_{p}_pct"] = median_or_nan([below(r["min"][p], r["cold"][p]) for r in multi])
        row[f"min_below_median_{p}_pct"] = median_or_nan([below(r["min"][p], r["median"][p]) for r in multi])
    return row


def warm_rows(name, renders):
    """The rows of OUT-warm.csv for the study NAME's RENDERS (render_times):
    one per repeat 1..WARM_REPEATS, over the processes of at least
    WARM_REPEATS repeats; with "unsplit", the renders whose processes could
    not be told apart (left out)."""
    procs = [p for r in renders if r["processes"] for p in r["processes"]
             if len(p["times"]["total"]) >= WARM_REPEATS]
    unsplit = sum(1 for r in renders if r["processes"] is None)
    rows = []
    for i in range(WARM_REPEATS):
        row = {"study": name, "repeat": i + 1, "processes": len(procs), "unsplit": unsplit}
        for ph in PHASES:
            ratios = [p["times"][ph][i] / min(p["times"][ph]) for p in procs if min(p["times"][ph]) > 0]
            row[f"{ph}_over_least_median"] = float(np.median(ratios)) if ratios else math.nan
            row[f"{ph}_warm_share"] = (float(np.mean([x <= 1 + WARM_MARGIN for x in ratios]))
                                       if ratios else math.nan)
        faults = [p["faults"][i] for p in procs if p["faults"] is not None]
        row["minor_faults_median"] = float(np.median(faults)) if faults else math.nan
        rows.append(row)
    return rows


def collect_all(results):
    """(rows of OUT.csv, rows of OUT-warm.csv): one per run root with a
    render, then ALL (warm: WARM_REPEATS rows each)."""
    by_root, left, every = {}, {}, []
    for root, path in stats_files(results):
        t = render_times(path)
        if t is None:
            left[root] = left.get(root, 0) + 1
            continue
        by_root.setdefault(root, []).append(t)
        every.append(t)
    roots = sorted(set(by_root) | set(left))
    rows = [summarise(root, by_root.get(root, []), left.get(root, 0)) for root in roots]
    warm = [w for root in roots for w in warm_rows(root, by_root.get(root, []))]
    if rows:
        rows.append(summarise(ALL, every, sum(left.values())))
        warm += warm_rows(ALL, every)
    return rows, warm


def collect(results):
    """The rows of OUT.csv: one per run root with a render, then ALL."""
    return collect_all(results)[0]


def fmt(v, spec):
    """V formatted with SPEC, or an em dash for nan."""
    return "—" if isinstance(v, float) and math.isnan(v) else format(v, spec)


def pct(v):
    """V as a percentage with one decimal, or an em dash for nan."""
    return "—" if math.isnan(v) else f"{v:.1f}%"


def duration(seconds):
    """SECONDS as h min s text."""
    s = int(round(seconds))
    h, m = divmod(s // 60, 60)
    return f"{h} h {m} min" if h else (f"{m} min {s % 60} s" if m else f"{seconds:.1f} s")


def repeats_section(rows):
    """The first section of OUT.md (Markdown lines)."""
    out = ["## The cost of repeats", ""]
    if not rows:
        return out + ["No render's stats file under runs/: no study has run.", ""]
    tot = rows[-1]
    left = f", {tot['left_out']} not ok left out" if tot["left_out"] else ""
    out += [f"Every render's stats file under runs/: {tot['renders']} renders in {len(rows) - 1} "
            f"{'study' if len(rows) == 2 else 'studies'} (run roots){left}. "
            f"One timed run of each would take {duration(tot['single_s'])} (the first repeat's total, the cold time); "
            f"the repeats took {duration(tot['repeats_s'])}, x{fmt(tot['factor'], '.2f')} "
            f"({duration(tot['extra_s'])} more). The untimed parts of a render (loading the scene, writing the "
            "image) are in neither.", "",
            "| study | renders | repeats median (range) | one run (s) | with repeats (s) | factor | extra (s) |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        name = f"**{r['study']}**" if r["study"] == ALL else f"`{r['study']}`"
        out.append(f"| {name} | {r['renders']} | {fmt(r['repeats_median'], 'g')} "
                   f"({fmt(r['repeats_min'], 'g')}-{fmt(r['repeats_max'], 'g')}) | {r['single_s']:.1f} | "
                   f"{r['repeats_s']:.1f} | {fmt(r['factor'], '.2f')} | {r['extra_s']:.1f} |")
    out += ["", "What the repeats remove: per phase, the median over the renders with at least two repeats of how "
            "far the minimum lies below the first run (cold) and below the repeats' median, in percent (— where "
            "no render of the study repeats or the phase takes no time).", "",
            "| study | repeated | " + " | ".join(f"{p}: below cold / median" for p in PHASES) + " |",
            "|---|---:|" + "---:|" * len(PHASES)]
    for r in rows:
        name = f"**{r['study']}**" if r["study"] == ALL else f"`{r['study']}`"
        out.append(f"| {name} | {r['renders_repeated']} | " + " | ".join(
            f"{pct(r[f'min_below_cold_{p}_pct'])} / {pct(r[f'min_below_median_{p}_pct'])}"
            for p in PHASES) + " |")
    return out + [""]


def warm_section(warm):
    """The section "which repeats are warm" of OUT.md (Markdown lines), from
    the rows of OUT-warm.csv: all studies' rows in a table, and a sentence
    on the second repeat."""
    out = ["## Which repeats are warm", ""]
    every = [w for w in warm if w["study"] == ALL]
    if not every or not every[0]["processes"]:
        return out + [f"No process of at least {WARM_REPEATS} repeats under runs/.", ""]
    second = every[1]
    unsplit = (f" {every[0]['unsplit']} renders whose processes could not be told apart are left out."
               if every[0]["unsplit"] else "")
    out += [f"Per process of a render, over the {every[0]['processes']} processes of at least {WARM_REPEATS} "
            f"repeats in all the studies under runs/: each of the first {WARM_REPEATS} repeats' time over the process's least "
            f"repeat (median), with the share of processes where it lies within {100 * WARM_MARGIN:g}% of the "
            "least (\"warm\"), and the repeat's page faults (median; `minor_faults_repeats`). The first repeat "
            "is the cold time by design." + unsplit, "",
            "| repeat | " + " | ".join(f"{p}: over least (warm)" for p in PHASES) + " | page faults |",
            "|---:|" + "---:|" * (len(PHASES) + 1)]
    for w in every:
        out.append(f"| {w['repeat']} | " + " | ".join(
            f"{fmt(w[f'{p}_over_least_median'], '.3f')} ({pct(100 * w[f'{p}_warm_share'])})" for p in PHASES)
            + f" | {fmt(w['minor_faults_median'], '.0f')} |")
    out += ["", f"The second repeat is warm (within {100 * WARM_MARGIN:g}% of the least) for the build in "
            f"{pct(100 * second['build_warm_share'])} of the processes, for the precompute in "
            f"{pct(100 * second['precompute_warm_share'])} and for the whole render in "
            f"{pct(100 * second['total_warm_share'])}; the numbers per study are in the warm CSV.", ""]
    return out


def model_section(model_path):
    """The second section of OUT.md: the cost model's seconds per unit of
    work (ns per unit), or that there is none, or why it cannot be used."""
    out = ["## The cost model, per unit of work", ""]
    try:
        loaded = calibrate.load_model(model_path)
    except calibrate.ModelError as e:  # a model of other counters: named, not fatal
        return out + [f"Not measured: {e}.", ""]
    if loaded is None:
        return out + [f"Not measured: run make calibrate (no {model_path}).", ""]
    model, validation = loaded
    with open(model_path, encoding="utf-8") as f:
        prov = json.load(f).get("provenance") or {}
    out += [f"From `{model_path}` of {calibrate.model_date(model_path)} (`make calibrate`, "
            f"experiments/calibrate.py): each phase's time (the minimum over `--repeats auto`, one thread) as a "
            f"non-negative linear function of its work counters; machine {prov.get('cpu', '?')}, binary "
            f"{prov.get('commit', '?')}. On the renders it did not fit, the predicted total is off by a median "
            f"of {100 * validation['median']:.1f}% and at most {100 * validation['largest']:.1f}%. Counters "
            "with a zero coefficient explain nothing the others do not and are left out.", "",
            "| phase | counter | ns per unit |", "|---|---|---:|"]
    for part in calibrate.PARTS:
        for name, c in zip(("constant",) + calibrate.FEATURES[part], model[part]):
            if c > 0:
                label = "(constant: ns per render)" if name == "constant" else name
                out.append(f"| {part} | {label} | {c * 1e9:.4g} |")
    return out + [""]


def write_csv(path, columns, rows):
    """ROWS under COLUMNS to PATH.tmp (nan as empty); the caller renames."""
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(",".join(columns) + "\n")
        for r in rows:
            f.write(",".join("" if isinstance(r[c], float) and math.isnan(r[c]) else
                             (f"{r[c]:.6g}" if isinstance(r[c], float) else str(r[c])) for c in columns) + "\n")


def write(rows, model_path, out, warm=()):
    """OUT.csv, OUT-warm.csv (the rows WARM) and OUT.md, each to a temporary
    name and renamed."""
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    write_csv(out + ".csv", CSV_COLUMNS, rows)
    write_csv(out + "-warm.csv", WARM_COLUMNS, warm)
    md = ["# Repeats and the cost model", "",
          f"Written by `make bench-repeats` (experiments/analysis/repeats_cost.py) on {report.today()}, commit "
          f"{report.commit()}, from the stats files of the "
          "renders under runs/ and the cost model of `make calibrate`; the numbers per study are in "
          f"`{os.path.basename(out)}.csv` and `{os.path.basename(out)}-warm.csv`.", ""]
    md += repeats_section(rows) + warm_section(warm) + model_section(model_path)
    with open(out + ".md.tmp", "w", encoding="utf-8") as f:
        f.write("\n".join(md))
    os.replace(out + ".csv.tmp", out + ".csv")
    os.replace(out + "-warm.csv.tmp", out + "-warm.csv")
    os.replace(out + ".md.tmp", out + ".md")


def main(argv=None):
    """The command line: returns 0, or 2 when a stats file or the model
    cannot be read (named on stderr)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    ap.add_argument("--results", required=True, help="the results directory (its runs/ and calibrate/)")
    ap.add_argument("--out", required=True, help="output stem: OUT.md and OUT.csv")
    ap.add_argument("--model", default="", help="the cost model (default RESULTS/calibrate/model.json)")
    a = ap.parse_args(argv)
    model_path = a.model or os.path.join(a.results, "calibrate", calibrate.MODEL_NAME)
    try:
        rows, warm = collect_all(a.results)
        write(rows, model_path, a.out, warm)
    except (StatsError, calibrate.ModelError) as e:
        print(f"repeats_cost: {e}", file=sys.stderr)
        return 2
    tot = rows[-1] if rows else None
    print(f"repeats_cost: {tot['renders'] if tot else 0} renders, repeats x{fmt(tot['factor'], '.2f') if tot else '—'}"
          f" -> {a.out}.md, {a.out}.csv, {a.out}-warm.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
