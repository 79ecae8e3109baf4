"""Image error metrics: the one implementation of relMSE, NMSE, RMSE and PSNR.

Owns reading a linear RGB EXR into a float64 array, windows of an image
(a region given as WxH+X+Y at one size, scaled to another), the per-image
metrics (relMSE, NMSE, RMSE, PSNR, the peak ratio of the brightest light) and the
split of a cell's error over seeds into a bias and a variance term in the
relMSE weighting. Every number about images in runs.csv, cells.csv, the
tables and the shell tools comes from here: the shell calls this module
(`python3 -m experiments.analysis.metrics TEST.exr REF.exr`, and
scripts/imgcmp.sh stats); reports quote DEFINITION below instead of
restating it.

DEFINITION, x = test, r = reference, over every pixel and RGB channel (or
only the pixels where a mask image has a non-zero channel):
  relMSE = mean((x - r)^2 / (r^2 + 0.01))
  NMSE   = mean((x - r)^2) / mean(r^2)
  RMSE   = sqrt(mean((x - r)^2))
  PSNR   = 10 log10(peak^2 / MSE) dB, peak 1 (linear radiance, 1.0 = white)
           or, asked for, the reference's largest value over those pixels;
           inf when the images are equal

The two errors. relMSE is kept as it was for continuity with every earlier
table; its offset 0.01 is absolute, so wherever r < 0.1 (19% of the paper
scene's pixels) it weighs the squared error by about 1/0.01 rather than
1/r^2: there it is an absolute error, and a whole image's relMSE changes
when the image is scaled. NMSE, the mean squared error normalised by the
reference's mean square, stays relative at every brightness: scaling test
and reference by k leaves it unchanged, and a dark pixel counts by its
squared error against the image's overall level, so noise in a dark region
neither dominates (as an unoffset per-pixel relative error would) nor
changes meaning with the exposure. PRIMARY names the error the tables and
the equal-error curves report; it stays relMSE (the studies' targets and
every earlier number are in it) and NMSE is reported beside it
(runs.csv nmse_ref, table1.csv nmse_ref_mean, nmse_ref_ci95).

Command line (exit 0; 2 on a usage error, an unreadable file or a size
mismatch):
  python3 -m experiments.analysis.metrics TEST.exr REF.exr [--mask MASK.exr] [--peak 1|max] [--csv|--header]
prints "relmse=... rmse=... psnr=... pixels=N peak=P" (%.6g), or with --csv
the values alone in that order, --header first the CSV header line.
"""

import argparse
import math
import sys

import numpy as np

# the relMSE weight's offset: keeps dark pixels from dominating
REL_EPS = 0.01
# the error the tables and the equal-error curves report (the module
# docstring says why): "relmse" (runs.csv relmse_ref); "nmse" is beside it
PRIMARY = "relmse"
# the runs.csv column of the primary error against the reference, and its
# definition as the reports quote it
PRIMARY_COLUMN = f"{PRIMARY}_ref"
PRIMARY_DEFINITION = {"relmse": "relMSE = mean((x - r)^2 / (r^2 + 0.01))",
                      "nmse": "NMSE = mean((x - r)^2) / mean(r^2)"}[PRIMARY]


def read_exr(path):
    """Return the RGB channels of the EXR at PATH as a float64 array (H, W, 3).

    Raises ValueError naming the file when it cannot be read or has fewer
    than three channels."""
    import OpenImageIO as oiio  # imported here: the statistics need no OIIO

    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        raise ValueError(f"{path}: cannot read: {buf.geterror()}")
    spec = buf.spec()
    if spec.nchannels < 3:
        raise ValueError(f"{path}: {spec.nchannels} channel(s), need RGB")
    pixels = buf.get_pixels(oiio.FLOAT)
    if pixels is None or buf.has_error:
        raise ValueError(f"{path}: cannot read pixels: {buf.geterror()}")
    return np.asarray(pixels, dtype=np.float64).reshape(spec.height, spec.width, spec.nchannels)[:, :, :3]


