#!/usr/bin/python3
"""evaluate.py: the stages of `make evaluate` (experiments/rules/evaluate.smk) that
are not renders of the grid: does the method pay on one scene?

Owns the pilot's verdict on whether a study of the scene means anything,
the rectangle thickness of the scene's POV-Ray export, the cross-check of
the converged reference against POV-Ray, and the report (OUT/report.md and
its images). Commands (each prints one progress line; exit 2 with a
message when the study is meaningless or an input is wrong, 1 on a failure):

  pilot --pm PM --scene S --size WxH --photons P --nn N --out DIR
      one render at the grid's middle setting; DIR/pilot.json holds the
      stats, the warnings and the verdict (ok, warn, stop: exit 2)
  thickness [--pm PM] --scene S --out FILE.json
      the largest of 1e-3 ... 1e-7 (of the scene's diagonal, the committed
      references' ladder, reference/README.md) at which no rectangle's box
      (behind its lit face) enters another shape; exit 2, naming the two
      shapes' lines, when none does (a shape crosses a rectangle)
  crosscheck --ref OURS.exr --pov-ref POV.exr --pov-fast POVF.exr [--b2-ours X --b2-pov Y] --out FILE.json
      block metric and channel means (reference/README.md's) of our
      converged reference against POV-Ray, and the 2-bounce comparison
  report ... [--gather-csv GATHER.csv] --out DIR: DIR/report.md and DIR/*.png;
      with GATHER.csv (analysis/gather.py over the final-gathering grids,
      the main grid as the map seen directly) the verdict gains final
      gathering's (gather_verdict) and the report its section
"""

import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

from experiments.analysis import equal_error
from experiments.analysis import metrics
from experiments.analysis import reference as refmod
from experiments.analysis import scene_info

# the pilot's limits: share of photons escaping (the renderer warns above
# 1%: config.h), eye samples ending at the depth limit (warns above 10%),
# empty estimates; above STOP the study is meaningless
ESCAPED_STOP = 0.01
DEPTH_WARN, DEPTH_STOP = 0.1, 0.5
EMPTY_WARN, EMPTY_STOP = 0.01, 0.1
# the POV-Ray check (reference/README.md, "Comparing images"): p99 of the
# block error over blocks of BLOCK_PX pixels, and the channel means
BLOCK_THRESHOLD = 0.15
MEAN_TOL = 0.05
BLOCK_PX = 8
# the exporter's rectangle thickness ladder (fractions of the diagonal)
THICKNESS_LADDER = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
# a shape within this fraction of the diagonal of a rectangle's edge meets
# it there (walls at a corner; a generated box's faces rounded to 6 digits)
EDGE_TOL = 1e-5


def die(msg, code=2):
    """Print MSG as the stage's refusal and exit with CODE."""
    print(f"evaluate: {msg}", file=sys.stderr)
    sys.exit(code)


