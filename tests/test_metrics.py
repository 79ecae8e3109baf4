"""Unit tests of experiments/analysis/metrics.py: relMSE and NMSE, bias and
variance over seeds, windows, the command line.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`); pytest rewrites
the asserts, so they check under `python3 -O` too. Every check compares
against a value computed another way (a closed form, a simulation with a
known answer, the definition computed directly), so each can fail. Random
numbers come from fixed seeds: the outcome is deterministic.
"""

import math
import os
import subprocess
import tempfile

import numpy as np

from experiments.analysis import metrics
from helpers import close

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


# ---- metrics

def test_relmse_known():
    """relMSE of identical images is 0 and PSNR inf; x = 2, r = 1 gives
    relMSE 1/1.01, RMSE 1, PSNR 0 dB; a size mismatch is an error."""
    r = np.full((4, 5, 3), 1.0)
    assert metrics.relmse(r, r) == 0.0 and metrics.psnr(r, r) == math.inf and metrics.rmse(r, r) == 0.0
    x = np.full((4, 5, 3), 2.0)
    close(metrics.relmse(x, r), 1 / 1.01, 1e-15, "relmse")
    close(metrics.rmse(x, r), 1.0, 1e-15, "rmse")
    close(metrics.psnr(x, r), 0.0, 1e-12, "psnr")
    try:
        metrics.relmse(x, np.zeros((5, 4, 3)))
    except ValueError:
        return
    raise AssertionError("size mismatch accepted")


def synthetic_truth(rng, bias_scale, sigma_scale, shape=(12, 16, 3)):
    """A reference r, a per-value bias b and noise sigma; returns (r, b,
    sigma, true bias term, true variance term) in the relMSE weighting."""
    r = rng.uniform(0.05, 1.0, size=shape)
    b = bias_scale * rng.uniform(-1.0, 1.0, size=shape)
    sigma = sigma_scale * rng.uniform(0.5, 1.5, size=shape)
    w = metrics.rel_weight(r)
    return r, b, sigma, float(np.mean(w * b * b)), float(np.mean(w * sigma * sigma))


def synthetic_cell(rng, seeds, bias_scale, sigma_scale):
    """SEEDS images x_s = r + b + sigma * N(0, 1) of one synthetic truth;
    returns (images, r)."""
    r, b, sigma, _, _ = synthetic_truth(rng, bias_scale, sigma_scale)
    return [r + b + sigma * rng.standard_normal(r.shape) for _ in range(seeds)], r


def test_bias_variance_recovers_truth():
    """Over 400 synthetic cells of 4 seeds whose noise is far larger than
    their bias (fresh noise, the same truth), the mean bias and variance
    estimates match the true terms within 4 standard errors; the plain
    squared error of the mean image (without the s^2/S correction) misses
    the bias by far (this would fail with that estimator)."""
    r, b, sigma, true_b, true_v = synthetic_truth(np.random.default_rng(11), 0.02, 0.1)
    rng = np.random.default_rng(3)
    est_b, est_v, naive = [], [], []
    for _ in range(400):
        imgs = [r + b + sigma * rng.standard_normal(r.shape) for _ in range(4)]
        bias, variance = metrics.bias_variance(imgs, r)
        est_b.append(bias)
        est_v.append(variance)
        naive.append(float(np.mean(metrics.rel_weight(r) * (np.mean(imgs, axis=0) - r) ** 2)))
    se_b = np.std(est_b, ddof=1) / math.sqrt(len(est_b))
    se_v = np.std(est_v, ddof=1) / math.sqrt(len(est_v))
    close(np.mean(est_b), true_b, 4 * se_b, "bias")
    close(np.mean(est_v), true_v, 4 * se_v, "variance")
    assert abs(np.mean(naive) - true_b) > 20 * se_b, "the uncorrected estimator should be far off"


def test_bias_variance_identity_and_definition():
    """bias + variance equals the mean over seeds of relMSE, and both equal
    the per-pixel definition written out here (mean image, ddof-1 variance)."""
    imgs, r = synthetic_cell(np.random.default_rng(5), 5, 0.05, 0.05)
    b, v = metrics.bias_variance(imgs, r)
    close(b + v, np.mean([metrics.relmse(x, r) for x in imgs]), 1e-12, "identity")
    w = 1.0 / (r * r + 0.01)
    stack = np.stack(imgs)
    s2 = stack.var(axis=0, ddof=1)
    close(v, float(np.mean(w * s2)), 1e-12, "variance definition")
    close(b, float(np.mean(w * ((stack.mean(axis=0) - r) ** 2 - s2 / 5))), 1e-12, "bias definition")
    assert all(math.isnan(x) for x in metrics.bias_variance(imgs[:1], r))


def test_bias_variance_counts_are_repeats():
    """Weighting seeds by bootstrap counts equals repeating the images."""
    imgs, r = synthetic_cell(np.random.default_rng(6), 3, 0.05, 0.05)
    g = metrics.weighted_gram(imgs, r)
    got = metrics.bias_variance_from_gram(g, [2, 0, 1])
    want = metrics.bias_variance([imgs[0], imgs[0], imgs[2]], r)
    close(got[0], want[0], 1e-12, "bias")
    close(got[1], want[1], 1e-12, "variance")


