"""pbrt_blocks.py: final gathering on cornell at 256x192 judged block by block
(tests/gather.test.sh says what and why).

    python3 tests/gather/pbrt_blocks.py SCENE PBRT1,PBRT2 POV DIRECT MODE C1 C2 P1 P2

C1 C2: the conventional method's two seeds, P1 P2: the precomputed one's.
MODE: check; scale=F (every image times F); indirect=F (DIRECT + F x (image -
DIRECT): the light beyond direct light off by F). Exits 1 when a block is out.
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "reference", "pbrt"))
from agreement import read_exr, shape_ids  # noqa: E402

W, H, B = 256, 192, 16
TOL = 0.01         # diffuse blocks: 1% of pbrt ...
K = 3              # ... plus K standard deviations of the two sides' noise
SPEC_TOL = 0.03    # blocks seen via mirror or glass: within 3% of POV-Ray
SPECULAR = ("mirror", "glass")


def blocks(sid):
    """(by, bx, shape) of every 16x16 block whose pixels all see one shape."""
    out = []
    for by in range(H // B):
        for bx in range(W // B):
            s = sid[by * B:(by + 1) * B, bx * B:(bx + 1) * B]
            if s[0, 0] >= 0 and (s == s[0, 0]).all():
                out.append((by, bx, int(s[0, 0])))
    return out


def bmean(img, by, bx):
    return img[by * B:(by + 1) * B, bx * B:(bx + 1) * B].mean()


def pooled(pair, blist):
    """Per shape: the relative standard deviation of the mean of the two
    images PAIR, the rms over the shape's blocks of |a - b| / (a + b)."""
    acc = {}
    for by, bx, k in blist:
        a, b = bmean(pair[0], by, bx), bmean(pair[1], by, bx)
        acc.setdefault(k, []).append(((a - b) / (a + b)) ** 2)
    return {k: math.sqrt(np.mean(v)) for k, v in acc.items()}


def main(argv):
    scene, pbrt, pov, direct, mode = argv[:5]
    ours = argv[5:9]
    ids, shapes = shape_ids(scene, W, H)
    sid = np.where((ids == ids[..., :1]).all(axis=2), ids[..., 0], -1)
    P = [read_exr(f).mean(axis=2) for f in pbrt.split(",")]
    ref = sum(P) / len(P)
    povi = read_exr(pov).mean(axis=2)
    blist = blocks(sid)
    diffuse = [b for b in blist if shapes[b[2]][2] not in SPECULAR]
    spec = [b for b in blist if shapes[b[2]][2] in SPECULAR]
    s_ref = pooled(P, diffuse)
    bad = 0
    for pair in (ours[0:2], ours[2:4]):
        imgs = [read_exr(f).mean(axis=2) for f in pair]
        if mode.startswith("scale="):
            imgs = [i * float(mode[6:]) for i in imgs]
        elif mode.startswith("indirect="):
            d = read_exr(direct).mean(axis=2)
            imgs = [d + float(mode[9:]) * (i - d) for i in imgs]
        elif mode != "check":
            raise SystemExit(f"pbrt_blocks.py: mode '{mode}': check, scale=F or indirect=F")
        s_ours = pooled(imgs, diffuse)
        img = sum(imgs) / 2
        worst = 0.0
        for by, bx, k in diffuse:
            r = bmean(img, by, bx) / bmean(ref, by, bx)
            tol = TOL + K * math.hypot(s_ref[k], s_ours[k])
            worst = max(worst, abs(r - 1) / tol)
            if abs(r - 1) > tol:
                bad += 1
                print(f"{pair[0]}: diffuse block ({by},{bx}) of shape {k} ({shapes[k][2]}): {r:.4f} of pbrt, allowed 1 +- {tol:.4f}")
        print(f"{pair[0]}: {len(diffuse)} diffuse blocks, the worst at {worst:.2f} of its tolerance; "
              f"relative noise per shape (pbrt, ours): " + ", ".join(f"{k}: {s_ref[k]:.4f} {s_ours[k]:.4f}" for k in sorted(s_ref)))
        for by, bx, k in spec:
            r_pov = bmean(img, by, bx) / bmean(povi, by, bx)
            r_pbrt = bmean(img, by, bx) / bmean(ref, by, bx)
            if abs(r_pov - 1) > SPEC_TOL or not r_pbrt > 1:
                bad += 1
                print(f"{pair[0]}: specular block ({by},{bx}) of shape {k} ({shapes[k][2]}): {r_pov:.4f} of POV-Ray "
                      f"(allowed 1 +- {SPEC_TOL}), {r_pbrt:.4f} of pbrt (must be above 1)")
        rs = [bmean(img, by, bx) / bmean(povi, by, bx) for by, bx, _ in spec]
        rp = [bmean(img, by, bx) / bmean(ref, by, bx) for by, bx, _ in spec]
        print(f"{pair[0]}: {len(spec)} specular blocks: {min(rs):.4f}..{max(rs):.4f} of POV-Ray, {min(rp):.4f}..{max(rp):.4f} of pbrt")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
