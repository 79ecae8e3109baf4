#!/usr/bin/env bash
# findref.sh WxH: prints the POV-Ray reference EXR of the full scene at that
# size from reference/ (issue 4's `make reference`), or nothing. Prefers
# reference/*reference-WxH*.exr (reference quality); never a direct-only,
# fast-preset or negative-control (nocaustic) render.
s=$1
{ ls reference/*reference*"-$s".exr 2>/dev/null
  ls reference/*"$s"*.exr 2>/dev/null | grep -viE 'direct|fast|nocaustic'; } | head -n 1
