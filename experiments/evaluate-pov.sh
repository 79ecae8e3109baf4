#!/usr/bin/env bash
# evaluate-pov.sh: one POV-Ray reference of a user's scene for `make
# evaluate` (experiments/rules/evaluate.smk), by the rule of the committed ones
# (reference/reference.mk): export-pov at 2W x 2H, POV-Ray single-threaded
# without antialiasing, oiiotool's 2x2 box filter down to W x H. Cached:
# the key is the SHA-256 of the exported SDL without its comment lines
# (the scene's content and every export setting, not its path), so a rerun,
# or the same scene under another name, renders nothing again.
#
#   evaluate-pov.sh SCENE W H CACHE OUT.exr EXPORT-OPTIONS...
#
# Writes CACHE/KEY/{scene.pov,image.exr,povray.log} (the image last, temp
# name then rename) and copies the image to OUT.exr (and the log beside it).
# Exit 1 with POV-Ray's last lines when it fails; 2 on a usage error.
set -euo pipefail
[ $# -ge 5 ] || { echo "usage: evaluate-pov.sh SCENE W H CACHE OUT.exr EXPORT-OPTIONS..." >&2; exit 2; }
scene=$1 w=$2 h=$3 cache=$4 out=$5; shift 5
PM=${PM:-build/photonmap}
POVRAY_FLAGS=${POVRAY_FLAGS:-+FE -A -J +WT1 -D -V +GS}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/evaluate-pov.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
"$PM" export-pov "$scene" --width $((2 * w)) --height $((2 * h)) "$@" -o "$tmp/scene.pov"
key=$(grep -v '^ *//' "$tmp/scene.pov" | sha256sum | cut -c1-16)
dir=$cache/$key
mkdir -p "$(dirname "$out")"
if [ -f "$dir/image.exr" ]; then
  echo "evaluate: POV-Ray $* at ${w}x${h}: cached ($dir)"
else
  command -v povray > /dev/null || { echo "evaluate: povray is not installed (make deps)" >&2; exit 1; }
  mkdir -p "$dir"
  cp "$tmp/scene.pov" "$dir/scene.pov"
  echo "evaluate: POV-Ray $* at ${w}x${h} (rendered at $((2 * w))x$((2 * h)), box-downsampled by 2)..."
  { echo "export: $PM export-pov $scene --width $((2 * w)) --height $((2 * h)) $*"
    echo "povray: povray +I$dir/scene.pov +O$tmp/raw.exr +W$((2 * w)) +H$((2 * h)) $POVRAY_FLAGS"
    echo "downsample: oiiotool raw.exr --resize:filter=box ${w}x${h} -d half"
    echo "version: $(povray --version 2>&1 | grep -m1 POV-Ray || true)"; } > "$tmp/povray.log"
  # shellcheck disable=SC2086  # the flags are words
  if ! nice povray +I"$dir/scene.pov" +O"$tmp/raw.exr" +W$((2 * w)) +H$((2 * h)) $POVRAY_FLAGS >> "$tmp/povray.log" 2>&1; then
    tail -n 20 "$tmp/povray.log" >&2; exit 1
  fi
  oiiotool "$tmp/raw.exr" --resize:filter=box "${w}x${h}" -d half -o "$tmp/image.exr"
  grep -v -e '^  *[0-9.]*%' -e 'Rendered [0-9]* of' "$tmp/povray.log" > "$dir/povray.log"
  mv "$tmp/image.exr" "$dir/image.exr.tmp" && mv "$dir/image.exr.tmp" "$dir/image.exr"
fi
cp "$dir/povray.log" "${out%.exr}.log"
cp "$dir/image.exr" "$out.tmp" && mv "$out.tmp" "$out"
