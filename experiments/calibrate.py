"""Cost model per machine: each phase's time as a non-negative linear
function of the work counters the renderer reports (stats' "work"), fitted
by non-negative least squares on renders timed with --repeats auto (the
minima), and validated on renders it did not fit.

    python3 -m experiments.calibrate --pm build/photonmap --out results/calibrate [--cpu first|N|none]

Every render runs pinned to one CPU (--cpu, default first: the lowest the
process may run on), as the studies' timed renders are (TIME_CPU), so that
the model is of the CPU the studies time on.

writes coefficients.csv (seconds per unit of each counter, per phase),
renders.csv (every render: counters, measured and predicted times, whether
it was fitted or held out), model.json (the coefficients and the validation,
read back by load_model: the analysis's model ratios) and calibrate.md (the
model and its validation: the median and the largest relative error of the
predicted total on the held-out renders; the goal is a median of at most
5%).

The analysis side: model_ratio (the model's paired time ratio of two sets
of renders from their work counters), explain (the phase and the counter
behind a measured ratio the model does not predict) and predict_seconds
(the wall time a list of render configurations will take, for a study's dry
run: each render's counters scaled from the calibration renders' work per
photon and per eye sample, times its repeats).

The fitted and held-out renders differ in their settings (scene, size,
photons, n), so the validation asks what the model is for: the time of a
render it has not seen."""

import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.optimize import nnls

from experiments import launch
from experiments.analysis import report

PHASES = ("trace", "build", "precompute", "render")
# the fitted parts of a render's total: its phases, and the rest of the total
# (allocating and freeing the photon list and map, the image, threads)
PARTS = PHASES + ("other",)
# the counters each part's time is a function of, besides a constant; the
# rest's are the trace's stored photons and the eye pass's rays
FEATURES = {
    "trace": ("traced_photons", "stored_photons", "rays", "shape_tests"),
    "build": ("tree_points",),
    "precompute": ("tree_points", "knn_queries", "map_nodes", "map_points", "rep_evaluations"),
    "render": ("rays", "shape_tests", "knn_queries", "map_nodes", "map_points", "rep_lookups", "rep_nodes",
               "rep_points", "rep_evaluations"),
    "other": ("stored_photons", "rays"),
}
OTHER_FROM = {"stored_photons": "trace", "rays": "render"}


def counter(row, part, name):
    """Counter `name` of `part` in row (the rest's from their phases)."""
    return row["work"][OTHER_FROM[name] if part == "other" else part][name]


def part_time(row, part):
    """The measured seconds of a part: a phase's, or the total less them."""
    if part == "other":
        return max(0.0, row["time"]["total"] - sum(row["time"][p] for p in PHASES))
    return row["time"][part]
GOAL_MEDIAN = 0.05  # the held-out renders' median relative error of the total
DEFAULT_OUT = os.path.join("results", "calibrate")  # make calibrate's --out with RESULTS=results
MODEL_NAME = "model.json"
DEFAULT_MODEL = os.path.join(DEFAULT_OUT, MODEL_NAME)


class ModelError(Exception):
    """A model file that cannot be read, with the reason."""

# (scene, method, photons, nn, width, height): the fitted renders, then the held-out ones
FIT = [(sc, m, p, n, w, h)
       for sc in ("cornell", "caustic")
       for m in ("conventional", "precomputed")
       for p, n, w, h in ((20000, 20, 128, 96), (50000, 50, 256, 192), (100000, 100, 128, 96),
                          (100000, 20, 256, 192))]
HELD_OUT = [(sc, m, p, n, w, h)
            for sc in ("cornell", "caustic")
            for m in ("conventional", "precomputed")
            for p, n, w, h in ((40000, 30, 192, 144), (80000, 70, 160, 120))]


