#!/usr/bin/python3
"""figures.py: the figures of `make figures` (experiments/rules/figures.smk).

Owns drawing, from the analysis layer's files and the renders they name:
  fig3.png          the paper's Figure 3 at 1:1: for each (P_e, n) cell a
                    crop of the conventional and the precomputed render (one
                    seed) and their signed difference, with time and error
                    (mean and 95% intervals over seeds) from table1.csv; the
                    POV-Ray reference once.
  fig3-errors.png   per-pixel error against the reference of every cell and
                    method, whole frame, on a logarithmic colour scale.
  fig2.png          the paper's Figure 2 for one real run: the
                    representatives (renderer's --dump-reps) with their
                    precomputed irradiance, the piecewise-constant estimate
                    they give, and the same region in the rendered image.
  tradeoff.png      time against relMSE for every cell, both estimates, with
                    intervals on both axes, and the rep-study's rules.
  ratio-vs-n.png    precomputed / conventional time against n per P_e, ours
                    with paired t intervals and the paper's.
  phases.png        per-phase times (trace, build, precompute, eye pass) of
                    every cell, both methods.
  glance.png        the project at a glance (README): the whole frame of
                    the reference and of both methods at one cell (--glance-
                    cell, else the second of --cells; seed --seed) with time
                    and error, and the speed-up
                    at equal error against the target for both estimates
                    (--equal-error), solid where at least 95% of the
                    bootstrap resamples reach the target on both fronts.
Tables are read with pandas by column name (table1.csv, runs.csv, cells.csv
for the reference, rep-study-cells.csv), images with OpenImageIO
(metrics.read_exr) from the paths runs.csv names;
statistics come from table1.csv (computed by table.py with stats.py) and
image metrics from metrics.py. Every figure names its data in a footer.
Each figure NAME is two functions: NAME_record computes what it shows (the
images, points, intervals, ranges and footer) from the inputs, and
draw_NAME draws that record and nothing else.
"""

import argparse
import math
import os
import re

import numpy as np
import pandas as pd

from experiments.analysis import metrics
from experiments.analysis import plotting
from experiments.analysis import report
from experiments.analysis import scene_info
from experiments.analysis import stats
from experiments.analysis.plotting import kilo, plt
from experiments.analysis.report import fmt, isnum

WHERE = "figures.py"
TABLE_NEED = ["photons", "nn", "method", "seeds", "cpu_median_s", "cpu_min_s", "cpu_max_s", "total_median_s",
              "total_min_s", "total_max_s", "relmse_ref_mean", "relmse_ref_ci95", "relmse_conv_mean",
              "relmse_conv_ci95", "cpu_ratio_percent", "cpu_ratio_ci95_lo", "cpu_ratio_ci95_hi",
              "ratio_percent", "ratio_ci95_lo", "ratio_ci95_hi", "paper_ratio_percent", "trace_median_s",
              "build_median_s", "precompute_median_s", "render_median_s", "width", "height", "subpixels"]


# ---- inputs

def read_csv(path, need, what):
    """report.read_csv for this script ('#' lines are comments)."""
    return report.read_csv(path, need, WHERE, what, comment="#")


def read_image(path, what):
    """An EXR as (H, W, 3) float64; exits naming PATH and WHAT it is."""
    if not os.path.isfile(path):
        report.die(WHERE, f"{path}: missing ({what}); run `make reproduce-table` first")
    try:
        return metrics.read_exr(path)
    except ValueError as e:
        report.die(WHERE, str(e))


def parse_cells(text):
    """'50000:10 100000:100' -> [(50000, 10), (100000, 100)]."""
    cells = []
    for item in text.split():
        m = re.fullmatch(r"(\d+):(\d+)", item)
        if not m:
            report.die(WHERE, f"cell '{item}': expected P_E:N")
        cells.append((int(m.group(1)), int(m.group(2))))
    return cells


def image_path(args, method, photons, nn):
    """The EXR of one render of the grid (paper estimate, seed --seed), as
    runs.csv names it; exits when runs.csv has no such ok render."""
    r = args.runs_frame
    sel = r[(r["method"] == method) & (r["estimate"] == "paper") & (r["photons"] == photons) & (r["nn"] == nn)
            & (r["seed"] == args.seed) & (r["status"] == "ok") & (r["role"] == "grid")]
    if sel.empty:
        report.die(WHERE, f"{args.runs} has no ok render of {method}, paper estimate, P_e={photons}, n={nn}, seed "
                   f"{args.seed}: add it to the grid (PHOTONS, NNS, SEEDS) or change FIG3_CELLS / FIG_SEED")
    return sel["run"].iloc[0] + ".exr"


def table_row(table, photons, nn, method):
    """The table1.csv row of a cell and method; exits when there is none."""
    r = table[(table["photons"] == photons) & (table["nn"] == nn) & (table["method"] == method)]
    if r.empty:
        report.die(WHERE, f"table1.csv has no row for {method} P_e={photons} n={nn}: add it to the grid "
                   "(PHOTONS, NNS) or change FIG3_CELLS")
    return r.iloc[0]


def sfx(estimate):
    """Column suffix of an estimate in table1.csv."""
    return "" if estimate == "paper" else f"_{estimate}"


def time_cols(args):
    """(median, min, max, label) columns of the time the figures show."""
    if args.time == "cpu_s":
        return "cpu_median_s", "cpu_min_s", "cpu_max_s", "CPU s"
    return "total_median_s", "total_min_s", "total_max_s", "wall s"


def time_text(row, args, est="paper"):
    """'3.21 s CPU [3.18-3.30]' for a table row (median, min-max over seeds)."""
    med, lo, hi, label = time_cols(args)
    s = sfx(est)
    return f"{fmt(row[med + s])} {label} [{fmt(row[lo + s])}-{fmt(row[hi + s])}]"


def error_text(row, est="paper"):
    """'relMSE 0.139 ± 0.011' (mean ± 95% t half-width over seeds)."""
    s = sfx(est)
    return f"relMSE {report.fmt_pm(row['relmse_ref_mean' + s], row['relmse_ref_ci95' + s])}"


def provenance(args, extra=""):
    """The footer text shared by the figures of the grid."""
    t = args.table_frame
    first = t.iloc[0]
    size = f"{int(first['width'])}x{int(first['height'])}, {int(first['subpixels'])}x{int(first['subpixels'])} samples"
    seeds = int(t["seeds"].max())
    return (f"Data: {args.table} and {args.runs} ({size}; {seeds} seeds per cell; the renders runs.csv names); "
            f"reference: {args.ref_label} ({args.ref}). Time: {time_cols(args)[3]} (panel captions: median [min-max] over seeds; the trade-off: mean, bars 95% t); "
            f"errors: mean over seeds with 95% t-interval." + (" " + extra if extra else ""))


# ---- Figure 3 at 1:1

