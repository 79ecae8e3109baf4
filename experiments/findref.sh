#!/usr/bin/env bash
# findref.sh WxH [SCENE]: prints the POV-Ray reference EXR of the full scene
# (default scenes/cornell.scene) at that size from reference/ (issue 4's
# `make reference`), or nothing. Prefers reference/<scene>-reference-WxH.exr
# (reference quality); never a direct-only, fast-preset or negative-control
# (nocaustic) render, nor another scene's.
s=$1
name=$(basename "${2:-${SCENE:-scenes/cornell.scene}}" .scene)
{ ls "reference/$name-reference-$s.exr" 2>/dev/null
  ls "reference/$name"-*"$s"*.exr 2>/dev/null | grep -viE 'direct|fast|nocaustic'; } | head -n 1