def parse_window(spec):
    """'WxH+X+Y' (oiiotool's --cut form) -> (w, h, x, y) integers; raises
    ValueError naming SPEC when it is not of that form."""
    import re

    m = re.fullmatch(r"\s*(\d+)x(\d+)\+(\d+)\+(\d+)\s*", str(spec))
    if not m:
        raise ValueError(f"window '{spec}': expected WxH+X+Y")
    w, h, x, y = (int(v) for v in m.groups())
    if w == 0 or h == 0:
        raise ValueError(f"window '{spec}': empty")
    return w, h, x, y


def scale_window(spec, at, size):
    """The window SPEC ('WxH+X+Y'), given for an image of size AT ('WxH'),
    scaled to an image of SIZE ('WxH' or (width, height)): (w, h, x, y) in
    SIZE's pixels, rounded to whole pixels (the same region of the frame).
    Raises ValueError when the window leaves the image."""
    w, h, x, y = parse_window(spec)
    aw, ah = (int(v) for v in str(at).lower().split("x"))
    sw, sh = (int(v) for v in (size.lower().split("x") if isinstance(size, str) else size))
    fx, fy = sw / aw, sh / ah
    out = (max(1, round(w * fx)), max(1, round(h * fy)), round(x * fx), round(y * fy))
    if out[2] + out[0] > sw or out[3] + out[1] > sh or x + w > aw or y + h > ah:
        raise ValueError(f"window '{spec}' at {at} leaves the {sw}x{sh} image")
    return out


def window(img, spec, at):
    """The pixels of IMG (H, W, C) inside window SPEC given at size AT (see
    scale_window)."""
    w, h, x, y = scale_window(spec, at, (img.shape[1], img.shape[0]))
    return img[y:y + h, x:x + w]


def _check_same_shape(x, r):
    """Raise ValueError unless the two images have the same shape."""
    if x.shape != r.shape:
        raise ValueError(f"image size mismatch: {x.shape} vs {r.shape}")


def rel_weight(r):
    """The per-value weight 1 / (r^2 + 0.01) of relMSE for reference R."""
    return 1.0 / (np.square(r) + REL_EPS)


def relmse(x, r):
    """relMSE of image X against reference R: mean((x-r)^2 / (r^2+0.01))."""
    _check_same_shape(x, r)
    return float(np.mean(np.square(x - r) * rel_weight(r)))


def mse(x, r):
    """Mean squared error of X against R over pixels and channels."""
    _check_same_shape(x, r)
    return float(np.mean(np.square(x - r)))


def nmse(x, r):
    """NMSE of X against R: mean((x-r)^2) / mean(r^2), a relative error at
    every brightness (invariant when X and R are scaled together); nan when
    R is black."""
    _check_same_shape(x, r)
    den = float(np.mean(np.square(r)))
    return float(np.mean(np.square(x - r))) / den if den > 0 else math.nan


def rmse(x, r):
    """Root mean squared error of X against R."""
    return math.sqrt(mse(x, r))


def psnr(x, r, peak=1.0):
    """PSNR in dB of X against R with the given peak; inf when X equals R."""
    m = mse(x, r)
    return math.inf if m == 0 else 10.0 * math.log10(peak * peak / m)


def peak_ratio(x, r, top=0.1):
    """How much of the reference's brightest light X keeps: mean luminance
    of X over the pixels where R's luminance is in its top TOP fraction,
    divided by R's mean there (1: kept; below 1: spread out or lost, as a
    blurred caustic). Luminance: Rec. 709 weights. nan when R is black."""
    _check_same_shape(x, r)
    w = np.array([0.2126, 0.7152, 0.0722])
    lx, lr = (x.reshape(-1, x.shape[-1])[:, :3] @ w), (r.reshape(-1, r.shape[-1])[:, :3] @ w)
    k = max(1, int(round(top * lr.size)))
    idx = np.argsort(lr)[-k:]
    den = float(lr[idx].mean())
    return float(lx[idx].mean()) / den if den > 0 else math.nan


