#!/usr/bin/env bash
# gather.test.sh: final gathering (--gather) on the paper's scene against the
# unbiased reference, pbrt-v3 BDPT (reference/cornell/cornell-pbrt-bdpt-
# 256x192-seed1,2.exr; reference/README.md, "A third reference: pbrt-v3").
#   cornell at 256x192, P_e = 1M, n = 50, N = 16 gather rays,
#   --bias-correction, seeds 1 and 2, both methods (about 60 CPU s in all):
#   - every 16x16 block of the directly seen diffuse surfaces (the regions:
#     pixels whose four subpixel rays hit one shape first, cast from the scene
#     file by reference/pbrt/agreement.py) is within 1% plus the noise of the
#     two sides (3 sigma of pbrt's and of ours, each from its two seeds'
#     difference pooled over the shape's blocks) of pbrt's mean;
#   - the blocks seen via mirror or glass (the right wall, the mirror and the
#     glass sphere) show paths light -> specular -> diffuse -> specular ->
#     eye, which BDPT cannot sample from a point light: there ours reads
#     above pbrt in every block, and POV-Ray's reference
#     (cornell-reference-256x192.exr, photons for those caustics) judges
#     them, each block within 3% (its own offset on the diffuse walls is up
#     to 1.4%);
#   negative controls: the image 2% dark, and the gathered light (all but
#   direct light, by --photons 0 --direct shadow-rays) 5% too strong, fail.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}
SCENE=scenes/cornell.scene
PBRT=reference/cornell/cornell-pbrt-bdpt-256x192-seed1.exr,reference/cornell/cornell-pbrt-bdpt-256x192-seed2.exr
POV=reference/cornell/cornell-reference-256x192.exr
GATHER=(--gather 16 --photons 1000000 --nn 50 --bias-correction --direct shadow-rays --width 256 --height 192 --threads 0 --quiet)

if ! "$PY" -c 'import numpy, OpenImageIO' 2>/dev/null; then
  echo "skipped: $PY lacks numpy or OpenImageIO"; echo "0 passed, 0 failed, 1 skipped"; exit 0
fi

render_all() {
  for m in conventional precomputed; do
    for s in 1 2; do
      $PM render "$SCENE" "${GATHER[@]}" --method "$m" --seed "$s" -o "$TMP/$m-$s.exr" || return 1
    done
  done
  $PM render "$SCENE" --photons 0 --direct shadow-rays --width 256 --height 192 --threads 0 --quiet -o "$TMP/direct.exr"
}
check "cornell 256x192 --gather 16, both methods, seeds 1-2, and its direct light" render_all

judge() { # MODE: check, scale=F (the image times F) or indirect=F (all but direct light times F)
  "$PY" tests/gather/pbrt_blocks.py "$SCENE" "$PBRT" "$POV" "$TMP/direct.exr" "$1" \
    "$TMP/conventional-1.exr" "$TMP/conventional-2.exr" "$TMP/precomputed-1.exr" "$TMP/precomputed-2.exr"
}
fails() { ! "$@"; }
check "every diffuse 16x16 block within 1% plus the noise of pbrt BDPT; specular blocks within 3% of POV-Ray" judge check
check "control: the image 2% dark fails" fails judge scale=0.98
check "control: the gathered light 5% too strong fails" fails judge indirect=1.05
finish
