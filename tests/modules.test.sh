#!/usr/bin/env bash
# modules: the renderer's modules depend one way. Module A depends on B when
# one of A's files (A.c, A.h, A.inc) includes "B.h" (or B.inc); the checks
# fail when that graph of renderer/ has a cycle, and show the checker finds
# one in a made-up directory (the negative control).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

# "A B" for each dependency of module A on module B among the files of $1
module_edges() {
  local f a b
  for f in "$1"/*.c "$1"/*.h "$1"/*.inc; do
    [ -e "$f" ] || continue
    a=$(basename "$f"); a=${a%.*}
    echo "$a $a"
    for b in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f"); do
      b=$(basename "$b"); b=${b%.*}
      [ "$a" = "$b" ] || echo "$a $b"
    done
  done
}

# passes when the module graph of $1 has no cycle; prints the cycle if it has
acyclic() {
  module_edges "$1" | tsort >/dev/null
}
has_cycle() { ! acyclic "$1" 2>/dev/null; }

check "renderer/: the module include graph has no cycle" acyclic renderer
mkdir -p "$TMP/cycle" "$TMP/line"
printf '#include "b.h"\n' >"$TMP/cycle/a.c"
printf '#include "c.h"\n' >"$TMP/cycle/b.h"
printf '#include "a.h"\n' >"$TMP/cycle/c.c"
printf '\n' >"$TMP/cycle/a.h"
cp "$TMP/cycle/"* "$TMP/line/"
printf '\n' >"$TMP/line/c.c"
check "negative control: a cycle a -> b -> c -> a is found" has_cycle "$TMP/cycle"
check "control: the same modules without c -> a pass" acyclic "$TMP/line"
finish
