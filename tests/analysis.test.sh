#!/usr/bin/env bash
# analysis.test.sh: the unit tests of the experiment analysis layer (the
# package experiments/analysis/), tests/test_analysis.py, run by pytest on
# Debian's python3 (numpy, scipy, pandas, OpenImageIO, python3-pytest) from
# the repository root. Shows pytest's own summary line, then the same counts
# as "N passed, N failed" for tests/run.sh; exits non-zero on a failure.
set -uo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-/usr/bin/python3}
out=$("$PY" -m pytest -q -p no:cacheprovider tests/test_analysis.py 2>&1); rc=$?
printf '%s\n' "$out"
summary=$(printf '%s\n' "$out" | grep -E '[0-9]+ (passed|failed|errors?)( |,|$)' | tail -n 1 | sed 's/^=* *//; s/ *=*$//')
num() { printf '%s\n' "$summary" | grep -oE "[0-9]+ $1" | grep -oE '[0-9]+' || echo 0; }
passed=$(num passed) failed=$(num failed) errors=$(num error)
[ -n "$summary" ] || { echo "analysis.test.sh: no pytest summary line (exit $rc)"; failed=1; }
echo "pytest: $summary"
echo "$passed passed, $((failed + errors)) failed"
[ "$rc" -eq 0 ]
