"""Shared pieces of the figures: how things are shown.

Owns the matplotlib setup (the Agg backend, font sizes), the colours and
markers every figure uses for a method, an estimate, a photon count and a
representative rule, the provenance footer each figure carries (which CSV or
run directory, seeds, size), the display transform of linear radiance
(sRGB, clipped) and the atomic PNG write. Nothing here computes a statistic
(stats.py) or an image metric (metrics.py).
"""

import os

import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np

# files only, never a window: pyplot's backend is chosen before any figure
plt.switch_backend("Agg")

plt.rcParams.update({
    "font.size": 10, "axes.titlesize": 10.5, "axes.labelsize": 10, "legend.fontsize": 8.5,
    "xtick.labelsize": 9, "ytick.labelsize": 9, "figure.dpi": 100, "savefig.dpi": 100,
    "axes.grid": True, "grid.alpha": 0.3,
})

METHOD_COLOUR = {"conventional": "#1f5fa8", "precomputed": "#c8341c"}
PAPER_COLOUR = "#222222"
# one marker per emitted-photon count, in the order of the grid
PHOTON_MARKERS = ["o", "s", "^", "D", "v", "P"]
# representative rules of the rep-study, in a fixed order of colours
RULE_COLOURS = ["#c8341c", "#e08a1e", "#8a6d00", "#3c8d2f", "#1b9e9e", "#6a51a3", "#b0368a", "#555555",
                "#9c6644", "#2f4b7c"]


def kilo(p):
    """'50k' for 50000, '1.5M' for 1500000, '123' for 123."""
    p = int(p)
    if p >= 1_000_000 and p % 100_000 == 0:
        return f"{p / 1e6:g}M"
    if p >= 1000 and p % 1000 == 0:
        return f"{p // 1000}k"
    return str(p)


def ordinal(k):
    """'1st', '2nd', '3rd', '4th', ..., '11th', '12th', '13th', '21st'."""
    k = int(k)
    suffix = "th" if 10 <= k % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(k % 10, "th")
    return f"{k}{suffix}"


def photon_marker(photons, all_photons):
    """The marker of an emitted-photon count among ALL_PHOTONS (sorted)."""
    order = sorted(set(int(p) for p in all_photons))
    return PHOTON_MARKERS[order.index(int(photons)) % len(PHOTON_MARKERS)]


def footer(fig, text, y=0.004):
    """Write the provenance TEXT (what data, seeds, size) at the bottom of
    FIG in small grey type, wrapped to the figure's width."""
    import textwrap

    width_chars = max(60, int(fig.get_figwidth() * fig.dpi / 6.2))
    wrapped = "\n".join(textwrap.fill(p, width_chars) for p in text.split("\n"))
    fig.text(0.006, y, wrapped, ha="left", va="bottom", fontsize=7.5, color="#444444", wrap=False)


def footer_lines(text, fig_width_in, dpi=100):
    """How many lines footer() will take for TEXT on a figure FIG_WIDTH_IN
    inches wide (to reserve space for it)."""
    import textwrap

    width_chars = max(60, int(fig_width_in * dpi / 6.2))
    return sum(len(textwrap.wrap(p, width_chars)) or 1 for p in text.split("\n"))


def save(fig, path):
    """Save FIG as PNG at PATH through a temporary name and a rename; close
    it; print what was written."""
    d = os.path.dirname(path)
    if d:
        os.makedirs(d, exist_ok=True)
    tmp = f"{path}.tmp.{os.getpid()}.png"
    fig.savefig(tmp, format="png")
    plt.close(fig)
    os.replace(tmp, path)
    print(f"wrote {path}")


def srgb(rgb):
    """Linear RGB radiance (float array, 1.0 = white) as display sRGB in
    [0, 1]: clipped, then the sRGB transfer curve (what the renderer's PNG
    preview shows at exposure 1)."""
    x = np.clip(np.asarray(rgb, dtype=np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def luminance(rgb):
    """Rec. 709 luminance of linear RGB (..., 3)."""
    rgb = np.asarray(rgb, dtype=np.float64)
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def pixel_figure(width_px, height_px, dpi=100):
    """A figure of exactly WIDTH_PX x HEIGHT_PX pixels (saved at DPI), for
    layouts that place images at 1:1 with pixel_axes()."""
    fig = plt.figure(figsize=(width_px / dpi, height_px / dpi), dpi=dpi)
    fig.dpi_px = (width_px, height_px)
    return fig


def pixel_axes(fig, x, y, w, h):
    """Axes at pixel rectangle (X, Y from the top-left, W x H) of a
    pixel_figure, without ticks or frame: an image of W x H pixels shown in
    it with imshow(..., interpolation='nearest') lands 1:1 on the PNG."""
    fw, fh = fig.dpi_px
    ax = fig.add_axes([x / fw, 1 - (y + h) / fh, w / fw, h / fh])
    ax.set_axis_off()
    return ax


def pixel_text(fig, x, y, text, **kw):
    """Text at pixel position (X, Y from the top-left) of a pixel_figure."""
    fw, fh = fig.dpi_px
    kw.setdefault("va", "top")
    kw.setdefault("ha", "left")
    return fig.text(x / fw, 1 - y / fh, text, **kw)


def count_label(v):
    """A count for an axis: '500', '5k', '50k', '1M', '2.5M'."""
    if v >= 1e6:
        return f"{v / 1e6:g}M"
    if v >= 1e3:
        return f"{v / 1e3:g}k"
    return f"{v:g}"


def log_ticks(axis, lo, hi, label=None, extra=()):
    """Major ticks at 1, 2, 5 x 10^k between LO and HI on a logarithmic
    AXIS (ax.xaxis or ax.yaxis), plus the values EXTRA (a reference line's),
    labelled as plain numbers (or by LABEL, a function of the value), no
    minor labels."""
    ticks = [v * 10.0 ** k for k in range(-6, 9) for v in (1, 2, 5) if lo <= v * 10.0 ** k <= hi]
    if len(ticks) < 3:  # a narrow range: evenly spaced plain numbers
        ticks = [float(t) for t in matplotlib.ticker.MaxNLocator(5).tick_values(lo, hi) if lo <= t <= hi and t > 0]
    if len(ticks) > 9:
        ticks = [t for t in ticks if f"{t:g}"[0] in "15"]
    ticks = sorted(set(ticks) | {float(v) for v in extra})
    axis.set_major_locator(matplotlib.ticker.FixedLocator(ticks))
    axis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: label(v) if label else f"{v:g}"))
    axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
