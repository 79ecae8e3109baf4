#!/usr/bin/python3
"""collect.py: the renders of a grid -> runs.csv and cells.csv.

Owns turning the files of experiments/launch.py (seed<k>.run.json,
seed<k>.stats.json, seed<k>.exr under RUNROOT/<method>-<estimate>-p<P_e>-n<n>/)
into numbers: every image-derived number of the analysis is computed here,
once, with metrics.py.

runs.csv, one row per render of the requested grid (a render that has not
been made yet is a row with status "missing"): the settings, the status
("ok", "refused": the renderer rejected the combination with exit 2, i.e.
not applicable, or "missing"), the renderer's per-phase times (each the
minimum over the render's repeats, `time_s`; total_s the minimum of the
repeats' totals), the number of repeats, the two sums of phases the
analysis compares as the minimum over repeats of each repeat's sum
(trace_build_s: photon pass + kd-tree build; precompute_render_s:
precompute + eye pass; never a sum of per-phase minima), the CPU
seconds of the process, its place in a back-to-back pair (pair_pos: 1 or 2,
rendered first or second by rule pair of experiments/rules/render.smk;
0: not paired; timed in several processes: the first round's, and the
times and CPU seconds the minima over the processes), the CPU it was
pinned to (cpu) and the processes it was timed in (processes,
TIME_PROCESSES: experiments/launch.py; gauge_added: how many of them the
photon pass's gauge added, TIME_GAUGE), photon
counts, and the image's relMSE/NMSE/RMSE/PSNR
against the reference and its relMSE against the conventional image of the
same seed and estimate (0 for the conventional image itself), and its role:
"grid" (a render of the requested grid) or "comparison" (a conventional
render from CONV_RUNROOT that the grid is compared with, listed when it is
not the grid's own).

The reference's own error travels with every row (reference.py): ref_noise
and ref_bias are the noise and kernel bias its JSON holds (empty for a
reference without one, e.g. POV-Ray's: its error is not measured, and no
number stands in for it), and relmse_ref_less_noise is relmse_ref minus the
noise term (reference.corrected: the expected share of relmse_ref that the
reference's own noise brings; equal to relmse_ref without a JSON, or when
the JSON's metric is not relMSE). The bias is not subtracted: its sign per
pixel is unknown.

cells.csv, one row per cell (all seeds of one method, estimate, P_e, n):
how many seeds rendered, the mean relMSE against the reference, the same
mean corrected for the reference's noise (relmse_ref_less_noise_mean), its
split into bias and variance over seeds (metrics.bias_variance_from_gram),
and the reference floor (the fast POV-Ray render against the reference).

The correction is one constant per reference, the same for every render
judged against it, so a paired difference between two renders of one seed
(stats.paired_difference: its mean, interval and p-value, hence the
verdicts' tests) is the same on relmse_ref and relmse_ref_less_noise: the
term cancels. What scales with the level does change: the equivalence margin
delta (a share of the conventional mean) and the relative difference both
refer to the corrected level when computed on the corrected column.
"""

import argparse
import math
import os

import numpy as np
import pandas as pd

from experiments.analysis import metrics
from experiments.analysis import reference
from experiments.analysis import report, runs as layout

RUN_COLUMNS = [
    "scene", "size", "width", "height", "subpixels", "threads", "tag", "method", "estimate",
    "photons", "nn", "seed", "rep_every", "rep_count", "status", "exit", "message",
    "trace_s", "build_s", "precompute_s", "render_s", "total_s", "repeats", "trace_build_s", "precompute_render_s",
    "cpu_s", "user_s", "sys_s", "photons_stored", "representatives", "empty_estimates", "nonfinite_pixels", "loadavg_1min", "pair_pos",
    "relmse_ref", "nmse_ref", "rmse_ref", "psnr_ref", "relmse_conv", "role", "run",
    "ref_noise", "ref_bias", "relmse_ref_less_noise", "cpu", "processes", "gauge_added",
]
CELL_COLUMNS = [
    "scene", "size", "subpixels", "tag", "method", "estimate", "photons", "nn",
    "seeds_ok", "seeds_refused", "seeds_missing",
    "relmse_ref_mean", "relmse_ref_less_noise_mean", "bias_ref", "variance_ref", "relmse_ref_floor", "ref", "ref_fast",
]


def load_json(path):
    """The JSON object in PATH; exits naming the file when it is not JSON."""
    try:
        return layout.load_json(path)
    except layout.RunError as e:
        report.die("collect.py", str(e))


def repeat_min(st, phases):
    """The minimum over the repeats in the stats ST of the sum of PHASES in
    one repeat (`time_s_repeats`); one timed run (stats without repeats):
    the sum of `time_s`."""
    reps = st.get("time_s_repeats")
    if not reps:
        return sum(float(st["time_s"][p]) for p in phases)
    return min(sum(float(reps[p][i]) for p in phases) for i in range(len(reps[phases[0]])))


