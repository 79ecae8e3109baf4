#!/usr/bin/env bash
# slurm.test.sh: `make sweep-slurm` end to end (experiments/README.md).
# A tiny sweep (4 renders of reproduce-table at 16x12) is written as a Slurm
# job array, submitted with `sbatch --wait` to a private single-node Slurm
# cluster that this script starts itself (munged, slurmctld and slurmd as
# root, on free ports, everything under a temporary directory) and stops at
# the end; what the array wrote must equal what plain `make` writes (images
# bit for bit, stats but for their times). Without root or without the
# Slurm binaries (scripts/install-deps.sh installs them), or with
# PM_SLURM=emulate, the array's tasks are run here one by one with
# SLURM_ARRAY_TASK_ID set instead, and the first check's name says so.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
# the makes below see only the variables given here, not those of a `make
# test` that runs this script
unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES

VARS=(SIZE=16x12 PHOTONS=2000 "NNS=10 20" SEEDS=1 ESTIMATES=paper)
CELLS=runs/cornell-16x12-s2-t1
DAEMON_PIDS=()

stop_cluster() { # stops only the daemons this script started, by their pid
  local p
  for p in "${DAEMON_PIDS[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${DAEMON_PIDS[@]}"; do wait "$p" 2>/dev/null; done
  DAEMON_PIDS=()
}
trap 'stop_cluster; rm -rf "$TMP"' EXIT

# A port nobody listens on (bash's /dev/tcp; ports above 20000).
free_port() {
  local p
  for _ in $(seq 1 50); do
    p=$((20000 + RANDOM % 20000))
    (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return 0; }
  done
  return 1
}

# start_cluster DIR: munged, slurmctld and slurmd with their state, logs and
# sockets under DIR; sets SLURM_CONF. Returns 1 (logs in DIR/log) when the
# node does not come up within 30 s.
start_cluster() {
  local d=$1 host cpus p1 p2
  host=$(hostname -s) cpus=$(nproc)
  p1=$(free_port) && p2=$(free_port) || return 1
  mkdir -p "$d/munge" "$d/state" "$d/spool" "$d/log" && chmod 711 "$d/munge"
  head -c 1024 /dev/urandom > "$d/munge/munge.key" && chmod 400 "$d/munge/munge.key"
  munged -F --force --socket="$d/munge/socket" --key-file="$d/munge/munge.key" --pid-file="$d/munge/pid" \
    --log-file="$d/log/munged.log" --seed-file="$d/munge/seed" > "$d/log/munged.out" 2>&1 &
  DAEMON_PIDS+=($!)
  cat > "$d/slurm.conf" <<EOF
# a single-node cluster for tests/slurm.test.sh
ClusterName=pmtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$p1
SlurmdPort=$p2
AuthType=auth/munge
AuthInfo=socket=$d/munge/socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$d/slurm.conf
  for _ in $(seq 1 20); do [ -S "$d/munge/socket" ] && break; sleep 0.25; done
  slurmctld -D -i > "$d/log/slurmctld.out" 2>&1 &
  DAEMON_PIDS+=($!)
  slurmd -D > "$d/log/slurmd.out" 2>&1 &
  DAEMON_PIDS+=($!)
  for _ in $(seq 1 60); do
    [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && return 0
    sleep 0.5
  done
  echo "slurm: the node did not become idle in 30 s; logs:"
  tail -n 5 "$d"/log/*
  return 1
}

MODE=emulate
if [ "${PM_SLURM:-auto}" != emulate ] && [ "$(id -u)" -eq 0 ] &&
   command -v munged >/dev/null && command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v sbatch >/dev/null; then
  MODE=slurm
fi

# run_array DIR: runs DIR/sweep.sbatch as the array it declares (sbatch
# --wait on the cluster, or each task here); the job's exit status.
run_array() {
  local d=$1 n
  if [ "$MODE" = slurm ]; then
    timeout 300 sbatch --wait --quiet "$d/sweep.sbatch"
  else
    n=$(wc -l < "$d/tasks")
    local rc=0
    for i in $(seq 1 "$n"); do
      SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_JOB_ID=0 bash "$d/sweep.sbatch" > "$d/logs/0_$i.out" 2>&1 || rc=1
    done
    return $rc
  fi
}

# same_results A B: the renders make wrote under A and under B agree: the
# same files, images bit for bit, stats JSON but for its times and its
# provenance (the load average at the start), run records
# (experiments/run.sh) in their exit status.
same_results() {
  local a=$1/$CELLS b=$2/$CELLS f
  [ -d "$a" ] && [ -d "$b" ] || { echo "missing $a or $b"; return 1; }
  diff <(cd "$a" && find . -type f | sort) <(cd "$b" && find . -type f | sort) || { echo "different files"; return 1; }
  [ "$(cd "$a" && find . -name 'seed1.exr' | wc -l)" -eq 4 ] || { echo "not 4 images"; return 1; }
  for f in $(cd "$a" && find . -type f | sort); do
    case "$f" in
      *.exr|*.png) cmp "$a/$f" "$b/$f" || return 1 ;;
      *.stats.json) diff <(grep -vE '"(time_s[a-z_]*|provenance)"' "$a/$f") <(grep -vE '"(time_s[a-z_]*|provenance)"' "$b/$f") || { echo "$f differs"; return 1; } ;;
      *.run.json) diff <(grep '"exit"' "$a/$f") <(grep '"exit"' "$b/$f") || { echo "$f differs"; return 1; } ;;
    esac
  done
}

# --- what plain make writes ---------------------------------------------------
make -s reproduce-runs "${VARS[@]}" RESULTS="$TMP/make" > "$TMP/make.log" 2>&1 || cat "$TMP/make.log"

# --- the job files ------------------------------------------------------------
JOB=$TMP/job
make -s sweep-slurm SWEEP=reproduce-runs "${VARS[@]}" RESULTS="$TMP/slurm" SLURM_DIR="$JOB" \
  SBATCH_OPTS="--time=10 --cpus-per-task=1" > "$TMP/gen.log" 2>&1
tasks_are_cells() {
  grep -q "2 tasks in .*submit with: sbatch .*sweep.sbatch" "$TMP/gen.log" &&
  diff <(sort "$JOB/tasks") <(cd "$TMP/make" && find "$PWD/$CELLS" -name '*.run.json' -path '*/precomputed-*' |
                              sed "s|^$TMP/make|$TMP/slurm|" | sort)
}
check "sweep-slurm SWEEP=reproduce-runs: one task per pair of renders (make's prerequisites, a pair's once)" tasks_are_cells
sbatch_ok() {
  local s=$JOB/sweep.sbatch
  bash -n "$s" && grep -qx '#SBATCH --array=1-2' "$s" && grep -qx '#SBATCH --time=10' "$s" &&
  grep -qx '#SBATCH --cpus-per-task=1' "$s" && grep -q "^#SBATCH --output=$JOB/logs/%A_%a.out" "$s" &&
  diff <(printf '%s\n' ESTIMATES=paper "NNS=10 20" PHOTONS=2000 "RESULTS=$TMP/slurm" SEEDS=1 SIZE=16x12) "$JOB/make-vars"
}
check "sweep-slurm writes the sbatch array script and the make variables" sbatch_ok

