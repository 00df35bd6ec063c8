#!/usr/bin/env bash
# Regenerate every named experiment's figure into docs/figures/ (svg, csv,
# json) at a trial count that fits in minutes on a 2-core machine.
# Usage: scripts/figures.sh [NAME ...]   (default: all of them)
#
# Trials per point under the default preset (paper-code), and the wall time
# of `make figures` on this project's 2-core machine (release build, 2
# threads, the machine shared with other work; MCTS costs are heavy-tailed,
# so another seed can take twice as long): see the README's "Experiments"
# section for the measured times. The paper used 10^3 trials per point; for
# that, shard the runs over a cluster (docs/cluster.md). TRIALS_SCALE=k
# multiplies every count.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=docs/figures
scale=${TRIALS_SCALE:-1}
declare -A trials=(
  [priors]=10000 [delta]=100 [loops]=30 [decision-time]=20 [uniform]=50
  [nsarw-convergence]=10 [known-n20]=20 [belief]=30 [levy-mu]=1000
  [c-sweep]=50 [sigma-sweep]=30 [goals]=100
)
order=(priors delta known-n20 levy-mu c-sweep decision-time uniform loops belief nsarw-convergence sigma-sweep goals)
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
  start=$SECONDS
  "$bin" experiment "$name" --trials "$t" --seed 1 --out "$out"
  echo "$name: $t trials per point in $((SECONDS - start)) s"
done
