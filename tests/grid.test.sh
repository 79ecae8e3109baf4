#!/usr/bin/env bash
# grid.test.sh: experiments/bench/grid.sh (the paper's grid behind `make
# bench`) on a tiny instance (one P_e): 8 rows and the summary line; every render
# pinned to the first CPU the script may run on (GRID_CPU=first, the
# default), the line saying so; the control GRID_CPU=none leaves the renders
# every CPU (where there is more than one) and says "unpinned".
cd "$(dirname "$0")/.." || exit 1
. tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}

if [ ! -x "$PM" ] || ! command -v taskset > /dev/null || ! "$PY" -c "import pandas" 2> /dev/null; then
  echo "skipped: grid.sh needs $PM, taskset and pandas"
  echo "0 passed, 0 failed, 1 skipped"
  exit 0
fi

# a renderer that logs the CPUs it may run on, then renders
cat > "$TMP/pm" << EOF
#!/bin/sh
grep Cpus_allowed_list /proc/self/status | cut -f2 >> "$TMP/cpus"
exec "$PWD/$PM" "\$@"
EOF
chmod +x "$TMP/pm"
first=$("$PY" -c 'import os; print(min(os.sched_getaffinity(0)))')
all=$(grep Cpus_allowed_list /proc/self/status | cut -f2)
tiny() {
  rm -f "$TMP/cpus"
  GRID_PHOTONS=2000 GRID_WIDTH=16 GRID_HEIGHT=12 GRID_REPEATS=1 PYTHON="$PY" "$@" \
    bash experiments/bench/grid.sh "$TMP/pm" > "$TMP/out"
}
check "grid.sh: 8 renders (one P_e) and the summary line, every render pinned to the first CPU" bash -c "
  $(declare -f tiny); TMP='$TMP'; PY='$PY'; tiny env || exit 1
  test \$(grep -c '^\(conventional\|precomputed\) 2000 ' '$TMP/out') -eq 8 &&
  tail -n 1 '$TMP/out' | grep -q '^grid: [0-9.]* s, conventional .*, every render pinned to CPU $first\$' &&
  test \"\$(sort -u '$TMP/cpus')\" = '$first' && test \$(wc -l < '$TMP/cpus') -eq 8"
check "control: GRID_CPU=none leaves the renders every CPU and says unpinned" bash -c "
  $(declare -f tiny); TMP='$TMP'; PY='$PY'; tiny env GRID_CPU=none || exit 1
  tail -n 1 '$TMP/out' | grep -q ', unpinned\$' && test \"\$(sort -u '$TMP/cpus')\" = '$all'"
finish