def write_json(path, obj):
    """OBJ as JSON at PATH (temp name, then renamed)."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path + ".tmp", "w") as fh:
        json.dump(obj, fh, indent=2)
        fh.write("\n")
    os.replace(path + ".tmp", path)


# ---- stage 1: the pilot
def pilot_verdict(st, stderr):
    """(verdict, [messages]) of a pilot's stats ST and stderr text: 'stop'
    where the study is meaningless, 'warn', or 'ok'."""
    stop, warn = [], []
    if st.get("status") != "ok":
        stop.append(f"the renderer refused the render: {st.get('reason') or st.get('status')}")
    emitted = max(int(st.get("photons_emitted", 0)), 1)
    esc = int(st.get("photons_escaped", 0)) / emitted
    if esc > ESCAPED_STOP:
        stop.append(f"{esc:.1%} of the photons escape the scene (above {ESCAPED_STOP:.0%}): it is open, or the "
                    "light is outside it; a photon map of an open scene wastes its photons and the study would "
                    "measure the leak. Close the scene (six walls) and run again")
    samples = max(int(st.get("samples", 0)), 1)
    depth = int(st.get("eye_depth_limit_hits", 0)) / samples
    if depth > DEPTH_STOP:
        stop.append(f"{depth:.0%} of the eye samples end at the eye-depth limit (black): the camera sits between "
                    "mirrors; raise --eye-depth or move the camera")
    elif depth > DEPTH_WARN:
        warn.append(f"{depth:.0%} of the eye samples end at the eye-depth limit (black)")
    empty = int(st.get("empty_estimates", 0)) / samples
    if empty > EMPTY_STOP:
        stop.append(f"{empty:.0%} of the eye samples found no photon (empty estimates): the visible surfaces "
                    "get (almost) no light")
    elif empty > EMPTY_WARN:
        warn.append(f"{empty:.1%} of the eye samples found no photon (empty estimates)")
    if any(s in stderr for s in ("is inside the opaque sphere",)):
        stop.append("the camera or the light is shut inside an opaque sphere (the renderer's warning: "
                    + next(l for l in stderr.splitlines() if "opaque sphere" in l).split("warning: ", 1)[-1] + ")")
    mean = st.get("mean_radiance") or [0, 0, 0]
    if not stop and max(mean) <= 0:
        stop.append("the image is black")
    for line in stderr.splitlines():
        if "warning:" in line and "opaque sphere" not in line and "photons" not in line and "eye-depth" not in line:
            warn.append(line.split("warning: ", 1)[-1])
    return ("stop" if stop else "warn" if warn else "ok"), stop + warn


def cmd_pilot(a):
    """Stage 1 (module docstring)."""
    os.makedirs(a.out, exist_ok=True)
    w, h = (int(v) for v in a.size.split("x"))
    base = os.path.join(a.out, "pilot")
    cmd = [a.pm, "render", a.scene, "--photons", str(a.photons), "--nn", str(a.nn), "--width", str(w),
           "--height", str(h), "--threads", "0", "-o", base + ".exr", "--png", base + ".png",
           "--stats", base + ".stats.json", "--quiet"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode == 2 and not os.path.exists(base + ".stats.json"):
        die(f"the scene does not render: {r.stderr.strip()}")
    if r.returncode not in (0, 2):
        die(f"the pilot render failed (exit {r.returncode}): {r.stderr.strip()}", 1)
    with open(base + ".stats.json") as fh:
        st = json.load(fh)
    verdict, msgs = pilot_verdict(st, r.stderr)
    out = {"verdict": verdict, "messages": msgs, "command": " ".join(cmd), "stats": st, "stderr": r.stderr}
    if verdict == "stop":
        write_json(base + ".refused.json", out)
        die(f"{a.scene}: the study would be meaningless: " + "; ".join(msgs) + f" (details: {base}.refused.json)")
    write_json(base + ".json", out)
    print(f"evaluate: [1/5] pilot: {verdict}" + (": " + "; ".join(msgs) if msgs else
                                                 f" (photons escaped {st['photons_escaped']}, "
                                                 f"depth-limit hits {st['eye_depth_limit_hits']}, "
                                                 f"empty estimates {st['empty_estimates']})"))


# ---- stage 2: the rectangle thickness of the POV-Ray export
def read_scene(a):
    """(light position, [shapes], diagonal) of the scene as the renderer reads
    it (`photonmap info --json`, scene_info.py): each shape a dict with its
    kind, line and geometry (corner, e1, e2 or center, radius)."""
    try:
        info = scene_info.load(a.scene, a.pm)
    except scene_info.SceneInfoError as e:
        die(f"{a.scene}: {e}")
    shapes = []
    for s in scene_info.shapes(info):
        if s["kind"] == "rect":
            shapes.append({"kind": "rect", "line": s["line"], "corner": s["corner"], "e1": s["edge1"],
                           "e2": s["edge2"]})
        else:
            shapes.append({"kind": "sphere", "line": s["line"], "center": s["center"], "radius": s["radius"]})
    return scene_info.light_position(info), shapes, float(info["bounds"]["diagonal"])


def clip(poly, n, d):
    """The convex polygon POLY (list of points) clipped to n . x <= d."""
    out = []
    for i in range(len(poly)):
        p, q = poly[i], poly[(i + 1) % len(poly)]
        fp, fq = n @ p - d, n @ q - d
        if fp <= 0:
            out.append(p)
        if (fp < 0 < fq) or (fq < 0 < fp):
            out.append(p + (q - p) * (fp / (fp - fq)))
    return out


def box_hits(a, b, depth, eps, edge):
    """True when shape B enters the open box of rectangle A: A's footprint
    shrunk by EDGE (a shape that only meets A's edge, as walls meet at a
    corner, or a box's faces rounded in the file, does not count) from
    EPS to DEPTH behind its lit face."""
    u, v = a["e1"], a["e2"]
    lu, lv = np.linalg.norm(u), np.linalg.norm(v)
    uh, vh = u / lu, v / lv
    nrm = np.cross(uh, vh)
    back = -nrm if nrm @ (a["light"] - a["corner"]) > 0 else nrm  # the box's side
    c = a["corner"]
    if b["kind"] == "rect":
        poly = [b["corner"], b["corner"] + b["e1"], b["corner"] + b["e1"] + b["e2"], b["corner"] + b["e2"]]
        for n_, d_ in ((-uh, -(uh @ c) - edge), (uh, uh @ c + lu - edge), (-vh, -(vh @ c) - edge),
                       (vh, vh @ c + lv - edge)):
            poly = clip(poly, n_, d_)
            if not poly:
                return False
        s = [back @ (p - c) for p in poly]
        return max(s) > eps and min(s) < depth - eps
    # sphere: the distance from its centre to the box
    q = b["center"] - c
    lo = np.array([edge, edge, eps])
    coords = np.array([q @ uh, q @ vh, q @ back])
    hi = np.array([lu - edge, lv - edge, depth - eps])
    if hi[2] <= lo[2]:
        return False
    dist = np.linalg.norm(coords - np.clip(coords, lo, hi))
    return dist < b["radius"] - eps


def choose_thickness(light, shapes, diag):
    """(thickness, None) the largest of THICKNESS_LADDER at which no box
    enters another shape of a scene of diagonal DIAG, or (None, reason)."""
    eps = 1e-9 * diag
    edge = EDGE_TOL * diag
    rects = [dict(s, light=light) for s in shapes if s["kind"] == "rect"]
    worst = None
    for t in THICKNESS_LADDER:
        clash = None
        for a in rects:
            for b in shapes:
                if b is a or b["line"] == a["line"]:
                    continue
                if box_hits(a, b, t * diag, eps, edge):
                    clash = (a["line"], b["line"])
                    break
            if clash:
                break
        if clash is None:
            return t, None
        worst = clash
    return None, (f"the rectangle of line {worst[0]} and the shape of line {worst[1]} cross: POV-Ray needs "
                  f"rectangles as boxes behind their lit face, and even {THICKNESS_LADDER[-1]:g} of the "
                  "diagonal enters that shape, so no POV-Ray reference of this scene is comparable")


def cmd_thickness(a):
    """Stage 2's thickness (module docstring)."""
    t, why = choose_thickness(*read_scene(a))
    if t is None:
        write_json(a.out + ".refused.json", {"reason": why})
        die(f"{a.scene}: no POV-Ray reference: {why}")
    write_json(a.out, {"rect_thickness": t, "rule": "the largest of " + ", ".join(f"{x:g}" for x in THICKNESS_LADDER)
                       + " (fractions of the scene's diagonal) at which no rectangle's box, behind its lit face, "
                       "enters another shape"})
    print(f"{t:g}")


# ---- stage 3: cross-check
def block_compare(t, r, block=BLOCK_PX):
    """reference/README.md's block metric: both box-downsampled to blocks of
    BLOCK pixels, e = |t - r| / (r + 0.01 mean(r)) per block and channel;
    returns (p99, per-block max error array (bh, bw), channel means t/r)."""
    h, w = r.shape[:2]
    bh, bw = max(1, h // block), max(1, w // block)
    def down(x):
        """The image X (h x w x 3) box-averaged into bh x bw blocks, the rows and columns that fill no
        whole block dropped."""
        x = x[:bh * (h // bh), :bw * (w // bw)]
        return x.reshape(bh, h // bh, bw, w // bw, 3).mean(axis=(1, 3))
    tb, rb = down(t), down(r)
    e = np.abs(tb - rb) / (rb + 0.01 * rb.mean())
    means = t.reshape(-1, 3).mean(axis=0) / np.maximum(r.reshape(-1, 3).mean(axis=0), 1e-30)
    return float(np.percentile(e, 99)), e.max(axis=2), [float(m) for m in means]


def where(e, thr):
    """Where in the image the blocks of E beyond THR lie, in words."""
    bad = np.argwhere(e > thr)
    if len(bad) == 0:
        return "nowhere"
    bh, bw = e.shape
    names_y = ("top", "middle", "bottom")
    names_x = ("left", "centre", "right")
    cells = {}
    for y, x in bad:
        k = (names_y[min(2, 3 * y // bh)], names_x[min(2, 3 * x // bw)])
        cells[k] = cells.get(k, 0) + 1
    top = sorted(cells.items(), key=lambda kv: -kv[1])[:3]
    return ", ".join(f"{y} {x} ({n} blocks)" for (y, x), n in top)


def compare(test, ref):
    """The cross-check numbers of TEST against REF (paths)."""
    t, r = metrics.read_exr(test), metrics.read_exr(ref)
    p99, e, means = block_compare(t, r)
    ok = p99 <= BLOCK_THRESHOLD and all(abs(m - 1) <= MEAN_TOL for m in means)
    return {"test": test, "ref": ref, "p99": p99, "means": means, "ok": bool(ok),
            "bad_share": float((e > BLOCK_THRESHOLD).mean()), "where": where(e, BLOCK_THRESHOLD)}


def cmd_crosscheck(a):
    """Stage 3's comparison (module docstring)."""
    out = {"full": compare(a.ref, a.pov_ref), "pov_floor": compare(a.pov_fast, a.pov_ref),
           "block_px": BLOCK_PX, "threshold": BLOCK_THRESHOLD, "mean_tol": MEAN_TOL}
    if a.b2_ours and a.b2_pov:
        out["b2"] = compare(a.b2_ours, a.b2_pov)
    f = out["full"]
    if f["ok"]:
        out["agree"] = "full"
        out["sentence"] = (f"POV-Ray (reference preset) and the converged reference agree at full bounces (p99 block "
                           f"error {f['p99']:.3f} <= {BLOCK_THRESHOLD}, channel means ours/POV-Ray "
                           f"{' '.join(f'{m:.3f}' for m in f['means'])}): the study uses the converged reference, "
                           "whose own error is measured (below), and POV-Ray confirms it.")
    elif "b2" in out and out["b2"]["ok"]:
        b = out["b2"]
        out["agree"] = "b2"
        out["sentence"] = (f"POV-Ray and the converged reference disagree at full bounces (p99 block error "
                           f"{f['p99']:.3f}, means {' '.join(f'{m:.3f}' for m in f['means'])}; mostly {f['where']}) "
                           f"but agree at 2 indirect bounces (export-pov --bounces 2 against --photon-depth 3: p99 "
                           f"{b['p99']:.3f}, means {' '.join(f'{m:.3f}' for m in b['means'])}): the difference lies in "
                           "the high-order bounces, which POV-Ray's irradiance cache does not follow (on an L-shaped "
                           "room its full radiosity was 31% too bright on an indirectly lit wall per an unbiased path "
                           "tracer, while its 2-bounce render agreed within 2-3%). The study uses the converged "
                           "reference.")
    else:
        out["agree"] = "none"
        b = out.get("b2")
        out["sentence"] = (f"POV-Ray and the converged reference DISAGREE at full bounces (p99 block error "
                           f"{f['p99']:.3f} > {BLOCK_THRESHOLD} or means {' '.join(f'{m:.3f}' for m in f['means'])} "
                           f"beyond 1 +- {MEAN_TOL}; mostly {f['where']})"
                           + (f" and at 2 bounces too (p99 {b['p99']:.3f}, means "
                              f"{' '.join(f'{m:.3f}' for m in b['means'])}; mostly {b['where']})" if b else "")
                           + ": the export or one of the renderers is wrong for this scene. The study still uses "
                           "the converged reference (method-neutral, its error measured), but its errors are "
                           "only as good as that reference; check the scene's materials and the export.")
    write_json(a.out, out)
    print(f"evaluate: [3/5] references: {out['agree']}: {out['sentence']}")


# ---- stage 5: the report
def srgb_png(img, path, exposure=1.0):
    """IMG as an sRGB PNG at PATH."""
    refmod.write_png(img * exposure, path)


def diff_png(a, b, path):
    """A signed difference map (a - b) / (b + 0.01 mean): red where A is
    brighter, blue where darker, full colour at +-50%; returns the scale."""
    lum = lambda x: x @ np.array([0.2126, 0.7152, 0.0722])
    la, lb = lum(a), lum(b)
    d = (la - lb) / (lb + 0.01 * lb.mean())
    s = np.clip(d / 0.5, -1, 1)
    img = np.ones(a.shape)
    img[..., 1] = 1 - np.abs(s)
    img[..., 0] = np.where(s < 0, 1 + s, 1)
    img[..., 2] = np.where(s > 0, 1 - s, 1)
    import OpenImageIO as oiio
    q = np.round(img * 255).astype(np.uint8)
    buf = oiio.ImageBuf(oiio.ImageSpec(a.shape[1], a.shape[0], 3, oiio.UINT8))
    buf.set_pixels(oiio.ROI(0, a.shape[1], 0, a.shape[0]), q)
    if not buf.write(path + ".tmp.png"):
        print(f"{path}: cannot write: {buf.geterror()}", file=sys.stderr)
        sys.exit(1)
    os.replace(path + ".tmp.png", path)


def fnum(x, nd=3):
    """X with ND significant digits, or n/a."""
    return "n/a" if x is None or not isinstance(x, (int, float)) or not math.isfinite(x) else f"{x:.{nd}g}"


def verdict_of(ee, estimate):
    """One sentence from the equal-error rows EE (a DataFrame) of ESTIMATE."""
    allc = ee[(ee["estimate"] == estimate) & (ee["kind"] == "curve")].sort_values("target")
    t = ee[(ee["estimate"] == estimate) & (ee["kind"] == "tightest")]
    if allc.empty:
        return f"{estimate} estimate: undetermined: the two methods' fronts share no relMSE range at this grid."
    # only targets that enough resamples reach on both fronts are worded (equal_error.DEFINED_MIN)
    c = allc[allc["defined_fraction"] >= equal_error.DEFINED_MIN]
    pays = c[c["lo"] > 1]
    loses = c[c["hi"] < 1]
    und = c[~((c["lo"] > 1) | (c["hi"] < 1))]
    parts = []
    h = equal_error.headline([r for _, r in allc.iterrows()])
    if h is None:
        parts.append(f"at the tightest target both reach and every other, fewer than "
                     f"{100 * equal_error.DEFINED_MIN:.0f}% of the resamples reach both fronts: no speed-up is worded")
    else:
        kind = "pays" if h["lo"] > 1 else "costs" if h["hi"] < 1 else "is undetermined"
        parts.append(f"at the tightest target {100 * equal_error.DEFINED_MIN:.0f}% of the resamples reach on both "
                     f"fronts (relMSE {fnum(h['target'], 2)}) the method {kind}: "
                     f"{fnum(h['speedup'], 2)}x [{fnum(h['lo'], 2)}, {fnum(h['hi'], 2)}]")
    if not t.empty:
        parts.append(f"the curve starts at relMSE {fnum(t.iloc[0]['target'], 2)}, the tightest target both reach")
    if not pays.empty:
        best = pays.loc[pays["lo"].idxmax()]
        parts.append(f"pays by {fnum(best['speedup'], 2)}x [{fnum(best['lo'], 2)}, {fnum(best['hi'], 2)}] at relMSE "
                     f"{fnum(best['target'], 2)}; the band lies above 1 for targets "
                     f"{fnum(pays['target'].min(), 2)}-{fnum(pays['target'].max(), 2)}")
    parts += band_tail(loses, und, "for targets")
    return f"{estimate} estimate: " + "; ".join(parts) + "."


def band_tail(loses, und, where):
    """The phrases of the targets whose band lies below 1 (LOSES) and
    contains 1 (UND), each 'WHERE lo-hi' (rows of an equal-error frame)."""
    out = []
    for rows, what in ((loses, "is slower (band below 1)"), (und, "undetermined (band contains 1)")):
        if not rows.empty:
            out.append(f"{what} {where} {fnum(rows['target'].min(), 2)}-{fnum(rows['target'].max(), 2)}")
    return out


def gather_verdict(g):
    """(sentence, section lines) of final gathering from the rows G (a
    DataFrame of analysis/gather.py's CSV): the equal-error speed-up of the
    precomputed method over the conventional one under final gathering at
    the targets enough resamples reach (gather.DEFINED_MIN), the gather
    phase's own speed-up, and the cheapest configuration per relMSE target
    over every mode (median time over seeds: the cheapest, not a ranking
    by intervals)."""
    from experiments.analysis import gather as gathermod
    ee = g[g["kind"] == "equal_error"].sort_values("target")
    counted = ee[ee["defined"] >= gathermod.DEFINED_MIN]
    if ee.empty:
        parts = ["the two methods' fronts share no relMSE range: no equal-error speed-up"]
    elif counted.empty:
        parts = [f"at no target do {100 * gathermod.DEFINED_MIN:.0f}% of the resamples reach both fronts: "
                 "no speed-up is worded"]
    else:
        pays, loses = counted[counted["lo"] > 1], counted[counted["hi"] < 1]
        und = counted[~((counted["lo"] > 1) | (counted["hi"] < 1))]
        parts = []
        if not pays.empty:
            parts.append(f"the precomputed method pays (band above 1) at relMSE {fnum(pays['target'].min(), 2)}-"
                         f"{fnum(pays['target'].max(), 2)}, by {fnum(pays['speedup'].min(), 2)}-"
                         f"{fnum(pays['speedup'].max(), 2)}x")
        parts += band_tail(loses, und, "at relMSE")
    ph = g[g["kind"] == "gather_phase"]
    if len(ph) and math.isfinite(ph.iloc[0]["speedup"]):
        r = ph.iloc[0]
        parts.append(f"the gather phase alone {fnum(r['speedup'], 2)}x [{fnum(r['lo'], 2)}, {fnum(r['hi'], 2)}]")
    best = g[g["kind"] == "best"].sort_values("target", ascending=False)
    def tie_text(r):
        """', not told apart from K other cells' of a best row R with K ties; '' without ties (or without
        the ties column)."""
        k = int(r["ties"]) if "ties" in r and math.isfinite(float(r["ties"])) else 0
        return f", not told apart from {k} other cell{'s' if k > 1 else ''}" if k else ""
    picks = [f"{fnum(r['target'], 2)}: {r['mode']} {r['setting']} ({fnum(r['conventional_s'])} s{tie_text(r)})"
             if isinstance(r["mode"], str) and r["mode"] else f"{fnum(r['target'], 2)}: none reaches it"
             for _, r in best.iterrows()]
    sentence = "Final gathering (--gather N, conventional time / precomputed time at equal relMSE): " + "; ".join(parts) + "."
    if picks:
        sentence += (" The cheapest configuration per relMSE target over every mode (median time over seeds): "
                     + "; ".join(picks) + ".")
    lines = ["## Final gathering", "",
             "Both methods with `--gather N --direct shadow-rays` (the gather grid: `gather/gather.md`, "
             "`gather/gather.csv`, `gather/gather.png`), against the same converged reference as the map seen "
             "directly.", ""]
    if len(ee):
        lines += ["| relMSE target | conventional s | precomputed s | speed-up | 95% band | resamples defined |",
                  "|---|---|---|---|---|---|"]
        lines += [f"| {fnum(r['target'])} | {fnum(r['conventional_s'])} | {fnum(r['precomputed_s'])} | "
                  f"{fnum(r['speedup'])} | [{fnum(r['lo'])}, {fnum(r['hi'])}] | {fnum(r['defined'], 2)}"
                  + ("" if r["defined"] >= gathermod.DEFINED_MIN else " (not counted)") + " |"
                  for _, r in ee.iterrows()] + [""]
    if len(best):
        lines += ["Which configuration to pick: the cheapest cell (median time over seeds) reaching each relMSE "
                  "target over every mode, final gathering and the map seen directly (not a ranking: cells whose "
                  "times overlap are not told apart).", "",
                  "| relMSE target | mode | setting | time s |", "|---|---|---|---|"]
        lines += [f"| {fnum(r['target'])} | {r['mode'] if isinstance(r['mode'], str) and r['mode'] else 'none reaches it'}"
                  f" | {r['setting'] if isinstance(r['setting'], str) else ''} | {fnum(r['conventional_s'])} |"
                  for _, r in best.iterrows()] + [""]
    return sentence, lines


def cmd_report(a):
    """Stage 5 (module docstring)."""
    import pandas as pd

    os.makedirs(a.out, exist_ok=True)
    with open(a.pilot) as fh:
        pilot = json.load(fh)
    with open(a.crosscheck) as fh:
        cc = json.load(fh)
    with open(a.thickness) as fh:
        thick = json.load(fh)
    info = refmod.load(a.ref)
    runs = pd.read_csv(a.runs_csv)
    ee = pd.read_csv(a.equal_error_csv)
    # the tightest target the reference judges: the smallest target of any curve
    tightest = refmod.tightest_of(a.equal_error_csv)
    ok, why = refmod.check(info, tightest)
    # images: both methods at the grid's largest P_e and n, corrected estimate, seed 1
    ok_runs = runs[(runs["status"] == "ok")]
    cell = ok_runs[(ok_runs["photons"] == ok_runs["photons"].max())]
    cell = cell[cell["nn"] == cell["nn"].max()]
    imgs = {}
    est = "corrected" if (cell["estimate"] == "corrected").any() else cell["estimate"].iloc[0]
    for m in ("conventional", "precomputed"):
        r = cell[(cell["method"] == m) & (cell["estimate"] == est)].sort_values("seed")
        if len(r):
            row = r.iloc[0]
            path = os.path.join(a.runroot, f"{m}-{est}-p{int(row['photons'])}-n{int(row['nn'])}", f"seed{int(row['seed'])}.exr")
            imgs[m] = (metrics.read_exr(path), row)
    ref_img = metrics.read_exr(a.ref)
    lines = [f"# Does the precomputed method pay on `{a.scene}`?", ""]
    verdicts = [verdict_of(ee, e) for e in a.estimates.split()]
    gather_sentence, gather_lines = gather_verdict(pd.read_csv(a.gather_csv)) if a.gather_csv else ("", [])
    agree = {"full": "the references (ours and POV-Ray) agree at full bounces",
             "b2": "the references agree at 2 bounces but not at full bounces (POV-Ray's high-order bounces)",
             "none": "the references DISAGREE (POV-Ray against ours): see References"}[cc["agree"]]
    lines += ["## Verdict", "", "Equal-error speed-up (conventional time / precomputed time at the same relMSE "
              f"against the converged reference, {a.time}, 95% bootstrap band): " + " ".join(verdicts)
              + f" Of the references: {agree}: p99 block error {cc['full']['p99']:.3f}, channel means "
              + " ".join(f"{m:.3f}" for m in cc["full"]["means"])
              + ("" if cc["agree"] == "full" else f", except on {cc['full']['where']}")
              + (f"; at 2 bounces p99 {cc['b2']['p99']:.3f}, means " + " ".join(f"{m:.3f}" for m in cc["b2"]["means"])
                 if "b2" in cc else "") + ".", ""]
    if gather_sentence:
        lines += [gather_sentence, ""]
    lines += ["## Pilot", "", f"`{pilot['command']}`: {pilot['verdict']}."]
    st = pilot["stats"]
    lines += [f"Photons escaped {st['photons_escaped']} of {st['photons_emitted']}, eye samples at the depth limit "
              f"{st['eye_depth_limit_hits']} of {st['samples']}, empty estimates {st['empty_estimates']}."]
    lines += [f"- {m}" for m in pilot["messages"]] + [""]
    lines += ["## References", "", cc["sentence"], "",
              "| comparison | p99 block error | channel means test/ref | blocks beyond threshold | where |",
              "|---|---|---|---|---|"]
    rows = [("converged reference vs POV-Ray reference preset, full bounces", cc["full"]),
            ("POV-Ray fast vs reference preset (POV-Ray's own floor)", cc["pov_floor"])]
    if "b2" in cc:
        rows.append(("converged reference at --photon-depth 3 vs POV-Ray --bounces 2", cc["b2"]))
    for name, c in rows:
        lines.append(f"| {name} | {c['p99']:.3f} | {' '.join(f'{m:.3f}' for m in c['means'])} | "
                     f"{c['bad_share']:.1%} | {c['where']} |")
    lines += ["", f"Blocks of {cc['block_px']}x{cc['block_px']} pixels, e = |t - r| / (r + 0.01 mean(r)); "
              f"agreement: p99 <= {cc['threshold']} and every channel mean within 1 +- {cc['mean_tol']} "
              "(reference/README.md, \"Comparing images\"). POV-Ray's export: rectangle thickness "
              f"{thick['rect_thickness']:g} of the diagonal ({thick['rule']}).", "",
              "### The reference's own error", "", refmod.describe(a.ref, tightest), ""]
    if ok is False:
        lines += ["**The reference's error is not small against the tightest targets: read the verdict there "
                  "with care.**", ""]
    lines += [f"Errors below are relMSE against the converged reference; corrected for its noise (the expected "
              f"share its own variance adds) they are {fnum(info['noise'] if info else math.nan)} lower "
              "(experiments/analysis/reference.py, corrected()).", ""]
    lines += ["## Images", ""]
    if len(imgs) == 2:
        (xc, rc), (xp, _) = imgs["conventional"], imgs["precomputed"]
        srgb_png(xc, os.path.join(a.out, "conventional.png"))
        srgb_png(xp, os.path.join(a.out, "precomputed.png"))
        srgb_png(ref_img, os.path.join(a.out, "reference.png"))
        diff_png(xp, xc, os.path.join(a.out, "difference.png"))
        lines += [f"P_e = {int(rc['photons']):,}, n = {int(rc['nn'])}, {est} estimate, seed {int(rc['seed'])}; "
                  "the difference map is (precomputed - conventional) / (conventional + 0.01 mean) in luminance, "
                  "red where the precomputed is brighter, blue where darker, full colour at +-50%.", "",
                  "| conventional | precomputed | difference | converged reference |", "|---|---|---|---|",
                  "| ![](conventional.png) | ![](precomputed.png) | ![](difference.png) | ![](reference.png) |", ""]
    lines += ["## Time ratios", "", f"Precomputed / conventional time ({a.time}: the renderer's own timer), paired "
              "per seed (back to back), the geometric mean over seeds (exp of the mean paired log ratio) with its 95% t "
              "interval; "
              "relMSE per method (mean over seeds).", "",
              "| variant | estimate | P_e | n | time ratio % [95%] | relMSE conventional | relMSE precomputed |",
              "|---|---|---|---|---|---|---|"]
    for label, tpath, rpath in [("precomputed", a.table_csv, a.runs_csv)] + [tuple(v.split("=", 1)[0:1]) + tuple(v.split("=", 1)[1].split(",")) for v in a.variant]:
        t = pd.read_csv(tpath)
        rr = pd.read_csv(rpath)
        for _, q in t[t["method"] == "precomputed"].sort_values(["photons", "nn"]).iterrows():
            for e in a.estimates.split():
                sfx = "" if e == "paper" else f"_{e}"
                # an estimate the table has no column for has no ratio (never the paper estimate's)
                pr = q.get("paired_ratio_percent" + sfx, math.nan)
                lo = q.get("paired_ratio_ci95_lo" + sfx, math.nan)
                hi = q.get("paired_ratio_ci95_hi" + sfx, math.nan)
                sel = rr[(rr["photons"] == q["photons"]) & (rr["nn"] == q["nn"]) & (rr["estimate"] == e) & (rr["status"] == "ok")]
                ec = runs[(runs["photons"] == q["photons"]) & (runs["nn"] == q["nn"]) & (runs["estimate"] == e)
                          & (runs["method"] == "conventional") & (runs["status"] == "ok")]["relmse_ref"].mean()
                ep = sel[sel["method"] == "precomputed"]["relmse_ref"].mean()
                lines.append(f"| {label} | {e} | {int(q['photons']):,} | {int(q['nn'])} | {fnum(pr)} "
                             f"[{fnum(lo)}, {fnum(hi)}] | {fnum(ec)} | {fnum(ep)} |")
    lines += ["", "(The paired ratio pairs two renders of one seed: in a variant the conventional render is the "
              "main grid's, not back to back with it.)", ""]
    lines += ["## Equal-error speed-up", "", "![](equal-error.png)", "",
              f"From `{a.equal_error_csv}` (the curve over the whole relMSE range both fronts span, bootstrap "
              f"over seeds); the tightest target both fronts reach is its own row. Reference noise against the "
              f"tightest target: {why}.", ""]
    for e in a.estimates.split():
        t = ee[(ee["estimate"] == e) & (ee["kind"].isin(["tightest", "target"]))]
        if len(t):
            lines += [f"| {e}: kind | relMSE target | speed-up | 95% band | defined |", "|---|---|---|---|---|"]
            for _, r in t.iterrows():
                lines.append(f"| {r['kind']} | {fnum(r['target'])} | {fnum(r['speedup'])} | [{fnum(r['lo'])}, "
                             f"{fnum(r['hi'])}] | {fnum(r['defined_fraction'], 2)} |")
            lines.append("")
    lines += gather_lines
    lines += ["## Settings", "", a.settings, ""]
    if os.path.exists(a.equal_error_png):
        import shutil
        shutil.copyfile(a.equal_error_png, os.path.join(a.out, "equal-error.png.tmp"))
        os.replace(os.path.join(a.out, "equal-error.png.tmp"), os.path.join(a.out, "equal-error.png"))
    with open(os.path.join(a.out, "report.md.tmp"), "w") as fh:
        fh.write("\n".join(lines))
    os.replace(os.path.join(a.out, "report.md.tmp"), os.path.join(a.out, "report.md"))
    print(f"evaluate: [5/5] report: {os.path.join(a.out, 'report.md')}: " + " ".join(verdicts)
          + (" " + gather_sentence if gather_sentence else ""))


def main(argv=None):
    """The command line of the module docstring; returns the exit status."""
    ap = argparse.ArgumentParser(prog="python3 -m experiments.analysis.evaluate")
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("pilot")
    for k in ("--pm", "--scene", "--size", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--photons", type=int, required=True)
    p.add_argument("--nn", type=int, required=True)
    t = sub.add_parser("thickness")
    t.add_argument("--scene", required=True)
    t.add_argument("--out", required=True)
    t.add_argument("--pm", default=scene_info.DEFAULT_PM, help="the renderer, for the scene (photonmap info)")
    c = sub.add_parser("crosscheck")
    for k in ("--ref", "--pov-ref", "--pov-fast", "--out"):
        c.add_argument(k, required=True)
    c.add_argument("--b2-ours")
    c.add_argument("--b2-pov")
    r = sub.add_parser("report")
    for k in ("--scene", "--pilot", "--thickness", "--crosscheck", "--ref", "--runs-csv", "--table-csv",
              "--equal-error-csv", "--equal-error-png", "--runroot", "--out", "--settings"):
        r.add_argument(k, required=True)
    r.add_argument("--estimates", default="paper corrected")
    r.add_argument("--time", default="total_s")
    r.add_argument("--variant", action="append", default=[], help="LABEL=TABLE.csv,RUNS.csv")
    r.add_argument("--gather-csv", default="", help="analysis/gather.py's CSV of the final-gathering grids")
    a = ap.parse_args(argv)
    {"pilot": cmd_pilot, "thickness": cmd_thickness, "crosscheck": cmd_crosscheck, "report": cmd_report}[a.cmd](a)
    return 0


if __name__ == "__main__":
    sys.exit(main())