def fig3_record(args):
    """What fig3.png shows: per cell of --cells the crops of its two renders
    (seed --seed) and their signed difference over the reference's
    luminance with the row's symmetric range, its table rows and the ratio
    column quoted; the reference's crop and whole frame; the crop window."""
    t = args.table_frame
    cells = parse_cells(args.cells)
    ref = read_image(args.ref, "the reference")
    H, W = ref.shape[:2]
    cw0, ch0, cx, cy = metrics.scale_window(args.crop, args.crop_at, (W, H))
    # small renders: each pixel drawn as a zoom x zoom block, so panels stay legible
    zoom = max(1, math.ceil(300 / cw0))
    crop = lambda img: np.repeat(np.repeat(img[cy:cy + ch0, cx:cx + cw0], zoom, 0), zoom, 1)  # noqa: E731
    rows = []
    for p, n in cells:
        imgs = {}
        for m in ("conventional", "precomputed"):
            path = image_path(args, m, p, n)
            img = read_image(path, f"{m} P_e={p} n={n} seed {args.seed}")
            if img.shape != ref.shape:
                report.die(WHERE, f"{path} is {img.shape[1]}x{img.shape[0]}, the reference {W}x{H}")
            imgs[m] = crop(img)
        lr = np.maximum(plotting.luminance(crop(ref)), 1e-3)
        diff = (plotting.luminance(imgs["precomputed"]) - plotting.luminance(imgs["conventional"])) / lr
        rp = table_row(t, p, n, "precomputed")
        rows.append({"photons": p, "nn": n, "images": imgs, "diff": diff, "conventional": table_row(t, p, n, "conventional"),
                     "precomputed": rp})
        # the paired ratio (per-seed log ratios, t interval) where the table has it, as ratio-vs-n.png
        rcol = "cpu_ratio" if args.time == "cpu_s" else "ratio"
        if isnum(rp.get(f"paired_{rcol}_percent")):
            rcol = "paired_" + rcol
        rows[-1]["rcol"] = rcol
    # each row its own symmetric range (the 99th percentile of that row's
    # |difference|): one range for all rows left rows (b)-(d) blank beside (a)
    for r in rows:
        r["lim"] = float(f"{max(float(np.quantile(np.abs(r['diff']), 0.99)), 1e-3):.1g}")
    return {"cells": cells, "ref": ref, "ref_crop": crop(ref), "size": (W, H), "window": (cw0, ch0, cx, cy),
            "zoom": zoom, "rows": rows, "footer": provenance(args)}


def draw_fig3(rec, args):
    """fig3.png from its record: crops at 1:1 of each cell's two renders and
    their signed difference, the reference once, time and error per panel."""
    cells, rows, ref, zoom = rec["cells"], rec["rows"], rec["ref"], rec["zoom"]
    W, H = rec["size"]
    cw0, ch0, cx, cy = rec["window"]
    cw, ch = cw0 * zoom, ch0 * zoom
    gap, head, cap = 12, 26, 36
    title_h, foot_h = 72, 14 * plotting.footer_lines(rec["footer"], (3 * cw + 4 * gap) / 100) + 10
    row_h = head + ch + cap
    fw = 3 * cw + 4 * gap + 40  # the difference column's colour bars
    fh = title_h + row_h * (len(rows) + 1) + foot_h
    fig = plotting.pixel_figure(fw, fh)
    scale = "1:1" if zoom == 1 else f"{zoom}:1 (each pixel a {zoom}x{zoom} block)"
    plotting.pixel_text(fig, gap, 8, f"Figure 3 at {scale}: conventional | precomputed | precomputed - conventional",
                        fontsize=12, weight="bold")
    plotting.pixel_text(fig, gap, 30, f"Rows (a)-({chr(ord('a') + len(rows) - 1)}): the paper's cells "
                        f"{', '.join(f'({kilo(p)}, {n})' for p, n in cells[:args.paper_cells])}"
                        + (f", and controls {', '.join(f'({kilo(p)}, {n})' for p, n in cells[args.paper_cells:])}"
                           if len(cells) > args.paper_cells else "")
                        + f". Crop {cw0}x{ch0}+{cx}+{cy} of the {W}x{H} renders, seed {args.seed}, paper "
                        "estimate.\nUnder each panel: median time [min-max] and relMSE against the reference "
                        "(mean ± 95% t half-width over seeds).", fontsize=9)
    y = title_h
    # the reference row: crop, the whole frame (reduced, for location only), colour bar
    plotting.pixel_text(fig, gap, y + 4, f"{args.ref_label}: the same crop, and the whole frame (reduced) "
                        "with the crop outlined", fontsize=10, weight="bold")
    ax = plotting.pixel_axes(fig, gap, y + head, cw, ch)
    ax.imshow(plotting.srgb(rec["ref_crop"]), interpolation="nearest")
    tw = int(round(W * ch / H))
    ax = plotting.pixel_axes(fig, 2 * gap + cw, y + head, min(tw, cw), ch)
    ax.imshow(plotting.srgb(ref), interpolation="antialiased", extent=(0, W, H, 0))
    ax.add_patch(plt.Rectangle((cx, cy), cw0, ch0, fill=False, ec="#ffdd00", lw=2))
    cx3 = 3 * gap + 2 * cw
    plotting.pixel_text(fig, cx3 + 4, y + head,
                        "Third column: (precomputed - conventional)\n/ reference, luminance, the same seed.\n"
                        "Each row on its own symmetric range ±L\n(L: that row's 99th percentile of\n|difference|, "
                        "its colour bar beside it;\nclipped). Red: precomputed brighter.\n"
                        "The line along the floor / red-wall\ncrease: there the nearest photons of a\n"
                        "point reach onto the other surface,\nand the precomputed value is taken at\n"
                        "the nearest representative, which may\nlie on either surface, so the two\n"
                        "methods mix the surfaces differently.", fontsize=8.5)
    y += row_h
    for i, row in enumerate(rows):
        p, n, imgs, rc, rp, rcol = row["photons"], row["nn"], row["images"], row["conventional"], row["precomputed"], \
            row["rcol"]
        letter = chr(ord("a") + i)
        kind = "the paper's Fig. 3 cell" if i < args.paper_cells else "control"
        plotting.pixel_text(fig, gap, y + 4, f"({letter}) P_e = {kilo(p)}, n = {n} ({kind})", fontsize=10.5,
                            weight="bold")
        ratio = report.fmt_ci(rp[f"{rcol}_percent"], rp[f"{rcol}_ci95_lo"], rp[f"{rcol}_ci95_hi"], 0)
        for j, (m, r) in enumerate((("conventional", rc), ("precomputed", rp))):
            x = gap + j * (cw + gap)
            ax = plotting.pixel_axes(fig, x, y + head, cw, ch)
            ax.imshow(plotting.srgb(imgs[m]), interpolation="nearest")
            plotting.pixel_text(fig, x, y + head + ch + 3, f"{m}: {time_text(r, args)}\n{error_text(r)}",
                                fontsize=8.5)
        x = gap + 2 * (cw + gap)
        ax = plotting.pixel_axes(fig, x, y + head, cw, ch)
        lim = row["lim"]
        ax.imshow(np.clip(row["diff"], -lim, lim), cmap="RdBu_r", vmin=-lim, vmax=lim, interpolation="nearest")
        cax = plotting.pixel_axes(fig, x + cw + 2, y + head, 8, ch)
        cax.set_axis_on()
        cax.grid(False)
        cb = fig.colorbar(plt.cm.ScalarMappable(cmap="RdBu_r", norm=plt.Normalize(-lim, lim)), cax=cax)
        cb.set_ticks([-lim, 0, lim])
        cb.ax.tick_params(labelsize=7)
        plotting.pixel_text(fig, x, y + head + ch + 3,
                            f"time prec./conv.{' (paired)' if rcol.startswith('paired') else ''} {ratio} %\nrelMSE prec. vs conv., same seed: "
                            f"{report.fmt_pm(rp['relmse_conv_mean'], rp['relmse_conv_ci95'])}", fontsize=8.5)
        y += row_h
    plotting.footer(fig, rec["footer"])
    plotting.save(fig, os.path.join(args.out, "fig3.png"))


