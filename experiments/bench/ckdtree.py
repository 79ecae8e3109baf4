#!/usr/bin/python3
"""ckdtree.py: the scipy side of the kNN benchmark, a co-process of
`bench --peers` (experiments/bench/bench.c), so that its timings interleave
with the other trees' run by run.

  ckdtree.py DIR LEAF

Reads DIR/points.f32 and DIR/queries.f32 (float32 xyz triples, the map
frame, the points in the order the other trees index them), builds
scipy.spatial.cKDTree(points, leafsize=LEAF) (defaults otherwise: balanced,
compact nodes) and prints "ready BUILD_S". Then, for each line
"K CAP WRITE" on stdin, answers every query in one documented call,
tree.query(queries, k=K, distance_upper_bound=sqrt(CAP), workers=1) (one
thread; neighbours in distance order, missing ones as index n), and prints
"SECONDS FOUND"; when WRITE is 1 it also writes the neighbour indices as
DIR/ckdtree.u32 (K per query, 4294967295 after the last found) for bench to
check. "quit" ends it. The distances are float64 from the float32
coordinates; the cap is passed as its square root's next float64 up, since
the bound's test is strict.
"""
import sys
import time

import numpy as np
from scipy.spatial import cKDTree


def main():
    d, leaf = sys.argv[1], int(sys.argv[2])
    pts = np.fromfile(d + "/points.f32", dtype=np.float32).reshape(-1, 3).astype(np.float64)
    qs = np.fromfile(d + "/queries.f32", dtype=np.float32).reshape(-1, 3).astype(np.float64)
    t0 = time.perf_counter()
    tree = cKDTree(pts, leafsize=leaf)
    print(f"ready {time.perf_counter() - t0:.6f}", flush=True)
    n = len(pts)
    for line in sys.stdin:
        w = line.split()
        if not w or w[0] == "quit":
            break
        k, cap, write = int(w[0]), float.fromhex(w[1]), w[2] == "1"
        ub = np.nextafter(np.sqrt(np.float64(cap)), np.inf)
        t0 = time.perf_counter()
        _, idx = tree.query(qs, k=k, distance_upper_bound=ub, workers=1)
        dt = time.perf_counter() - t0
        idx = np.asarray(idx).reshape(len(qs), k)
        found = int(np.count_nonzero(idx < n))
        if write:
            out = np.where(idx < n, idx, 4294967295).astype(np.uint32)
            out.tofile(d + "/ckdtree.u32")
        print(f"{dt:.9f} {found}", flush=True)


if __name__ == "__main__":
    main()