def design(rows, phase):
    """The phase's design matrix: a constant, then its counters, each column
    scaled to a maximum of 1 (returned, to unscale the coefficients)."""
    cols = [np.ones(len(rows))] + [np.array([counter(r, phase, f) for r in rows], float)
                                    for f in FEATURES[phase]]
    x = np.column_stack(cols)
    scale = np.where(x.max(axis=0) > 0, x.max(axis=0), 1.0)
    return x / scale, scale


def fit(rows):
    """Per phase, non-negative coefficients (seconds; seconds per unit) of
    the constant and each counter, least squares on relative errors (each
    row weighted by 1 / its time), so a short render counts as much as a
    long one."""
    model = {}
    for phase in PARTS:
        x, scale = design(rows, phase)
        t = np.array([part_time(r, phase) for r in rows], float)
        wgt = 1.0 / np.maximum(t, 1e-4)
        coef, _ = nnls(x * wgt[:, None], t * wgt)
        model[phase] = coef / scale
    return model


def predict(model, row):
    """Predicted seconds per phase and their total for one render."""
    out = {}
    for phase in PARTS:
        v = np.array([1.0] + [counter(row, phase, f) for f in FEATURES[phase]], float)
        out[phase] = float(v @ model[phase])
    out["total"] = sum(out[p] for p in PARTS)
    return out


def validate(model, rows):
    """Relative errors of the predicted totals on rows: (median, largest)."""
    errs = [abs(predict(model, r)["total"] - r["time"]["total"]) / r["time"]["total"] for r in rows]
    return float(np.median(errs)), float(np.max(errs))


def part_error(model, rows, part):
    """The median relative error of one phase's prediction on rows (those
    where the phase took any time)."""
    errs = [abs(predict(model, r)[part] - r["time"][part]) / r["time"][part] for r in rows if r["time"][part] > 0]
    return float(np.median(errs)) if errs else float("nan")


def write_model(path, model, median, largest, phase_errors, provenance, per_unit=None, written=None):
    """model.json: per part its counters and coefficients (seconds; seconds
    per unit), the held-out validation (median and largest relative error
    of the total, the median per phase), the machine's provenance, the
    calibration renders' work per unit (work_per_unit) and the UTC date it
    is written (WRITTEN, default today: "written"); written to a temporary
    name and renamed."""
    doc = {"parts": {p: {"counters": ["constant", *FEATURES[p]], "seconds_per_unit": [float(c) for c in model[p]]}
                     for p in PARTS},
           "validation": {"median": median, "largest": largest, "phases": phase_errors},
           "provenance": provenance, "work_per_unit": per_unit or {},
           "written": written or time.strftime("%Y-%m-%d", time.gmtime())}
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(path + ".tmp", path)


def load_model(path=DEFAULT_MODEL):
    """(model, validation) of the model file PATH (write_model), or None when
    there is none; ModelError when it is not a model of these counters."""
    if not os.path.isfile(path):
        return None
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
        model = {}
        for p in PARTS:
            part = doc["parts"][p]
            if part["counters"] != ["constant", *FEATURES[p]]:
                raise ModelError(f"{path}: the {p} counters {part['counters']} are not this version's; "
                                 "run `make calibrate` again")
            model[p] = np.array(part["seconds_per_unit"], float)
        validation = {"median": float(doc["validation"]["median"]), "largest": float(doc["validation"]["largest"])}
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise ModelError(f"{path}: not a cost model ({e.__class__.__name__}: {e}); run `make calibrate` again")
    return model, validation


def model_date(path=DEFAULT_MODEL):
    """The UTC date (YYYY-MM-DD) the model file PATH was written: its
    "written" key, else the file's modification date."""
    try:
        with open(path, encoding="utf-8") as f:
            written = json.load(f).get("written")
    except (OSError, ValueError, AttributeError) as e:
        raise ModelError(f"{path}: not a cost model ({e}); run `make calibrate` again")
    return str(written) if written else time.strftime("%Y-%m-%d", time.gmtime(os.path.getmtime(path)))


