#!/usr/bin/env bash
# pytest.test.sh: every tests/test_*.py (the analysis package
# experiments/analysis/, one file per module), collected by one `pytest
# tests/` on Debian's python3 (numpy, scipy, pandas, OpenImageIO,
# python3-pytest) from the repository root. Shows pytest's own summary line,
# then the same counts as "N passed, N failed, N skipped" for tests/run.sh;
# exits non-zero on a failure. No test collected (pytest's exit 5) is one
# skip, not a failure; no pytest at all is one skip too.
set -uo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-/usr/bin/python3}
if ! "$PY" -c 'import pytest' 2>/dev/null; then
  echo "skipped: $PY has no pytest (python3-pytest)"; echo "0 passed, 0 failed, 1 skipped"; exit 0
fi
out=$("$PY" -m pytest -q -p no:cacheprovider tests/ 2>&1); rc=$?
printf '%s\n' "$out"
if [ "$rc" -eq 5 ]; then
  echo "pytest: no test collected under tests/"; echo "0 passed, 0 failed, 1 skipped"; exit 0
fi
summary=$(printf '%s\n' "$out" | grep -E '[0-9]+ (passed|failed|errors?|skipped)( |,|$)' | tail -n 1 | sed 's/^=* *//; s/ *=*$//')
num() { printf '%s\n' "$summary" | grep -oE "[0-9]+ $1" | grep -oE '[0-9]+' || echo 0; }
passed=$(num passed) failed=$(num failed) errors=$(num error) skipped=$(num skipped)
[ -n "$summary" ] || { echo "pytest.test.sh: no pytest summary line (exit $rc)"; failed=1; }
echo "pytest: $summary"
echo "$passed passed, $((failed + errors)) failed, $skipped skipped"
[ "$rc" -eq 0 ]
