#!/usr/bin/env bash
# measure-scenes.sh: the measurements behind tests/scenes.test.sh (quoted in
# reference/README.md, "More scenes"): for each scene that stresses the
# method, correct pairs (ours with the test's settings, both methods and both
# --direct modes, against POV-Ray fast and reference) and wrong pairs (the
# negative controls), by the block metric and the channel means.
#   bash reference/measure-scenes.sh [OUTDIR]     (run after `make`)
# Prints one line per pair: what, then scripts/imgcmp.sh's verdict line.
set -u
cd "$(dirname "$0")/.."
PM=build/photonmap
OUT=${1:-build/measure-scenes}
mkdir -p "$OUT"
R=reference
. tests/scenes.settings.sh

show() { # label, imgcmp args...
  local label=$1; shift
  printf '%-62s %s\n' "$label" "$(bash scripts/imgcmp.sh "$@" 2>&1 | sed 's/sRGB8.*//' | tr '\n' ' ')"
}
# render NAME SCENE SETTINGS-ARRAY-NAME [extra options]
render() {
  local name=$1 scene=$2 arr=$3[@]; shift 3
  $PM render "$scene" "${!arr}" "$@" --quiet -o "$OUT/$name.exr"
}

echo "== direct light only, per pixel (129x96, 3x3), against <scene>-direct-129x96"
for s in slabs library tworooms caustic; do
  [ -e $R/$s/$s-direct-129x96.exr ] || continue
  $PM render scenes/$s.scene "${DIRECT[@]}" -o "$OUT/$s-direct.exr"
  show "$s" pixel "$OUT/$s-direct.exr" $R/$s/$s-direct-129x96.exr "$DIRECT_REL" 1
done

echo "== slabs: ${SLABS[*]}, blocks ${SLABS_BLOCKS[*]}"
for m in conventional precomputed; do
  for d in photons shadow-rays; do
    render slabs-$m-$d scenes/slabs.scene SLABS --method $m --direct $d
    for q in fast reference; do show "ours $m --direct $d vs POV $q" block "$OUT/slabs-$m-$d.exr" $R/slabs/slabs-$q-128x96.exr "${SLABS_BLOCKS[@]}" 1; done
  done
done
show "POV fast vs POV reference" block $R/slabs/slabs-fast-128x96.exr $R/slabs/slabs-reference-128x96.exr "${SLABS_BLOCKS[@]}" 1
oiiotool "$OUT/slabs-precomputed-photons.exr" --mulc 0.8 -o "$OUT/slabs-x08.exr"
show "control: ours x0.8" block "$OUT/slabs-x08.exr" $R/slabs/slabs-reference-128x96.exr "${SLABS_BLOCKS[@]}" 1
sed "$SLABS_GREEN_WALL" scenes/slabs.scene > "$OUT/slabs-green.scene"
render slabs-green "$OUT/slabs-green.scene" SLABS --method precomputed
show "control: red wall green" block "$OUT/slabs-green.exr" $R/slabs/slabs-reference-128x96.exr "${SLABS_BLOCKS[@]}" 1
grep -v "$SLABS_NO_BLINDS" scenes/slabs.scene > "$OUT/slabs-noblinds.scene"
render slabs-noblinds "$OUT/slabs-noblinds.scene" SLABS --method precomputed
show "control: blinds removed" block "$OUT/slabs-noblinds.exr" $R/slabs/slabs-reference-128x96.exr "${SLABS_BLOCKS[@]}" 1
for p in 500000 1000000; do
  render slabs-p$p scenes/slabs.scene SLABS --method precomputed --photons $p
  show "precomputed at P_e = $p (finding: thin-geometry bias)" block "$OUT/slabs-p$p.exr" $R/slabs/slabs-reference-128x96.exr "${SLABS_BLOCKS[@]}" 1
done

echo "== tworooms: ${TWOROOMS[*]}, blocks ${TWOROOMS_BLOCKS[*]}, against 2 bounces"
for m in conventional precomputed; do
  for d in photons shadow-rays; do
    render tworooms-$m-$d scenes/tworooms.scene TWOROOMS --method $m --direct $d
    for q in fast reference; do show "ours $m --direct $d vs POV b2 $q" block "$OUT/tworooms-$m-$d.exr" $R/tworooms/tworooms-b2-$q-128x96.exr "${TWOROOMS_BLOCKS[@]}" 1; done
  done
done
show "POV b2 fast vs POV b2 reference" block $R/tworooms/tworooms-b2-fast-128x96.exr $R/tworooms/tworooms-b2-reference-128x96.exr "${TWOROOMS_BLOCKS[@]}" 1
oiiotool "$OUT/tworooms-conventional-photons.exr" --mulc 0.8 -o "$OUT/tworooms-x08.exr"
show "control: ours x0.8" block "$OUT/tworooms-x08.exr" $R/tworooms/tworooms-b2-reference-128x96.exr "${TWOROOMS_BLOCKS[@]}" 1
render tworooms-depth2 scenes/tworooms.scene TWOROOMS --photon-depth 2
show "control: one bounce (--photon-depth 2)" block "$OUT/tworooms-depth2.exr" $R/tworooms/tworooms-b2-reference-128x96.exr "${TWOROOMS_BLOCKS[@]}" 1
sed "$TWOROOMS_WHITE_WALL" scenes/tworooms.scene > "$OUT/tworooms-white.scene"
render tworooms-white "$OUT/tworooms-white.scene" TWOROOMS
show "control: orange wall white" block "$OUT/tworooms-white.exr" $R/tworooms/tworooms-b2-reference-128x96.exr "${TWOROOMS_BLOCKS[@]}" 1
echo "-- every bounce (--photon-depth 64) against POV-Ray's 20 (finding: POV-Ray stops adding light)"
render tworooms-all scenes/tworooms.scene TWOROOMS --photon-depth 64
for q in fast reference; do show "ours all bounces vs POV $q (20 bounces)" block "$OUT/tworooms-all.exr" $R/tworooms/tworooms-$q-128x96.exr "${TWOROOMS_BLOCKS[@]}" 1; done

echo "== library: ${LIBRARY[*]}, blocks ${LIBRARY_BLOCKS[*]}"
for m in conventional precomputed; do
  for d in photons shadow-rays; do
    render library-$m-$d scenes/library.scene LIBRARY --method $m --direct $d
    for q in fast reference; do show "ours $m --direct $d vs POV $q" block "$OUT/library-$m-$d.exr" $R/library/library-$q-128x96.exr "${LIBRARY_BLOCKS[@]}" 1; done
  done
done
show "POV fast vs POV reference" block $R/library/library-fast-128x96.exr $R/library/library-reference-128x96.exr "${LIBRARY_BLOCKS[@]}" 1
oiiotool "$OUT/library-conventional-photons.exr" --mulc 0.8 -o "$OUT/library-x08.exr"
show "control: ours x0.8" block "$OUT/library-x08.exr" $R/library/library-reference-128x96.exr "${LIBRARY_BLOCKS[@]}" 1
sed "$LIBRARY_GREY_BOOKS" scenes/library.scene > "$OUT/library-grey.scene"
render library-grey "$OUT/library-grey.scene" LIBRARY
show "control: every book grey" block "$OUT/library-grey.exr" $R/library/library-reference-128x96.exr "${LIBRARY_BLOCKS[@]}" 1
