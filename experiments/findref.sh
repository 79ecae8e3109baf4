#!/usr/bin/env bash
# findref.sh [--fast] WxH [SCENE]: prints the POV-Ray reference EXR of the
# full scene (default scenes/cornell.scene) at that size from
# reference/<scene>/ (`make reference`), or nothing. Prefers, for the
# studies' per-pixel metrics, the one rendered with the renders' own 2x2
# subpixel rays: reference/<scene>/<scene>-reference-2x2-WxH.exr, then
# reference/<scene>/<scene>-reference-WxH.exr (at 1024x768 that one has one
# sample per pixel: block metrics only, reference/README.md); never a
# direct-only, fast-preset, bounce-limited (-bK-), negative-control
# (nocaustic) or pbrt render, nor
# another scene's. With --fast: the fast preset of the same pixels and the
# same sampling as the reference printed without --fast
# (<scene>-fast-2x2-WxH.exr beside a 2x2 reference, <scene>-fast-WxH.exr
# beside the other), whose error against it is the reference's floor; nothing
# if there is none.
set -euo pipefail
fast=0
[ "${1:-}" = --fast ] && { fast=1; shift; }
s=$1
name=$(basename "${2:-${SCENE:-scenes/cornell.scene}}" .scene)
d=reference/$name
if [ "$fast" -eq 1 ]; then
  if [ -e "$d/$name-reference-2x2-$s.exr" ]; then
    ls "$d/$name-fast-2x2-$s.exr" 2>/dev/null || true
  else
    ls "$d/$name-fast-$s.exr" 2>/dev/null || true
  fi
  exit 0
fi
{ ls "$d/$name-reference-2x2-$s.exr" 2>/dev/null || true
  ls "$d/$name-reference-$s.exr" 2>/dev/null || true
  ls "$d/$name"-*"$s"*.exr 2>/dev/null | grep -viE 'direct|fast|nocaustic|pbrt|-b[0-9]+-' || true; } | head -n 1
