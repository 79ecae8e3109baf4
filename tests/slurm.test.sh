#!/usr/bin/env bash
# slurm.test.sh: `make sweep-slurm SWEEP=TARGET` end to end
# (experiments/README.md): the study target's renders submitted through
# Snakemake (sbatch --parsable, experiments/slurm/status.sh on
# squeue/scontrol, no sacct) to a private single-node Slurm cluster that this
# script starts itself (munged, slurmctld and slurmd as root, on free ports,
# everything under a temporary directory) and stops at the end; what Slurm
# wrote must equal what plain `make` writes (images bit for bit, stats but
# for their times). Without root or without the Slurm binaries
# (scripts/install-deps.sh installs them), or with PM_SLURM=emulate, only
# the checks that need no cluster run (the refusals, the dry run) and the
# first check's name says so.
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

# same_results A B: the renders make wrote under A and under B agree: the
# same files, images bit for bit, stats JSON but for its times, its
# provenance (the load average at the start) and the counts of repeats and
# processes (the photon pass's gauge, TIME_GAUGE, adds processes where a
# render's times say so), run records (experiments/launch.py) in their
# exit status.
same_results() {
  local a=$1/$CELLS b=$2/$CELLS f
  [ -d "$a" ] && [ -d "$b" ] || { echo "missing $a or $b"; return 1; }
  diff <(cd "$a" && find . -type f | sort) <(cd "$b" && find . -type f | sort) || { echo "different files"; return 1; }
  [ "$(cd "$a" && find . -name 'seed1.exr' | wc -l)" -eq 4 ] || { echo "not 4 images"; return 1; }
  for f in $(cd "$a" && find . -type f | sort); do
    case "$f" in
      *.exr|*.png) cmp "$a/$f" "$b/$f" || return 1 ;;
      *.stats.json) diff <(grep -vE '"(time_s[a-z_]*|minor_faults_repeats|provenance|repeats|processes)"' "$a/$f") <(grep -vE '"(time_s[a-z_]*|minor_faults_repeats|provenance|repeats|processes)"' "$b/$f") || { echo "$f differs"; return 1; } ;;
      *.run.json) diff <(grep '"exit"' "$a/$f") <(grep '"exit"' "$b/$f") || { echo "$f differs"; return 1; } ;;
    esac
  done
}

# --- what plain make writes ---------------------------------------------------
make -s reproduce-runs "${VARS[@]}" RESULTS="$TMP/make" > "$TMP/make.log" 2>&1 || cat "$TMP/make.log"

# --- refusals and the dry run (no cluster needed) ---------------------------------
check "sweep-slurm without SWEEP fails" expect_exit 2 "give SWEEP=TARGET" make -s sweep-slurm
check "sweep-slurm SWEEP=unknown target fails" expect_exit 2 "SWEEP=no-such-sweep: not one study target" \
  make -s sweep-slurm SWEEP=no-such-sweep
check "make -n sweep-slurm SWEEP=reproduce-runs: the engine's dry run on Slurm, writes nothing" \
  bash -c "make -n sweep-slurm SWEEP=reproduce-runs ${VARS[*]@Q} RESULTS=$TMP/dry SLURM_DIR=$TMP/dryjob > $TMP/dry.log 2>&1 &&
           grep -q 'pair' $TMP/dry.log && [ ! -e $TMP/dry ] && [ ! -e $TMP/dryjob ]"
[ "$MODE" = slurm ] || check "no Slurm here (PM_SLURM=${PM_SLURM:-auto}, uid $(id -u)): the cluster checks are SKIPPED" true

# --- run it -------------------------------------------------------------------
CLUSTER_UP=1
if [ "$MODE" = slurm ]; then
  t0=$(date +%s)
  start_cluster "$TMP/cluster" > "$TMP/cluster.log" 2>&1 || CLUSTER_UP=0
  [ $CLUSTER_UP -eq 1 ] || cat "$TMP/cluster.log"
  check "a private single-node Slurm starts ($(sinfo --version 2>/dev/null), $(($(date +%s) - t0)) s)" test $CLUSTER_UP -eq 1