def fig3(args):
    """fig3.png (fig3_record, draw_fig3)."""
    draw_fig3(fig3_record(args), args)


# ---- error maps

def fig3_errors_record(args):
    """What fig3-errors.png shows: per cell and method the square root of
    the relMSE integrand against the reference averaged over
    --error-block-square blocks, the render's own relMSE and its table row;
    the colour scale's ends (1% and 99.9% quantiles of every map)."""
    t = args.table_frame
    cells = parse_cells(args.cells)
    ref = read_image(args.ref, "the reference")
    H, W = ref.shape[:2]
    b = max(1, int(args.error_block))
    h2, w2 = H // b, W // b
    wgt = metrics.rel_weight(ref)
    maps = []
    for p, n in cells:
        row = []
        for m in ("conventional", "precomputed"):
            x = read_image(image_path(args, m, p, n), f"{m} P_e={p} n={n}")
            if x.shape != ref.shape:
                report.die(WHERE, f"{image_path(args, m, p, n)}: {x.shape[1]}x{x.shape[0]}, the reference {W}x{H}")
            # the relMSE integrand averaged over channels, then over bxb blocks:
            # the map's mean is the image's relMSE; shown as its square root
            e = (np.square(x - ref) * wgt).mean(axis=2)[:h2 * b, :w2 * b]
            e = e.reshape(h2, b, w2, b).mean(axis=(1, 3))
            row.append((m, np.sqrt(e), table_row(t, p, n, m), metrics.relmse(x, ref)))
        maps.append((p, n, row))
    allv = np.concatenate([r[1].ravel() for _, _, rr in maps for r in rr])
    lo = float(f"{max(np.quantile(allv, 0.01), 1e-4):.1g}")
    hi = float(f"{np.quantile(allv, 0.999):.1g}")
    foot = provenance(args, f"Map: sqrt of the relMSE integrand (x - r)^2 / (r^2 + 0.01), mean over RGB and "
                            f"{b}x{b}-pixel blocks (its square's mean is the image's relMSE), seed {args.seed}.")
    return {"block": b, "shape": (h2, w2), "maps": maps, "range": (lo, hi), "footer": foot}


def draw_fig3_errors(rec, args):
    """fig3-errors.png from its record: the maps of every cell and method,
    whole frame, on a logarithmic colour scale with a colour bar."""
    b, maps, foot = rec["block"], rec["maps"], rec["footer"]
    h2, w2 = rec["shape"]
    lo, hi = rec["range"]
    norm = plt.matplotlib.colors.LogNorm(vmin=lo, vmax=hi)
    zoom = max(1, math.ceil(300 / w2))  # small renders: each block drawn as zoom x zoom pixels
    gap, head, cap = 10, 22, 20
    pw, ph = w2 * zoom, h2 * zoom
    cbar_w = 90
    fw = 2 * pw + 3 * gap + cbar_w
    foot_h = 14 * plotting.footer_lines(foot, fw / 100) + 8
    fh = 40 + len(maps) * (head + ph + cap) + foot_h
    fig = plotting.pixel_figure(fw, fh)
    plotting.pixel_text(fig, gap, 8, f"Error against {args.ref_label}, per {b}x{b}-pixel block, logarithmic scale "
                        f"(seed {args.seed}, paper estimate)", fontsize=12, weight="bold")
    y = 40
    for i, (p, n, row) in enumerate(maps):
        plotting.pixel_text(fig, gap, y + 2, f"({chr(ord('a') + i)}) P_e = {kilo(p)}, n = {n}", fontsize=10.5,
                            weight="bold")
        for j, (m, e, r, this) in enumerate(row):
            x = gap + j * (pw + gap)
            ax = plotting.pixel_axes(fig, x, y + head, pw, ph)
            ax.imshow(np.repeat(np.repeat(e, zoom, 0), zoom, 1), cmap="magma", norm=norm, interpolation="nearest")
            plotting.pixel_text(fig, x, y + head + ph + 2,
                                f"{m}: this seed {fmt(this)}; over seeds {error_text(r)}", fontsize=8.5)
        y += head + ph + cap
    cax = plotting.pixel_axes(fig, 2 * pw + 3 * gap + 8, 60, 18, fh - 60 - foot_h - 30)
    cax.set_axis_on()
    cax.grid(False)
    cb = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="magma"), cax=cax)
    ticks = [v * 10.0 ** k for k in range(-5, 3) for v in (1, 2, 5) if lo <= v * 10.0 ** k <= hi]
    cb.set_ticks(ticks, labels=[f"{v:g}" for v in ticks])
    cb.ax.minorticks_off()
    cb.set_label("relative RMS error per block (log scale)")
    plotting.footer(fig, foot)
    plotting.save(fig, os.path.join(args.out, "fig3-errors.png"))


def fig3_errors(args):
    """fig3-errors.png (fig3_errors_record, draw_fig3_errors)."""
    draw_fig3_errors(fig3_errors_record(args), args)


# ---- Figure 2: the representatives and the cells they make

def scene_facts(args, width, height):
    """The scene's facts with the camera basis of a WIDTH x HEIGHT image
    (`photonmap info --json`, scene_info.py); exits with the renderer's
    message when it refuses the scene."""
    try:
        return scene_info.load(args.scene, args.pm, width, height)
    except scene_info.SceneInfoError as e:
        report.die(WHERE, f"{args.scene}: cannot read the camera: {e}")


