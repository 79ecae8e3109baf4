#!/usr/bin/env bash
# render.sh SCENE W H BDPT_SPP PATH_SPP SEED: one independent pbrt-v3
# reference of scenes/SCENE.scene at WxH, written to
# reference/SCENE/SCENE-pbrt-bdpt-WxH-seedSEED.{exr,log}: bidirectional path
# tracing of paths with up to 24 bounces (maxdepth 24, i.e. export-pbrt
# --bounces 23) plus the path tracer for bounces 25 to 64 (--min-bounces 23
# --bounces 63, the local mindepth change), summed: disjoint path sets. The
# path tracer cannot sample a path that reaches the point light only through
# mirror or glass (reference/pbrt/README.md), so BDPT carries every bounce
# that matters and the path tracer only the faint tail. The exported scenes
# are kept beside them (SCENE-pbrt-bdpt-WxH.pbrt, SCENE-pbrt-path-WxH.pbrt).
# PBRT_SEED=SEED (the local seed change) makes the runs independent.
# PBRT: the pbrt binary (default: pbrt on PATH); PBRT_THREADS (default 2).
# PBRT_SCENE_FILE, PBRT_OUT_DIR (tests/pbrt.test.sh): render that scene file
# into that directory instead of scenes/SCENE.scene into reference/SCENE.
# PBRT_SPLIT (default 23): the bounces BDPT takes; PBRT_MIN_BOUNCES (default
# PBRT_SPLIT): the path tracer's --min-bounces (both for the tests' negative
# controls; the references use the defaults).
# Exit 2 on bad arguments, 1 when pbrt is missing or a step fails; nothing
# that reads as a finished EXR is left behind then (temp files and mv).
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: $0 SCENE W H BDPT_SPP PATH_SPP SEED" >&2; exit 2; }
scene=$1 w=$2 h=$3 sb=$4 sp=$5 seed=$6
for v in "$w" "$h" "$sb" "$sp" "$seed"; do
  [[ $v =~ ^[0-9]+$ ]] || { echo "$0: '$v' is not a non-negative integer" >&2; exit 2; }
done
cd "$(dirname "$0")/../.."
pbrt=${PBRT:-$(command -v pbrt || true)}
[ -n "$pbrt" ] && [ -x "$pbrt" ] || {
  echo "$0: pbrt-v3 not found (set PBRT=/path/to/pbrt; reference/pbrt/README.md says how to build it)" >&2; exit 1; }
threads=${PBRT_THREADS:-2}
split=${PBRT_SPLIT:-23}
min=${PBRT_MIN_BOUNCES:-$split}
for v in "$split" "$min"; do
  [[ $v =~ ^[0-9]+$ ]] || { echo "$0: PBRT_SPLIT or PBRT_MIN_BOUNCES '$v' is not a non-negative integer" >&2; exit 2; }
done
src=${PBRT_SCENE_FILE:-scenes/$scene.scene} dir=${PBRT_OUT_DIR:-reference/$scene}
base=$scene-pbrt-bdpt-${w}x${h}
tmp=${PBRT_OUT_DIR:+$PBRT_OUT_DIR/tmp}; tmp=${tmp:-build/reference/pbrt}; mkdir -p "$tmp" "$dir"
pb=$dir/$scene-pbrt-bdpt-${w}x${h}.pbrt pp=$dir/$scene-pbrt-path-${w}x${h}.pbrt
build/photonmap export-pbrt "$src" --width "$w" --height "$h" --integrator bdpt --bounces "$split" \
  --spp "$sb" -o "$tmp/$scene-b.pbrt"
build/photonmap export-pbrt "$src" --width "$w" --height "$h" --integrator path --bounces 63 \
  --min-bounces "$min" --spp "$sp" -o "$tmp/$scene-p.pbrt"
cmp -s "$tmp/$scene-b.pbrt" "$pb" || mv "$tmp/$scene-b.pbrt" "$pb"
cmp -s "$tmp/$scene-p.pbrt" "$pp" || mv "$tmp/$scene-p.pbrt" "$pp"
log=$tmp/$base-seed$seed.log
{ echo "pbrt reference $base-seed$seed: $scene ${w}x${h}, seed $seed"
  echo "export: build/photonmap export-pbrt $src --width $w --height $h --integrator bdpt --bounces $split --spp $sb"
  echo "export: build/photonmap export-pbrt $src --width $w --height $h --integrator path --bounces 63 --min-bounces $min --spp $sp"
  echo "pbrt: PBRT_SEED=$seed nice pbrt --nthreads $threads --outfile B.exr $pb; the same with $pp to P.exr"
  echo "sum: oiiotool B.exr P.exr --add -d half -o $base-seed$seed.exr"
  echo "version: pbrt-v3 $(git -C "$(dirname "$pbrt")/.." log -1 --format=%h 2>/dev/null || echo unknown) with the two local changes; $(oiiotool --version 2>&1 | head -n1)"
  echo "host: $(uname -m), $(nproc) cores; date: $(date -u +%Y-%m-%dT%H:%MZ)"; } > "$log"
for part in b p; do
  f=$pb; [ $part = p ] && f=$pp
  { echo "---- pbrt ($part)"; PBRT_SEED=$seed /usr/bin/time -f "pbrt $part: %e s wall, %U s user" \
      nice -n 5 "$pbrt" --nthreads "$threads" --quiet --outfile "$tmp/$base-seed$seed-$part.exr" "$f"; } >> "$log" 2>&1 || {
    tail -n 20 "$log" >&2; exit 1; }
done
oiiotool "$tmp/$base-seed$seed-b.exr" "$tmp/$base-seed$seed-p.exr" --add -d half -o "$tmp/$base-seed$seed.exr"
mv "$log" "$dir/$base-seed$seed.log"
mv "$tmp/$base-seed$seed.exr" "$dir/$base-seed$seed.exr"
rm -f "$tmp/$base-seed$seed-b.exr" "$tmp/$base-seed$seed-p.exr"
