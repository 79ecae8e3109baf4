#!/usr/bin/env bash
# findref.sh [--fast] WxH [SCENE]: prints the POV-Ray reference EXR of the
# full scene (default scenes/cornell.scene) at that size from
# reference/<scene>/ (`make reference`), or nothing. Prefers
# reference/<scene>/<scene>-reference-WxH.exr (reference quality); never a
# direct-only, fast-preset or negative-control (nocaustic) render, nor another
# scene's. With --fast: reference/<scene>/<scene>-fast-WxH.exr, the fast preset of the
# same pixels, whose error against the reference is the reference's floor.
set -euo pipefail
fast=0
[ "${1:-}" = --fast ] && { fast=1; shift; }
s=$1
name=$(basename "${2:-${SCENE:-scenes/cornell.scene}}" .scene)
if [ "$fast" -eq 1 ]; then
  ls "reference/$name/$name-fast-$s.exr" 2>/dev/null || true
  exit 0
fi
{ ls "reference/$name/$name-reference-$s.exr" 2>/dev/null || true
  ls "reference/$name/$name"-*"$s"*.exr 2>/dev/null | grep -viE 'direct|fast|nocaustic' || true; } | head -n 1