def load_work_per_unit(path=DEFAULT_MODEL):
    """The work per unit of the model file PATH (work_per_unit), or None
    when there is no model file or it has none."""
    if not os.path.isfile(path):
        return None
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f).get("work_per_unit") or None
    except (OSError, ValueError) as e:
        raise ModelError(f"{path}: not a cost model ({e}); run `make calibrate` again")


def driver(phase, name):
    """What counter NAME of PHASE grows with: the photons emitted ("P"), the
    eye samples ("S"), or either times n for the points a k-nearest search
    examines ("Pn", "Sn")."""
    d = "S" if phase == "render" else "P"
    return d + "n" if name == "map_points" else d


def drivers(photons, nn, samples):
    return {"P": float(photons), "Pn": float(photons) * nn, "S": float(samples), "Sn": float(samples) * nn}


def work_per_unit(rows):
    """{scene: {method: {phase: {counter: count per unit of its driver}}}}:
    the mean over the calibration renders ROWS of each counter divided by
    what it grows with (driver)."""
    acc = {}
    for r in rows:
        d = drivers(r["photons"], r["nn"], r["samples"])
        for ph in PHASES:
            for name, v in r["work"][ph].items():
                acc.setdefault(r["scene"], {}).setdefault(r["method"], {}).setdefault(ph, {}).setdefault(
                    name, []).append(v / d[driver(ph, name)])
    return {sc: {m: {ph: {n: float(np.mean(v)) for n, v in c.items()} for ph, c in ph_.items()}
                 for m, ph_ in ms.items()} for sc, ms in acc.items()}


def auto_repeats_rule(config_h=os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                            "renderer", "config.h")):
    """(minimum, maximum, budget seconds) of the renderer's --repeats auto,
    read from renderer/config.h (the one place they are set)."""
    with open(config_h, encoding="utf-8") as f:
        text = f.read()
    get = lambda name: re.search(r"#define\s+" + name + r"\s+([0-9.]+)", text).group(1)  # noqa: E731
    return int(get("CONFIG_REPEATS_AUTO_MIN")), int(get("CONFIG_REPEATS_AUTO_MAX")), float(get("CONFIG_REPEATS_AUTO_BUDGET_S"))


def repeats_of(repeats, seconds, rule):
    """How many times a render of SECONDS is run under --repeats REPEATS
    ("auto": at least rule's minimum, then until the repeats add up to its
    budget, at most its maximum)."""
    if str(repeats) != "auto":
        return int(repeats)
    lo, hi, budget = rule
    return min(hi, max(lo, math.ceil(budget / seconds) if seconds > 0 else hi))


def predict_seconds(model, per_unit, configs, repeats="auto", rule=None):
    """The predicted wall seconds of each render configuration in CONFIGS
    (dicts: scene (a path or a name), method, photons, nn, width, height,
    subpixels), as a list: the model's total of the counters a render of
    that configuration does (the calibration renders' work per unit of the
    same scene and method, times its photons, eye samples and n; a scene
    not calibrated: the mean over the calibrated scenes), times its repeats
    (REPEATS: a count or "auto", the renderer's rule). nan for a method the
    calibration did not render."""
    rule = rule or auto_repeats_rule()
    out = []
    for c in configs:
        scene = os.path.splitext(os.path.basename(str(c["scene"])))[0]
        known = [per_unit[s][c["method"]] for s in (per_unit if scene not in per_unit else [scene])
                 if c["method"] in per_unit[s]]
        if not known:
            out.append(math.nan)
            continue
        d = drivers(c["photons"], c["nn"], c["width"] * c["height"] * c["subpixels"] ** 2)
        work = {ph: {n: float(np.mean([k[ph][n] for k in known])) * d[driver(ph, n)] for n in known[0][ph]}
                for ph in PHASES}
        t = predict(model, {"work": work})["total"]
        out.append(t * repeats_of(repeats, t, rule))
    return out


