"""The run layout: where one render of a study keeps its files and what its
record (seed<k>.run.json) says. The one place that spells a run's path: the
Snakemake rules (experiments/Snakefile), the render launcher
(experiments/launch.py) and every analysis reader call these functions.

A study's renders live under a run root (RESULTS/runs/<scene>-<W>x<H>-s<S>-
t<T>[-TAG], run_root below), one directory per cell
<method>-<estimate>-p<P_e>-n<n>, one set of files per seed: seed<k>.exr,
seed<k>.stats.json, seed<k>.err (seed<k>.reps.csv for a study that dumps
the representatives) and, written last by the launcher, seed<k>.run.json. experiments/README.md ("The run layout") states the same.

The one rule of a record's status: exit 0 is "ok", exit 2 is "refused" (the
renderer rejected the combination: not applicable), no record is "missing";
the launcher records nothing else, so any other exit is an error of the files.
"""

import json
import os

OK, REFUSED, MISSING = "ok", "refused", "missing"
EXIT_STATUS = {0: OK, 2: REFUSED}
RECORD_KEYS = ("exit", "loadavg_1min", "cpu_s", "user_s", "sys_s")


class RunError(Exception):
    """A run's files contradict the layout (unreadable or incomplete record)."""


def cell_name(method, estimate, photons, nn):
    """The directory name of a cell under the run root."""
    return f"{method}-{estimate}-p{photons}-n{nn}"


def run_base(root, method, estimate, photons, nn, seed):
    """The path of one render's files without their extensions."""
    return os.path.join(root, cell_name(method, estimate, photons, nn), f"seed{seed}")


def threads_label(threads):
    """The run root's thread part: t<N>, or tall for all cores (THREADS empty)."""
    threads = str(threads).strip()
    return f"t{threads}" if threads else "tall"


def run_root(results, scene, size, subpixels, threads, tag=""):
    """Where a study's renders live: RESULTS/runs/<scene>-<W>x<H>-s<S>-t<T>[-TAG]."""
    name = os.path.splitext(os.path.basename(scene))[0]
    tag = str(tag).strip()
    return os.path.join(results, "runs", f"{name}-{size}-s{subpixels}-{threads_label(threads)}" + (f"-{tag}" if tag else ""))


def converged_ref(results, scene, size, photons, nn, direct, subpixels, seeds):
    """Our converged reference of SCENE at SIZE (WxH), rendered by
    experiments/analysis/reference.py: RESULTS/runs/<scene>-convref-p<P>-n<n>-
    <direct>-s<S>-seeds<a_b_..>/<W>x<H>.exr, the JSON of its measured error
    beside it and its renders in <W>x<H>/. SEEDS: a list, or the text of the
    seeds part as it stands (a rule's wildcard)."""
    name = os.path.splitext(os.path.basename(scene))[0]
    seeds = seeds if isinstance(seeds, str) else "_".join(map(str, seeds))
    return os.path.join(results, "runs", f"{name}-convref-p{photons}-n{nn}-{direct}-s{subpixels}-seeds{seeds}",
                        f"{size}.exr")


def run_names(photons, nns, methods, estimates, seeds):
    """Every render of a grid as CELL/seed<k>, seeds outermost (a partial run
    has every cell at the first seeds, and slow phases of a shared machine
    spread over all cells), then P_e, n, method, estimate."""
    return [f"{cell_name(m, e, p, n)}/seed{s}" for s in seeds for p in photons for n in nns
            for m in methods for e in estimates]


def record_path(root, name):
    """The record of the render NAME (CELL/seed<k>) under ROOT."""
    return os.path.join(root, name + ".run.json")


def load_json(path):
    """The JSON object in PATH; raises RunError naming the file when it is
    unreadable or not JSON."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise RunError(f"{path}: {e}") from e


def read_record(base):
    """(status, record) of the render at BASE: (MISSING, None) without a
    record, else OK or REFUSED by the record's exit and the record (a dict
    with RECORD_KEYS). Raises RunError on a record without those keys or
    with another exit status."""
    path = base + ".run.json"
    if not os.path.isfile(path):
        return MISSING, None
    rec = load_json(path)
    for key in RECORD_KEYS:
        if key not in rec:
            raise RunError(f"{path}: no '{key}'")
    if rec["exit"] not in EXIT_STATUS:
        raise RunError(f"{path}: exit {rec['exit']} (the launcher records only 0 and 2)")
    return EXIT_STATUS[rec["exit"]], rec