def read_run(root, method, estimate, photons, nn, seed):
    """The numbers of one render from its files (no image metrics yet):
    a dict with the runs.csv fields, status ok / refused / missing."""
    base = layout.run_base(root, method, estimate, photons, nn, seed)
    row = {"method": method, "estimate": estimate, "photons": photons, "nn": nn, "seed": seed,
           "run": base, "status": layout.MISSING, "exit": math.nan, "message": ""}
    try:
        status, rec = layout.read_record(base)
    except layout.RunError as e:
        report.die("collect.py", str(e))
    if status == layout.MISSING:
        return row
    for key in layout.RECORD_KEYS:
        row[key] = math.nan if rec[key] is None else rec[key]
    row["message"] = rec.get("message", "")
    row["pair_pos"] = rec.get("pair_pos", 0)  # records of unpaired renders have none: not paired
    cpu = rec.get("cpu")  # the CPU the render was pinned to (TIME_CPU); none, or a record before pinning: NaN
    row["cpu"] = math.nan if cpu is None else cpu
    row["gauge_added"] = rec.get("gauge_added", 0)  # processes the gauge added (TIME_GAUGE; launch.py)
    if status == layout.REFUSED:
        row["status"] = status
        return row
    st = load_json(base + ".stats.json")
    try:
        for phase in ("trace", "build", "precompute", "render", "total"):
            row[f"{phase}_s"] = float(st["time_s"][phase])
        row["repeats"] = st.get("repeats", 1)
        row["processes"] = st.get("processes", 1)  # the processes it was timed in (TIME_PROCESSES; launch.py)
        row["trace_build_s"] = repeat_min(st, ("trace", "build"))
        row["precompute_render_s"] = repeat_min(st, ("precompute", "render"))
        for key in ("photons_stored", "representatives", "empty_estimates", "nonfinite_pixels", "rep_every", "threads"):
            row[key] = st[key]
        row["width"], row["height"] = st["width"], st["height"]
        row["rep_count"] = st.get("rep_count", 0)  # renderers before --rep-count have none
    except KeyError as e:
        report.die("collect.py", f"{base}.stats.json: no {e}")
    if not os.path.isfile(base + ".exr"):
        report.die("collect.py", f"{base}.exr: missing although {base}.run.json says the render succeeded")
    row["status"] = layout.OK
    return row


def image_of(row):
    """The image of an ok run row."""
    return metrics.read_exr(row["run"] + ".exr")


def reference_error(ref_path):
    """(info, ref_noise, ref_bias) of the reference at REF_PATH for
    runs.csv (reference.measured: None, nan, nan when not measured, or
    measured in other units than relmse_ref, so nothing is subtracted);
    exits 2 (bad input) naming its JSON when that is not JSON or lacks the
    numbers."""
    try:
        return reference.measured(ref_path)
    except ValueError as e:
        report.die("collect.py", str(e), report.EXIT_BAD_INPUT)
    return None, math.nan, math.nan


def measure(row, x, ref, ref_path, conv_imgs, ref_info=None):
    """Add to ROW (an ok run whose image is X) its errors against the
    reference REF (if any; read from REF_PATH) and against the conventional
    image of the same seed in CONV_IMGS (seed -> image), if there is one;
    REF_INFO: the reference's JSON (reference_error), for the corrected
    relMSE."""
    if ref is not None:
        if x.shape != ref.shape:
            raise ValueError(f"{row['run']}.exr is {x.shape[1]}x{x.shape[0]}, "
                             f"the reference {ref_path} {ref.shape[1]}x{ref.shape[0]}")
        row["relmse_ref"] = metrics.relmse(x, ref)
        row["relmse_ref_less_noise"] = reference.corrected(row["relmse_ref"], ref_info)
        row["nmse_ref"] = metrics.nmse(x, ref)
        row["rmse_ref"] = metrics.rmse(x, ref)
        row["psnr_ref"] = metrics.psnr(x, ref)
    if row["seed"] in conv_imgs:
        row["relmse_conv"] = metrics.relmse(x, conv_imgs[row["seed"]])