def fig2_record(args):
    """What fig2.png shows of the run --fig2-run: its representatives on one
    wall (the plane whose normal is +FIG2_PLANE, at that coordinate's
    minimum: the back wall for z, the floor for y) inside the window with
    their irradiance's luminance and its 1%-99% range; the estimate they
    give on a fine grid of the window (the nearest one within the radius
    cap, as the eye pass looks it up); the window's outline projected into
    the image, the pixels around it and their luminance range inside it."""
    from scipy.spatial import cKDTree

    d = args.fig2_run
    reps = read_csv(d + ".reps.csv", ["x", "y", "z", "nx", "ny", "nz", "e_r", "e_g", "e_b"],
                    "the representatives of the Fig. 2 run (--dump-reps)")
    img = read_image(d + ".exr", "the Fig. 2 run's image")
    st = pd.read_json(d + ".stats.json", typ="series")
    H, W = img.shape[:2]
    axis = args.fig2_plane
    if axis not in ("x", "y", "z"):
        report.die(WHERE, f"FIG2_PLANE '{axis}': expected x, y or z")
    u, v = [a for a in "xyz" if a != axis]
    try:
        u0, u1, v0, v1 = (float(w) for w in args.fig2_window.split())
    except ValueError:
        report.die(WHERE, f"FIG2_WINDOW '{args.fig2_window}': expected four numbers u0 u1 v0 v1")
    facing = reps[reps["n" + axis] > args.normal_cos]
    if facing.empty:
        report.die(WHERE, f"{d}.reps.csv: no representative faces +{axis}")
    at = float(facing[axis].min())
    wall = facing[np.abs(facing[axis] - at) <= 1e-6 * max(1.0, abs(at))]
    e = plotting.luminance(wall[["e_r", "e_g", "e_b"]].to_numpy())
    inwin = ((wall[u] >= u0) & (wall[u] <= u1) & (wall[v] >= v0) & (wall[v] <= v1)).to_numpy()
    if inwin.sum() < 3:
        report.die(WHERE, f"FIG2_WINDOW '{args.fig2_window}' holds {int(inwin.sum())} representatives of the plane "
                   f"{axis} = {at:g}")
    ew = e[inwin]
    # (b): the nearest representative of the plane within the radius cap, on a fine grid
    tree = cKDTree(wall[[u, v]].to_numpy())
    res = 700
    gu = np.linspace(u0, u1, res)
    gv = np.linspace(v0, v1, max(2, int(res * (v1 - v0) / (u1 - u0))))
    GU, GV = np.meshgrid(gu, gv)
    dist, idx = tree.query(np.column_stack([GU.ravel(), GV.ravel()]))
    field = np.where(dist <= float(st["max_radius"]), e[idx], 0.0).reshape(GU.shape)
    # (c): the window's outline in the image and the pixels around it
    corners = np.zeros((4, 3))
    ia, iu, iv = "xyz".index(axis), "xyz".index(u), "xyz".index(v)
    corners[:, ia] = at
    corners[:, iu] = [u0, u1, u1, u0]
    corners[:, iv] = [v0, v0, v1, v1]
    px, py = scene_info.project(scene_facts(args, W, H), corners)
    cx0, cx1 = max(0, int(px.min()) - 4), min(W, int(math.ceil(px.max())) + 4)
    cy0, cy1 = max(0, int(py.min()) - 4), min(H, int(math.ceil(py.max())) + 4)
    if cx1 - cx0 < 2 or cy1 - cy0 < 2:
        report.die(WHERE, f"FIG2_WINDOW '{args.fig2_window}' is not in view of {args.scene}'s camera")
    sub = img[cy0:cy1, cx0:cx1]
    lum = plotting.luminance(sub)
    inside = plt.matplotlib.path.Path(np.column_stack([px, py]))
    yy, xx = np.mgrid[cy0:cy1, cx0:cx1]
    mask = inside.contains_points(np.column_stack([xx.ravel() + 0.5, yy.ravel() + 0.5])).reshape(lum.shape)
    return {"run": d, "stats": st, "size": (W, H), "axis": axis, "u": u, "v": v, "window": (u0, u1, v0, v1),
            "at": at, "on_plane": len(wall), "in_window": int(inwin.sum()), "wall_u": wall[u][inwin],
            "wall_v": wall[v][inwin], "e": ew, "e_range": (float(np.quantile(ew, 0.01)), float(np.quantile(ew, 0.99))),
            "field": field, "outline": (px, py), "pixels": (cx0, cx1, cy0, cy1), "sub": sub, "lum": lum,
            "lum_range": tuple(np.quantile(lum[mask] if mask.any() else lum, [0.01, 0.99]))}


def draw_fig2(rec, args):
    """fig2.png from its record: (a) the representatives on the wall,
    coloured by their precomputed irradiance; (b) the estimate they give
    there, constant around each representative; (c) the same region in the
    rendered image as luminance and (d) as displayed, its pixels enlarged
    without smoothing."""
    d, st, axis, u, v, at = rec["run"], rec["stats"], rec["axis"], rec["u"], rec["v"], rec["at"]
    W, H = rec["size"]
    u0, u1, v0, v1 = rec["window"]
    px, py = rec["outline"]
    cx0, cx1, cy0, cy1 = rec["pixels"]
    ew, field, sub, lum = rec["e"], rec["field"], rec["sub"], rec["lum"]
    norm = plt.Normalize(*rec["e_range"])
    fig = plt.figure(figsize=(19, 6.0))
    rule = (f"a fixed count of {st['rep_count']}" if st.get("rep_count", 0) else
            "every stored photon" if int(st["rep_every"]) == 1 else
            f"every {plotting.ordinal(st['rep_every'])} stored photon")
    foot = (f"Data: {d}.* (.reps.csv from `photonmap render --dump-reps`, .exr and .stats.json of the same render): "
            f"{st['scene']}, precomputed method, P_e = {kilo(st['photons_emitted'])}, n = {st['nn']}, seed "
            f"{st['seed']}, {W}x{H}, {int(st['representatives'])} representatives ({rule}), {rec['on_plane']} on the plane "
            f"{axis} = {at:g}, {rec['in_window']} in the window {u} in [{u0:g}, {u1:g}], {v} in [{v0:g}, {v1:g}]. "
            f"(b) is computed from reps.csv: the representative of this plane nearest to each point (within the "
            f"radius cap {float(st['max_radius']):.3g}; on a plane every normal agrees), i.e. the eye pass's lookup "
            "restricted to the plane; the radiance is rho/pi times this irradiance.")
    gs = fig.add_gridspec(1, 4, left=0.04, right=0.995, top=0.84, bottom=0.2, wspace=0.2)
    flip = axis == "y"  # the floor seen from above: z (towards the camera) downwards
    vlim = (v1, v0) if flip else (v0, v1)
    ax = fig.add_subplot(gs[0, 0])
    sc = ax.scatter(rec["wall_u"], rec["wall_v"], c=ew, cmap="viridis", norm=norm, s=22, edgecolors="none")
    ax2 = fig.add_subplot(gs[0, 1], sharex=ax, sharey=ax)
    ax2.imshow(field, cmap="viridis", norm=norm, extent=(u0, u1, v0, v1), origin="lower", interpolation="nearest")
    ax2.plot(rec["wall_u"], rec["wall_v"], ".", color="white", ms=2, alpha=0.9)
    for a in (ax, ax2):
        a.set_xlim(u0, u1)
        a.set_ylim(*vlim)
        a.set_aspect("equal")
        a.set_xlabel(f"{u} (scene units)")
        a.grid(False)
    ax.set_ylabel(f"{v} (scene units)")
    where = {"x": "the wall x", "y": "the floor", "z": "the back wall"}[axis] + f" ({axis} = {at:g})"
    ax.set_title(f"(a) representatives on {where},\ncoloured by their precomputed irradiance E")
    ax2.set_title("(b) the estimate at every point: E of the nearest\nrepresentative (white dots): constant cells")
    cb = fig.colorbar(sc, ax=[ax, ax2], orientation="horizontal", fraction=0.05, pad=0.12, aspect=50)
    cb.set_label("irradiance E, luminance (W per scene unit^2)")
    lnorm = plt.Normalize(*rec["lum_range"])
    for k, (panel, title) in enumerate((
            (None, f"(c) this run's rendered image: luminance of\npixels {cx0}-{cx1} x {cy0}-{cy1} (radiance = "
                   "rho/pi x E;\nits own colour scale), enlarged without smoothing"),
            (plotting.srgb(sub), "(d) the same pixels as displayed (sRGB):\nthe cells are the blotches of the "
                                 "paper's remark"))):
        a = fig.add_subplot(gs[0, 2 + k])
        if panel is None:
            a.imshow(lum, cmap="viridis", norm=lnorm, interpolation="nearest", extent=(cx0, cx1, cy1, cy0))
        else:
            a.imshow(panel, interpolation="nearest", extent=(cx0, cx1, cy1, cy0))
        a.add_patch(plt.Polygon(np.column_stack([px, py]), closed=True, fill=False, ec="#ff3030", lw=1.2))
        a.set_xlabel("image x (pixels; outline: the window of (a), (b))")
        a.grid(False)
        a.set_title(title)
        if panel is None:
            a.set_ylabel("image y (pixels)")
            cb3 = fig.colorbar(plt.cm.ScalarMappable(cmap="viridis", norm=lnorm), ax=a, orientation="horizontal",
                               fraction=0.05, pad=0.18)
            cb3.set_label("rendered luminance (this panel's scale)")
    fig.suptitle("Figure 2 reproduced: representatives carry precomputed irradiance; the eye pass takes the "
                 "nearest one's, so the radiance is piecewise constant", fontsize=12, weight="bold")
    plotting.footer(fig, foot)
    plotting.save(fig, os.path.join(args.out, "fig2.png"))


