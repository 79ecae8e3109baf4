#!/usr/bin/env bash
# status.sh JOBID: the state of one Slurm job for Snakemake's --cluster-status,
# one word: running, success or failed. Asks squeue, then scontrol (which
# keeps a finished job for MinJobAge seconds), never sacct: a cluster without
# job accounting (accounting_storage/none) cannot answer sacct. A job that
# neither knows any more is reported as success: Snakemake then checks that
# its outputs exist, and fails the job when they do not.
set -u
id=${1:?status.sh JOBID}
id=${id%%;*}   # sbatch --parsable prints JOBID[;CLUSTER]
state=$(squeue -h -j "$id" -o %T 2>/dev/null | head -n 1)
if [ -z "$state" ]; then
  state=$(scontrol show job "$id" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1)
fi
case $state in
  ""|COMPLETED) echo success ;;
  PENDING|RUNNING|CONFIGURING|COMPLETING|SUSPENDED|REQUEUED|REQUEUE_HOLD|REQUEUE_FED|RESIZING|STAGE_OUT|SIGNALING|STOPPED) echo running ;;
  *) echo failed ;;   # FAILED CANCELLED TIMEOUT NODE_FAIL OUT_OF_MEMORY BOOT_FAIL DEADLINE PREEMPTED ...
esac
