#!/usr/bin/env bash
# measure.sh: the measurements quoted in reference/README.md, re-run from
# the committed references (run from the repository root after `make`):
#   bash reference/measure.sh [OUTDIR]
# Prints one line per comparison: what was compared, then scripts/imgcmp.sh's
# verdict line. Renders of ours go to OUTDIR (default build/measure).
set -u
cd "$(dirname "$0")/.."
PM=build/photonmap
OUT=${1:-build/measure}
mkdir -p "$OUT"
CMP="bash scripts/imgcmp.sh"
S=scenes/cornell.scene
R=reference

show() { # label, imgcmp args...
  local label=$1; shift
  printf '%-58s %s\n' "$label" "$($CMP "$@" 2>&1 | tr '\n' ' ')"
}

sed 's/^material red   lambert rho 0.63 0.065 0.05/material red   lambert rho 0.065 0.63 0.05/' $S > "$OUT/green.scene"
sed 's/^\(rect corner  1 0 -1 .*\)material mirror  # right/\1material white   # right/' $S > "$OUT/diffmirror.scene"

echo "== direct light only (ours: --direct shadow-rays --photons 0; POV-Ray: --no-radiosity --no-photons)"
$PM render $S --direct shadow-rays --photons 0 --width 129 --height 96 --subpixels 3 --quiet -o "$OUT/direct-129.exr"
$PM render $S --direct shadow-rays --photons 0 --width 256 --height 192 --quiet -o "$OUT/direct-256.exr"
show "direct 129x96 3x3 vs cornell-direct-129x96 (pixel)" pixel "$OUT/direct-129.exr" $R/cornell/cornell-direct-129x96.exr 1e-3 1
show "direct 256x192 2x2 vs cornell-direct-256x192 (pixel)" pixel "$OUT/direct-256.exr" $R/cornell/cornell-direct-256x192.exr 1e-3 1
show "direct 256x192 2x2 vs cornell-direct-256x192 (block 32x24)" block "$OUT/direct-256.exr" $R/cornell/cornell-direct-256x192.exr 32 24 0.15

echo "== full image, P_e = 500k, n = 100, 256x192, vs POV-Ray fast and reference"
for m in photons shadow-rays; do
  $PM render $S --photons 500000 --nn 100 --width 256 --height 192 --direct $m --quiet -o "$OUT/full-256-$m.exr"
  for q in fast reference; do
    [ -e $R/cornell/cornell-$q-256x192.exr ] || continue
    show "ours --direct $m vs POV $q (block 32x24)" block "$OUT/full-256-$m.exr" $R/cornell/cornell-$q-256x192.exr 32 24 0.15
    show "ours --direct $m vs POV $q (block 16x12)" block "$OUT/full-256-$m.exr" $R/cornell/cornell-$q-256x192.exr 16 12 0.15
    show "ours --direct $m vs POV $q (stats)" stats "$OUT/full-256-$m.exr" $R/cornell/cornell-$q-256x192.exr
  done
done

echo "== POV-Ray against itself"
if [ -e $R/cornell/cornell-reference-256x192.exr ]; then
  show "POV fast vs POV reference 256x192 (stats)" stats $R/cornell/cornell-fast-256x192.exr $R/cornell/cornell-reference-256x192.exr
  show "POV fast vs POV reference 256x192 (block 32x24)" block $R/cornell/cornell-fast-256x192.exr $R/cornell/cornell-reference-256x192.exr 32 24 0.15
  show "POV fast vs POV reference 256x192 (block 16x12)" block $R/cornell/cornell-fast-256x192.exr $R/cornell/cornell-reference-256x192.exr 16 12 0.15
fi
if [ -e $R/cornell/cornell-reference-1024x768.exr ]; then
  oiiotool $R/cornell/cornell-reference-1024x768.exr --resize:filter=box 256x192 -o "$OUT/pov-ref-1024-to-256.exr"
  show "POV reference 1024x768 downsampled vs POV reference 256x192" block "$OUT/pov-ref-1024-to-256.exr" $R/cornell/cornell-reference-256x192.exr 32 24 0.15
fi
oiiotool $R/cornell/cornell-fast-256x192.exr --resize:filter=box 128x96 -o "$OUT/pov-fast-256-to-128.exr"
show "POV fast 256x192 downsampled vs POV fast 128x96 (block 16x12)" block "$OUT/pov-fast-256-to-128.exr" $R/cornell/cornell-fast-128x96.exr 16 12 0.15

echo "== negative controls, 256x192, against POV-Ray fast"
oiiotool "$OUT/full-256-photons.exr" --mulc 0.8 -o "$OUT/x08.exr"
oiiotool "$OUT/full-256-photons.exr" --mulc 3.14159265 -o "$OUT/xpi.exr"
$PM render "$OUT/green.scene" --photons 500000 --nn 100 --width 256 --height 192 --quiet -o "$OUT/green.exr"
$PM render "$OUT/diffmirror.scene" --photons 500000 --nn 100 --width 256 --height 192 --quiet -o "$OUT/diffmirror.exr"
for c in x08 xpi green diffmirror; do
  show "control $c (block 32x24)" block "$OUT/$c.exr" $R/cornell/cornell-fast-256x192.exr 32 24 0.15
  show "control $c (block 16x12)" block "$OUT/$c.exr" $R/cornell/cornell-fast-256x192.exr 16 12 0.15