def fig2(args):
    """fig2.png (fig2_record, draw_fig2)."""
    draw_fig2(fig2_record(args), args)


# ---- plots of the grid: each has a record function (the points, intervals
# and ranges it shows, from the tables) and a drawing function (from the
# record alone)

def cell_time(args, method, est, photons, nn):
    """(mean, 95% t half-width) over seeds of the time args.time of one
    cell's ok grid renders (runs.csv): the same kind of interval as the
    error's, so both axes carry a 95% t interval of a mean."""
    r = args.runs_frame
    sel = r[(r["status"] == "ok") & (r["role"] == "grid") & (r["method"] == method) & (r["estimate"] == est)
            & (r["photons"] == photons) & (r["nn"] == nn)]
    return stats.t_interval(sel[args.time].to_numpy(float)) if args.time in sel else (math.nan, math.nan)


def errbar_points(t, est, args):
    """Mean time against mean relMSE of the rows T of table1.csv for
    estimate EST, both with 95% t intervals over seeds, in order of n, the
    points without both means left out: a dict of arrays x, xh (time
    half-width), y, ye (error half-width)."""
    s = sfx(est)
    t = t.sort_values("nn")
    tm = [cell_time(args, r["method"], est, r["photons"], r["nn"]) for _, r in t.iterrows()]
    x = np.array([m for m, _ in tm], dtype=float)
    xh = np.nan_to_num(np.array([h for _, h in tm], dtype=float))
    y = t["relmse_ref_mean" + s].to_numpy(float)
    ok = np.isfinite(x) & np.isfinite(y)
    if not ok.any():
        return {"x": np.array([]), "xh": np.array([]), "y": np.array([]), "ye": np.array([])}
    return {"x": x[ok], "xh": xh[ok], "y": y[ok], "ye": np.nan_to_num(t["relmse_ref_ci95" + s].to_numpy(float)[ok])}


def draw_errbar(ax, pts, colour, marker, label, **kw):
    """The points PTS (errbar_points) with their intervals on both axes,
    joined in order; nothing when there are none."""
    x, xh, y, ye = pts["x"], pts["xh"], pts["y"], pts["ye"]
    if not x.size:
        return
    ax.errorbar(x, y, xerr=[np.minimum(xh, x * 0.999), xh], yerr=[np.minimum(ye, y * 0.999), ye], fmt=marker + "-",
                color=colour, label=label, ms=6, lw=1.1, capsize=2, elinewidth=0.9, **kw)


def draw_front(ax, x, y, idx, colour, label):
    """The Pareto front IDX (stats.pareto_front) of the points (X time, Y
    error) as the equal-error analysis interpolates it: straight segments in
    log-log between the front's cells (stats.time_at_error)."""
    if len(idx) >= 2:
        ax.plot(np.asarray(x)[idx], np.asarray(y)[idx], "--", color=colour, lw=2.2, alpha=0.55, zorder=0, label=label)


def tradeoff_record(args):
    """What tradeoff.png shows: per estimate, method and P_e the cells'
    points (errbar_points) and each method's Pareto front; the rep-study's
    rules at one P_e (the largest, where they differ most) against its
    conventional cells; the axes' ranges from the cells' means."""
    t = args.table_frame
    estimates = ["paper"] + (["corrected"] if "relmse_ref_mean_corrected" in t
                             and t["relmse_ref_mean_corrected"].notna().any() else [])
    rs = None
    if args.rep_study_cells and os.path.isfile(args.rep_study_cells):
        rs = read_csv(args.rep_study_cells, ["rule", "label", "photons", "nn", "time_median_s", "time_min_s",
                                             "time_max_s", "relmse_ref_mean", "relmse_ref_ci95"], "rep-study cells")
    allp = sorted(set(t["photons"]))
    panels = []
    for est in estimates:
        methods = []
        for m in ("conventional", "precomputed"):
            lines = [(p, errbar_points(t[(t["method"] == m) & (t["photons"] == p)], est, args)) for p in allp]
            xs = [v for _, pts in lines for v in pts["x"]]
            ys = [v for _, pts in lines for v in pts["y"]]
            methods.append({"method": m, "lines": lines, "front_x": xs, "front_y": ys,
                            "front": stats.pareto_front(xs, ys)})
        panels.append({"estimate": est, "methods": methods})
    rules = None
    if rs is not None:
        pr = max(set(rs["photons"]) & set(allp)) if set(rs["photons"]) & set(allp) else max(rs["photons"])
        conv = errbar_points(t[(t["method"] == "conventional") & (t["photons"] == pr)], "paper", args)
        lines = []
        for j, rule in enumerate(dict.fromkeys(rs["rule"])):
            r = rs[(rs["rule"] == rule) & (rs["photons"] == pr)].sort_values("nn")
            if r.empty:
                continue
            x = r["time_median_s"].to_numpy(float)
            lines.append({"index": j, "label": r["label"].iloc[0], "x": x, "y": r["relmse_ref_mean"].to_numpy(float),
                          "lo": x - r["time_min_s"], "hi": r["time_max_s"] - x,
                          "ye": np.nan_to_num(r["relmse_ref_ci95"].to_numpy(float))})
        rules = {"photons": pr, "conventional": conv, "lines": lines}
    # the y range from the cells' means (few seeds give long error bars: they are clipped at the axes)
    ys = [t["relmse_ref_mean" + sfx(e)] for e in estimates] + ([rs["relmse_ref_mean"]] if rs is not None else [])
    ys = np.concatenate([np.asarray(v, dtype=float) for v in ys])
    ys = ys[np.isfinite(ys) & (ys > 0)]
    # the x range from the cells' mean times too (bars past it are clipped)
    xs = np.array([cell_time(args, r["method"], e, r["photons"], r["nn"])[0] for e in estimates
                   for _, r in t.iterrows()], dtype=float)
    xs = xs[np.isfinite(xs) & (xs > 0)]
    return {"photons": allp, "panels": panels, "rules": rules,
            "xlim": (xs.min() / 1.3, xs.max() * 1.3) if xs.size else None,
            "ylim": (ys.min() / 1.6, ys.max() * 1.6) if ys.size else None,
            "footer": provenance(args, (f"Rep-study points: {args.rep_study_cells} (their seeds; error bars reaching "
                                        "past the axes are clipped)." if rs is not None else
                                        "No rep-study data (run `make rep-study` to add its rules)."))}


