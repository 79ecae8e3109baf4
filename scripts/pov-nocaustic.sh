#!/usr/bin/env bash
# pov-nocaustic.sh IN.pov SCENE W H: prints IN.pov (exported with photons on)
# changed into the "glass caustic missing" negative control: the glass is no
# longer a photon target, so it gets no caustic, and the shadow-only proxy
# that `export-pov --no-photons` writes is added so that the glass still
# blocks direct light. Everything else (radiosity, mirror caustics) stays.
set -eu -o pipefail
in=$1 scene=$2 w=$3 h=$4
proxy=$(build/photonmap export-pov "$scene" --width "$w" --height "$h" --no-photons |
        awk '/shadow-only proxy/ { p = 1 } p { print } p && /^}/ { p = 0 }')
[ -n "$proxy" ] || { echo "pov-nocaustic: no glass proxy in the export of $scene" >&2; exit 1; }
grep -q 'photons { target reflection on refraction on' "$in" || { echo "pov-nocaustic: no glass target in $in" >&2; exit 1; }
sed 's|^  photons { target reflection on refraction on collect off }|  // glass caustic removed (negative control)|' "$in"
printf '%s\n' "$proxy"