def model_ratio(model, works_a, works_b):
    """The model's paired time ratio A / B: exp of the mean over pairs of the
    log of the predicted totals' ratio, the work counters (stats' "work") of
    A[s] and B[s] one pair each; nan with no pair."""
    logs = [math.log(predict(model, {"work": a})["total"] / predict(model, {"work": b})["total"])
            for a, b in zip(works_a, works_b)]
    return math.exp(sum(logs) / len(logs)) if logs else math.nan


def explain(model, rows_a, rows_b):
    """(phase, counter) behind the difference between the measured and the
    model's paired ratio of the renders ROWS_A against ROWS_B (pairs; each
    row {"work": ..., "time": {phase: seconds, "total": ...}}): the phase
    whose measured times, put in the place of its predicted ones in both
    renders of every pair, bring the model's ratio closest to the measured
    one; the counter, of that phase's counters, with the largest predicted
    seconds (coefficient x count, mean over the pairs) in the set where the
    phase's measured time is furthest from its prediction."""
    def ratio(rows_x, rows_y, swap=None):
        logs = []
        for x, y in zip(rows_x, rows_y):
            tot = []
            for r in (x, y):
                q = predict(model, r)
                tot.append(q["total"] - q[swap] + part_time(r, swap) if swap else r["time"]["total"])
            logs.append(math.log(tot[0] / tot[1]))
        return sum(logs) / len(logs)
    measured = ratio(rows_a, rows_b)
    phase = min(PARTS, key=lambda p: abs(ratio(rows_a, rows_b, p) - measured))
    off = [abs(np.mean([part_time(r, phase) - predict(model, r)[phase] for r in rows])) for rows in (rows_a, rows_b)]
    rows = rows_a if off[0] >= off[1] else rows_b
    share = {f: np.mean([c * counter(r, phase, f) for r in rows])
             for f, c in zip(FEATURES[phase], model[phase][1:])}
    name = max(share, key=share.get)
    return phase, name if share[name] > 0 else "constant"


def render(pm, scene, method, photons, nn, width, height, tmp, cpu=None):
    """One render with --repeats auto, pinned to CPU (None: unpinned): its
    counters and its times' minima."""
    stats = os.path.join(tmp, "s.json")
    subprocess.run([pm, "render", os.path.join("scenes", scene + ".scene"), "--method", method, "--photons",
                    str(photons), "--nn", str(nn), "--width", str(width), "--height", str(height), "--threads", "1",
                    "--repeats", "auto", "--quiet", "--stats", stats], check=True, preexec_fn=launch.pinned(cpu))
    with open(stats) as f:
        s = json.load(f)
    return {"scene": scene, "method": method, "photons": photons, "nn": nn, "width": width, "height": height,
            "samples": s["samples"], "work": s["work"], "time": s["time_s"], "repeats": s["repeats"],
            "provenance": s["provenance"]}


