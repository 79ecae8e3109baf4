#!/usr/bin/python3
"""reference.py: the method-neutral converged reference and its measured error.

Owns the converged reference a study judges its renders against when it
renders its own (make scenes, make resolution, make evaluate): how it is
made, how its own error is measured, and the error corrected for it.

The reference is neither grid method at a grid setting: the corrected
estimate (--bias-correction, photons strictly inside r: no n/(n-1) factor
to fit) with direct light by shadow rays (exact direct light; the photon
map carries only indirect light and caustics, so the photon noise is that
of the indirect part alone; the same image whatever method it then judges),
at many times the grid's largest photon count, averaged over S >= 2 seeds
none of which the grid uses (photon i of seed s is the same path whatever
P_e, so a grid seed would share its photons with the renders it judges).

Its own error, both in the units of the primary metric (metrics.PRIMARY:
the expected share of a test render's error against the reference that the
reference itself brings), written to a JSON beside the EXR:

  noise  the variance the mean of S seeds keeps. The seeds are split into
         halves A, B (a and b seeds); D = mean_A - mean_B has per-value
         variance sigma^2 (1/a + 1/b), the mean of all S has sigma^2 / S, so
         noise = PRIMARY(m~ + D, m~) / (S (1/a + 1/b)), m~ the mean of all S
         box-blurred (WEIGHT_BLUR: the metric's weight taken at it, not at
         the noisy mean, with which the differences correlate).
  bias   the kernel bias, by halving the photon count: the same seeds at
         P/2 give h, mean over seeds. For the corrected estimate the bias
         is the kernel's smoothing, proportional to r^2, i.e. to n / P at
         fixed n, so bias(P/2) - bias(P) = bias(P) and
         bias = PRIMARY(m~ + (h - m), m~) - the noise of h - m (from the
         seed halves of the per-seed differences, as above).
         A number below 0 means "not measurable at this noise"; the JSON
         keeps the raw value.

check() compares both with the tightest target the reference judges: each
should be at most MARGIN (10%) of it, else the report says so (warn, not
refuse: the study still runs, its tightest targets are then flagged).
corrected() is a test's primary error minus the reference's noise term
(the expectation of the squared reference noise that the metric adds;
the bias cannot be removed, its sign is unknown).
measured() is what a table's columns carry (runs.csv's ref_noise and
ref_bias, beyond.csv's, gather.csv's): the two numbers, nan where the
reference has no JSON (a POV-Ray reference: its error is not measured and
no number stands in for it).

Command line:
  python3 -m experiments.analysis.reference build --pm PM --scene S --width W --height H
      --subpixels K --photons P --nn N --direct shadow-rays|photons --seeds "A B ..."
      --grid-seeds "1 2 3" --dir DIR --out OUT.exr [--pm-args "--photon-depth 3"]
  renders each seed at P and P/2 in DIR (kept: a rerun renders only what is
  missing), writes OUT.exr (the mean at P), OUT.png and OUT.json; exit 2 on
  a usage error (a seed the grid uses, fewer than two seeds), 1 on a render
  failure.
  python3 -m experiments.analysis.reference describe OUT.exr [--tightest T]
  prints the sentence reports quote.
"""

import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

from experiments.analysis import metrics

# the largest share of the tightest target the reference's noise and bias may each be
MARGIN = 0.1


def primary_metric():
    """The function of metrics.PRIMARY (x, r) -> float: metrics.py's own,
    never re-implemented here."""
    f = getattr(metrics, "primary", None)
    if callable(f):
        return f
    return getattr(metrics, metrics.PRIMARY)


def halves(n):
    """The seed indices of the two halves of N seeds: (A, B), a = N // 2."""
    a = n // 2
    return list(range(a)), list(range(a, n))


# the metric's weight is taken at the mean image box-blurred over
# WEIGHT_BLUR x WEIGHT_BLUR pixels: a weight from the noisy mean itself
# correlates with the differences it weighs (relMSE's 1/(r^2 + 0.01) is
# convex: measured on synthetic seeds, +10% on the squared difference, 2.5x
# the bias term it was to find)
WEIGHT_BLUR = 5


