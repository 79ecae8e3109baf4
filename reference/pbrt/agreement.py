"""agreement.py: the three references' agreement, region by region.

Usage (reference/measure-pbrt.sh runs it):
  python3 reference/pbrt/agreement.py OUT.md SCENE:W:H:POV_EXR:PM_DIR:PM_HALF_DIR ...

Writes OUT.md (a table per scene) and, beside it, OUT.csv with the same
rows as numbers (CSV_FIELDS; empty where a value is undefined), which
`make findings` reads for its section on the three references.

For each scene: the regions are the pixels whose four subpixel rays (the
renderer's 2x2 points (x + (s + 0.5)/2) / W) all hit one shape first; this
file casts those rays itself (numpy, on the spheres, rectangles and camera
basis `photonmap info --json` gives) since the renderer writes no shape ids.
In each region it takes the mean of the RGB mean over its pixels, per
image, and reports, as ratios to pbrt (BDPT to 24 bounces + path tracing
25-64, the mean over its seeds):
  - photonmap converged (every PM_DIR/*.exr: one per seed), mean of seeds;
  - POV-Ray's reference preset (one render, no seed noise known);
  - photonmap's kernel bias: the corrected estimate's bias falls as the
    kernel's area, i.e. as 1/photons at fixed n, so (half - full)/pbrt, the
    mean of PM_HALF_DIR's seeds less PM_DIR's, estimates the bias of the
    full-photon render itself.
Intervals: t intervals (95%) over seeds of the per-seed region means (pbrt,
photonmap), combined in quadrature for the ratio. BDPT fireflies: a region
mean of one seed is an average over many pixels, and the interval comes
from the spread of those means between independent seeds, so a firefly
widens the interval instead of hiding; as a check, `robust` is the region
mean of the per-pixel median over pbrt's seeds divided by the mean one
(a firefly-dominated region reads well below 1; a skewed but clean one a
little below 1).
The verdict column is worded by the rules in verdict() below.
"""
import csv
import glob
import math
import os
import sys

import numpy as np
from scipy import stats

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
from experiments.analysis import scene_info  # noqa: E402


def read_exr(path):
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise SystemExit(f"agreement.py: cannot read {path}: {oiio.geterror()}")
    img = np.asarray(inp.read_image("float"), dtype=np.float64)[:, :, :3]
    inp.close()
    return img


def box_down(img, w, h):
    """Box-downsample img to w x h (an integer factor)."""
    fy, fx = img.shape[0] // h, img.shape[1] // w
    assert fy * h == img.shape[0] and fx * w == img.shape[1] and fx == fy
    return img.reshape(h, fy, w, fx, 3).mean(axis=(1, 3))


