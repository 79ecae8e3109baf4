# lib.sh: helpers for the tests/*.test.sh scripts (sourced). `check NAME CMD...`
# runs one check; `skip NAME` counts one that cannot run here; `finish`
# prints "N passed, N failed" (", N skipped" when any was) and sets the exit
# code.
PASS=0
FAIL=0
SKIP=0
PM=${PM:-build/photonmap}
TMP=$(mktemp -d /tmp/pm-test.XXXXXX)
trap 'rm -rf "$TMP"' EXIT

check() { # name, command...: passes when the command exits 0
  local name=$1; shift
  if ( "$@" ) >"$TMP/.out" 2>&1; then
    PASS=$((PASS + 1)); echo "ok   $name"
  else
    FAIL=$((FAIL + 1)); echo "FAIL $name"; sed 's/^/     /' "$TMP/.out" | head -n 20
  fi
}

# expect_exit CODE PATTERN CMD...: the command exits CODE and its stderr matches PATTERN
expect_exit() {
  local code=$1 pattern=$2; shift 2
  local rc=0
  "$@" >"$TMP/.stdout" 2>"$TMP/.stderr" || rc=$?
  if [ "$rc" -ne "$code" ]; then echo "exit $rc, wanted $code; stderr:"; cat "$TMP/.stderr"; return 1; fi
  if ! grep -qE -- "$pattern" "$TMP/.stderr"; then echo "stderr does not match '$pattern':"; cat "$TMP/.stderr"; return 1; fi
}

skip() { # name: a check that cannot run here, reported and counted as skipped
  SKIP=$((SKIP + 1)); echo "skip $1"
}

finish() {
  if [ "$SKIP" -gt 0 ]; then echo "$PASS passed, $FAIL failed, $SKIP skipped"; else echo "$PASS passed, $FAIL failed"; fi
  [ "$FAIL" -eq 0 ]
}
