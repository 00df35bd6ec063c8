//! UCT Monte Carlo Tree Search: shared selection maths and the two variants.
//!
//! * [`cells`] keeps statistics per lattice cell, as the paper and its code do.
//! * [`tree`] keeps a real search tree of move sequences.

pub mod cells;
pub mod tree;

use crate::lattice::{Move, Torus};
use crate::rng::{self, Rng};
use crate::searchers::{Outcome, Policy, Visit};

/// Which MCTS variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// Per-cell statistics, depth-1 selection (the paper).
    Cells,
    /// A search tree of move sequences with subtree reuse.
    Tree,
}

impl Variant {
    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Cells => "cells",
            Variant::Tree => "tree",
        }
    }

    /// Parses a lower-case name.
    pub fn parse(s: &str) -> Option<Variant> {
        [Variant::Cells, Variant::Tree]
            .into_iter()
            .find(|v| v.name() == s)
    }
}

/// How the real move is chosen once a decision's loops are done.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FinalRule {
    /// The child selected most often in this decision (robust child).
    Visits,
    /// The child with the best mean reward.
    Mean,
    /// The child with the best UCT value (the paper's Gaussian code).
    Uct,
}

impl FinalRule {
    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            FinalRule::Visits => "visits",
            FinalRule::Mean => "mean",
            FinalRule::Uct => "uct",
        }
    }

    /// Parses a lower-case name.
    pub fn parse(s: &str) -> Option<FinalRule> {
        [FinalRule::Visits, FinalRule::Mean, FinalRule::Uct]
            .into_iter()
            .find(|v| v.name() == s)
    }
}

/// The statistics of one of the four moves at the decision under way.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ChildStat {
    /// The cell the move leads to.
    pub cell: u32,
    /// N(v_i): visits of the child.
    pub visits: u32,
    /// Q(v_i): summed reward 1/τ.
    pub reward: f64,
    /// Q/N, the exploitation term (0 when unvisited).
    pub mean: f64,
    /// c·sqrt(ln N_parent / N_child), the exploration term (∞ when unvisited).
    pub explore: f64,
    /// mean + explore.
    pub uct: f64,
    /// Times this move was selected in the current decision.
    pub selected: u32,
}

impl ChildStat {
    /// The statistics of a child with `visits` and summed `reward` under a
    /// parent with `parent_visits`, selected `selected` times this decision.
    pub fn new(
        cell: u32,
        visits: u32,
        reward: f64,
        parent_visits: u32,
        c: f64,
        selected: u32,
    ) -> ChildStat {
        let (mean, explore, uct) = uct_terms(reward, visits, parent_visits, c);
        ChildStat {
            cell,
            visits,
            reward,
            mean,
            explore,
            uct,
            selected,
        }
    }
}

/// A snapshot of the decision under way.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct DecisionView {
    /// N(v): visits of the parent (the searcher's cell or the root node).
    pub parent_visits: u32,
    /// The exploration constant.
    pub c: f64,
    /// Per move, in `Move::ALL` order (up, right, down, left).
    pub children: [ChildStat; 4],
}

/// The UCT terms `(mean, explore, uct)` of a child.
#[inline]
pub fn uct_terms(reward: f64, visits: u32, parent_visits: u32, c: f64) -> (f64, f64, f64) {
    if visits == 0 {
        return (0.0, f64::INFINITY, f64::INFINITY);
    }
    let mean = reward / visits as f64;
    let lnp = libm::log(parent_visits.max(1) as f64);
    let explore = c * libm::sqrt(lnp / visits as f64);
    (mean, explore, mean + explore)
}

/// The index of the largest valid value, ties broken uniformly at random.
/// Returns `None` when nothing is valid.
pub fn argmax_random(values: [f64; 4], valid: [bool; 4], rng: &mut Rng) -> Option<usize> {
    let mut best = f64::NEG_INFINITY;
    let mut ties = [0usize; 4];
    let mut k = 0;
    for i in 0..4 {
        if !valid[i] {
            continue;
        }
        let v = values[i];
        if k == 0 || v > best {
            best = v;
            k = 0;
        }
        if v == best {
            ties[k] = i;
            k += 1;
        }
    }
    if k == 0 {
        None
    } else {
        Some(ties[rng::below(rng, k as u32) as usize])
    }
}

/// The final move under `rule` from the children's statistics.
pub fn final_move(view: &DecisionView, rule: FinalRule, rng: &mut Rng) -> Move {
    let ch = &view.children;
    let values: [f64; 4] = std::array::from_fn(|i| match rule {
        FinalRule::Visits => ch[i].selected as f64,
        // An unvisited child has no evidence; it ranks below every visited one.
        FinalRule::Mean => {
            if ch[i].visits == 0 {
                -1.0
            } else {
                ch[i].mean
            }
        }
        FinalRule::Uct => ch[i].uct,
    });
    Move::from_index(argmax_random(values, [true; 4], rng).unwrap_or(0) as u32)
}

/// What one MCTS loop needs besides the variant's own statistics.
pub struct LoopEnv<'a> {
    /// The lattice.
    pub torus: &'a Torus,
    /// Detection mask of the practice target.
    pub mask: &'a [u8],
    /// The practice target.
    pub practice: u32,
    /// The rollout (default) policy.
    pub policy: &'a mut Policy,
    /// The searcher's random stream.
    pub rng: &'a mut Rng,
    /// Rollout step cap.
    pub rollout_cap: u32,
    /// Exploration constant.
    pub c: f64,
    /// Where to record this loop's trace (tree path then rollout), if wanted.
    pub trace: Option<&'a mut Vec<u32>>,
}

/// What one loop did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopReport {
    /// Steps of the rollout proper (after the selected cell/leaf).
    pub rollout_steps: u32,
    /// False when the rollout hit its cap.
    pub detected: bool,
    /// The backpropagated reward.
    pub reward: f64,
}

/// A visitor that forwards to an optional trace and an inner visitor.
pub(crate) struct Tee<'a, V: Visit> {
    pub inner: V,
    pub trace: Option<&'a mut Vec<u32>>,
}

impl<V: Visit> Visit for Tee<'_, V> {
    #[inline]
    fn visit(&mut self, cell: u32, step: u32) {
        self.inner.visit(cell, step);
        if let Some(t) = self.trace.as_deref_mut() {
            t.push(cell);
        }
    }
}

/// Runs the rollout policy from `from` and returns the outcome.
pub(crate) fn rollout<V: Visit>(env: &mut LoopEnv<'_>, from: u32, visit: &mut V) -> Outcome {
    env.policy.begin(from, env.practice);
    env.policy
        .rollout(env.torus, env.mask, env.rng, from, env.rollout_cap, visit)
}