def shape_ids(scene, w, h):
    """(h, w, 4) index of the first shape each 2x2 subpixel ray hits (-1:
    none), and the shapes [(kind, params, material)]: the camera basis and
    the shapes as the renderer reads them (`photonmap info --json`)."""
    info = scene_info.load(scene, width=w, height=h)
    b = info["camera"]["basis"]
    pos, fwd, right, up = (np.array(b[k], dtype=float) for k in ("origin", "forward", "right", "up"))
    shapes = [(sh["kind"], {k: ([v] if k == "radius" else v) for k, v in sh.items()}, sh["material"])
              for sh in info["shapes"]]
    ys, xs, ss = np.meshgrid(np.arange(h), np.arange(w), np.arange(4), indexing="ij")
    u = (xs + (ss % 2 + 0.5) / 2) / w
    v = (ys + (ss // 2 + 0.5) / 2) / h
    d = fwd + (2 * u - 1)[..., None] * right + (1 - 2 * v)[..., None] * up
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    d = d.reshape(-1, 3)
    best = np.full(d.shape[0], np.inf)
    ids = np.full(d.shape[0], -1)
    for k, (kind, kv, _) in enumerate(shapes):
        if kind == "sphere":
            oc = pos - np.array(kv["center"])
            b = d @ oc
            c = oc @ oc - kv["radius"][0] ** 2
            disc = b * b - c
            ok = disc >= 0
            sq = np.sqrt(np.where(ok, disc, 0))
            t0, t1 = -b - sq, -b + sq
            t = np.where(t0 > 1e-9, t0, t1)
            ok &= t > 1e-9
        else:
            corner, e1, e2 = (np.array(kv[n]) for n in ("corner", "edge1", "edge2"))
            n = np.cross(e1, e2)
            dn = d @ n
            with np.errstate(divide="ignore", invalid="ignore"):
                t = ((corner - pos) @ n) / dn
            ok = np.isfinite(t) & (t > 1e-9)
            p = pos + np.where(ok, t, 0)[:, None] * d - corner
            a = p @ e1 / (e1 @ e1)
            bb = p @ e2 / (e2 @ e2)
            ok &= (a >= 0) & (a <= 1) & (bb >= 0) & (bb <= 1)
        closer = ok & (t < best)
        best[closer] = t[closer]
        ids[closer] = k
    return ids.reshape(h, w, 4), shapes


def tint(x, df):
    """Half-width of the 95% t interval of the mean of x (len df+1)."""
    return stats.t.ppf(0.975, df) * np.std(x, ddof=1) / math.sqrt(len(x)) if len(x) > 1 else float("nan")


def verdict(kind_name, r_pm, e_pm, r_pov, e_pb):
    """Which reference holds in a region, and why (the rules, worded)."""
    if kind_name == "-":
        return "mixed: see the regions"
    agree = abs(r_pm - 1) <= max(e_pm, 0.005)
    pov_ok = r_pov is not None and abs(r_pov - 1) <= 0.02 + e_pb
    if kind_name in ("mirror", "glass"):
        if agree:
            return "pbrt and photonmap agree"
        return ("photonmap (BDPT cannot sample a caustic seen via a specular surface)"
                if r_pm > 1 else "undetermined: photonmap below pbrt on a specular surface")
    if agree and pov_ok:
        return "all three agree"
    if agree:
        return "pbrt and photonmap agree; POV-Ray off by more than 2% plus pbrt's noise"
    return "pbrt and photonmap disagree beyond their noise: undetermined"


CSV_FIELDS = ("scene", "size", "region", "shape", "kind", "material", "material_kind", "pixels", "pbrt_mean",
              "pbrt_ci", "robust", "pbrt_seeds", "pm_ratio", "pm_ci", "pm_bias", "pm_seeds", "pov_ratio", "holds")


def main():
    out = sys.argv[1]
    lines = []
    rows = []
    for spec in sys.argv[2:]:
        scene, w, h, pov, pmdir, halfdir = spec.split(":")
        w, h = int(w), int(h)
        pb_files = sorted(glob.glob(f"reference/{scene}/{scene}-pbrt-bdpt-256x192-seed*.exr"))
        pm_files = sorted(glob.glob(os.path.join(pmdir, "*.exr")))
        if len(pb_files) < 2 or not pm_files:
            lines.append(f"\n{scene}: skipped ({len(pb_files)} pbrt seeds, {len(pm_files)} photonmap renders)\n")
            continue
        pb = np.stack([box_down(read_exr(f), w, h).mean(axis=2) for f in pb_files])
        pm = np.stack([box_down(read_exr(f), w, h).mean(axis=2) for f in pm_files])
        half_files = sorted(glob.glob(os.path.join(halfdir, "*.exr")))
        ph = np.stack([box_down(read_exr(f), w, h).mean(axis=2) for f in half_files]) if half_files else None
        pv = read_exr(pov).mean(axis=2) if pov != "-" else None
        ids, shapes = shape_ids(f"scenes/{scene}.scene", w, h)
        mats = {}
        with open(f"scenes/{scene}.scene") as f:
            for line in f:
                t = line.split("#", 1)[0].split()
                if len(t) >= 3 and t[0] == "material":
                    mats[t[1]] = t[2]
        one = (ids == ids[..., :1]).all(axis=2) & (ids[..., 0] >= 0)
        sid = np.where(one, ids[..., 0], -1)
        regions = [("image (every pixel)", np.ones((h, w), bool), "-", "", "", "")]
        counts = np.bincount(sid[sid >= 0], minlength=len(shapes))
        order = np.argsort(-counts)
        minpix = max(64, (w * h) // 400)
        for k in order[:10]:
            if counts[k] < minpix:
                break
            kind, kv, mat = shapes[k]
            regions.append((f"shape {k + 1} ({kind}, {mat})", sid == k, mats.get(mat, "?"), k + 1, kind, mat))
        lines.append(f"\n**{scene}** at {w}x{h}: pbrt {len(pb_files)} seeds, photonmap {len(pm_files)} seeds, "
                     f"POV-Ray `{os.path.basename(pov) if pv is not None else 'none'}`; "
                     f"{one.mean() * 100:.1f}% of the pixels lie in one shape.\n")
        lines.append("| region | pixels | pbrt mean | pbrt ±95% | robust | photonmap / pbrt | photonmap kernel bias | POV-Ray / pbrt | holds |")
        lines.append("|---|---|---|---|---|---|---|---|---|")
        for name, m, kname, shape, kind, mat in regions:
            pbm = pb[:, m].mean(axis=1)
            pmm = pm[:, m].mean(axis=1)
            ref = pbm.mean()
            e_pb = tint(pbm, len(pbm) - 1) / ref
            rpm = pmm.mean() / ref
            e_pm = math.hypot(tint(pmm, len(pmm) - 1) / pmm.mean() if len(pmm) > 1 else 0, e_pb) * rpm
            robust = np.median(pb, axis=0)[m].mean() / ref
            rpov = pv[m].mean() / ref if pv is not None else None
            pov_s = f"{rpov:.4f}" if rpov is not None else "-"
            bias_s = f"{(ph[:, m].mean() - pmm.mean()) / ref:+.4f}" if ph is not None else "-"
            holds = verdict(kname, rpm, e_pm, rpov, e_pb)
            lines.append(f"| {name} | {int(m.sum())} | {ref:.5f} | {e_pb * 100:.2f}% | {robust:.3f} | "
                         f"{rpm:.4f} ± {e_pm:.4f} | {bias_s} | {pov_s} | {holds} |")
            rows.append({"scene": scene, "size": f"{w}x{h}", "region": name, "shape": shape, "kind": kind,
                         "material": mat, "material_kind": "" if kname == "-" else kname, "pixels": int(m.sum()),
                         "pbrt_mean": f"{ref:.6g}", "pbrt_ci": f"{e_pb:.4g}", "robust": f"{robust:.4f}",
                         "pbrt_seeds": len(pb_files), "pm_ratio": f"{rpm:.5f}", "pm_ci": f"{e_pm:.5f}",
                         "pm_bias": bias_s.lstrip("+") if ph is not None else "", "pm_seeds": len(pm_files),
                         "pov_ratio": f"{rpov:.5f}" if rpov is not None else "", "holds": holds})
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, out)
    out_csv = os.path.splitext(out)[0] + ".csv"
    with open(out_csv + ".tmp", "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=CSV_FIELDS)
        wr.writeheader()
        wr.writerows(rows)
    os.replace(out_csv + ".tmp", out_csv)


if __name__ == "__main__":
    main()
