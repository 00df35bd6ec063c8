#!/usr/bin/env bash
# Runs the authors' MCTSgaussian.m under GNU Octave and appends per-trial
# rows to a CSV.
#
#   fidelity/run_code.sh TRIDENT_CHECKOUT N SIGMA FIRST COUNT SEED OUT.csv
#
# Trials FIRST..FIRST+COUNT-1 are run; trial i seeds rand and randn with
# SEED*1e6+i, so a file can be extended or any trial rerun on its own.
# Needs: octave, octave-statistics (normrnd). The authors' files are copied
# from the checkout (paths and hashes in fidelity/MANIFEST.tsv) into a
# temporary directory; the script gets only these edits, each checked to
# match exactly once:
#   T = 1000  -> T = 1          (one trial per call, seeded by the driver)
#   N = 40    -> N = FIDELITY_N
#   sigma = 2.5 -> sigma = FIDELITY_SIGMA
#   after the real target is placed, record it (FIDELITY_TX/TY)
#   the per-trial echo of t is silenced.
# FAST_RANDI=1 also puts fidelity/fast/randi.m first on the path: Octave's
# randi(2) without its argument checks (the same draws, half the time; see
# that file and README.md for the check that trials come out identical).
# CSV columns: trial,n,sigma,seed,steps,mopt,tx,ty,seconds where steps is the
# script's MCTS(t) = length(Px) (moves + 1; 0 if detected at the start;
# 10001 when the move cap stops it) and mopt its optsteps.
set -euo pipefail
if [ $# -ne 7 ]; then
  sed -n '2,10p' "$0" >&2
  exit 2
fi
src=$1 n=$2 sigma=$3 first=$4 count=$5 seed=$6 out=$7
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
while IFS=$'\t' read -r role path commit sha; do
  case $role in '#'*|'') continue ;; esac
  f="$src/$path"
  [ -f "$f" ] || { echo "missing $f (see fidelity/MANIFEST.tsv)" >&2; exit 1; }
  got=$(sha256sum "$f" | cut -d' ' -f1)
  if [ "$got" != "$sha" ]; then
    # A checkout with other line ends differs only in \r: compare without them.
    want_lf=$(tr -d '\r' <"$f" | sha256sum | cut -d' ' -f1)
    echo "note: $path sha256 $got differs from the manifest's (commit $commit); LF-only hash $want_lf" >&2
  fi
  if [ "$role" = script ]; then
    cp "$f" "$work/MCTSgaussian.m"
  else
    cp "$f" "$work/$role"
  fi
done <"$here/MANIFEST.tsv"
python3 - "$work/MCTSgaussian.m" "$work/MCTSgaussian_fidelity.m" <<'PY'
import re, sys
text = open(sys.argv[1], newline="").read()
edits = [
    (r"^T = 1000;", "T = 1;"),
    (r"^N = 40;", "global FIDELITY_N FIDELITY_SIGMA; N = FIDELITY_N;"),
    (r"^sigma = 2\.5;", "sigma = FIDELITY_SIGMA;"),
    (r"^(    \[Tx, Ty\] = gausstarget\(N, sigma\);.*)$", r"\1 FIDELITY_TX = Tx; FIDELITY_TY = Ty;"),
    (r"^   t(\r?)$", r"   %t\1"),
]
for pat, rep in edits:
    text, k = re.subn(pat, rep, text, flags=re.M)
    if k != 1:
        sys.exit(f"edit {pat!r} matched {k} times, expected 1")
open(sys.argv[2], "w", newline="").write(text)
PY
if [ "${FAST_RANDI:-0}" = 1 ]; then
  cp "$here/fast/randi.m" "$work/randi.m"
fi
[ -f "$out" ] || echo "trial,n,sigma,seed,steps,mopt,tx,ty,seconds" >"$out"
out_abs=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
cd "$work"
octave-cli --no-init-file --quiet --eval \
  "addpath('$here'); code_trials('$work', $n, $sigma, $first, $count, $seed, '$out_abs')" \
  >"$work/octave.log" 2> >(grep -v -e 'shadows a core library function' -e 'preparing to exit' -e '^warning: called from' -e '^    ' -e '^$' >&2)