def smooth(img, k=WEIGHT_BLUR):
    """IMG (H, W, C) box-blurred over k x k pixels (edges: the nearest pixel)."""
    p = k // 2
    x = np.pad(img, ((p, p), (p, p), (0, 0)), mode="edge")
    c = np.cumsum(np.cumsum(x, axis=0), axis=1)
    c = np.pad(c, ((1, 0), (1, 0), (0, 0)))
    h, w = img.shape[:2]
    return (c[k:k + h, k:k + w] - c[0:h, k:k + w] - c[k:k + h, 0:w] + c[0:h, 0:w]) / (k * k)


def split_noise(images, wref):
    """The primary-metric noise term of the mean of IMAGES (S >= 2 per-seed
    images): PRIMARY(wref + D, wref) / (S (1/a + 1/b)), D the difference of
    the two halves' means, WREF the image the metric's weight is taken at.
    nan with fewer than two images."""
    s = len(images)
    if s < 2:
        return math.nan
    ia, ib = halves(s)
    ma = np.mean([images[i] for i in ia], axis=0)
    mb = np.mean([images[i] for i in ib], axis=0)
    return primary_metric()(wref + (ma - mb), wref) / (s * (1.0 / len(ia) + 1.0 / len(ib)))


def measure(full, half):
    """{'noise', 'bias', 'bias_raw', 'noise_half', 'noise_of_difference'} of
    the reference from its per-seed images at P (FULL) and P/2 (HALF), the
    same seeds in the same order (module docstring)."""
    if len(full) != len(half) or len(full) < 2:
        raise ValueError("measure: need the same S >= 2 seeds at P and at P/2")
    m = np.mean(full, axis=0)
    h = np.mean(half, axis=0)
    wref = smooth(m)
    noise = split_noise(full, wref)
    # the noise of mean(h - m): the same split, on the per-seed differences
    noise_diff = split_noise([hh - ff for hh, ff in zip(half, full)], wref)
    bias_raw = primary_metric()(wref + (h - m), wref) - noise_diff
    return {"noise": float(noise), "bias": float(max(bias_raw, 0.0)), "bias_raw": float(bias_raw),
            "noise_half": float(split_noise(half, smooth(h))), "noise_of_difference": float(noise_diff)}


def sidecar(exr):
    """The JSON path beside the reference EXR."""
    return os.path.splitext(str(exr))[0] + ".json"


def load(exr):
    """The reference's JSON (noise, bias, settings) beside EXR, or None when
    there is none (a POV-Ray or user-given reference)."""
    p = sidecar(exr)
    if not os.path.exists(p):
        return None
    with open(p) as fh:
        return json.load(fh)


def measured(exr, unit="relmse"):
    """(info, noise, bias) of the reference at EXR for a table in UNIT: its
    JSON (load) with the two numbers, or (None, nan, nan) when its error is
    not measured (no EXR named, no JSON beside it) or is measured in another
    metric than UNIT (its numbers would not subtract from UNIT's). Raises
    ValueError naming the JSON when it is not JSON or lacks the numbers."""
    try:
        info = load(exr) if exr else None
    except (OSError, ValueError) as e:
        raise ValueError(f"{sidecar(exr)}: not the reference's JSON ({e})") from e
    if info is None or info.get("metric", metrics.PRIMARY) != unit:
        return None, math.nan, math.nan
    try:
        return info, float(info["noise"]), float(info["bias"])
    except (KeyError, TypeError, ValueError) as e:
        raise ValueError(f"{sidecar(exr)}: no numeric noise and bias ({e})") from e


def corrected(err, info):
    """A test's primary error ERR against a reference with INFO (load()):
    minus the reference's noise term; ERR unchanged when INFO is None."""
    if info is None or not math.isfinite(info.get("noise", math.nan)):
        return err
    return err - info["noise"]


