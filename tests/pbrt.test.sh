#!/usr/bin/env bash
# pbrt.test.sh: `photonmap export-pbrt` (renderer/pbrt.c), without pbrt itself:
#   - a tiny scene's export checked structurally: the mirrored camera before
#     LookAt, fov of the shorter axis, the light's I = P/(4 pi), each
#     material and shape; negative controls: the same checker on doctored
#     exports (each mapping undone) must fail;
#   - refusals with a named cause (exit 2, no output file left);
#   - the committed reference/SCENE/*-pbrt-*.pbrt are what the exporter
#     writes now at their split (else the pbrt references are stale), and a
#     scene with mirror or glass uses render.sh's split (control: cornell at
#     the split 10 fails);
#   - with pbrt (PBRT=/path/to/pbrt or on PATH), direct light alone against
#     --direct shadow-rays per pixel, and the references' recipe
#     (reference/pbrt/render.sh: BDPT plus the path-traced tail) on two scenes
#     of exact radiance: the closed sphere at albedo 0.9 (each bounce order's
#     share known: the seam between BDPT and the tail) and the half sphere
#     closed by a mirror (half the light reaches the walls only through the
#     mirror, which the path tracer cannot sample from a point light), and
#     the closed sphere at the split 10 too; negative controls: a seam
#     shifted by one bounce, and the mirror half sphere split at 10 bounces,
#     must fail; skipped otherwise.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}

cat > "$TMP/tiny.scene" <<'SCENE'
camera position 0 1 3  look_at 0 1 0  up 0 1 0  fov 80
light point position 0.1 1.8 0.2  power 25.132741228718345 12.566370614359172 6.283185307179586
material wall lambert rho 0.7 0.6 0.5
material shiny mirror reflectance 0.9 0.8 0.7
material clear glass ior 1.45
rect corner -1 0 -1  edge1 2 0 0  edge2 0 2 0  material wall
rect corner -1 0 -1  edge1 0 0 3  edge2 2 0 0  material shiny
sphere center 0.2 0.4 -0.3  radius 0.3  material clear
SCENE

# structure CHECKS FILE: the export of tiny.scene at 256x192 is right
structure() {
  "$PY" - "$1" <<'PYEOF'
import math, re, sys
t = open(sys.argv[1]).read()
lines = [l for l in t.splitlines() if l and not l.startswith("#")]
def num(s): return [float(x) for x in s.split()]
i_scale = next(i for i, l in enumerate(lines) if l.startswith("Scale"))
i_look = next(i for i, l in enumerate(lines) if l.startswith("LookAt"))
assert lines[i_scale].split() == ["Scale", "-1", "1", "1"] and i_scale + 1 == i_look, "Scale -1 1 1 right before LookAt"
assert num(lines[i_look][6:]) == [0, 1, 3, 0, 1, 0, 0, 1, 0], "LookAt from the camera"
fov = float(re.search(r'"float fov" \[ ([^ ]+) \]', t).group(1))
want = 2 * math.degrees(math.atan(math.tan(math.radians(40)) * 192 / 256))
assert abs(fov - want) < 1e-9 and abs(fov - 64.3664) < 1e-4, f"fov {fov}, want {want} (the shorter axis's)"
m = re.search(r'LightSource "point" "point from" \[ ([^\]]+) \] "rgb I" \[ ([^\]]+) \]', t)
assert num(m.group(1)) == [0.1, 1.8, 0.2], "light position"
I = num(m.group(2))
assert all(abs(a - b) < 1e-12 for a, b in zip(I, [2, 1, 0.5])), f"I = P/(4 pi): {I}"
assert re.search(r'"matte" "float sigma" \[ 0 \] "rgb Kd" \[ 0.7 0.6 0.5 \]', t), "matte Kd"
assert re.search(r'"mirror" "rgb Kr" \[ 0.9 0.8 0.7 \]', t), "mirror Kr"
assert re.search(r'"glass" "rgb Kr" \[ 1 1 1 \] "rgb Kt" \[ 1 1 1 \] "float eta" \[ 1.45 \]', t), "glass eta"
meshes = re.findall(r'NamedMaterial "pm_mat(\d)"\n  Shape "trianglemesh" "integer indices" \[ 0 1 2 0 2 3 \] "point P" \[([^\]]+)\]', t)
assert [m[0] for m in meshes] == ["0", "1"], "two rectangles, their materials"
assert num(meshes[0][1]) == [-1, 0, -1, 1, 0, -1, 1, 2, -1, -1, 2, -1], "rectangle corners"
assert re.search(r'NamedMaterial "pm_mat2"\n  Translate 0.2 0.4 -0.3\n  Shape "sphere" "float radius" \[ 0.3 \]', t), "sphere"
assert 'Integrator "bdpt" "integer maxdepth" [ 10 ]' in t, "maxdepth = bounces + 1"
assert '"integer xsamples" [ 4 ] "integer ysamples" [ 4 ] "bool jitter" "true"' in t, "16 spp, jittered"
assert 'PixelFilter "box" "float xwidth" [ 0.5 ] "float ywidth" [ 0.5 ]' in t, "one-pixel box filter"
assert t.rstrip().endswith("WorldEnd")
PYEOF
}
tiny_export() { $PM export-pbrt "$TMP/tiny.scene" --width 256 --height 192 --bounces 9 --spp 16 -o "$TMP/tiny.pbrt"; }
check "export-pbrt writes the tiny scene" tiny_export
check "its structure: camera, fov, I = P/4pi, materials, shapes" structure "$TMP/tiny.pbrt"

