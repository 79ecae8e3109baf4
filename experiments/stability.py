#!/usr/bin/env python3
"""stability: the renderer at its extremes, each case with what it should
give and a verdict that can fail.

Every case renders with build/photonmap (small images, few photons) and
compares what it observed with what it expected:
  - "same as": the image mean over channels equals a multiple of a baseline
    render's (same seed, so the same photon paths) within a stated relative
    tolerance, or the EXR files are identical byte for byte;
  - "exact": the mean equals a known value (the analytic scene
    scenes/furnace.scene has radiance 1 everywhere; its direct light alone is
    0.5) within a tolerance, over several seeds with a 99.9% interval where
    the estimate is random, and then only when that interval is narrow
    enough to see a bias of RESOLVE (10%) of the value: a noisy estimate
    does not pass by a wide interval;
  - "refused": exit status 2 and a message naming the limit.
Prints a Markdown table (case, command, expected, observed, verdict) on
stdout, with --quick only the cases `make test` runs. Exits 1 when any
verdict is FAIL.

  /usr/bin/python3 -m experiments.stability [--quick] [--pm build/photonmap] > table.md
"""
import argparse
import filecmp
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from experiments.analysis import report, stats

CORNELL = "scenes/cornell.scene"
FURNACE = "scenes/furnace.scene"
BASE = ["--photons", "20000", "--nn", "20", "--width", "64", "--height", "48", "--quiet"]
P0 = 12.566371  # cornell.scene's light power per channel
# an "exact" case over seeds must resolve a bias of this share of the value:
# its 99.9% interval's half-width at most this, or the case fails (more seeds)
RESOLVE = 0.1


def transform(src, scale=1.0, shift=0.0, power=1.0, extra=()):
    """Scene text of src with every length times scale, then x + shift, the
    light power times `power`, and extra statement lines appended."""
    out = []
    for line in open(src):
        code = line.split("#", 1)[0].split()
        if not code:
            continue
        o, i = [], 0
        while i < len(code):
            w = code[i]
            if w in ("position", "look_at", "corner", "center"):
                v = [float(x) * scale for x in code[i + 1:i + 4]]
                v[0] += shift
                o += [w] + ["%.17g" % x for x in v]
                i += 4
            elif w in ("edge1", "edge2"):
                o += [w] + ["%.17g" % (float(x) * scale) for x in code[i + 1:i + 4]]
                i += 4
            elif w == "radius":
                o += [w, "%.17g" % (float(code[i + 1]) * scale)]
                i += 2
            elif w == "power":
                o += [w] + ["%.17g" % (float(x) * power) for x in code[i + 1:i + 4]]
                i += 4
            else:
                o.append(w)
                i += 1
        out.append(" ".join(o))
    return "\n".join(out + list(extra)) + "\n"


class Runner:
    """Renders cases into a temporary directory and keeps the verdicts."""

    def __init__(self, pm, work):
        self.pm, self.work, self.n = pm, work, 0
        self.rows, self.failed = [], 0

    def scene(self, text):
        self.n += 1
        path = os.path.join(self.work, f"s{self.n}.scene")
        with open(path, "w") as f:
            f.write(text)
        return path

    def render(self, scene, args):
        """(exit status, stats dict or None, exr path, stderr)."""
        self.n += 1
        exr, js = os.path.join(self.work, f"r{self.n}.exr"), os.path.join(self.work, f"r{self.n}.json")
        p = subprocess.run([self.pm, "render", scene, *args, "-o", exr, "--stats", js],
                           capture_output=True, text=True)
        st = json.load(open(js)) if os.path.exists(js) else None
        return p.returncode, st, exr, p.stderr.strip().replace(self.work + "/", "")

    def mean(self, scene, args, seeds=None):
        """Image means (over channels) of one render, or of one per seed."""
        vals = []
        for s in seeds or [None]:
            rc, st, exr, err = self.render(scene, args + ([] if s is None else ["--seed", str(s)]))
            if rc != 0:
                return None, f"exit {rc}: {err[:120]}"
            if st["nonfinite_pixels"] or st.get("underflow_pixels"):
                return None, f"{st['nonfinite_pixels']} non-finite pixels"
            vals.append(float(np.mean(st["mean_radiance"])))
        return vals, None

    def add(self, case, command, expected, observed, ok):
        self.rows.append((case, command, expected, observed, "ok" if ok else "FAIL"))
        self.failed += not ok

    # ---- the kinds of case ----

    def same_as(self, case, command, scene, args, base_mean, factor=1.0, tol=5e-3):
        """The image mean is factor x base_mean within tol (relative)."""
        vals, err = self.mean(scene, args)
        if err:
            self.add(case, command, f"{factor:g} x baseline ± {tol:g} relative", err, False)
            return
        ratio = vals[0] / (factor * base_mean)
        self.add(case, command, f"{factor:g} x baseline ± {tol:g} relative", f"{ratio:.6f} x", abs(ratio - 1) <= tol)

    def identical(self, case, command, scene, args, base_exr):
        rc, st, exr, err = self.render(scene, args)
        ok = rc == 0 and filecmp.cmp(exr, base_exr, shallow=False)
        self.add(case, command, "the baseline's EXR, byte for byte", "identical" if ok else f"exit {rc}, differs", ok)

    def exact(self, case, command, scene, args, value, seeds=None, tol=0.0):
        """The mean equals value within tol, or over seeds within the 99.9% CI (plus tol)."""
        vals, err = self.mean(scene, args, seeds)
        if err:
            self.add(case, command, f"{value:g}", err, False)
            return
        self.add(case, command, *exact_verdict(vals, value, tol))

    def refused(self, case, command, scene, args, pattern):
        rc, st, exr, err = self.render(scene, args)
        ok = rc == 2 and re.search(pattern, err) is not None and not os.path.exists(exr)
        self.add(case, command, f"exit 2, no image, message matching '{pattern}'",
                 f"exit {rc}: {err[:200]}", ok)


