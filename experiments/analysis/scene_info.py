"""The facts of a scene as the renderer reads them: `photonmap info SCENE
--json` (renderer/README.md) run once per scene, and the projection of 3-D
points to pixels through the camera basis it prints. The one way the
analysis learns a scene's camera, light, shapes and bounds: nothing here
parses the scene format.
"""

import json
import subprocess

import numpy as np

DEFAULT_PM = "build/photonmap"


class SceneInfoError(Exception):
    """The renderer refused the scene (its message: file:line:col) or did not run."""


def load(scene, pm=DEFAULT_PM, width=None, height=None):
    """The JSON object `photonmap info SCENE --json` prints, with the camera
    basis for a WIDTH x HEIGHT image (the renderer's default size when not
    given). Raises SceneInfoError with the renderer's message."""
    cmd = [pm, "info", scene, "--json"]
    if width is not None:
        cmd += ["--width", str(width)]
    if height is not None:
        cmd += ["--height", str(height)]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        raise SceneInfoError(f"{pm}: {e}") from e
    if r.returncode != 0:
        raise SceneInfoError(r.stderr.strip() or f"{' '.join(cmd)}: exit {r.returncode}")
    return json.loads(r.stdout)


def project(info, pts):
    """Pixel coordinates (x, y), floats, of world points PTS (N, 3) in the
    image of info's basis: the inverse of the eye pass's ray through image
    point (u, v), direction forward + right (2u - 1) + up (1 - 2v)."""
    b = info["camera"]["basis"]
    o, f, r, u = (np.array(b[k], dtype=float) for k in ("origin", "forward", "right", "up"))
    d = np.asarray(pts, dtype=float) - o
    z = d @ f
    a = (d @ r) / (z * (r @ r))
    c = (d @ u) / (z * (u @ u))
    return (a + 1) / 2 * b["width"], (1 - c) / 2 * b["height"]


def shapes(info):
    """The shapes as dicts with numpy vectors (center, corner, edge1, edge2)
    beside the JSON's kind, radius, material and line."""
    out = []
    for s in info["shapes"]:
        s = dict(s)
        for k in ("center", "corner", "edge1", "edge2"):
            if k in s:
                s[k] = np.array(s[k], dtype=float)
        out.append(s)
    return out


def light_position(info):
    """The (one) point light's position as a numpy vector."""
    return np.array(info["lights"][0]["position"], dtype=float)