def weighted_gram(images, r):
    """The S x S matrix G[s, t] = mean((x_s - r)(x_t - r) / (r^2 + 0.01)).

    IMAGES is a sequence of S images of one cell (one per seed), R the
    reference. G holds everything the relMSE-weighted statistics of the cell
    need: G[s, s] is seed s's relMSE, and bias_variance() and its bootstrap
    are functions of G alone, so the images are read once."""
    if len(images) == 0:
        raise ValueError("weighted_gram: no image")
    for x in images:
        _check_same_shape(x, r)
    sw = np.sqrt(rel_weight(r)).ravel()
    d = np.stack([(x.ravel() - r.ravel()) * sw for x in images])
    return d @ d.T / d.shape[1]


def bias_variance_from_gram(g, counts=None):
    """Split the mean relMSE of a cell into (bias, variance) terms from G.

    With S seeds, xbar the per-value mean over seeds and s^2 the per-value
    sample variance over seeds (ddof = 1), w = 1 / (r^2 + 0.01):
      variance = mean(w s^2)
      bias     = mean(w ((xbar - r)^2 - s^2 / S))
    Both are unbiased for the expected terms, and bias + variance equals the
    mean over seeds of relMSE exactly (so bias can come out slightly
    negative when the true bias is small). COUNTS, if given, weights seed s
    by counts[s] (a bootstrap resample: how often each seed was drawn).
    Returns (nan, nan) with fewer than two draws."""
    g = np.asarray(g, dtype=np.float64)
    c = np.ones(g.shape[0]) if counts is None else np.asarray(counts, dtype=np.float64)
    n = c.sum()
    if n < 2:
        return math.nan, math.nan
    mean_sq = float(c @ g @ c) / (n * n)          # mean(w (xbar - r)^2)
    second = float(c @ np.diag(g)) / n            # mean(w mean_s (x_s - r)^2)
    variance = (second - mean_sq) * n / (n - 1)   # mean(w s^2), ddof = 1
    bias = mean_sq - variance / n
    return bias, variance


def bias_variance(images, r):
    """(bias, variance) of a cell's seed IMAGES against reference R: the
    terms of bias_variance_from_gram, from the images."""
    return bias_variance_from_gram(weighted_gram(images, r))


def masked_values(x, r, mask=None):
    """(x, r) restricted to the pixels where MASK (same H x W) has a
    non-zero channel, as (N, 3) arrays; raises ValueError on a size
    mismatch or a mask that selects no pixel."""
    _check_same_shape(x, r)
    if mask is None:
        return x.reshape(-1, 3), r.reshape(-1, 3)
    if mask.shape[:2] != x.shape[:2]:
        raise ValueError(f"image size mismatch: mask {mask.shape} vs {x.shape}")
    sel = np.any(mask != 0, axis=2)
    if not sel.any():
        raise ValueError("the mask selects no pixel")
    return x[sel], r[sel]


def main(argv=None):
    """The command line of the module docstring; returns the exit status."""
    ap = argparse.ArgumentParser(prog="python3 -m experiments.analysis.metrics",
                                 description="relMSE, RMSE and PSNR of TEST against REF (metrics.py's definition)")
    ap.add_argument("test")
    ap.add_argument("ref")
    ap.add_argument("--mask")
    ap.add_argument("--peak", choices=["1", "max"], default="1")
    ap.add_argument("--csv", action="store_true")
    ap.add_argument("--header", action="store_true")
    a = ap.parse_args(argv)
    try:
        x, r = read_exr(a.test), read_exr(a.ref)
        x, r = masked_values(x, r, read_exr(a.mask) if a.mask else None)
    except ValueError as e:
        print(f"metrics: {e}", file=sys.stderr)
        return 2
    peak = float(r.max()) if a.peak == "max" else 1.0
    vals = (relmse(x, r), rmse(x, r), psnr(x, r, peak))
    f = ["%.6g" % v for v in vals]
    if a.csv or a.header:
        if a.header:
            print("relmse,rmse,psnr,pixels,peak")
        print(f"{f[0]},{f[1]},{f[2]},{len(x)},{peak:.6g}")
    else:
        print(f"relmse={f[0]} rmse={f[1]} psnr={f[2]} pixels={len(x)} peak={peak:.6g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