def exact_verdict(vals, value, tol=0.0):
    """(expected, observed, ok) of an "exact" case from its image means VALS:
    one render, |mean - VALUE| <= TOL; several seeds, VALUE inside the
    mean's 99.9% t interval widened by TOL, and the interval's half-width at
    most RESOLVE x |VALUE| (else the case could not have seen a bias that
    large: it fails, asking for more seeds)."""
    m = float(np.mean(vals))
    if len(vals) < 2:
        return f"{value:g} ± {tol:g}", f"{m:.6g}", abs(m - value) <= tol
    h = stats.t_interval(vals, 0.999)[1]
    resolves = h <= RESOLVE * abs(value)
    return (f"{value:g} (mean of {len(vals)} seeds, 99.9% CI, half-width at most {100 * RESOLVE:g}%)",
            f"{m:.5g} ± {h:.2g}" + ("" if resolves else f" (too wide to see a {100 * RESOLVE:g}% bias)"),
            abs(m - value) <= h + tol and resolves)


def run(r, quick):
    base_rc, base_st, base_exr, _ = r.render(CORNELL, BASE)
    if base_rc != 0:
        raise RuntimeError(f"the baseline render failed (exit {base_rc})")
    base = float(np.mean(base_st["mean_radiance"]))
    r.add("baseline: the Cornell room", "`" + " ".join(BASE) + "`", "exit 0, finite", f"mean L {base:.6g}",
          base_st["nonfinite_pixels"] == 0)

    # ---- the three sweeps ----
    scales = [1e-30, 1e14] if quick else [1e-30, 1e-25, 1e-20, 1e-15, 1e-10, 1e-5, 1e-3, 1e3, 1e5, 1e10, 1e14]
    for s in scales:
        power = min(s * s, 1e35 / P0)
        r.same_as(f"scale x{s:g}, power x{power:g} (same radiance)", f"[room x{s:g}]",
                  r.scene(transform(CORNELL, scale=s, power=power)), BASE, base, factor=power / (s * s))
    if not quick:
        for s in [1e-3, 1e3, 1e10]:
            r.same_as(f"scale x{s:g}, fixed power: L x 1/s^2", f"[room x{s:g}]",
                      r.scene(transform(CORNELL, scale=s)), BASE, base, factor=1 / (s * s))
    r.refused("scale x1e-20, fixed power: radiance ~4e39 > float max", "[room x1e-20]",
              r.scene(transform(CORNELL, scale=1e-20)), BASE, "beyond the largest float")
    r.refused("scale x1e14, power x1e-30: radiance ~1e-60 < float min", "[room x1e14, power x1e-30]",
              r.scene(transform(CORNELL, scale=1e14, power=1e-30)), BASE, "below the smallest normal float")
    shifts = [1e12] if quick else [1, 1e3, 1e6, 1e7, 1e9, 1e10, 1e11, 1e12]
    for t in shifts:
        r.same_as(f"translated by x + {t:g}", f"[room at x+{t:g}]", r.scene(transform(CORNELL, shift=t)), BASE, base)
    for t in ([3e12] if quick else [3e12, 1e13, 1e15 - 3]):
        r.refused(f"translated by x + {t:.17g}: too far for double precision", f"[room at x+{t:.17g}]",
                  r.scene(transform(CORNELL, shift=t)), BASE, "move the scene toward the origin")
    for f in ([1e15] if quick else [1e1, 1e4, 1e6, 1e10, 1e15]):
        r.identical(f"one unit sphere far outside the closed room, at ({f:g}, {f:g}, {f:g})", "[room + sphere]",
                    r.scene(transform(CORNELL, extra=[f"sphere center {f:.17g} {f:.17g} {f:.17g} radius 1 material white"])),
                    BASE, base_exr)
    if not quick:
        r.identical("a sphere of radius 1e15 around everything", "[room + sphere]",
                    r.scene(transform(CORNELL, extra=["sphere center 0 0 0 radius 1e15 material white"])), BASE, base_exr)
    if quick:
        return

    # ---- the estimator's extremes, exact in the analytic scene ----
    fb = ["--photons", "50000", "--width", "48", "--height", "36", "--subpixels", "1", "--quiet"]
    seeds = list(range(1, 11))
    r.refused("n = 1", "`--nn 1`", CORNELL, BASE + ["--nn", "1"], r"expected an integer in \[2,")
    r.refused("n = 2, precomputed (paper): no finite mean", "`--nn 2 --method precomputed`", CORNELL,
              BASE + ["--nn", "2", "--method", "precomputed"], "no finite mean")
    for m in ("conventional", "precomputed"):
        r.exact(f"furnace, {m}, n = 2, corrected: exact", f"[furnace] `--method {m} --nn 2 --bias-correction`",
                FURNACE, fb + ["--method", m, "--nn", "2", "--bias-correction"], 1.0, seeds)
    for n in (3, 5, 20):
        r.exact(f"furnace, conventional, n = {n}, paper: n/(n-1)", f"[furnace] `--nn {n}`", FURNACE,
                fb + ["--nn", str(n)], n / (n - 1), seeds)
    r.exact("furnace, P_e = 200, n = 1000 (> stored): the disc estimate, unbiased", "[furnace] `--photons 200 --nn 1000`",
            FURNACE, fb + ["--photons", "200", "--nn", "1000"], 1.0, list(range(1, 41)))
    r.exact("furnace, P_e = 200, n = 100000 (max): the disc estimate, unbiased", "[furnace] `--photons 200 --nn 100000`",
            FURNACE, fb + ["--photons", "200", "--nn", "100000"], 1.0, list(range(1, 41)))
    r.exact("furnace, P_e = 1: the disc estimate, unbiased", "[furnace] `--photons 1 --nn 20`", FURNACE,
            fb + ["--photons", "1", "--nn", "20"], 1.0, list(range(1, 3001)))
    r.exact("furnace, P_e = 0: black", "[furnace] `--photons 0`", FURNACE, fb + ["--photons", "0"], 0.0)
    r.exact("furnace, P_e = 0, precomputed: black", "[furnace] `--photons 0 --method precomputed`", FURNACE,
            fb + ["--photons", "0", "--method", "precomputed"], 0.0)
    r.exact("furnace, P_e = 0, direct light by shadow rays: rho/pi x Phi/(4 pi R^2) = 0.5",
            "[furnace] `--photons 0 --direct shadow-rays`", FURNACE,
            fb + ["--photons", "0", "--direct", "shadow-rays"], 0.5, tol=1e-6)
    r.exact("no photon within the radius cap (R = 1e-6): black", "`--max-radius 1e-6`", CORNELL,
            BASE + ["--max-radius", "1e-6"], 0.0)
    r.exact("no representative's normal agrees (--normal-cos 1): black", "`--method precomputed --normal-cos 1`",
            CORNELL, BASE + ["--method", "precomputed", "--normal-cos", "1"], 0.0)
    for p in (1e-30, 1e30, 1e35):
        r.same_as(f"light power {p:g}: L linear in power", f"[power {p:g}]", r.scene(transform(CORNELL, power=p / P0)),
                  BASE, base, factor=p / P0, tol=1e-5)
    grazing = transform(FURNACE).replace("camera position 0 0 0.3  look_at 0.3 -0.2 -1",
                                         "camera position 0 0 0.3 look_at 0.3 -0.2 -1")
    grazing = re.sub(r"^camera .*$", "camera position 0 -0.999 0 look_at 1 -0.999 0 up 0 1 0 fov 60",
                     grazing, flags=re.M)
    r.exact("furnace seen at grazing angles (camera 0.001 from the wall, looking along it), corrected: exact",
            "[furnace, grazing camera] `--nn 20 --bias-correction`", r.scene(grazing),
            fb + ["--nn", "20", "--bias-correction"], 1.0, list(range(1, 21)))
    glass = transform(FURNACE, extra=["material glass glass ior 1.5", "sphere center 0 0 0 radius 0.4 material glass"])
    glass = re.sub(r"^camera .*$", "camera position 0.1 0.05 0 look_at 1 0.2 -1 up 0 1 0 fov 90", glass, flags=re.M)
    r.exact("furnace with a glass ball around light and camera (camera inside the glass): exact (radiance is not "
            "scaled by n^2 across interfaces)", "[furnace + glass ball] `--nn 20 --bias-correction`", r.scene(glass),
            fb + ["--nn", "20", "--bias-correction"], 1.0, seeds, tol=1e-3)
    tir = transform(FURNACE, extra=["material dense glass ior 10", "sphere center 0 0 0 radius 0.9 material dense"])
    # looking outwards from off the centre: rays within about 10 degrees of the
    # radial direction leave the ball (critical angle 5.7 degrees); the others
    # circle in it by total internal reflection for ever
    tir = re.sub(r"^camera .*$", "camera position 0 0.5 0 look_at 0 1 0.2 up 1 0 0 fov 90", tir, flags=re.M)
    tir_scene = r.scene(tir)
    vals = {}
    for d in (0, 16, 1000):
        v, err = r.mean(tir_scene, fb + ["--nn", "20", "--bias-correction", "--eye-depth", str(d)])
        vals[d] = None if err else v[0]
    ok = None not in vals.values() and vals[0] == 0.0 and 0.0 < vals[16] <= vals[1000] <= 1.0 + 0.05
    r.add("total internal reflection chains in an ior-10 ball (furnace), --eye-depth 0 / 16 / 1000",
          "[furnace + ior-10 ball]", "0 at depth 0; paths cut at the limit are black, so 0 < L(16) <= L(1000) <= 1",
          " / ".join("-" if vals[d] is None else f"{vals[d]:.4g}" for d in (0, 16, 1000)), ok)
    r.refused("P_e = 1e9: the map would exceed memory", "`--photons 1000000000`", CORNELL,
              BASE + ["--photons", "1000000000"], "needs about .* GiB")
    r.refused("P_e = 2e9: more than 2^32-1 stored photons", "`--photons 2000000000`", CORNELL,
              BASE + ["--photons", "2000000000"], "at most 2\\^32-1")


