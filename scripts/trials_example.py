#!/usr/bin/env python3
"""Reads a sigma-sweep's tidy per-trial CSV with pandas (EXPERIMENTS.md, "Per-trial data").

Usage: python3 scripts/trials_example.py docs/figures/sigma-sweep
Prints the mean steps per σ and searcher (the figure's means) and, trial by
trial, how much longer the Lévy flight took than MCTS with RW rollouts;
exits 1 unless the means are those of <name>.csv.
"""
import sys

import pandas as pd

name = sys.argv[1]
t = pd.read_csv(f"{name}.trials.csv", comment="#")
means = t.pivot_table(index="sigma", columns="series", values="steps", aggfunc="mean")
print(means.round(1).to_string())
steps = t.pivot_table(index=["sigma", "trial"], columns="series", values="steps")
diff = steps["Lévy flight"] - steps["MCTS, RW rollouts"]
print(diff.groupby("sigma").agg(mean="mean", lfs_more=lambda d: (d > 0).sum()).to_string())

points = pd.read_csv(f"{name}.csv", comment="#").set_index("index")
mine = t.groupby("point")["value"].mean()
sys.exit(0 if ((mine - points["mean"]).abs() < 1e-9).all() else 1)