fi
if [ "$MODE" = slurm ] && [ $CLUSTER_UP -eq 1 ]; then
  JOB=$TMP/job
  t0=$(date +%s)
  timeout 600 make -s sweep-slurm SWEEP=reproduce-runs "${VARS[@]}" RESULTS="$TMP/slurm" SLURM_DIR="$JOB" \
    GROUP_RENDERS=2 SBATCH_OPTS="--time=10 --cpus-per-task=1" > "$TMP/run.log" 2>&1
  rc=$?
  [ $rc -eq 0 ] || tail -n 30 "$TMP/run.log"
  check "sweep-slurm SWEEP=reproduce-runs: Snakemake runs the renders on Slurm in $(($(date +%s) - t0)) s" test $rc -eq 0
  # one Slurm job's log holds all four renders (a job Slurm or Snakemake
  # ran again leaves a second log, so the count of logs is not the test);
  # on failure every log's run lines are shown
  grouped_ok() {
    local f
    for f in "$JOB"/logs/*.out; do
      # each render once, whatever its processes (TIME_PROCESSES: "(process I/P)";
      # TIME_GAUGE: "(process I, added by the gauge)")
      [ "$(grep '^run ' "$f" | sed 's/ (process [^)]*)//; s/:.*//' | sort -u | wc -l)" -eq 4 ] && return 0
    done
    grep -H '^run ' "$JOB"/logs/*.out
    return 1
  }
  check "sweep-slurm: the two pairs of renders went to Slurm as one grouped job, each render logged" grouped_ok
  check "sweep-slurm: Slurm wrote what plain make writes" same_results "$TMP/make" "$TMP/slurm"
  # after Slurm, make finds every render done
  rerun_nothing() {
    make -s reproduce-runs "${VARS[@]}" RESULTS="$TMP/slurm" > "$TMP/rerun.log" 2>&1 && ! grep -q '^run ' "$TMP/rerun.log"
  }
  check "make finds Slurm's renders up to date" rerun_nothing

  # the analysis too: reproduce-table with CLUSTER=slurm
  t0=$(date +%s)
  timeout 600 make -s reproduce-table "${VARS[@]}" RESULTS="$TMP/engine" CLUSTER=slurm GROUP_RENDERS=2 \
    SLURM_DIR="$TMP/ejob" SBATCH_OPTS="--time=10" REF="$TMP/make/$CELLS/conventional-paper-p2000-n10/seed1.exr" \
    > "$TMP/engine.log" 2>&1
  rc=$?
  [ $rc -eq 0 ] || tail -n 30 "$TMP/engine.log"
  check "make reproduce-table CLUSTER=slurm: Snakemake runs it on Slurm in $(($(date +%s) - t0)) s" \
    bash -c "[ $rc -eq 0 ] && [ -s '$TMP/engine/table1/table1.md' ]"
  check "CLUSTER=slurm: the engine wrote what plain make writes" same_results "$TMP/make" "$TMP/engine"

  # negative controls: a failing render fails the sweep; a differing image is seen
  printf '#!/bin/sh\nexit 1\n' > "$TMP/failing-pm" && chmod +x "$TMP/failing-pm"
  fails() {
    ! timeout 600 make -s sweep-slurm SWEEP=reproduce-runs "${VARS[@]}" PM="$TMP/failing-pm" RESULTS="$TMP/bad" \
      SLURM_DIR="$TMP/badjob" SBATCH_OPTS="--time=10" > "$TMP/bad.log" 2>&1 &&
    ! find "$TMP/bad" -name '*.run.json' 2>/dev/null | grep -q .
  }
  check "control: a failing render fails the sweep and records nothing" fails
  cp -r "$TMP/slurm" "$TMP/altered"
  oiiotool "$TMP/altered/$CELLS/precomputed-paper-p2000-n20/seed1.exr" --mulc 0.999 -o "$TMP/altered/$CELLS/precomputed-paper-p2000-n20/seed1.exr"
  differ() { ! same_results "$@" > /dev/null 2>&1; }
  check "control: one image scaled by 0.999 is seen" differ "$TMP/make" "$TMP/altered"
  rm "$TMP/altered/$CELLS/conventional-paper-p2000-n10/seed1.stats.json"
  check "control: a missing file is seen" differ "$TMP/make" "$TMP/altered"
fi
stop_cluster

finish
