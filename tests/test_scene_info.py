"""Tests of `photonmap info SCENE --json` and experiments/analysis/
scene_info.py: the JSON's camera basis projects a sphere's centre onto the
pixel where the renderer draws it (and a basis without the aspect does
not: the negative control), the shapes and lines are the file's, and a bad
scene fails as `render` fails (file:line:col, exit 2).

Run by pytest from the repository root; needs build/photonmap (`make`).
"""

import os
import subprocess
import tempfile

import numpy as np
import pytest

from experiments.analysis import metrics, scene_info

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PM = os.path.join(ROOT, "build", "photonmap")

# a black room, a small white sphere off the image's centre lit by the light
SCENE = """camera position 0.3 1.1 2.4 look_at -0.1 0.9 0 up 0.1 1 0 fov 60
light point position 0 1.8 1 power 10 10 10
material black lambert rho 0 0 0
material white lambert rho 1 1 1
rect corner -1 0 -1 edge1 2 0 0 edge2 0 2 0 material black
rect corner -1 0 -1 edge1 0 0 3.5 edge2 2 0 0 material black
sphere center {x} {y} {z} radius 0.06 material white
"""
CENTRE = (0.45, 1.3, -0.2)
W, H = 96, 54


def write_scene(d, text):
    path = os.path.join(d, "s p.scene")  # a path with a space
    with open(path, "w") as f:
        f.write(text)
    return path


@pytest.fixture(scope="module")
def rendered():
    if not os.access(PM, os.X_OK):
        pytest.skip("build/photonmap is not built")
    with tempfile.TemporaryDirectory() as d:
        path = write_scene(d, SCENE.format(x=CENTRE[0], y=CENTRE[1], z=CENTRE[2]))
        exr = os.path.join(d, "i.exr")
        subprocess.run([PM, "render", path, "--photons", "0", "--direct", "shadow-rays", "--width", str(W),
                        "--height", str(H), "--subpixels", "4", "--quiet", "-o", exr], check=True)
        yield path, metrics.read_exr(exr)


def test_projection_hits_the_rendered_pixel(rendered):
    """The centroid of the lit pixels (the sphere, all else is black) is
    within one pixel of the centre projected through the JSON basis; the
    same projection with the basis of a square image (no aspect) misses it
    by several pixels, so the check can fail."""
    path, img = rendered
    lum = img.sum(axis=2)
    ys, xs = np.nonzero(lum > 0)
    assert len(xs) > 4, "the sphere is not in the image"
    cx, cy = xs.mean() + 0.5, ys.mean() + 0.5
    info = scene_info.load(path, PM, W, H)
    px, py = scene_info.project(info, [CENTRE])
    assert abs(px[0] - cx) < 1.0 and abs(py[0] - cy) < 1.0, (px, py, cx, cy)
    wrong = scene_info.load(path, PM, W, W)
    wrong["camera"]["basis"]["height"] = H
    qx, qy = scene_info.project(wrong, [CENTRE])
    assert abs(qy[0] - cy) > 3.0, (qy, cy)


def test_facts_are_the_files(rendered):
    """Shapes in file order with their lines, materials, the light, bounds."""
    path, _ = rendered
    info = scene_info.load(path, PM)
    assert info["scene"] == path
    assert [s["line"] for s in info["shapes"]] == [5, 6, 7]
    assert [s["kind"] for s in info["shapes"]] == ["rect", "rect", "sphere"]
    sph = scene_info.shapes(info)[2]
    assert np.array_equal(sph["center"], CENTRE) and sph["radius"] == 0.06
    assert sph["material"] == "white" and sph["material_kind"] == "lambert"
    assert [m["name"] for m in info["materials"]] == ["black", "white"]
    assert [m["line"] for m in info["materials"]] == [3, 4]
    assert info["lights"] == [{"kind": "point", "position": [0, 1.8, 1], "power": [10, 10, 10]}]
    assert info["camera"]["fov_deg"] == 60
    assert info["camera"]["basis"]["width"] == 1024 and info["camera"]["basis"]["height"] == 768
    assert info["bounds"]["lo"] == [-1, 0, -1] and info["bounds"]["hi"] == [1, 2, 2.5]
    assert np.isclose(info["bounds"]["diagonal"], np.linalg.norm([2, 2, 3.5]))


def test_bad_scene_fails_like_render():
    """A scene the parser refuses: info exits 2 with render's file:line:col
    message, and scene_info raises it."""
    if not os.access(PM, os.X_OK):
        pytest.skip("build/photonmap is not built")
    with tempfile.TemporaryDirectory() as d:
        path = write_scene(d, SCENE.format(x=0, y="oops", z=0))
        info = subprocess.run([PM, "info", path, "--json"], capture_output=True, text=True)
        render = subprocess.run([PM, "render", path, "--no-output"], capture_output=True, text=True)
        assert info.returncode == 2 and render.returncode == 2
        assert info.stderr == render.stderr and info.stderr.startswith(f"{path}:7:")
        assert info.stdout == ""
        with pytest.raises(scene_info.SceneInfoError, match=":7:"):
            scene_info.load(path, PM)
        no_json = subprocess.run([PM, "info", path], capture_output=True, text=True)
        assert no_json.returncode == 2 and "--json" in no_json.stderr