fails() { ! "$@"; }
# negative controls: each doctored export undoes one mapping
doctored() { # SED: the checker fails on the export edited by SED
  sed "$1" "$TMP/tiny.pbrt" > "$TMP/bad.pbrt" && ! cmp -s "$TMP/tiny.pbrt" "$TMP/bad.pbrt" && fails structure "$TMP/bad.pbrt"
}
check "control: no Scale -1 1 1 (a mirrored image) fails" doctored '/^Scale -1 1 1$/d'
check "control: the horizontal fov (80) fails" doctored 's/"float fov" \[ [^ ]* \]/"float fov" [ 80 ]/'
check "control: I = P (no 1/4pi) fails" doctored 's/"rgb I" \[ 2 1 0.5 \]/"rgb I" [ 25.132741228718345 12.566370614359172 6.283185307179586 ]/'
check "control: I = P/pi fails" doctored 's/"rgb I" \[ 2 1 0.5 \]/"rgb I" [ 8 4 2 ]/'
check "control: a swapped Kd fails" doctored 's/"rgb Kd" \[ 0.7 0.6 0.5 \]/"rgb Kd" [ 0.5 0.6 0.7 ]/'
check "control: glass eta 1.5 (pbrt's default) fails" doctored 's/"float eta" \[ 1.45 \]/"float eta" [ 1.5 ]/'
portrait() {
  $PM export-pbrt "$TMP/tiny.scene" --width 192 --height 256 -o "$TMP/p.pbrt" && grep -q '"float fov" \[ 80 \]' "$TMP/p.pbrt"
}
check "portrait film: fov is the horizontal one (the shorter axis)" portrait
directl() {
  $PM export-pbrt "$TMP/tiny.scene" --integrator directlighting --spp 4 --fixed-subpixels -o "$TMP/d.pbrt" &&
  grep -q '"bool jitter" "false"' "$TMP/d.pbrt" && grep -q '"directlighting" "integer maxdepth" \[ 64 \] "string strategy" "all"' "$TMP/d.pbrt"
}
check "directlighting at fixed 2x2 subpixel points" directl
pathmin() {
  $PM export-pbrt "$TMP/tiny.scene" --integrator path --bounces 63 --min-bounces 9 -o "$TMP/m.pbrt" &&
  grep -q '"path" "integer maxdepth" \[ 64 \] "integer mindepth" \[ 10 \]' "$TMP/m.pbrt"
}
check "path with --min-bounces 9: mindepth 10" pathmin

help_ok() {
  $PM export-pbrt --help > "$TMP/h.txt" && for o in --width --height --integrator --bounces --min-bounces --spp --fixed-subpixels -o; do
    grep -A1 -E "^  $o( |\$)" "$TMP/h.txt" | grep -q "(default: " || { echo "$o without a default"; return 1; }
  done && $PM --help | grep -q 'usage: photonmap export-pbrt'
}
check "export-pbrt --help: every option with its default; photonmap --help lists it" help_ok