def collect(args):
    """Build the runs and cells tables for the grid in ARGS; returns
    (runs DataFrame, cells DataFrame)."""
    ref = metrics.read_exr(args.ref) if args.ref else None
    floor = math.nan
    if ref is not None and args.ref_fast:
        floor = metrics.relmse(metrics.read_exr(args.ref_fast), ref)
    info, ref_noise, ref_bias = reference_error(args.ref)
    seeds = [int(s) for s in args.seeds.split()]
    common = {"scene": args.scene, "size": f"{args.width}x{args.height}", "width": args.width,
              "height": args.height, "subpixels": args.subpixels, "tag": args.tag}
    # every row of runs.csv carries the reference's own error (empty: not measured)
    ref_err = {"ref_noise": ref_noise, "ref_bias": ref_bias}
    methods = args.methods.split()
    # the conventional runs the others are compared with come from
    # CONV_RUNROOT; when they are not this grid's own conventional runs they
    # are listed too, with role "comparison"
    separate = "conventional" not in methods or args.conv_runroot != args.runroot
    runs, cells = [], []
    for estimate in args.estimates.split():
        for photons in [int(p) for p in args.photons.split()]:
            for nn in [int(n) for n in args.nns.split()]:
                conv_rows = {s: read_run(args.conv_runroot, "conventional", estimate, photons, nn, s) for s in seeds}
                conv_imgs = {s: image_of(r) for s, r in conv_rows.items() if r["status"] == "ok"}
                if separate:
                    for s, r in conv_rows.items():
                        if r["status"] == "ok":
                            measure(r, conv_imgs[s], ref, args.ref, conv_imgs, info)
                    runs.extend({**common, **r, **ref_err, "tag": "", "role": "comparison"}
                                for r in conv_rows.values())
                for method in methods:
                    own_conv = method == "conventional" and not separate
                    rows = [conv_rows[s] if own_conv else read_run(args.runroot, method, estimate, photons, nn, s)
                            for s in seeds]
                    imgs = [conv_imgs[r["seed"]] if own_conv else image_of(r) for r in rows if r["status"] == "ok"]
                    for r, x in zip([r for r in rows if r["status"] == "ok"], imgs):
                        measure(r, x, ref, args.ref, conv_imgs, info)
                    bias = variance = mean = math.nan
                    if ref is not None and imgs:
                        g = metrics.weighted_gram(imgs, ref)
                        mean = float(np.mean(np.diag(g)))
                        bias, variance = metrics.bias_variance_from_gram(g)
                    status = [r["status"] for r in rows]
                    cells.append({**common, "method": method, "estimate": estimate, "photons": photons, "nn": nn,
                                  "seeds_ok": status.count("ok"), "seeds_refused": status.count("refused"),
                                  "seeds_missing": status.count("missing"), "relmse_ref_mean": mean,
                                  "relmse_ref_less_noise_mean": reference.corrected(mean, info),
                                  "bias_ref": bias, "variance_ref": variance, "relmse_ref_floor": floor,
                                  "ref": args.ref, "ref_fast": args.ref_fast})
                    runs.extend({**common, **r, **ref_err, "role": "grid"} for r in rows)
    runs = pd.DataFrame(runs).reindex(columns=RUN_COLUMNS)
    cells = pd.DataFrame(cells).reindex(columns=CELL_COLUMNS)
    return runs, cells


def main():
    """Command line: see the module docstring and experiments/rules/grid.smk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runroot", required=True)
    ap.add_argument("--conv-runroot", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--width", type=int, required=True)
    ap.add_argument("--height", type=int, required=True)
    ap.add_argument("--subpixels", type=int, required=True)
    ap.add_argument("--threads", default="", help="(unused: the threads column is the stats JSON's)")
    ap.add_argument("--tag", default="")
    ap.add_argument("--methods", required=True)
    ap.add_argument("--estimates", required=True)
    ap.add_argument("--photons", required=True)
    ap.add_argument("--nns", required=True)
    ap.add_argument("--seeds", required=True)
    ap.add_argument("--ref", default="", help="reference EXR (empty: no error against a reference)")
    ap.add_argument("--ref-fast", default="", help="fast POV-Ray EXR for the reference floor (optional)")
    ap.add_argument("--runs-csv", required=True)
    ap.add_argument("--cells-csv", required=True)
    args = ap.parse_args()
    for name, path in (("reference", args.ref), ("fast reference", args.ref_fast)):
        if path and not os.path.isfile(path):
            report.die("collect.py", f"{name} {path} not found")
    try:
        runs, cells = collect(args)
    except ValueError as e:
        report.die("collect.py", str(e))
    if not (runs["status"] == "ok").any():
        report.die("collect.py", f"no render of the grid under {args.runroot} succeeded "
                   f"({(runs['status'] == 'refused').sum()} refused, {(runs['status'] == 'missing').sum()} missing)")
    report.write_csv_atomic(runs, args.runs_csv, "%.8g")
    report.write_csv_atomic(cells, args.cells_csv, "%.8g")
    n = runs["status"].value_counts()
    print(f"wrote {args.runs_csv} ({len(runs)} renders: {n.get('ok', 0)} ok, {n.get('refused', 0)} not applicable, "
          f"{n.get('missing', 0)} missing) and {args.cells_csv} ({len(cells)} cells)")


if __name__ == "__main__":
    main()
