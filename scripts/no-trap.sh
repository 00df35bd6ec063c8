#!/usr/bin/env bash
# The no-trap check of issue 11: no searcher in the page's list may be
# capped in TRIALS trials at step cap 20·N², at N = 40, r_v = 1, start
# (1,1), default loops, for a delta target, Gaussian σ = 2.5, 5, 10 and a
# uniform target. Prints one line per searcher/variant and prior: mean steps
# with its 95% interval, capped episodes and the lower bound, and exits 1 if any
# episode was capped. The paper presets (--preset paper-text, paper-code)
# are excepted: they keep the paper's table, which can trap (README).
#
#   scripts/no-trap.sh [TRIALS] [SEED] [SEARCHERS...]
#
# TRIALS defaults to 1000, SEED to 3; SEARCHERS are labels from the list
# below (default: all). `make test` does not run it: the full check takes
# about an hour on 2 cores (tests/suite/trap.rs is the reduced version).
set -euo pipefail
cd "$(dirname "$0")/.."
TRIALS=${1:-1000}
SEED=${2:-3}
shift $(($# > 2 ? 2 : $#))
N=40
CAP=$((20 * N * N))
declare -A SEARCHER=(
  [cells]="--searcher mcts --variant cells"
  [tree]="--searcher mcts --variant tree"
  [pomcp]="--searcher mcts --variant pomcp"
  [rw]="--searcher rw"
  [levy]="--searcher levy"
  [nsarw]="--searcher nsarw"
)
ORDER=(cells tree pomcp rw levy nsarw)
if (($# > 0)); then ORDER=("$@"); fi
PRIORS=("--sigma 0" "--sigma 2.5" "--sigma 5" "--sigma 10" "--prior uniform")
cargo build --release --quiet
BIN=target/release/torus-search
failed=0
printf '%-6s %-16s %10s %22s %7s %8s\n' searcher prior mean "95% interval" capped bound
for s in "${ORDER[@]}"; do
  args=${SEARCHER[$s]:?"unknown searcher label $s (one of ${!SEARCHER[*]})"}
  for p in "${PRIORS[@]}"; do
    # shellcheck disable=SC2086
    line=$("$BIN" run --n $N $args $p --trials "$TRIALS" --seed "$SEED" \
      --step-cap $CAP --json | python3 -c '
import json, sys
d = json.load(sys.stdin)
m = d["mean_steps"]
print("%10.1f [%9.1f, %9.1f] %7d %8.1f" % (m["estimate"], m["lo"], m["hi"], d["capped"], d["lower_bound"]))')
    capped=$(echo "$line" | awk '{print $(NF-1)}')
    printf '%-6s %-16s %s\n' "$s" "$p" "$line"
    if [ "$capped" != 0 ]; then failed=1; fi
  done
done
exit $failed