# --- refusals ---------------------------------------------------------------
refused() { # SED PATTERN [OPTIONS]: the edited scene is refused, exit 2, cause named, no file left
  local s=$1 pat=$2; shift 2
  sed "$s" "$TMP/tiny.scene" > "$TMP/r.scene" || return 1
  rm -f "$TMP/r.pbrt"
  expect_exit 2 "$pat" $PM export-pbrt "$TMP/r.scene" "$@" -o "$TMP/r.pbrt" && [ ! -e "$TMP/r.pbrt" ] &&
  [ -z "$(ls "$TMP" | grep '^r\.pbrt.')" ]
}
check "refuses a glass rectangle" refused 's/edge2 2 0 0  material shiny/edge2 2 0 0  material clear/' 'shape 2: glass rectangle'
check "refuses the camera inside a glass sphere" refused 's/^sphere center 0.2 0.4 -0.3  radius 0.3/sphere center 0 1 3  radius 0.5/' 'camera is inside a glass sphere'
check "refuses the light inside a glass sphere" refused 's/^sphere center 0.2 0.4 -0.3  radius 0.3/sphere center 0 1.7 0  radius 0.5/' 'light is inside a glass sphere'
check "refuses --min-bounces with bdpt" refused 's/x/x/' 'only the path integrator' --min-bounces 3
check "refuses --min-bounces not below --bounces" refused 's/x/x/' 'must be below --bounces' --integrator path --bounces 5 --min-bounces 5
check "refuses an unknown integrator" refused 's/x/x/' 'integrator' --integrator sppm
check "control: the tiny scene itself is accepted" fails refused 's/x/x/' 'glass'