def draw_tradeoff(rec, args):
    """tradeoff.png from its record: time against relMSE, with intervals on
    both axes: (a) the paper estimate, (b) the corrected one, (c) the
    rep-study's rules."""
    npanel = len(rec["panels"]) + (1 if rec["rules"] is not None else 0)
    fig, axes = plt.subplots(1, npanel, figsize=(max(6.2 * npanel, 9.0), 7.6), sharey=True, squeeze=False)
    axes = axes[0]
    allp = rec["photons"]
    shades = {"conventional": ["#9ecae1", "#3182bd", "#08306b"], "precomputed": ["#fcae91", "#e6550d", "#7f2704"]}
    for k, panel in enumerate(rec["panels"]):
        ax = axes[k]
        for m in panel["methods"]:
            for i, (p, pts) in enumerate(m["lines"]):
                draw_errbar(ax, pts, shades[m["method"]][i % 3], plotting.photon_marker(p, allp),
                            f"{m['method']}, P_e = {kilo(p)}")
            draw_front(ax, m["front_x"], m["front_y"], m["front"], shades[m["method"]][1],
                       f"{m['method']} front (log-log interpolation of the equal-error number)")
        est = panel["estimate"]
        ax.set_title(f"({chr(ord('a') + k)}) {est} estimate" + (" (--bias-correction)" if est == "corrected" else ""))
    if rec["rules"] is not None:
        ax = axes[-1]
        pr = rec["rules"]["photons"]
        draw_errbar(ax, rec["rules"]["conventional"], "#888888", plotting.photon_marker(pr, allp), "conventional")
        for r in rec["rules"]["lines"]:
            col = plotting.RULE_COLOURS[r["index"] % len(plotting.RULE_COLOURS)]
            x, y, ye = r["x"], r["y"], r["ye"]
            ax.errorbar(x, y, xerr=[r["lo"], r["hi"]], yerr=[np.minimum(ye, y * 0.999), ye],
                        fmt=plotting.photon_marker(pr, allp) + "-", color=col, ms=5, lw=1, capsize=1.5,
                        label=r["label"])
        ax.set_title(f"({chr(ord('a') + npanel - 1)}) representative rules at P_e = {kilo(pr)} "
                     "(paper estimate; rep-study)")
    tl = time_cols(args)[3]
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"mean time, {tl} (1 thread; bars: 95% t over seeds, as the error's)")
        ax.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2)
        if rec["xlim"] is not None:
            ax.set_xlim(*rec["xlim"])
        plotting.log_ticks(ax.xaxis, *ax.get_xlim())
    if rec["ylim"] is not None:
        axes[0].set_ylim(*rec["ylim"])
    plotting.log_ticks(axes[0].yaxis, *axes[0].get_ylim())
    axes[0].set_ylabel(f"relMSE against {args.ref_label}")
    fig.suptitle("Speed against accuracy: each line one method and P_e,\nn = 10, 20, 50, 100 from top to "
                 "bottom (markers: P_e); dashed: each method's Pareto front", fontsize=11 if npanel > 1 else 9.5,
                 weight="bold")
    foot = rec["footer"]
    fig.subplots_adjust(left=0.08, right=0.99, top=0.88, bottom=0.3 + 0.02 * plotting.footer_lines(foot, 6.2 * npanel))
    plotting.footer(fig, foot)
    plotting.save(fig, os.path.join(args.out, "tradeoff.png"))


def tradeoff(args):
    """tradeoff.png (tradeoff_record, draw_tradeoff)."""
    draw_tradeoff(tradeoff_record(args), args)


def ratio_vs_n_record(args):
    """What ratio-vs-n.png shows: per P_e the precomputed / conventional
    time (%) against n, ours with the t interval of the paired per-seed log
    ratio (a table1.csv without paired columns: its ratio of medians with
    the bootstrap interval) for each estimate the table has, the paper's
    (single runs, no interval), and the y range."""
    t = args.table_frame
    pre = t[t["method"] == "precomputed"]
    cpu = args.time == "cpu_s"
    col, lo, hi = ("cpu_ratio_percent", "cpu_ratio_ci95_lo", "cpu_ratio_ci95_hi") if cpu else \
        ("ratio_percent", "ratio_ci95_lo", "ratio_ci95_hi")
    # the paired ratio (per-seed log ratios, t interval) where the table has it
    paired = ("paired_" + col) in args.table_frame
    if paired:
        col, lo, hi = "paired_" + col, "paired_" + lo, "paired_" + hi
    ymax = 100
    panels = []
    for p in sorted(set(pre["photons"])):
        g = pre[pre["photons"] == p].sort_values("nn")
        ours = []
        for est in ("paper", "corrected"):
            s = sfx(est)
            if col + s not in g or not g[col + s].notna().any():
                continue
            y = g[col + s].to_numpy(float)
            ours.append({"estimate": est, "nn": g["nn"].to_numpy(), "y": y,
                         "err": np.nan_to_num([y - g[lo + s].to_numpy(float), g[hi + s].to_numpy(float) - y])})
            ymax = max(ymax, np.nanmax(g[hi + s]))
        paper = None
        if g["paper_ratio_percent"].notna().any():
            paper = (g["nn"].to_numpy(), g["paper_ratio_percent"].to_numpy())
            ymax = max(ymax, g["paper_ratio_percent"].max())
        panels.append({"photons": p, "nns": sorted(set(g["nn"])), "ours": ours, "paper": paper})
    foot = provenance(args, ("Ours: paired ratio (the geometric mean of the per-seed ratios of the two renders of "
                             "one seed, rendered back to back), 95% t interval over seeds. " if paired else "") +
                      "Without paired columns: ratio of the median times, interval from resampling the seeds of both cells "
                            "(table.py); offsets along n only separate the estimates.")
    return {"panels": panels, "paired": paired, "cpu": cpu, "ymax": ymax, "footer": foot}


def draw_ratio_vs_n(rec, args):
    """ratio-vs-n.png from its record, one panel per P_e."""
    panels = rec["panels"]
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels), 5), sharey=True, squeeze=False)
    style = {"paper": ("o-", 0.97), "corrected": ("s--", 1.03)}
    for ax, pan in zip(axes[0], panels):
        for o in pan["ours"]:
            est = o["estimate"]
            fmt_, off = style[est]
            ax.errorbar(o["nn"] * off, o["y"], yerr=o["err"], fmt=fmt_, color=plotting.METHOD_COLOUR["precomputed"]
                        if est == "paper" else "#e08a1e", capsize=3, ms=6,
                        label=f"ours, {est} estimate (95% {'paired t' if rec['paired'] else 'bootstrap'})")
        if pan["paper"] is not None:
            ax.plot(*pan["paper"], "*-", color=plotting.PAPER_COLOUR, ms=10,
                    label="paper, Table 1 (one run per cell)")
        ax.axhline(100, color="#777777", lw=1, ls=":")
        ax.text(min(pan["nns"]), 101, "equal time", fontsize=8, color="#555555", va="bottom")
        ax.set_xscale("log")
        ax.set_xticks(pan["nns"], [str(v) for v in pan["nns"]])
        ax.set_xlabel("n (nearest photons)")
        ax.set_title(f"P_e = {kilo(pan['photons'])}")
    for ax in axes[0]:
        ax.set_ylim(0, rec["ymax"] * 1.08)
    axes[0][0].set_ylabel(f"precomputed / conventional time, % ({'CPU' if rec['cpu'] else 'wall'})")
    axes[0][0].legend(fontsize=8, loc="lower left")
    fig.suptitle("The comparable quantity: time of the precomputed method relative to the conventional one",
                 fontsize=11.5, weight="bold")
    foot = rec["footer"]
    fig.subplots_adjust(left=0.07, right=0.99, top=0.86, wspace=0.08,
                        bottom=0.13 + 0.025 * plotting.footer_lines(foot, 4.6 * len(panels)))
    plotting.footer(fig, foot)
    plotting.save(fig, os.path.join(args.out, "ratio-vs-n.png"))


