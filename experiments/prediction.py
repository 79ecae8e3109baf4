"""prediction.py: the line a study's dry run prints, once: the wall time the
cost model of this machine (`make calibrate`: RESULTS/calibrate/model.json,
experiments/calibrate.py) predicts for the study's renders that are missing
(no record yet), each at its --repeats (TIME_REPEATS, or 1 where the study
renders it once) in its processes (TIME_PROCESSES, or 1 there; the
processes the photon pass's gauge adds, TIME_GAUGE, depend on the machine
at the time and are not predicted: runs.csv's gauge_added counts them).
The model predicts a render's minimum over its repeats, so the time is of
the repeats at their minimum; the wall a study takes is longer (repeats
above their minimum, the processes the gauge adds, each process's start and
image writing), and the line says so:

    predicted: 12 renders missing, about 0 h 7 min on this machine at the repeats' minima; the wall is longer (repeats above their minimum, processes the gauge adds, each process's start) (cost model results/calibrate/model.json of 2026-12-05)

or "no cost model: run make calibrate" when there is none. The Snakefile
prints it when make's front door passes PREDICT=1 (a dry run:
experiments/snakemake.mk). The model knows the settings scene, method, P_e,
n, size and subpixels; renders with final gathering (--gather N in the
grid's PM_ARGS) and methods it did not calibrate are counted and named as
not predicted, and the converged references a study renders are not in the
prediction.
"""

import os
import re

from experiments import calibrate

CELL = re.compile(r"(?P<method>[a-z]+)-(?P<estimate>[a-z]+)-p(?P<photons>[0-9]+)-n(?P<nn>[0-9]+)/seed[0-9]+")


def model_path(study):
    """The cost model a study's prediction reads: RESULTS/calibrate/model.json."""
    return os.path.join(study.results, "calibrate", calibrate.MODEL_NAME)


def gathers(pm_args):
    """The gather rays per eye sample that PM_ARGS asks for (--gather N; 0 without)."""
    m = re.search(r"--gather[= ]+([0-9]+)", pm_args or "")
    return int(m[1]) if m else 0


def missing(study):
    """The study's renders that have no record: (grid, method, photons, nn)
    per render, in the study's run order."""
    out = []
    for g in study.grids:
        for name, record in zip(g.run_names, g.run_files):
            if not os.path.isfile(record):
                m = CELL.fullmatch(name)
                out.append((g, m["method"], int(m["photons"]), int(m["nn"])))
    return out


def duration(seconds):
    """SECONDS as "H h M min" (rounded to the minute)."""
    minutes = int(round(seconds / 60.0))
    return f"{minutes // 60} h {minutes % 60} min"


def line(study, path=None):
    """The dry run's line for STUDY (the cost model at PATH, default
    model_path(study))."""
    path = path or model_path(study)
    try:
        loaded = calibrate.load_model(path)
        per_unit = calibrate.load_work_per_unit(path) if loaded else None
    except calibrate.ModelError as e:
        return f"no cost model: {e}"
    if loaded is None:
        return "no cost model: run make calibrate"
    if not per_unit:
        return f"no cost model: {path} has no work per unit; run make calibrate again"
    model = loaded[0]
    todo = missing(study)
    seconds, unknown = 0.0, 0
    for g, method, photons, nn in todo:
        if gathers(g.pm_args):
            unknown += 1
            continue
        config = {"scene": g.scene, "method": method, "photons": photons, "nn": nn, "width": g.width,
                  "height": g.height, "subpixels": g.subpixels}
        t = calibrate.predict_seconds(model, per_unit, [config], g.repeats(method, nn))[0] * g.processes(method, nn)
        if t != t:  # nan: a method the calibration did not render
            unknown += 1
        else:
            seconds += t
    text = (f"predicted: {len(todo)} render{'' if len(todo) == 1 else 's'} missing, about {duration(seconds)} "
            f"on this machine at the repeats' minima; the wall is longer (repeats above their minimum, processes "
            f"the gauge adds, each process's start) (cost model {path} of {calibrate.model_date(path)})")
    if unknown:
        text += (f"; {unknown} of them not predicted (final gathering or a method the cost model did not "
                 "calibrate), so the time is a lower bound")
    return text
