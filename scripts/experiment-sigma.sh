#!/usr/bin/env bash
# Steps and ASOO against sigma on the paper's 40x40 torus, for every searcher.
# Usage: scripts/experiment-sigma.sh [TRIALS] [SEED] > docs/experiment-sigma.md
# Trial i of every row uses the same seed stream, so rows are paired. The
# step cap (5000) ends trapped episodes (see README: the prior belief) as
# failures, counted in "capped".
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
trials=${1:-200}
seed=${2:-1}
cargo build --release --quiet
bin=target/release/torus-search
echo "Produced by \`scripts/experiment-sigma.sh $trials $seed\` (N = 40, r_v = 1, start (1,1), L = 100, c = √2, RW rollouts for MCTS, step cap 5000; a capped episode counts 5000 steps). Rows with the same sigma share the target of each trial."
echo
echo "| searcher | sigma | mean steps [95% CI] | ASOO [95% CI] | median | capped |"
echo "| --- | --- | --- | --- | --- | --- |"
for sigma in 0 2 5 10 inf; do
  for who in "mcts cells posterior" "mcts cells prior" "mcts tree posterior" "rw" "levy" "nsarw"; do
    set -- $who
    args=(run --n 40 --trials "$trials" --seed "$seed" --sigma "$sigma" --json --step-cap 5000)
    if [[ $1 == mcts ]]; then args+=(--searcher mcts --variant "$2" --belief "$3"); else args+=(--searcher "$1"); fi
    "$bin" "${args[@]}" | python3 -c '
import json, sys
d = json.load(sys.stdin)
who, sigma = sys.argv[1], sys.argv[2]
lo, hi = d["ci95_steps"]
alo, ahi = d["ci95_asoo"]
m, a, med, cap = d["mean_steps"], d["asoo"], d["median_steps"], d["capped"]
print(f"| {who} | {sigma} | {m:.1f} [{lo:.1f}, {hi:.1f}] | {a:.1f} [{alo:.1f}, {ahi:.1f}] | {med:.0f} | {cap} |")
' "$who" "$sigma"
  done
done