def ratio_vs_n(args):
    """ratio-vs-n.png (ratio_vs_n_record, draw_ratio_vs_n)."""
    draw_ratio_vs_n(ratio_vs_n_record(args), args)


def phase_medians(args):
    """{(photons, nn, method): {phase: seconds}}: per render of the paper
    estimate, each phase's wall-clock time times the render's CPU / wall
    ratio (cpu_s / total_s: the share of the wall clock the process ran,
    so on a quiet machine the factor is about 1 and on a shared one the
    phases add up to the CPU time), then the median over seeds."""
    r = args.runs_frame
    r = r[(r["status"] == "ok") & (r["role"] == "grid") & (r["estimate"] == "paper")]
    out = {}
    for (p, n, m), g in r.groupby(["photons", "nn", "method"]):
        f = (g["cpu_s"] / g["total_s"]).to_numpy(float) if args.time == "cpu_s" else np.ones(len(g))
        out[(int(p), int(n), m)] = {ph: stats.median_range(g[f"{ph}_s"].to_numpy(float) * f)[0]
                                    for ph in ("trace", "build", "precompute", "render")}
    return out


PHASES = [("trace", "trace photons", "#8c8c8c"), ("build", "build kd-tree", "#c7b37a"),
          ("precompute", "precompute at representatives", "#e6550d"), ("render", "eye pass", "#3182bd")]


def phases_record(args):
    """What phases.png shows: per P_e and n of the table the per-phase
    median times of each method (phase_medians, a missing phase as 0), and
    the renders' median load average."""
    t = args.table_frame
    med = phase_medians(args)
    panels = []
    for p in sorted(set(t["photons"])):
        ns = sorted(set(t[t["photons"] == p]["nn"]))
        bars = {}
        for n in ns:
            for m in ("conventional", "precomputed"):
                r = med.get((int(p), int(n), m))
                if r is not None:
                    bars[(n, m)] = {k: float(r[k]) if isnum(r[k]) else 0.0 for k, _, _ in PHASES}
        panels.append({"photons": p, "nns": ns, "bars": bars})
    load = args.runs_frame.loc[args.runs_frame["status"] == "ok", "loadavg_1min"]
    foot = provenance(args, "Phases: the renderer's monotonic clock per phase (runs.csv *_s from the stats JSON)"
                            + (", scaled per render by its CPU seconds / wall seconds (cpu_s / total_s) so that a "
                               "shared machine's waiting is left out" if args.time == "cpu_s" else "")
                            + "; median over seeds of each phase on its own, so they need not add up to the median "
                            f"total. 1-minute load average at the renders' start: median {fmt(load.median())} on "
                            f"{os.cpu_count()} cores.")
    return {"panels": panels, "footer": foot}


def draw_phases(rec, args):
    """phases.png from its record: the phases stacked per cell, both
    methods, one panel per P_e."""
    panels = rec["panels"]
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels), 5.2), sharey=True, squeeze=False)
    for ax, pan in zip(axes[0], panels):
        ns = pan["nns"]
        for i, n in enumerate(ns):
            for j, m in enumerate(("conventional", "precomputed")):
                r = pan["bars"].get((n, m))
                if r is None:
                    continue
                x = i + (j - 0.5) * 0.38
                bottom = 0.0
                for key, label, colour in PHASES:
                    v = r[key]
                    ax.bar(x, v, 0.36, bottom=bottom, color=colour, edgecolor="white", lw=0.5,
                           label=label if (i, j) == (0, 1) or (key != "precompute" and (i, j) == (0, 0)) else None)
                    bottom += v
                ax.text(x, bottom, "C" if m == "conventional" else "P", ha="center", va="bottom", fontsize=8)
        ax.set_xticks(range(len(ns)), [f"n={n}" for n in ns])
        ax.set_title(f"P_e = {kilo(pan['photons'])}   (C: conventional, P: precomputed)")
        ax.grid(axis="x", visible=False)
    axes[0][0].set_ylabel("seconds per phase, median over seeds\n" + ("(CPU-scaled wall clock, 1 thread)"
                                                                      if args.time == "cpu_s" else "(wall clock, 1 thread)"))
    handles, labels = axes[0][0].get_legend_handles_labels()
    order = [labels.index(lab) for _, lab, _ in PHASES if lab in labels]
    axes[0][0].legend([handles[i] for i in order], [labels[i] for i in order], fontsize=8, loc="upper left")
    fig.suptitle("Where the time goes: the precomputed method moves kNN work from the eye pass to the "
                 "precompute", fontsize=11.5, weight="bold")
    foot = rec["footer"]
    fig.subplots_adjust(left=0.07, right=0.99, top=0.87, wspace=0.06,
                        bottom=0.1 + 0.025 * plotting.footer_lines(foot, 4.6 * len(panels)))
    plotting.footer(fig, foot)
    plotting.save(fig, os.path.join(args.out, "phases.png"))


def phases(args):
    """phases.png (phases_record, draw_phases)."""
    draw_phases(phases_record(args), args)