# --- run it -------------------------------------------------------------------
CLUSTER_UP=1
if [ "$MODE" = slurm ]; then
  t0=$(date +%s)
  start_cluster "$TMP/cluster" > "$TMP/cluster.log" 2>&1 || CLUSTER_UP=0
  [ $CLUSTER_UP -eq 1 ] || cat "$TMP/cluster.log"
  check "a private single-node Slurm starts ($(sinfo --version 2>/dev/null), $(($(date +%s) - t0)) s)" test $CLUSTER_UP -eq 1
fi
if [ $CLUSTER_UP -eq 1 ]; then
  t0=$(date +%s)
  run_array "$JOB" > "$TMP/run.log" 2>&1
  rc=$?
  label=$([ "$MODE" = slurm ] && echo "on Slurm (sbatch --wait)" || echo "EMULATED (SLURM_ARRAY_TASK_ID, no Slurm: PM_SLURM=${PM_SLURM:-auto}, uid $(id -u))")
  check "the job array runs $label in $(($(date +%s) - t0)) s" test $rc -eq 0
  check "every task logged its make command" \
    bash -c "[ \$(grep -l '^sweep task [1-2]/2 on .*: make ESTIMATES=paper NNS=10 20 PHOTONS=2000 RESULTS=.* SEEDS=1 SIZE=16x12 /' $JOB/logs/*.out | wc -l) -eq 2 ]"
  check "the array wrote what plain make writes" same_results "$TMP/make" "$TMP/slurm"
  # after the array, make finds every cell done: the analysis runs on them
  rerun_nothing() {
    make -s reproduce-runs "${VARS[@]}" RESULTS="$TMP/slurm" > "$TMP/rerun.log" 2>&1 && ! grep -q '^run ' "$TMP/rerun.log"
  }
  check "make finds the array's cells up to date" rerun_nothing

  # the studies on the workflow engine: Snakemake submits the renders to
  # Slurm itself (sbatch --parsable, experiments/slurm/status.sh on
  # squeue/scontrol, no sacct), the short renders grouped into one job
  if [ "$MODE" = slurm ]; then
    t0=$(date +%s)
    timeout 600 make -s reproduce-table "${VARS[@]}" RESULTS="$TMP/engine" CLUSTER=slurm GROUP_RENDERS=2 \
      SLURM_DIR="$TMP/ejob" SBATCH_OPTS="--time=10" REF="$TMP/make/$CELLS/conventional-paper-p2000-n10/seed1.exr" \
      > "$TMP/engine.log" 2>&1
    rc=$?
    [ $rc -eq 0 ] || tail -n 30 "$TMP/engine.log"
    check "make reproduce-table CLUSTER=slurm: Snakemake runs it on Slurm in $(($(date +%s) - t0)) s" \
      bash -c "[ $rc -eq 0 ] && [ -s '$TMP/engine/table1/table1.md' ]"
    check "CLUSTER=slurm: the two pairs of renders went to Slurm as one grouped job, each job logged" \
      bash -c "[ \$(grep -l '^run ' '$TMP/ejob/logs/'*.out | wc -l) -eq 1 ] &&
               [ \$(grep -h '^run ' '$TMP/ejob/logs/'*.out | wc -l) -eq 4 ]"
    check "CLUSTER=slurm: the engine wrote what plain make writes" same_results "$TMP/make" "$TMP/engine"
  fi

  # negative controls: a failing task fails the job; a differing image is seen
  printf '# a task that cannot be made\nno-such-target\n' > "$TMP/bad-tasks"
  make -s sweep-slurm TASKS="$TMP/bad-tasks" SLURM_DIR="$TMP/badjob" > /dev/null 2>&1
  job_fails() { ! run_array "$1" > /dev/null 2>&1; }
  check "control: a job with a failing task fails" job_fails "$TMP/badjob"
  cp -r "$TMP/slurm" "$TMP/altered"
  oiiotool "$TMP/altered/$CELLS/precomputed-paper-p2000-n20/seed1.exr" --mulc 0.999 -o "$TMP/altered/$CELLS/precomputed-paper-p2000-n20/seed1.exr"
  differ() { ! same_results "$@" > /dev/null 2>&1; }
  check "control: one image scaled by 0.999 is seen" differ "$TMP/make" "$TMP/altered"
  rm "$TMP/altered/$CELLS/conventional-paper-p2000-n10/seed1.stats.json"
  check "control: a missing file is seen" differ "$TMP/make" "$TMP/altered"
