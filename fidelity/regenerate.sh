#!/usr/bin/env bash
# Regenerates the fidelity comparison's data and tables (README.md):
#
#   fidelity/regenerate.sh [mirror] [crate] [table] [cause]
#
#   mirror  the code's trials: data/mirror-nN-sS.csv (examples/fidelity.rs
#           `mirror`, trials 0..COUNT-1, seed 1, the seeds of run_code.sh)
#   crate   the crate's two readings: data/crate-nN-sS.tsv (`crate`)
#   table   the tables between the markers of README.md and EXPERIMENTS.md,
#           from data/ (`table`);
#           also checks every Octave trial (data/code-*.csv) against the
#           mirror
#   cause   the code with one departure changed at a time (`cause`)
#
# Everything on one core (nice): about 25 minutes of a core for mirror,
# 10 for crate, 3 for cause, seconds for table, which needs only the
# committed data. Octave's own trials: run_code.sh.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cd "$here/.."
cargo build --release --quiet --example fidelity
x=${CARGO_TARGET_DIR:-target}/release/examples/fidelity
steps=${*:-table}
for step in $steps; do
  case $step in
    mirror)
      for p in "20 0 4000" "20 5 2000" "40 0 2000" "40 5 1000"; do
        set -- $p
        nice -n 10 "$x" mirror "$1" "$2" 0 "$3" 1 >"$here/data/mirror-n$1-s$2.csv"
      done ;;
    crate)
      for p in "20 0 10000" "20 5 5000" "40 0 3000" "40 5 800"; do
        set -- $p
        nice -n 10 "$x" crate "$1" "$2" "$3" 1 >"$here/data/crate-n$1-s$2.tsv"
      done ;;
    table) nice -n 10 "$x" table --write ;;
    cause)
      for p in "20 0 2000"; do
        set -- $p
        nice -n 10 "$x" cause "$1" "$2" "$3" 1 >"$here/data/cause-n$1-s$2.md"
      done
      nice -n 10 "$x" table --write ;;
    *) sed -n '2,16p' "$0" >&2; exit 2 ;;
  esac
done