def downsample(img, f):
    """IMG (H, W, 3) averaged over F x F blocks (the edge rows and columns
    that do not fill a block dropped)."""
    H, W = (img.shape[0] // f) * f, (img.shape[1] // f) * f
    return img[:H, :W].reshape(H // f, f, W // f, f, 3).mean(axis=(1, 3))


def glance_record(args):
    """What glance.png shows: the reference and the two renders of
    --glance-cell (paper estimate, seed --seed), whole frame, halved until
    at most 512 wide, with their table rows; the equal-error curve of each
    estimate (equal-error.csv, kind curve) with its band and which targets
    at least equal_error.DEFINED_MIN of the resamples reach."""
    from experiments.analysis import equal_error
    fig3_cells = parse_cells(args.cells)
    (p, n), = parse_cells(args.glance_cell) if args.glance_cell else [fig3_cells[min(1, len(fig3_cells) - 1)]]
    ref = read_image(args.ref, "the reference")
    f = 1
    while ref.shape[1] // f > 512:
        f *= 2
    imgs = {"reference": downsample(ref, f)}
    for m in ("conventional", "precomputed"):
        imgs[m] = downsample(read_image(image_path(args, m, p, n), f"{m} P_e={p} n={n} seed {args.seed}"), f)
    curves = {}
    if args.equal_error and os.path.isfile(args.equal_error):
        e = read_csv(args.equal_error, ["estimate", "kind", "target", "speedup", "lo", "hi", "defined_fraction"],
                     "run `make reproduce-table` first")
        for est, g in e[e["kind"] == "curve"].groupby("estimate", sort=False):
            g = g.sort_values("target")
            curves[est] = {k: g[k].to_numpy(np.float64) for k in ("target", "speedup", "lo", "hi", "defined_fraction")}
    t = args.table_frame
    return {"cell": (p, n), "images": imgs, "factor": f, "rows": {m: table_row(t, p, n, m) for m in
            ("conventional", "precomputed")}, "curves": curves, "defined_min": equal_error.DEFINED_MIN,
            "footer": provenance(args, f" Equal error: {args.equal_error}.")}


def draw_glance(rec, args):
    """glance.png from its record."""
    p, n = rec["cell"]
    fig = plt.figure(figsize=(13.5, 8.6))
    titles = {"reference": args.ref_label[0].upper() + args.ref_label[1:],
              "conventional": f"conventional (eq. 1), P_e = {kilo(p)}, n = {n}",
              "precomputed": f"precomputed (eq. 2), P_e = {kilo(p)}, n = {n}"}
    for i, m in enumerate(("reference", "conventional", "precomputed")):
        ax = fig.add_axes([0.01 + i * 0.33, 0.50, 0.31, 0.42])
        ax.imshow(plotting.srgb(rec["images"][m]), interpolation="antialiased")
        ax.set_axis_off()
        ax.set_title(titles[m], fontsize=10)
        if m != "reference":
            r = rec["rows"][m]
            ax.text(0.0, -0.03, f"{time_text(r, args)} (median over seeds)\n{error_text(r)} (mean ± 95% over seeds)",
                    transform=ax.transAxes, va="top", fontsize=9)
    ax = fig.add_axes([0.08, 0.10, 0.88, 0.28])
    colours = {"paper": "#c0392b", "corrected": "#2471a3"}
    for est, c in rec["curves"].items():
        col = colours.get(est, "black")
        ok = c["defined_fraction"] >= rec["defined_min"]
        ax.fill_between(c["target"], c["lo"], c["hi"], where=ok, color=col, alpha=0.18, linewidth=0)
        ax.plot(c["target"], c["speedup"], color=col, alpha=0.35, linestyle=":")
        ax.plot(np.where(ok, c["target"], np.nan), np.where(ok, c["speedup"], np.nan), color=col,
                label=f"{est} estimate (band: 95% bootstrap)")
    ax.axhline(1.0, color="grey", linewidth=0.8)
    ax.set_xscale("log")
    ax.set_xlabel("relMSE target (error both methods must reach)")
    ax.set_ylabel("speed-up at equal error\n(conventional / precomputed time)")
    ax.set_title(f"What the precomputation buys on the paper's scene (P_e and n chosen per method at each target):\n"
                 f"solid where at least {100 * rec['defined_min']:.0f}% of the bootstrap resamples reach the target "
                 "on both fronts, dotted elsewhere", fontsize=9.5, loc="left")
    if rec["curves"]:
        ax.legend(fontsize=8.5, loc="best")
    else:
        ax.text(0.5, 0.5, "no equal-error curve (equal-error.csv missing)", transform=ax.transAxes, ha="center")
    fig.suptitle("The paper's scene at a glance", fontsize=13, weight="bold", x=0.01, ha="left")
    plotting.footer(fig, rec["footer"])
    plotting.save(fig, os.path.join(args.out, "glance.png"))


def glance(args):
    """glance.png (glance_record, draw_glance)."""
    draw_glance(glance_record(args), args)


FIGURES = {"fig3": fig3, "fig3-errors": fig3_errors, "fig2": fig2, "tradeoff": tradeoff, "ratio-vs-n": ratio_vs_n,
           "phases": phases, "glance": glance}


def main():
    """Command line: see the module docstring and experiments/rules/figures.smk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--table", required=True, help="table1.csv of the FIG_SIZE grid")
    ap.add_argument("--runs", required=True, help="runs.csv of the same grid")
    ap.add_argument("--cells-csv", required=True, help="cells.csv of the same grid (names its reference)")
    ap.add_argument("--ref", default="", help="reference EXR (default: the one cells.csv names)")
    ap.add_argument("--ref-label", default="", help="what the reference is (default: from its file name)")
    ap.add_argument("--cells", default="50000:10 100000:100 500000:100 50000:100 500000:10")
    ap.add_argument("--paper-cells", type=int, default=3, help="how many of --cells are the paper's")
    ap.add_argument("--seed", type=int, default=1, help="the seed whose images are shown")
    ap.add_argument("--crop", default="384x288+150+440", help="Fig. 3 crop WxH+X+Y, given at --crop-at")
    ap.add_argument("--crop-at", default="1024x768")
    ap.add_argument("--error-block", type=int, default=2)
    ap.add_argument("--fig2-run", default="", help="the Fig. 2 render's files without their extensions (the run "
                    "layout's CELL/seedK): .reps.csv, .exr, .stats.json")
    ap.add_argument("--fig2-plane", default="z", help="the plane of Fig. 2: normal +x, +y or +z, at the lowest "
                    "such coordinate (z: the back wall, y: the floor)")
    ap.add_argument("--fig2-window", default="-0.4 0.2 1.0 1.45",
                    help="window 'u0 u1 v0 v1' on that plane (u, v: the other two axes in x, y, z order)")
    ap.add_argument("--normal-cos", type=float, default=0.9)
    ap.add_argument("--scene", default="scenes/cornell.scene")
    ap.add_argument("--pm", default=scene_info.DEFAULT_PM, help="the renderer, for the scene's camera (photonmap info)")
    ap.add_argument("--rep-study-cells", default="", help="rep-study-cells.csv (optional)")
    ap.add_argument("--equal-error", default="", help="the grid's equal-error.csv (glance.png; optional)")
    ap.add_argument("--glance-cell", default="", help="glance.png's cell P_E:N (empty: the second of --cells)")
    ap.add_argument("--time", default="cpu_s", choices=sorted(report.TIME_LABEL))
    ap.add_argument("--out", required=True, help="output directory")
    ap.add_argument("--only", default="", help="draw only these figures (space-separated names)")
    args = ap.parse_args()
    args.table_frame = read_csv(args.table, TABLE_NEED, "run `make reproduce-table` first")
    args.runs_frame = read_csv(args.runs, ["method", "estimate", "photons", "nn", "seed", "status", "role", "run",
                                           "loadavg_1min", "cpu_s", "total_s", "trace_s", "build_s", "precompute_s",
                                           "render_s"], "run `make reproduce-table` first")
    cells = read_csv(args.cells_csv, ["ref"], "run `make reproduce-table` first")
    if not args.ref:
        refs = cells["ref"].dropna()
        if refs.empty or not str(refs.iloc[0]):
            report.die(WHERE, f"{args.cells_csv} names no reference (the grid had none of its size): set FIG_REF")
        args.ref = str(refs.iloc[0])
    if not args.ref_label:
        base = os.path.basename(args.ref)
        args.ref_label = ("the POV-Ray reference" if base.startswith(("cornell-reference", "caustic-reference"))
                          else f"the reference {base}")
    names = args.only.split() or list(FIGURES)
    for n in names:
        if n not in FIGURES:
            report.die(WHERE, f"unknown figure '{n}' (one of {', '.join(FIGURES)})")
        if n == "fig2" and not args.fig2_run:
            report.die(WHERE, "fig2 needs --fig2-run")
        FIGURES[n](args)


if __name__ == "__main__":
    main()
