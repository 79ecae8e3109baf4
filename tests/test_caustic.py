"""Tests of experiments/analysis/caustic.py's window enlargement: nearest
neighbour by an integer factor to at least PANEL_MIN_PX wide, every value
the render's own (a control: a smoothing resize would invent values)."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments.analysis import caustic  # noqa: E402


def is_block_enlargement(big, img, k):
    """Whether BIG is IMG with every pixel a k x k block of its own value."""
    if big.shape[:2] != (img.shape[0] * k, img.shape[1] * k):
        return False
    return all((big[y * k:(y + 1) * k, x * k:(x + 1) * k] == img[y, x]).all()
               for y in range(img.shape[0]) for x in range(img.shape[1]))


def test_enlarge_small_window_nearest_neighbour():
    rng = np.random.default_rng(1)
    img = rng.random((5, 6))  # the 6x5 window of a 32x24 render
    big, k = caustic.enlarge(img)
    assert k == 43 and big.shape == (5 * 43, 6 * 43) and big.shape[1] >= caustic.PANEL_MIN_PX
    assert is_block_enlargement(big, img, k)
    assert set(np.unique(big)) == set(np.unique(img))


def test_enlarge_keeps_colour_channels_and_large_windows():
    img = np.arange(160 * 192 * 3, dtype=float).reshape(160, 192, 3)  # the window at 1024x768
    big, k = caustic.enlarge(img)
    assert k == 2 and big.shape == (320, 384, 3)
    assert (big[1, 1] == img[0, 0]).all() and (big[2, 0] == img[1, 0]).all()
    wide = np.zeros((4, 300))
    assert caustic.enlarge(wide)[1] == 1  # already wide enough: unchanged


def test_a_smoothing_resize_is_caught():
    """Negative control of the block check: a bilinear enlargement of the
    same size fails it."""
    from scipy import ndimage
    img = np.random.default_rng(2).random((5, 6))
    smooth = ndimage.zoom(img, 43, order=1)
    assert smooth.shape == (215, 258) and not is_block_enlargement(smooth, img, 43)
