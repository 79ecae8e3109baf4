#!/usr/bin/env bash
# pbrt.test.sh: `photonmap export-pbrt` (renderer/pbrt.c), without pbrt itself:
#   - a tiny scene's export checked structurally: the mirrored camera before
#     LookAt, fov of the shorter axis, the light's I = P/(4 pi), each
#     material and shape; negative controls: the same checker on doctored
#     exports (each mapping undone) must fail;
#   - refusals with a named cause (exit 2, no output file left);
#   - the committed reference/SCENE/*-pbrt-*.pbrt are what the exporter
#     writes now (else the pbrt references are stale);
#   - with pbrt (PBRT=/path/to/pbrt or on PATH), direct light alone against
#     --direct shadow-rays per pixel; skipped otherwise.
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
current() {
  local n=0 f scene size
  for f in reference/*/*-pbrt-bdpt-*.pbrt reference/*/*-pbrt-path-*.pbrt; do
    [ -e "$f" ] || continue
    scene=${f#reference/}; scene=${scene%%/*}
    size=${f##*-}; size=${size%.pbrt}
    if [[ $f == *-pbrt-bdpt-* ]]; then
      $PM export-pbrt scenes/$scene.scene --width ${size%x*} --height ${size#*x} --integrator bdpt --bounces 9 \
        --spp "$(sed -n 's/.*"integer xsamples" \[ \([0-9]*\) \].*/\1/p' "$f" | awk '{print $1 * $1}')" -o "$TMP/c.pbrt"
    else
      $PM export-pbrt scenes/$scene.scene --width ${size%x*} --height ${size#*x} --integrator path --bounces 63 \
        --min-bounces 9 --spp "$(sed -n 's/.*"integer xsamples" \[ \([0-9]*\) \].*/\1/p' "$f" | awk '{print $1 * $1}')" -o "$TMP/c.pbrt"
    fi
    cmp "$TMP/c.pbrt" "$f" || return 1
    n=$((n + 1))
  done
  [ "$n" -gt 0 ] || { echo "no committed pbrt scene found"; return 1; }
}
check "committed reference/*/*-pbrt-*.pbrt are the exporter's output" current

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
else
  echo "skip pbrt direct-light check: pbrt-v3 not found (PBRT=/path/to/pbrt; reference/pbrt/README.md)"
fi
finish