def test_metrics_command_line_matches_functions():
    """On a real pair of renders, the command line the shell tools call
    (python3 -m experiments.analysis.metrics) prints metrics.py's relMSE,
    RMSE and PSNR, and these equal a direct numpy computation of the
    definition; read_exr gives H x W x 3."""
    pm = os.environ.get("PM", os.path.join(ROOT, "build", "photonmap"))
    scene = os.path.join(ROOT, "scenes", "cornell.scene")
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "a.exr"), os.path.join(d, "b.exr")
        for path, method in ((a, "conventional"), (b, "precomputed")):
            subprocess.run([pm, "render", scene, "--width", "32", "--height", "24", "--photons", "3000", "--nn", "10",
                            "--method", method, "-o", path, "--quiet"], check=True)
        out = subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.metrics", b, a, "--csv"], check=True,
                             capture_output=True, text=True, cwd=ROOT).stdout.strip()
        c_rel, c_rmse, c_psnr = (float(v) for v in out.split(",")[:3])
        x, r = metrics.read_exr(b), metrics.read_exr(a)
        assert x.shape == (24, 32, 3), x.shape
        got = (metrics.relmse(x, r), metrics.rmse(x, r), metrics.psnr(x, r))
        d2 = (x - r) ** 2
        direct = (float((d2 / (r * r + 0.01)).sum() / d2.size), math.sqrt(d2.sum() / d2.size),
                  10 * math.log10(1.0 / (d2.sum() / d2.size)))
        for name, g, c, e in zip(("relMSE", "RMSE", "PSNR"), got, (c_rel, c_rmse, c_psnr), direct):
            assert abs(g - c) <= 1e-5 * abs(g), f"{name}: function {g} vs command line {c}"
            assert abs(g - e) <= 1e-9 * abs(e), f"{name}: function {g} vs the definition {e}"
        same = subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.metrics", a, a], check=True,
                              capture_output=True, text=True, cwd=ROOT).stdout.strip()
        assert same == "relmse=0 rmse=0 psnr=inf pixels=768 peak=1", same


def test_read_exr_missing_file():
    """A missing file is a ValueError that names it."""
    try:
        metrics.read_exr("/nonexistent/x.exr")
    except ValueError as e:
        assert "/nonexistent/x.exr" in str(e), str(e)
        return
    raise AssertionError("no error")


def test_window_scaling():
    """The caustic window 24x20+52+76 at 128x96 is 96x80+208+304 at 512x384
    and the same pixels at 128x96; a window that leaves the image, or a
    malformed one, is an error."""
    assert metrics.scale_window("24x20+52+76", "128x96", "512x384") == (96, 80, 208, 304)
    assert metrics.scale_window("24x20+52+76", "128x96", (128, 96)) == (24, 20, 52, 76)
    img = np.arange(96 * 128 * 3, dtype=float).reshape(96, 128, 3)
    win = metrics.window(img, "24x20+52+76", "128x96")
    assert win.shape == (20, 24, 3) and win[0, 0, 0] == img[76, 52, 0] and win[-1, -1, 2] == img[95, 75, 2]
    for bad in ("24x20+110+0", "24x20", "0x5+1+1"):
        try:
            metrics.scale_window(bad, "128x96", "128x96")
        except ValueError:
            continue
        raise AssertionError(f"{bad} accepted")


def test_peak_ratio_known():
    """A copy keeps its peak (1); a box-blurred spot keeps less (about the
    blurred mean over the spot); a uniform scale is the scale."""
    r = np.full((20, 24, 3), 0.1)
    r[8:12, 10:14] = 2.0
    close(metrics.peak_ratio(r, r), 1.0, 1e-12, "copy")
    close(metrics.peak_ratio(0.5 * r, r), 0.5, 1e-12, "scale")
    from scipy.ndimage import uniform_filter
    blurred = uniform_filter(r, size=(5, 5, 1), mode="nearest")
    pr = metrics.peak_ratio(blurred, r, top=16 / 480)
    close(pr, float(blurred[8:12, 10:14, 1].mean()) / 2.0, 1e-9, "blur")
    assert pr < 0.7


# ---- metrics: the relative error that stays relative

def test_nmse_known_and_scale_invariant():
    """NMSE = mean((x-r)^2) / mean(r^2) on a known pair (r = 1, 2; x = 1.1,
    1.8: (0.01 + 0.04) / 2 / 2.5 = 0.01); scaling both images by 0.01 leaves
    it unchanged, while relMSE (its absolute offset 0.01) falls by far more
    than rounding: the negative control that shows why NMSE is added."""
    r = np.array([[[1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]])
    x = np.array([[[1.1, 1.1, 1.1], [1.8, 1.8, 1.8]]])
    close(metrics.nmse(x, r), 0.01, 1e-12, "nmse")
    close(metrics.nmse(0.01 * x, 0.01 * r), metrics.nmse(x, r), 1e-12, "nmse scaled")
    assert metrics.relmse(0.01 * x, 0.01 * r) < 0.05 * metrics.relmse(x, r)
    assert math.isnan(metrics.nmse(x, 0 * r))
    assert metrics.PRIMARY in ("relmse", "nmse")