def check(info, tightest, margin=MARGIN):
    """(ok, sentence): whether the reference's noise and bias are each at
    most MARGIN of TIGHTEST (the tightest target it judges); ok is None
    when TIGHTEST is unknown (nan or None)."""
    if info is None:
        return None, "the reference's own error is not measured (no JSON beside it)"
    if tightest is None or not (isinstance(tightest, (int, float)) and math.isfinite(tightest)) or tightest <= 0:
        return None, "no tightest target to judge it by"
    lim = margin * tightest
    bad = [k for k in ("noise", "bias") if not info[k] <= lim]
    if not bad:
        return True, (f"both at most {margin:.0%} of the tightest target it judges ({tightest:.3g}): "
                      f"noise {info['noise'] / tightest:.1%}, bias {info['bias'] / tightest:.1%} of it")
    return False, ("WARNING: " + " and ".join(f"its {k} is {info[k] / tightest:.0%}" for k in bad)
                   + f" of the tightest target it judges ({tightest:.3g}), above {margin:.0%}: "
                   "errors near that target are the reference's as much as the render's; "
                   "raise CONV_REF_PHOTONS or CONV_REF_SEEDS")


def tightest_of(equal_error_csv):
    """The tightest target a reference judges in a study: the smallest
    relMSE of the equal-error curves in EQUAL_ERROR_CSV (its `kind`
    tightest and curve rows), or None when there is none or no file."""
    import pandas as pd

    try:
        ee = pd.read_csv(equal_error_csv)
    except (OSError, ValueError):
        return None
    t = ee[ee["kind"].isin(["tightest", "curve"])]["target"].astype(float)
    t = t[np.isfinite(t)]
    return float(t.min()) if len(t) else None


def describe(exr, tightest=None):
    """The sentence a report prints about the reference at EXR: its settings
    and measured error (and, given TIGHTEST, the check against it)."""
    info = load(exr)
    if info is None:
        return f"Reference `{exr}`: its own error is not measured here (no `{os.path.basename(sidecar(exr))}`)."
    s = info["settings"]
    unit = info.get("metric", metrics.PRIMARY)
    out = (f"Reference `{exr}`: {s['method']} method, corrected estimate, direct light by {s['direct']}, "
           f"P_e = {s['photons']:,}, n = {s['nn']}, mean of {len(s['seeds'])} seeds "
           f"({', '.join(str(x) for x in s['seeds'])}; no grid render uses them). Its own error in {unit}: "
           f"noise {info['noise']:.3g} (from the seeds), kernel bias {info['bias']:.3g} "
           f"(from halving P_e; raw {info['bias_raw']:.3g}).")
    if tightest is not None:
        ok, why = check(info, tightest)
        out += " " + why[0].upper() + why[1:] + "."
    return out


def render(pm, scene, w, h, sub, photons, nn, direct, seed, out, extra=()):
    """One render of the reference's settings to OUT (a temp name, then
    renamed); skips it when OUT exists. Raises RuntimeError on failure."""
    if os.path.exists(out):
        return
    tmp = out + ".tmp.exr"
    cmd = [pm, "render", scene, "--method", "conventional", "--bias-correction", "--direct", direct,
           "--photons", str(photons), "--nn", str(nn), "--seed", str(seed), "--width", str(w),
           "--height", str(h), "--subpixels", str(sub), "--threads", "0", *extra, "-o", tmp, "--quiet"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()}")
    os.replace(tmp, out)


def write_exr(img, path):
    """IMG (H, W, 3) as a float EXR at PATH (temp name, then renamed)."""
    import OpenImageIO as oiio

    hgt, wid = img.shape[:2]
    spec = oiio.ImageSpec(wid, hgt, 3, oiio.FLOAT)
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(0, wid, 0, hgt), np.ascontiguousarray(img, dtype=np.float32))
    tmp = path + ".tmp.exr"
    if not buf.write(tmp):
        raise RuntimeError(f"{path}: cannot write: {buf.geterror()}")
    os.replace(tmp, path)


def write_png(img, path):
    """An sRGB 8-bit preview of IMG at PATH (temp name, then renamed)."""
    import OpenImageIO as oiio

    x = np.clip(img, 0.0, 1.0)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    q = np.round(x * 255).astype(np.uint8)
    spec = oiio.ImageSpec(img.shape[1], img.shape[0], 3, oiio.UINT8)
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(0, img.shape[1], 0, img.shape[0]), q)
    tmp = path + ".tmp.png"
    if not buf.write(tmp):
        raise RuntimeError(f"{path}: cannot write: {buf.geterror()}")
    os.replace(tmp, path)


