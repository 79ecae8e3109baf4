# pin.sh (sourced by the measurement scripts: bench/run.sh, bench/grid.sh,
# accel.sh): pin_to SPEC sets CPU, the CPU SPEC names, and pin, the words
# that run a command pinned to it (taskset -c CPU; empty for none). SPEC:
# first (the lowest CPU this shell may run on, as launch.py --cpu first
# picks for the studies), a CPU number, or none.
pin_to() {
  CPU=$1
  if [ "$CPU" = first ]; then
    CPU=$("${PYTHON:-/usr/bin/python3}" -c 'import os; print(min(os.sched_getaffinity(0)))')
  fi
  pin=()
  if [ "$CPU" != none ]; then
    pin=(taskset -c "$CPU")
  fi
}