done

echo "== test size 128x96 (tests/povray.test.sh): full image and controls, 16x12 blocks"
F=(--photons 500000 --nn 100 --width 128 --height 96 --quiet)
for m in photons shadow-rays; do
  $PM render $S "${F[@]}" --direct $m -o "$OUT/full-128-$m.exr"
  show "ours --direct $m vs POV fast 128x96" block "$OUT/full-128-$m.exr" $R/cornell/cornell-fast-128x96.exr 16 12 0.15
done
oiiotool "$OUT/full-128-photons.exr" --mulc 0.8 -o "$OUT/x08-128.exr"
show "control x0.8" block "$OUT/x08-128.exr" $R/cornell/cornell-fast-128x96.exr 16 12 0.15
show "POV no glass caustic vs POV fast (cornell.scene)" block $R/cornell/cornell-nocaustic-128x96.exr $R/cornell/cornell-fast-128x96.exr 16 12 0.15
if [ -e $R/caustic/caustic-fast-128x96.exr ]; then
  $PM render $R/caustic.scene "${F[@]}" -o "$OUT/caustic-128.exr"
  $PM render $R/caustic.scene "${F[@]}" --direct shadow-rays -o "$OUT/caustic-128-sr.exr"
  show "caustic scene: ours vs POV fast" block "$OUT/caustic-128.exr" $R/caustic/caustic-fast-128x96.exr 16 12 0.15
  show "caustic scene: ours shadow-rays vs POV fast" block "$OUT/caustic-128-sr.exr" $R/caustic/caustic-fast-128x96.exr 16 12 0.15
  show "caustic scene: POV no caustic vs POV fast" block $R/caustic/caustic-nocaustic-128x96.exr $R/caustic/caustic-fast-128x96.exr 16 12 0.15
  if [ -e $R/caustic/caustic-reference-128x96.exr ]; then
    show "caustic scene: ours vs POV reference" block "$OUT/caustic-128.exr" $R/caustic/caustic-reference-128x96.exr 16 12 0.15
    show "caustic scene: ours shadow-rays vs POV reference" block "$OUT/caustic-128-sr.exr" $R/caustic/caustic-reference-128x96.exr 16 12 0.15
    show "caustic scene: POV fast vs POV reference" block $R/caustic/caustic-fast-128x96.exr $R/caustic/caustic-reference-128x96.exr 16 12 0.15
  fi
fi
if [ -e $R/caustic/caustic-fast-128x96.exr ]; then
  export IMGCMP_CUT=24x20+52+76
  show "caustic window: ours vs POV fast (6x5 blocks)" block "$OUT/caustic-128.exr" $R/caustic/caustic-fast-128x96.exr 6 5 0.15
  show "caustic window: ours shadow-rays vs POV fast" block "$OUT/caustic-128-sr.exr" $R/caustic/caustic-fast-128x96.exr 6 5 0.15
  show "caustic window: POV no caustic vs POV fast" block $R/caustic/caustic-nocaustic-128x96.exr $R/caustic/caustic-fast-128x96.exr 6 5 0.15
  oiiotool "$OUT/caustic-128.exr" --mulc 0.8 -o "$OUT/caustic-x08.exr"
  show "caustic window: control x0.8" block "$OUT/caustic-x08.exr" $R/caustic/caustic-fast-128x96.exr 6 5 0.15
  unset IMGCMP_CUT
fi

echo "== direct-light controls (test size: 129x96, 3x3 subpixels)"
D=(--direct shadow-rays --photons 0 --width 129 --height 96 --subpixels 3 --quiet)
oiiotool "$OUT/direct-129.exr" --mulc 0.8 -o "$OUT/direct-x08.exr"
oiiotool "$OUT/direct-129.exr" --mulc 3.14159265 -o "$OUT/direct-xpi.exr"
$PM render "$OUT/green.scene" "${D[@]}" -o "$OUT/direct-green.exr"
$PM render "$OUT/diffmirror.scene" "${D[@]}" -o "$OUT/direct-diffmirror.exr"
awk '/shadow-only proxy/ { skip = 1 } !skip { print } skip && /^}/ { skip = 0 }' $R/cornell/cornell-direct-129x96.pov > "$OUT/noproxy.pov"
povray +I"$OUT/noproxy.pov" +O"$OUT/noproxy-raw.exr" +W387 +H288 +FE -A -J +WT1 -D -V +GS >/dev/null 2>&1
oiiotool "$OUT/noproxy-raw.exr" --resize:filter=box 129x96 -o "$OUT/direct-noshadow.exr"
for c in x08 xpi green diffmirror noshadow; do
  show "direct control $c (pixel)" pixel "$OUT/direct-$c.exr" $R/cornell/cornell-direct-129x96.exr 1e-3 1
done

echo "== POV-Ray re-run (single thread) vs the committed file"
povray +I$R/cornell/cornell-fast-16x12.pov +O"$OUT/rerun-raw.exr" +W32 +H24 +FE -A -J +WT1 -D -V +GS >/dev/null 2>&1
oiiotool "$OUT/rerun-raw.exr" --resize:filter=box 16x12 -d half -o "$OUT/rerun.exr"
printf '%-58s %s\n' "cornell-fast-16x12 re-rendered" "$(idiff -fail 0 -warn 0 "$OUT/rerun.exr" $R/cornell/cornell-fast-16x12.exr | tail -n 1)"