fi
stop_cluster

# --- the task file and its errors -----------------------------------------------
printf '# two targets\n\n  build/photonmap\t\nbuild/obj/image.o\n' > "$TMP/tasks.txt"
tasks_file() {
  make -s sweep-slurm TASKS="$TMP/tasks.txt" SLURM_DIR="$TMP/tjob" > /dev/null &&
  diff <(printf 'build/photonmap\nbuild/obj/image.o\n') "$TMP/tjob/tasks" && grep -qx '#SBATCH --array=1-2' "$TMP/tjob/sweep.sbatch" &&
  [ ! -s "$TMP/tjob/make-vars" ]
}
check "sweep-slurm TASKS=FILE: comments and blanks skipped, no variables" tasks_file
check "sweep-slurm without TASKS or SWEEP fails" expect_exit 2 "give TASKS=FILE .* or SWEEP=TARGET" \
  make -s sweep-slurm SLURM_DIR="$TMP/e1"
check "sweep-slurm with both fails" expect_exit 2 "give TASKS or SWEEP, not both" \
  make -s sweep-slurm TASKS="$TMP/tasks.txt" SWEEP=reproduce-runs SLURM_DIR="$TMP/e2"
check "sweep-slurm SWEEP=unknown target fails" expect_exit 2 "SWEEP=no-such-sweep: no such make target" \
  make -s sweep-slurm SWEEP=no-such-sweep SLURM_DIR="$TMP/e3"
check "sweep-slurm SWEEP=a target without prerequisites fails" expect_exit 2 "has no prerequisites" \
  make -s sweep-slurm SWEEP=sweep-slurm-nothing SLURM_DIR="$TMP/e4"
printf 'a b\n' > "$TMP/spaces.txt"
check "sweep-slurm: a line with two words fails, naming file:line" expect_exit 2 "spaces.txt:1: one make target per line" \
  make -s sweep-slurm TASKS="$TMP/spaces.txt" SLURM_DIR="$TMP/e5"
printf 'build/photonmap\r\n\r\nbuild/obj/image.o\r\n' > "$TMP/crlf.txt"
check "sweep-slurm: a task file with CRLF line ends gives the same tasks" bash -c "
  make -s sweep-slurm TASKS='$TMP/crlf.txt' SLURM_DIR='$TMP/e7' > /dev/null &&
  diff <(printf 'build/photonmap\nbuild/obj/image.o\n') '$TMP/e7/tasks'"
printf 'build/photonmap\nno-such-target\n' > "$TMP/missing.txt"
check "sweep-slurm: a task make has no rule for fails, naming it, and writes no job" bash -c "
  ! make -s sweep-slurm TASKS='$TMP/missing.txt' SLURM_DIR='$TMP/e8' > '$TMP/e8.log' 2>&1 &&
  grep -q 'no make rule for: no-such-target' '$TMP/e8.log' && [ ! -e '$TMP/e8/sweep.sbatch' ]"
: > "$TMP/empty.txt"
check "sweep-slurm: an empty task file fails" expect_exit 2 "no targets" make -s sweep-slurm TASKS="$TMP/empty.txt" SLURM_DIR="$TMP/e6"
finish
