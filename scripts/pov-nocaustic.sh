#!/usr/bin/env bash
# pov-nocaustic.sh IN.pov SCENE W H: prints the "glass caustic missing"
# negative control of IN.pov (exported from SCENE at WxH with photons on):
# `export-pov --no-glass-caustics` at IN.pov's quality.
set -eu -o pipefail
in=$1 scene=$2 w=$3 h=$4
quality=$(sed -n 's|^// settings: .*, quality \([a-z]*\),.*|\1|p' "$in")
[ -n "$quality" ] || { echo "pov-nocaustic: no settings line in $in" >&2; exit 1; }
build/photonmap export-pov "$scene" --width "$w" --height "$h" --quality "$quality" --no-glass-caustics
