#!/usr/bin/env bash
# run.sh: one render of the experiment grid, the recipe of one make target
# (experiments/study.mk). Owns the files of that render and nothing else.
#
#   run.sh RUNROOT CELL/seedK
#
# CELL is METHOD-ESTIMATE-pPHOTONS-nNN (ESTIMATE: paper, or corrected = the
# renderer's --bias-correction). Settings from the environment: PM SCENE
# WIDTH HEIGHT SUBPIXELS THREADS_ARG PM_ARGS (extra render options), PYTHON,
# RUN_LIST (every run of the grid in order, for "run k/N"), PAIR_POS (1 or 2:
# the render's place in a back-to-back pair run by experiments/pair.sh, 1..N
# in a group run by experiments/group.sh; 0 or unset: not paired).
#
# Writes, in RUNROOT/CELL/: seedK.exr (the image), seedK.stats.json (the
# renderer's --stats), seedK.err (its stderr) and, last, seedK.run.json
# (the make target): exit status, user/system CPU seconds from /usr/bin/time
# -f "%U %S", the 1-minute load average when the run started, its place in
# a pair (pair_pos), the command,
# and for a refused run (exit 2: the renderer rejects the combination, e.g.
# --bias-correction with --rep-every 1) its message. Everything is written to
# a temporary name and renamed, so a killed run leaves no result and is
# re-rendered by the next `make`. Any other failure exits 1 and records
# nothing. Prints one progress line.
set -euo pipefail
root=$1 stem=$2
cell=${stem%/*} seedname=${stem##*/}
seed=${seedname#seed}
IFS=- read -r method estimate pp nn extra <<< "$cell"
photons=${pp#p} nn=${nn#n}
if [ -n "${extra:-}" ] || [ "$seedname" = "$seed" ] || [ -z "$method" ] || [ -z "$estimate" ] ||
   [ "$pp" = "$photons" ] || ! [[ "$photons$nn$seed" =~ ^[0-9]+$ ]]; then
  echo "run.sh: $root/$stem: not METHOD-ESTIMATE-pPHOTONS-nNN/seedK" >&2; exit 1
fi
case $estimate in
  paper) est_args=() ;;
  corrected) est_args=(--bias-correction) ;;
  *) echo "run.sh: $root/$stem: estimate '$estimate' is neither paper nor corrected" >&2; exit 1 ;;
esac
: "${WIDTH:?}" "${HEIGHT:?}" "${SUBPIXELS:?}" "${SCENE:?}"
PM=${PM:-build/photonmap}
PYTHON=${PYTHON:-/usr/bin/python3}
pair_pos=${PAIR_POS:-0}
[[ "$pair_pos" =~ ^(0|[1-9][0-9]*)$ ]] || { echo "run.sh: PAIR_POS=$pair_pos: not 0 or a position 1..N" >&2; exit 1; }

# "run k/N": this run's place in the grid make was given
k=0 i=0
for r in ${RUN_LIST:-$stem}; do i=$((i + 1)); [ "$r" = "$stem" ] && k=$i; done
label="run $k/$i $method $estimate P_e=$photons n=$nn seed $seed"

dir=$root/$cell
mkdir -p "$dir"
base=$dir/$seedname
rm -f "$base".tmp.* "$base.exr" "$base.stats.json" "$base.err"
# shellcheck disable=SC2206  # PM_ARGS: words on purpose
cmd=("$PM" render "$SCENE" --method "$method" --photons "$photons" --nn "$nn" --seed "$seed"
     --width "$WIDTH" --height "$HEIGHT" --subpixels "$SUBPIXELS" --threads "${THREADS_ARG:-1}"
     ${PM_ARGS:-} "${est_args[@]}" -o "$base.tmp.exr" --stats "$base.tmp.json" --quiet)
load=$(cut -d' ' -f1 /proc/loadavg)
rc=0
/usr/bin/time -f "%U %S" -o "$base.tmp.time" "${cmd[@]}" 2> "$base.tmp.err" || rc=$?
msg=$(tr '\t\n' '  ' < "$base.tmp.err" | tr -d '\000-\010\013-\037' | sed 's/ *$//')

# JSON string of $1 (backslash, quote; control characters were removed above)
json_str() { local s=${1//\\/\\\\}; s=${s//\"/\\\"}; printf '"%s"' "$s"; }
record() { # EXIT USER SYS CPU MESSAGE: the run record, written last
  { printf '{\n  "exit": %s,\n  "user_s": %s,\n  "sys_s": %s,\n  "cpu_s": %s,\n' "$1" "$2" "$3" "$4"
    printf '  "loadavg_1min": %s,\n  "pair_pos": %s,\n  "message": %s,\n  "command": %s\n}\n' "$load" "$pair_pos" \
      "$(json_str "$5")" "$(json_str "${cmd[*]}")"
  } > "$base.tmp.run"
  mv "$base.tmp.run" "$base.run.json"
}

if [ "$rc" -eq 0 ]; then
  read -r user sys < <(tail -n 1 "$base.tmp.time")
  mv "$base.tmp.exr" "$base.exr"
  mv "$base.tmp.json" "$base.stats.json"
  mv "$base.tmp.err" "$base.err"
  rm -f "$base.tmp.time"
  cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f\n", u + s }')
  record 0 "$user" "$sys" "$cpu" ""
  total=$("$PYTHON" -c 'import json, sys; print("%.2f" % json.load(open(sys.argv[1]))["time_s"]["total"])' "$base.stats.json")
  echo "$label: total $total s, cpu $cpu s"
elif [ "$rc" -eq 2 ]; then
  # refused: the combination does not apply; recorded so that make does not retry it
  mv "$base.tmp.err" "$base.err"
  rm -f "$base".tmp.*
  record 2 null null null "$msg"
  echo "$label: not applicable (the renderer refused it, exit 2): $msg"
else
  rm -f "$base".tmp.*
  echo "run.sh: $label failed (exit $rc): ${cmd[*]}" >&2
  echo "run.sh: $msg" >&2
  exit 1
fi
