#!/usr/bin/env bash
# pair.sh: the two renders of one (cell, seed), conventional and
# precomputed, back to back: the recipe of one make target of a study with
# both methods (experiments/study.mk's pair rule), so that the two are paired
# samples of the same machine state.
#
#   pair.sh RUNROOT ESTIMATE-pPHOTONS-nNN/seedK
#
# Runs experiments/run.sh RUNROOT METHOD-ESTIMATE-pPHOTONS-nNN/seedK for both
# methods (the same environment: PM SCENE WIDTH ... RUN_LIST), in an order
# that alternates with the seed: odd seeds conventional first, even seeds
# precomputed first, so that a drift within a pair (a machine warming up, a
# neighbour starting) falls on each method equally often. Each render writes
# its own files and record in the run layout (run.sh); the record says its
# place in the pair (PAIR_POS: 1 or 2). Exits as run.sh does: the first
# failure stops the pair (the other render is not made), and the next make
# renders the pair again, both renders (a pair is only paired if back to back).
# The two-member case of experiments/group.sh, which does all of this.
set -euo pipefail
root=${1:?pair.sh: RUNROOT ESTIMATE-pPHOTONS-nNN/seedK} rest=${2:?pair.sh: RUNROOT ESTIMATE-pPHOTONS-nNN/seedK}
exec bash "$(dirname "$0")/group.sh" "$rest" "$root" conventional "${PM_ARGS:-}" "$root" precomputed "${PM_ARGS:-}"