def build(a):
    """The `build` command: renders, measures, writes OUT.exr/.png/.json;
    returns the exit status."""
    try:
        seeds = [int(s) for s in a.seeds.split()]
        grid = {int(s) for s in a.grid_seeds.split()}
    except ValueError:
        print(f"reference: CONV_REF_SEEDS='{a.seeds}' or the grid's seeds '{a.grid_seeds}': not whole numbers",
              file=sys.stderr)
        return 2
    if len(seeds) < 2 or len(set(seeds)) != len(seeds):
        print(f"reference: CONV_REF_SEEDS={a.seeds}: need at least two different seeds", file=sys.stderr)
        return 2
    if grid & set(seeds):
        print(f"reference: CONV_REF_SEEDS={a.seeds}: seed(s) {sorted(grid & set(seeds))} are the grid's: the "
              "reference would share photon paths with the renders it judges", file=sys.stderr)
        return 2
    if a.photons < 2:
        print(f"reference: CONV_REF_PHOTONS={a.photons}: too few to halve", file=sys.stderr)
        return 2
    os.makedirs(a.dir, exist_ok=True)
    half_p = a.photons // 2
    full, half = [], []
    try:
        for s in seeds:
            for p, acc in ((a.photons, full), (half_p, half)):
                f = os.path.join(a.dir, f"p{p}-seed{s}.exr")
                print(f"reference: {a.scene} at {a.width}x{a.height}: P_e={p} n={a.nn} seed {s}", flush=True)
                render(a.pm, a.scene, a.width, a.height, a.subpixels, p, a.nn, a.direct, s, f, a.pm_args.split())
                acc.append(metrics.read_exr(f))
    except (RuntimeError, ValueError) as e:
        print(f"reference: {e}", file=sys.stderr)
        return 1
    info = measure(full, half)
    info.update({"metric": metrics.PRIMARY,
                 "settings": {"scene": a.scene, "width": a.width, "height": a.height, "subpixels": a.subpixels,
                              "method": "conventional", "estimate": "corrected", "direct": a.direct,
                              "photons": a.photons, "half_photons": half_p, "nn": a.nn, "seeds": seeds,
                              "grid_seeds": sorted(grid), "pm_args": a.pm_args},
                 "how": "noise: the seed halves' difference, scaled to the mean of all seeds; bias: the "
                        "mean at P/2 against the mean at P, less the noise of that difference "
                        "(experiments/analysis/reference.py)"})
    m = np.mean(full, axis=0)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    write_png(m, os.path.splitext(a.out)[0] + ".png")
    tmp = sidecar(a.out) + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(info, fh, indent=2)
        fh.write("\n")
    os.replace(tmp, sidecar(a.out))
    write_exr(m, a.out)  # last: the make target
    print(f"reference: {a.out}: noise {info['noise']:.3g}, bias {info['bias']:.3g} ({metrics.PRIMARY})")
    return 0


def main(argv=None):
    """The command line of the module docstring; returns the exit status."""
    ap = argparse.ArgumentParser(prog="python3 -m experiments.analysis.reference")
    sub = ap.add_subparsers(dest="cmd", required=True)
    b = sub.add_parser("build")
    b.add_argument("--pm", required=True)
    b.add_argument("--scene", required=True)
    b.add_argument("--width", type=int, required=True)
    b.add_argument("--height", type=int, required=True)
    b.add_argument("--subpixels", type=int, default=2)
    b.add_argument("--photons", type=int, required=True)
    b.add_argument("--nn", type=int, required=True)
    b.add_argument("--direct", choices=["shadow-rays", "photons"], default="shadow-rays")
    b.add_argument("--seeds", required=True)
    b.add_argument("--grid-seeds", default="")
    b.add_argument("--dir", required=True)
    b.add_argument("--out", required=True)
    b.add_argument("--pm-args", default="", help="extra render options (e.g. --photon-depth 3)")
    d = sub.add_parser("describe")
    d.add_argument("exr")
    d.add_argument("--tightest", type=float)
    a = ap.parse_args(argv)
    if a.cmd == "build":
        return build(a)
    print(describe(a.exr, a.tightest))
    return 0


if __name__ == "__main__":
    sys.exit(main())