def controls(r):
    """The quick cases' kinds of verdict against deliberately wrong
    expectations: every one must come out FAIL."""
    base_rc, base_st, base_exr, _ = r.render(CORNELL, BASE)
    base = float(np.mean(base_st["mean_radiance"]))
    r.same_as("control: the room scaled by 1e-30 against 1.01 x the baseline", "[room x1e-30]",
              r.scene(transform(CORNELL, scale=1e-30, power=1e-60)), BASE, base, factor=1.01)
    r.same_as("control: the room moved by 1e12 against 0.99 x the baseline", "[room at x+1e12]",
              r.scene(transform(CORNELL, shift=1e12)), BASE, base, factor=0.99)
    r.identical("control: another seed against the baseline's bytes", "`--seed 2`", CORNELL, BASE + ["--seed", "2"],
                base_exr)
    r.refused("control: the room moved by 1e12 (renderable) expected refused", "[room at x+1e12]",
              r.scene(transform(CORNELL, shift=1e12)), BASE, "move the scene toward the origin")
    r.exact("control: furnace direct light against 0.49", "[furnace] `--photons 0 --direct shadow-rays`", FURNACE,
            ["--photons", "0", "--direct", "shadow-rays", "--width", "16", "--height", "12", "--quiet"], 0.49, tol=1e-6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pm", default="build/photonmap")
    ap.add_argument("--quick", action="store_true", help="only the cases make test runs")
    ap.add_argument("--controls", action="store_true",
                    help="negative controls: wrong expectations, every verdict must FAIL (exit 0 when all do)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="pm-stability.") as work:
        r = Runner(a.pm, work)
        if a.controls:
            controls(r)
            for row in r.rows:
                print(" | ".join(str(c) for c in row))
            sys.exit(0 if r.failed == len(r.rows) else 1)
        run(r, a.quick)
    print(f"Generated by `make stability` (experiments/stability.py) on {report.today()}, commit {report.commit()}; "
          f"renderer: {report.renderer_note(a.pm)}.")
    print()
    print("| case | command (beyond the defaults) | expected | observed | verdict |")
    print("|---|---|---|---|---|")
    for row in r.rows:
        print("| " + " | ".join(str(c).replace("|", "/").replace("\n", " ") for c in row) + " |")
    print()
    print(f"Defaults: cornell cases `{' '.join(BASE)}`; furnace cases `--photons 50000 --width 48 --height 36 "
          "--subpixels 1`; seed 1 unless a seed range is stated; all cores.")
    print(f"\n{len(r.rows) - r.failed} ok, {r.failed} FAIL", file=sys.stderr)
    sys.exit(1 if r.failed else 0)


if __name__ == "__main__":
    main()
