#!/usr/bin/env bash
# slurm.sh: the work of `make sweep-slurm` (experiments/slurm.mk): writes a
# Slurm job array that runs a list of make targets, one array task per
# target, each as `make VARS TARGET` in this repository.
#
#   SLURM_DIR=DIR REPO=DIR MAKE_CMD=make [TASKS=FILE | SWEEP=TARGET] [SBATCH_OPTS=...] \
#     bash experiments/slurm.sh
#
# Reads DIR/make-vars (one NAME=VALUE per line: the variables given on the
# make command line, written by slurm.mk) and writes
#   DIR/tasks      the make targets, one per line (task i = line i)
#   DIR/sweep.sbatch  the job: `sbatch DIR/sweep.sbatch` submits it
#   DIR/logs/      where each task's output goes (%A_%a.out)
# TASKS names a file of targets (blank lines and lines starting with # are
# skipped); SWEEP names a make target whose prerequisites are the tasks
# (read from `make -pq`, i.e. make's own database, so any sweep that lists
# its independent runs as the prerequisites of one target can be sent).
# Exit status: 0, or 2 with a message for a usage error.
set -euo pipefail

die() { echo "sweep-slurm: $*" >&2; exit 2; }
: "${SLURM_DIR:?}" "${REPO:?}"
MAKE_CMD=${MAKE_CMD:-make}
TASKS=${TASKS:-} SWEEP=${SWEEP:-} SBATCH_OPTS=${SBATCH_OPTS:-}
[ -n "$TASKS" ] || [ -n "$SWEEP" ] || die "give TASKS=FILE (one make target per line) or SWEEP=TARGET (its prerequisites are the tasks)"
[ -z "$TASKS" ] || [ -z "$SWEEP" ] || die "give TASKS or SWEEP, not both"
[ -r "$SLURM_DIR/make-vars" ] || die "$SLURM_DIR/make-vars: missing (run through make sweep-slurm)"
mapfile -t vars < "$SLURM_DIR/make-vars"

list=$SLURM_DIR/tasks.tmp
if [ -n "$TASKS" ]; then
  [ -r "$TASKS" ] || die "TASKS=$TASKS: cannot read"
  awk -v f="$TASKS" '
    { sub(/\r$/, ""); sub(/^[ \t]+/, ""); sub(/[ \t]+$/, "") }
    $0 == "" || /^#/ { next }
    /[ \t]/ { printf "sweep-slurm: %s:%d: one make target per line, got \"%s\"\n", f, NR, $0 > "/dev/stderr"; bad = 1; next }
    { print }
    END { exit bad ? 2 : 0 }' "$TASKS" > "$list" || exit 2
  # every task must be a target this make can make: one dry run of them all
  # (-k goes on past the first) lists those it has no rule for
  if [ -s "$list" ]; then
    mapfile -t targets < "$list"
    missing=$("$MAKE_CMD" -C "$REPO" --no-print-directory -n -k "${vars[@]}" "${targets[@]}" 2>&1 >/dev/null |
      sed -n "s/.*No rule to make target '\([^']*\)'.*/\1/p" | sort -u | tr '\n' ' ' || true)
    [ -z "$missing" ] || die "TASKS=$TASKS: no make rule for: ${missing% }"
  fi
else
  case "$SWEEP" in *[[:space:]]*|"") die "SWEEP=$SWEEP: one target name" ;; esac
  # make's database: "TARGET: PREREQS | ORDER-ONLY" (rules merged over every
  # makefile); nothing is made (the goal is an empty target, -q).
  db=$SLURM_DIR/make-db.tmp
  "$MAKE_CMD" -C "$REPO" --no-print-directory -pq "${vars[@]}" sweep-slurm-nothing > "$db" 2>/dev/null || true
  grep -q '^# Files' "$db" || die "could not read make's database (make -pq)"
  awk -v t="$SWEEP" '
    /^# Files/ { files = 1 }
    files && index($0, t ":") == 1 && !found {
      rest = substr($0, length(t) + 2); sub(/^:/, "", rest)   # also "t::"
      n = split(rest, w, /[ \t]+/)
      for (i = 1; i <= n; i++) { if (w[i] == "|") break; if (w[i] != "") print w[i] }
      found = 1
    }
    END { exit found ? 0 : 3 }' "$db" > "$list" || die "SWEEP=$SWEEP: no such make target"
  rm -f "$db"
  # one task per recipe: the two records of a pair (experiments/study.mk's
  # pair rule, ROOT/conventional-X and ROOT/precomputed-X) are made together,
  # so the conventional one goes when its precomputed partner is listed
  awk '{ line[NR] = $0; have[$0] = 1 }
       END { for (i = 1; i <= NR; i++) { p = line[i]
               if (sub(/\/conventional-/, "/precomputed-", p) && (p in have)) continue
               print line[i] } }' "$list" > "$list.pairs"
  mv "$list.pairs" "$list"
  [ -s "$list" ] || die "SWEEP=$SWEEP: the target has no prerequisites to run as tasks"
fi
n=$(wc -l < "$list")
[ "$n" -gt 0 ] || die "TASKS=$TASKS: no targets in the file"
mv "$list" "$SLURM_DIR/tasks"
mkdir -p "$SLURM_DIR/logs"

# the job script: absolute paths, so it can be submitted from anywhere on a
# cluster that shares this file system
dir=$(cd "$SLURM_DIR" && pwd)
repo=$(cd "$REPO" && pwd)
q() { printf '%q' "$1"; }
{
  echo "#!/bin/bash"
  echo "# Written by \`make sweep-slurm\` on $(date -u +%Y-%m-%dT%H:%MZ) from $(q "$repo") (experiments/README.md)."
  echo "# One array task per make target in $dir/tasks; task i runs, in the repository,"
  echo "#   make <the make-vars> <line i of tasks>"
  echo "# exactly what \`make\` runs for that target, so results land where make puts them."
  echo "#SBATCH --job-name=photonmap-sweep"
  echo "#SBATCH --array=1-$n"
  echo "#SBATCH --output=$dir/logs/%A_%a.out"
  for o in $SBATCH_OPTS; do echo "#SBATCH $o"; done
  echo "set -euo pipefail"
  echo "dir=$(q "$dir")"
  echo "repo=$(q "$repo")"
  echo ': "${SLURM_ARRAY_TASK_ID:?run this through sbatch (or set SLURM_ARRAY_TASK_ID=1..'"$n"')}"'
  echo 'target=$(sed -n "${SLURM_ARRAY_TASK_ID}p" "$dir/tasks")'
  echo '[ -n "$target" ] || { echo "sweep: no task $SLURM_ARRAY_TASK_ID in $dir/tasks" >&2; exit 2; }'
  echo 'mapfile -t vars < "$dir/make-vars"'
  echo '# only the make-vars: no jobserver or flags of a make that submitted this'
  echo 'unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES'
  echo 'echo "sweep task $SLURM_ARRAY_TASK_ID/'"$n"' on $(hostname): make ${vars[*]} $target"'
  echo "cd \"\$repo\""
  echo "exec $(q "$MAKE_CMD") --no-print-directory \"\${vars[@]}\" \"\$target\""
} > "$dir/sweep.sbatch.tmp"
chmod +x "$dir/sweep.sbatch.tmp"
mv "$dir/sweep.sbatch.tmp" "$dir/sweep.sbatch"
echo "sweep-slurm: $n tasks in $dir/tasks; submit with: sbatch $dir/sweep.sbatch"