# --- the committed pbrt scenes are current ------------------------------------
# Each committed scene is the exporter's output at the split it was rendered
# with (its BDPT maxdepth, its path tracer's mindepth: the same split); a
# scene with mirror or glass must use render.sh's split, since there the path
# tracer's tail cannot carry the light that reaches the lamp through them
# (reference/pbrt/README.md, "The split"); without them any split holds.
current() { # [ROOT]: the committed scenes under ROOT (default reference)
  local root=${1:-reference} n=0 f scene size split want spp
  declare -A split_of
  want=$(sed -n 's/^split=\${PBRT_SPLIT:-\([0-9]*\)}$/\1/p' reference/pbrt/render.sh)
  [ -n "$want" ] || { echo "no split in reference/pbrt/render.sh"; return 1; }
  for f in "$root"/*/*-pbrt-bdpt-*.pbrt "$root"/*/*-pbrt-path-*.pbrt; do
    [ -e "$f" ] || continue
    scene=${f#"$root"/}; scene=${scene%%/*}
    size=${f##*-}; size=${size%.pbrt}
    spp=$(sed -n 's/.*"integer xsamples" \[ \([0-9]*\) \].*/\1/p' "$f" | awk '{print $1 * $1}')
    if [[ $f == *-pbrt-bdpt-* ]]; then
      split=$(sed -n 's/.*"bdpt" "integer maxdepth" \[ \([0-9]*\) \].*/\1/p' "$f")
    else
      split=$(sed -n 's/.*"path" "integer maxdepth" \[ 64 \] "integer mindepth" \[ \([0-9]*\) \].*/\1/p' "$f")
    fi
    [ -n "$split" ] || { echo "$f: no maxdepth/mindepth"; return 1; }
    split=$((split - 1))
    if grep -qE '^material +[^ ]+ +(mirror|glass) ' scenes/$scene.scene && [ "$split" != "$want" ]; then
      echo "$f: split $split, but scenes/$scene.scene has mirror or glass: render.sh's $want"; return 1
    fi
    [ -n "${split_of[$scene]:-}" ] && [ "${split_of[$scene]}" != "$split" ] && { echo "$scene: BDPT and path splits differ"; return 1; }
    split_of[$scene]=$split
    if [[ $f == *-pbrt-bdpt-* ]]; then
      $PM export-pbrt scenes/$scene.scene --width ${size%x*} --height ${size#*x} --integrator bdpt --bounces "$split" \
        --spp "$spp" -o "$TMP/c.pbrt"
    else
      $PM export-pbrt scenes/$scene.scene --width ${size%x*} --height ${size#*x} --integrator path --bounces 63 \
        --min-bounces "$split" --spp "$spp" -o "$TMP/c.pbrt"
    fi
    cmp "$TMP/c.pbrt" "$f" || return 1
    n=$((n + 1))
  done
  [ "$n" -gt 0 ] || { echo "no committed pbrt scene found"; return 1; }
}
check "committed reference/*/*-pbrt-*.pbrt are the exporter's output" current
old_split() { # SCENE: SCENE's committed exports redone at the split 9 (BDPT to 10 bounces) fail current
  mkdir -p "$TMP/old-$1/$1" &&
  $PM export-pbrt scenes/$1.scene --width 256 --height 192 --integrator bdpt --bounces 9 --spp 64 \
    -o "$TMP/old-$1/$1/$1-pbrt-bdpt-256x192.pbrt" &&
  $PM export-pbrt scenes/$1.scene --width 256 --height 192 --integrator path --bounces 63 --min-bounces 9 --spp 64 \
    -o "$TMP/old-$1/$1/$1-pbrt-path-256x192.pbrt" && current "$TMP/old-$1"
}
check "control: cornell (mirror, glass) split at 10 bounces fails" fails old_split cornell
check "the split of a scene without mirror or glass is free: tworooms at 10 bounces passes" old_split tworooms

# --- with pbrt: direct light against --direct shadow-rays --------------------
pbrt=${PBRT:-$(command -v pbrt || true)}
if [ -n "$pbrt" ] && [ -x "$pbrt" ] && "$PY" -c 'import OpenImageIO, numpy' 2>/dev/null; then
  direct_match() { # [SCALE]: median per-pixel ratio within 1e-4 of 1 (SCALE: the control's light factor)
    local sc=${1:-1}
    sed "s/^light point position \(.*\)  power .*/light point position \1  power $(awk "BEGIN{printf \"%.17g %.17g %.17g\", 25.132741228718345*$sc, 12.566370614359172*$sc, 6.283185307179586*$sc}")/" \
      "$TMP/tiny.scene" > "$TMP/l.scene"
    $PM export-pbrt "$TMP/l.scene" --width 64 --height 48 --integrator directlighting --spp 4 --fixed-subpixels \
      -o "$TMP/l.pbrt" && "$pbrt" --nthreads 1 --quiet --outfile "$TMP/l.exr" "$TMP/l.pbrt" &&
    $PM render "$TMP/tiny.scene" --direct shadow-rays --photons 0 --width 64 --height 48 --quiet -o "$TMP/pm.exr" &&
    "$PY" - "$TMP/l.exr" "$TMP/pm.exr" <<'PYEOF'
import sys, numpy as np
sys.path.insert(0, "reference/pbrt")
from agreement import read_exr
a, b = read_exr(sys.argv[1]), read_exr(sys.argv[2])
m = (a > 1e-3) & (b > 1e-3)
r = np.median(a[m] / b[m])
print("median ratio", r, "over", m.sum())
assert m.sum() > 1000 and abs(r - 1) < 1e-4
PYEOF
  }
  check "pbrt directlighting = --direct shadow-rays per pixel (median ratio)" direct_match
  check "control: pbrt with the light x1.01 fails" fails direct_match 1.01

  # The recipe of the references (reference/pbrt/render.sh, its own split and
  # seam) on scenes of exact radiance. EXACT_KIND: furnace (uniform: 1 less the
  # paths of more than 64 bounces, rho^64) or dome (the image method: the full
  # sphere with the light and its mirror image; direct term per point, the
  # rest uniform). Passes when the image mean of pbrt / exact is within 3
  # standard errors (from the spread over pixels) plus 0.1% of 1.
  exact_match() { # SCENE W H BDPT_SPP PATH_SPP KIND [VAR=VALUE...]: the recipe's image is exact
    local sc=$1 w=$2 h=$3 sb=$4 sp=$5 kind=$6 name; shift 6
    name=$(basename "$sc" .scene); rm -rf "$TMP/x-$name"
    env "$@" PBRT="$pbrt" PBRT_THREADS=2 PBRT_SCENE_FILE="$sc" PBRT_OUT_DIR="$TMP/x-$name" \
      bash reference/pbrt/render.sh "$name" "$w" "$h" "$sb" "$sp" 1 > /dev/null &&
    "$PY" - "$TMP/x-$name/$name-pbrt-bdpt-${w}x${h}-seed1.exr" "$sc" "$kind" <<'PYEOF'
import math, sys
import numpy as np
sys.path.insert(0, "reference/pbrt")
from agreement import parse_scene, read_exr
img, scene, kind = read_exr(sys.argv[1]).mean(axis=2), sys.argv[2], sys.argv[3]
h, w = img.shape
cam, shapes = parse_scene(scene)
light = [l.split() for l in open(scene) if l.startswith("light point")][0]
p, Phi = np.array([float(x) for x in light[3:6]]), float(light[7])
rho = [float(l.split()[4]) for l in open(scene) if " lambert rho " in l][0]
if kind == "furnace":  # L = 1 (scenes/furnace.scene), less the orders above 64
    exact = np.full((h, w), 1 - rho ** 64)
else:  # dome: unit sphere above the mirror y = 0 (reflectance 1), seen without the mirror
    S = 8  # pbrt averages over the pixel's area: 8x8 points per pixel
    pos = np.array(cam["position"]); fwd = np.array(cam["look_at"]) - pos; fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, np.array(cam["up"])); right /= np.linalg.norm(right); up = np.cross(right, fwd)
    hw = math.tan(0.5 * math.radians(cam["fov"][0])); right, up = right * hw, up * hw * h / w
    ys, xs, sy, sx = np.meshgrid(np.arange(h), np.arange(w), np.arange(S), np.arange(S), indexing="ij")
    u, v = (xs + (sx + 0.5) / S) / w, (ys + (sy + 0.5) / S) / h
    d = fwd + (2 * u - 1)[..., None] * right + (1 - 2 * v)[..., None] * up
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    b = d @ pos; x = pos + (-b + np.sqrt(b * b - (pos @ pos - 1)))[..., None] * d
    assert (x[..., 1] > 0).all(), "the camera sees the mirror (BDPT cannot sample L S D S E there)"
    E = 0
    for q in (p, p * np.array([1, -1, 1])):  # the light and its mirror image
        t = q - x; r = np.linalg.norm(t, axis=-1)
        E = E + Phi / (4 * math.pi) * (t * -x).sum(-1) / r ** 3
    exact = (rho / math.pi * (E + 2 * Phi / (4 * math.pi) * rho / (1 - rho))).mean(axis=(2, 3))
r = img / exact
m, se = r.mean(), r.std(ddof=1) / math.sqrt(r.size)
print(f"{kind}: pbrt / exact {m:.5f} +- {se:.5f} (1 s.e.), tolerance {3 * se + 1e-3:.5f}")
assert abs(m - 1) < 3 * se + 1e-3
PYEOF
  }
  sed -e 's/^material wall lambert rho .*/material wall lambert rho 0.9 0.9 0.9/' \
      -e "s/^light point position 0 0 0  power .*/light point position 0 0 0  power $(awk 'BEGIN{p = 4 * atan2(0, -1)^2 * 0.1 / 0.9; printf "%.17g %.17g %.17g", p, p, p}')/" \
      scenes/furnace.scene > "$TMP/furnace9.scene"
  cat > "$TMP/dome.scene" <<'SCENE'
camera position 0.2 0.25 0.3  look_at -0.3 0.8 -0.4  up 0 1 0  fov 90
light point position 0 0.35 0  power 39.47841760435743 39.47841760435743 39.47841760435743
material wall lambert rho 0.7 0.7 0.7
material m mirror reflectance 1 1 1
sphere center 0 0 0  radius 1  material wall
rect corner -1 0 -1  edge1 0 0 2  edge2 2 0 0  material m
SCENE
  shown() { local f=$FAIL; check "$@"; [ "$FAIL" != "$f" ] || grep -h 'pbrt / exact' "$TMP/.out" | sed 's/^/     /'; }  # and the measured line
  shown "recipe: the closed sphere at albedo 0.9 is exact (1 - 0.9^64)" exact_match "$TMP/furnace9.scene" 16 12 16 1024 furnace
  shown "the closed sphere (no mirror, no glass) is exact at the split 10 too (slabs, library, tworooms)" exact_match "$TMP/furnace9.scene" 16 12 16 1024 furnace PBRT_SPLIT=9
  shown "control: the seam one bounce late (bounce 24 lost) fails" fails exact_match "$TMP/furnace9.scene" 16 12 16 1024 furnace PBRT_MIN_BOUNCES=24
  shown "recipe: the half sphere closed by a mirror is exact" exact_match "$TMP/dome.scene" 16 12 64 1024 dome
  shown "control: BDPT to 10 bounces, the path tracer above (light via the mirror lost) fails" fails exact_match "$TMP/dome.scene" 16 12 64 1024 dome PBRT_SPLIT=9
else
  echo "skip pbrt direct-light and recipe checks: pbrt-v3 not found (PBRT=/path/to/pbrt; reference/pbrt/README.md)"
fi
finish
