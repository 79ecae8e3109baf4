#!/usr/bin/env bash
# group.sh: every render of one (cell, seed) of a group back to back: the
# recipe of one make target with all the group's records as its targets, so
# that their time ratios are paired samples of one machine state; pair.sh,
# the two-member case of a grid, runs it for make's reproduce-runs
# (experiments/study.mk). The studies on Snakemake use experiments/launch.py,
# which does the same.
#
#   group.sh ESTIMATE-pPHOTONS-nNN/seedK RUNROOT METHOD ARGS [RUNROOT METHOD ARGS ...]
#
# Each member (RUNROOT METHOD ARGS) is experiments/run.sh RUNROOT
# METHOD-ESTIMATE-pPHOTONS-nNN/seedK with PM_ARGS=ARGS (the rest of the
# environment, PM SCENE WIDTH ..., shared). The order alternates with the
# seed: odd seeds in the order given, even seeds reversed, so that a linear
# drift within a group (a machine warming up, a neighbour starting) falls on
# every member's mean position equally. Each record says its place in the
# group (PAIR_POS: 1..N). The records of all members are removed first, and
# when a render fails or the group is interrupted the records this group
# made are removed again: a group is finished only when every member's
# record exists, and the next make renders all of it again. Exits 1 (with
# run.sh's message) on the first failure.
set -euo pipefail
stem=${1:-}
shift || true
seedname=${stem##*/}
seed=${seedname#seed}
if [ -z "$stem" ] || [ "$seedname" = "$stem" ] || ! [[ "$seed" =~ ^[0-9]+$ ]]; then
  echo "group.sh: '$stem': not ESTIMATE-pPHOTONS-nNN/seedK" >&2; exit 1
fi
if [ $# -eq 0 ] || [ $(($# % 3)) -ne 0 ]; then
  echo "group.sh: $stem: members are RUNROOT METHOD ARGS triples (got $# words)" >&2; exit 1
fi
roots=() methods=() margs=()
while [ $# -gt 0 ]; do roots+=("$1"); methods+=("$2"); margs+=("$3"); shift 3; done
n=${#roots[@]}
order=()
if [ $((seed % 2)) -eq 1 ]; then
  for ((i = 0; i < n; i++)); do order+=("$i"); done
else
  for ((i = n - 1; i >= 0; i--)); do order+=("$i"); done
fi
record() { echo "${roots[$1]}/${methods[$1]}-$stem.run.json"; }
for ((i = 0; i < n; i++)); do rm -f "$(record "$i")"; done
done_ok=0
cleanup() { # the group unfinished: none of its records stays
  if [ "$done_ok" -ne 1 ]; then
    for ((i = 0; i < n; i++)); do rm -f "$(record "$i")"; done
  fi
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP
here=$(dirname "$0")
pos=0
for i in "${order[@]}"; do
  pos=$((pos + 1))
  PAIR_POS=$pos PM_ARGS=${margs[$i]} bash "$here/run.sh" "${roots[$i]}" "${methods[$i]}-$stem"
done
done_ok=1
