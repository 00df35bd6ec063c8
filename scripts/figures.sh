#!/usr/bin/env bash
# Regenerate every named experiment's files into docs/figures/ (json, csv,
# svg, png, each with its provenance) at trial counts that fit in `make
# figures` on a 2-core machine. tests/suite/committed_results.rs checks that every
# committed result reloads with the current build: when a change makes them
# stale, this script is how they are made again.
# Usage: scripts/figures.sh [NAME ...]   (default: all of them)
#
# Trials per point under the default preset (paper-code). The script prints
# each figure's time and the total (docs/performance.md has the measured
# times; MCTS costs are heavy-tailed, so another seed can take twice as
# long). The paper used 10^3 trials per point; for that, shard the runs over
# a cluster (docs/cluster.md). TRIALS_SCALE=k multiplies every count;
# FIGURES_OUT=DIR writes elsewhere than docs/figures.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=${FIGURES_OUT:-docs/figures}
scale=${TRIALS_SCALE:-1}
declare -A trials=(
  [priors]=10000 [delta]=100 [loops]=30 [decision-time]=20 [uniform]=50
  [nsarw-convergence]=10 [known-n20]=20 [belief]=30 [levy-mu]=1000
  [c-sweep]=50 [sigma-sweep]=30 [sigma-tail]=30 [goals]=100
)
order=(priors delta known-n20 levy-mu c-sweep decision-time uniform loops belief nsarw-convergence sigma-sweep sigma-tail goals)
names=("$@")
[[ ${#names[@]} -eq 0 ]] && names=("${order[@]}")
for name in "${names[@]}"; do
  [[ -n ${trials[$name]:-} ]] || { echo "figures.sh: no figure named $name (one of ${order[*]})" >&2; exit 2; }
done
cargo build --release --quiet
bin=target/release/torus-search
mkdir -p "$out"
begin=$SECONDS
for name in "${names[@]}"; do
  t=$(( ${trials[$name]} * scale ))
  printf '\n==== %s (%s trials per point) ====\n' "$name" "$t"
  start=$SECONDS
  "$bin" experiment "$name" --trials "$t" --seed 1 --out "$out"
  echo "$name: $t trials per point in $((SECONDS - start)) s"
done
printf '\n%s figures in %s s\n' "${#names[@]}" "$((SECONDS - begin))"