def write(out, model, fitted, held, median, largest, cpu=None):
    """OUT's coefficients.csv, renders.csv, model.json and calibrate.md, each
    through a temporary name and a rename; calibrate.md names the commit of
    the analysis (report.commit) beside the renderer's binary, and the CPU
    the renders were pinned to (None: unpinned)."""
    coef = ["phase,counter,seconds_per_unit"]
    for phase in PARTS:
        for name, c in zip(("constant",) + FEATURES[phase], model[phase]):
            coef.append("%s,%s,%.6g" % (phase, name, c))
    report.write_atomic(os.path.join(out, "coefficients.csv"), "\n".join(coef) + "\n")
    rend = ["set,scene,method,photons,nn,width,height,repeats,measured_total,predicted_total,rel_error,"
            + ",".join("measured_%s,predicted_%s" % (p, p) for p in PHASES)]
    for name, rows in (("fit", fitted), ("held_out", held)):
        for r in rows:
            p = predict(model, r)
            rend.append("%s,%s,%s,%d,%d,%d,%d,%d,%.6f,%.6f,%.4f,%s" % (
                name, r["scene"], r["method"], r["photons"], r["nn"], r["width"], r["height"], r["repeats"],
                r["time"]["total"], p["total"], (p["total"] - r["time"]["total"]) / r["time"]["total"],
                ",".join("%.6f,%.6f" % (r["time"][ph], p[ph]) for ph in PHASES)))
    report.write_atomic(os.path.join(out, "renders.csv"), "\n".join(rend) + "\n")
    write_model(os.path.join(out, MODEL_NAME), model, median, largest,
                {p: part_error(model, held, p) for p in PHASES}, fitted[0]["provenance"], work_per_unit(fitted + held))
    prov = fitted[0]["provenance"]
    md = ["# Cost model of this machine\n",
          "Generated by `make calibrate` (experiments/calibrate.py) on %s, commit %s. Each phase's time (the minimum "
          "over `--repeats auto`, one thread, %s) as a non-negative linear "
          "function of its work counters (`other`: the total less the phases, on the stored photons and the eye "
          "rays), fitted on %d renders, validated on %d renders of other "
          "settings (`renders.csv`). Machine: %s; binary %s (%s), %s `%s`.\n" % (
              report.today(), report.commit(), "unpinned" if cpu is None else "every render pinned to CPU %d" % cpu,
              len(fitted), len(held), prov["cpu"], prov["commit"], prov["tree"],
              prov["compiler"], prov["flags"]),
          "**Held-out renders: median relative error of the total %.1f%%, largest %.1f%%** (goal: median "
          "at most %.0f%%: %s).\n" % (100 * median, 100 * largest, 100 * GOAL_MEDIAN,
                                       "met" if median <= GOAL_MEDIAN else "not met")]
    loads = [r["provenance"]["loadavg"][0] for r in fitted + held if r["provenance"]["loadavg"][0] is not None]
    if loads:
        md.append("The 1-minute load average when the renders started: %.1f to %.1f on %s; the times are minima "
                  "of repeats, and a machine shared more than its cores moves them nonetheless.\n" % (
                      min(loads), max(loads), prov["cpu"]))
    md.append("| held-out median relative error | %s |\n|---|%s\n| | %s |\n" % (
        " | ".join(PHASES), "---:|" * len(PHASES),
        " | ".join("%.1f%%" % (100 * part_error(model, held, p)) for p in PHASES)))
    table = ["| phase | counter | ns per unit |", "|---|---|---:|"]
    for phase in PARTS:
        for name, c in zip(("constant",) + FEATURES[phase], model[phase]):
            if c > 0:
                table.append("| %s | %s | %.4g |" % (phase, name, c * 1e9))
    md.append("\n".join(table) + "\n")
    md.append("Counters with a zero coefficient explain nothing the others do not (`coefficients.csv` "
              "lists them all).\n")
    report.write_atomic(os.path.join(out, "calibrate.md"), "\n".join(md))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pm", default="build/photonmap")
    ap.add_argument("--out", default=DEFAULT_OUT)
    ap.add_argument("--cpu", default="first",
                    help="the CPU every render is pinned to, as the studies' timed renders are (TIME_CPU): "
                         "first, a number, or none")
    a = ap.parse_args(argv)
    try:
        cpu = launch.resolve_cpu(a.cpu)
    except launch.LaunchError as e:
        ap.error(str(e))
    with tempfile.TemporaryDirectory() as tmp:
        fitted = [render(a.pm, *c, tmp, cpu) for c in FIT]
        held = [render(a.pm, *c, tmp, cpu) for c in HELD_OUT]
    model = fit(fitted)
    median, largest = validate(model, held)
    write(a.out, model, fitted, held, median, largest, cpu)
    print("calibrate: held-out median error %.1f%%, largest %.1f%% -> %s" % (100 * median, 100 * largest, a.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
