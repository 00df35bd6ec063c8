#!/usr/bin/env bash
# Regenerate every named experiment's figure into docs/figures/ (svg, csv,
# json) at a trial count that fits in minutes on a 2-core machine.
# Usage: scripts/figures.sh [NAME ...]   (default: all of them)
#
# Trials per point, and the wall time measured by `make figures` on this
# project's 2-core machine (release build, 2 threads; the machine was shared
# with other work, and MCTS costs are heavy-tailed: one episode trapped under
# paper-text runs to the 10 000-step cap at L rollouts per move, so a rerun
# with another seed can take twice as long):
#   priors             10000 samples     2 s
#   delta                100            16 s
#   known-n20            100            61 s
#   levy-mu             1000             1 s
#   c-sweep              100           134 s
#   decision-time         50            98 s (timed: machine-dependent)
#   uniform               20          ~120 s (50 trials took 303 s)
#   loops                 20           116 s
#   belief                10          ~165 s (20 trials took 332 s)
#   nsarw-convergence      5           290 s (MCTS at N = 80-100 dominates)
#   sigma-sweep            5           227 s
# About 20 minutes in all. The paper used 10^3 trials per point; for that,
# shard the runs over a cluster (docs/cluster.md). TRIALS_SCALE=k multiplies
# every count (TRIALS_SCALE=10 for a run of a few hours).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=docs/figures
scale=${TRIALS_SCALE:-1}
declare -A trials=(
  [priors]=10000 [delta]=100 [loops]=20 [decision-time]=50 [uniform]=20
  [nsarw-convergence]=5 [known-n20]=100 [belief]=10 [levy-mu]=1000
  [c-sweep]=100 [sigma-sweep]=5
)
order=(priors delta known-n20 levy-mu c-sweep decision-time uniform loops belief nsarw-convergence sigma-sweep)
names=("$@")
[[ ${#names[@]} -eq 0 ]] && names=("${order[@]}")
for name in "${names[@]}"; do
  [[ -n ${trials[$name]:-} ]] || { echo "figures.sh: no figure named $name (one of ${order[*]})" >&2; exit 2; }
done
cargo build --release --quiet
bin=target/release/torus-search
mkdir -p "$out"
for name in "${names[@]}"; do
  t=$(( ${trials[$name]} * scale ))
  printf '\n==== %s (%s trials per point) ====\n' "$name" "$t"
  "$bin" experiment "$name" --trials "$t" --seed 1 --out "$out"
done
