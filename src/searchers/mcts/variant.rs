//! What an MCTS variant provides: its statistics ([`Stats`]), one loop's
//! environment and report, and the rollout every variant runs.

use crate::game::belief::BeliefState;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::named::named_enum;
use crate::game::rng::Rng;
use crate::searchers::decision::{DecisionView, Planning};
use crate::searchers::phase::PhaseRecord;
use crate::searchers::tree_export::{TreeError, TreeExport, TreeQuery};
use crate::searchers::walks::policy::Policy;
use crate::searchers::walks::visit::{Outcome, Visit};

named_enum! {
    /// Which MCTS variant.
    pub enum Variant {
        /// Per-cell statistics, depth-1 selection (the paper).
        Cells = "cells",
        /// A search tree of move sequences with subtree reuse.
        Tree = "tree",
        /// The statistics of the authors' `MCTSgaussian.m` (the `paper-code` preset).
        Code = "code",
        /// A belief MCTS (POMCP-style): posterior practice targets, a reused
        /// tree, range-scaled expected-time returns, coverage-walk rollouts.
        Pomcp = "pomcp",
    }
}

/// A variant's statistics: what the MCTS searcher
/// ([`crate::searchers::mcts::search::Mcts`]) needs from `cells`, `tree`,
/// `code` and `pomcp`.
///
/// A loop is its four phases in order, [`Stats::select`],
/// [`Stats::expand`], [`Stats::roll_out`] and [`Stats::back_up`], each
/// given the same environment (the practice target armed): run one after
/// the other ([`Stats::iterate`]) or a call apart, they draw the same
/// random numbers and leave the same statistics. Each phase fills `rec`,
/// when given, with what it did.
pub trait Stats: Clone {
    /// True when practice targets come from the posterior whatever the
    /// `belief` parameter says.
    const POSTERIOR_TARGETS: bool = false;
    /// Starts a decision at `root`; `reset` clears persistent statistics.
    fn begin_decision(&mut self, torus: &Torus, root: u32, reset: bool);
    /// Selection: from `root` by UCT down to the node to expand (the
    /// tables: one of the root's four neighbours).
    fn select(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>);
    /// Expansion: one node added below the selected one, if any.
    fn expand(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>);
    /// The rollout from the loop's leaf.
    fn roll_out(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>);
    /// Backpropagation: the loop's reward to the nodes it went through.
    fn back_up(
        &mut self,
        env: &mut LoopEnv<'_>,
        root: u32,
        rec: Option<&mut PhaseRecord>,
    ) -> LoopReport;
    /// One loop from `root`: select, expand, roll out, backpropagate.
    #[inline]
    fn iterate(&mut self, env: &mut LoopEnv<'_>, root: u32) -> LoopReport {
        self.select(env, root, None);
        self.expand(env, root, None);
        self.roll_out(env, root, None);
        self.back_up(env, root, None)
    }
    /// The decision's tree (a table's star) at `root`, cut by `q`.
    ///
    /// # Errors
    /// A [`TreeError`] for a query the tree cannot answer.
    fn tree(
        &self,
        torus: &Torus,
        root: u32,
        c: f64,
        q: &TreeQuery,
    ) -> Result<TreeExport, TreeError>;
    /// Heap bytes held (what a copy of the statistics allocates).
    fn heap_bytes(&self) -> usize;
    /// The decision statistics at `root`.
    fn view(&self, torus: &Torus, root: u32, c: f64) -> DecisionView;
    /// The real move `m` was made (a tree keeps that subtree).
    fn advance(&mut self, m: Move);
    /// Visit counts per cell of a lattice of `cells` cells (`scratch` is
    /// room to project a tree into).
    fn visits<'a>(&'a self, cells: usize, scratch: &'a mut Vec<u32>) -> &'a [u32];
    /// Since the last decision the moves searched a share `lost` (in
    /// (0, 1]) of the belief's unsearched planning mass: that share of the
    /// practice targets the statistics were gathered on is now impossible.
    fn belief_changed(&mut self, _lost: f64) {}
    /// The cells the statistics mean to enter next (see [`Searcher::intent`]).
    fn intent(&self) -> &[u32] {
        &[]
    }
    /// Work a decision does before its first loop, a slice at a time
    /// (the belief MCTS makes its plan): does a slice and returns false
    /// while some is left, true once the loops can run. It draws no random
    /// numbers, so where the slices fall changes nothing.
    fn prepare(
        &mut self,
        _torus: &Torus,
        _sensor: &Sensor,
        _belief: &BeliefState,
        _root: u32,
        _cap: u32,
    ) -> bool {
        true
    }
    /// How far the work of [`Stats::prepare`] has got, while some is left.
    fn planning(&self) -> Option<Planning> {
        None
    }
    /// True while the statistics follow a plan that completes the search
    /// (the belief MCTS's): such a searcher cannot be trapped, so the
    /// escape must not walk it off the plan.
    fn holds_plan(&self) -> bool {
        false
    }
    /// Ends a decision with the statistics' own choice of move, or `None`
    /// to leave it to the final rule (`cap`: the rollout step cap).
    fn conclude(
        &mut self,
        _torus: &Torus,
        _sensor: &Sensor,
        _belief: &BeliefState,
        _cap: u32,
    ) -> Option<Move> {
        None
    }
}

/// What one MCTS loop needs besides the variant's own statistics.
pub struct LoopEnv<'a> {
    /// The lattice.
    pub torus: &'a Torus,
    /// What is known about the target (the belief MCTS plans on it).
    pub belief: &'a BeliefState,
    /// The detection sensor, armed with the practice target.
    pub sensor: &'a Sensor,
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
    /// False for a rollout that is not one of the decision's loops (the
    /// `code` variant's expansion rollouts): it is counted as a rollout but
    /// not against the loop budget.
    pub counts: bool,
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

/// Runs the rollout policy from `from` with `visit`, recording its cells in
/// the loop's trace when there is one; returns the outcome and the visitor.
/// Without a trace the walk runs with `visit` alone: no test of the trace
/// at every step.
pub(crate) fn rollout_traced<V: Visit>(env: &mut LoopEnv<'_>, from: u32, visit: V) -> (Outcome, V) {
    match env.trace.take() {
        None => {
            let mut v = visit;
            let out = rollout(env, from, &mut v);
            (out, v)
        }
        Some(t) => {
            let mut tee = Tee {
                inner: visit,
                trace: Some(t),
            };
            let out = rollout(env, from, &mut tee);
            env.trace = tee.trace;
            (out, tee.inner)
        }
    }
}

/// Runs the rollout policy from `from` and returns the outcome.
pub(crate) fn rollout<V: Visit>(env: &mut LoopEnv<'_>, from: u32, visit: &mut V) -> Outcome {
    env.policy.begin(from, env.practice);
    env.policy
        .rollout(env.torus, env.mask, env.rng, from, env.rollout_cap, visit)
}

/// The root and its four neighbours (in `Move::ALL` order): the cells a
/// table variant's decision selects among.
pub(crate) fn star(torus: &Torus, root: u32) -> [u32; 5] {
    let mut s = [root; 5];
    for (i, &m) in Move::ALL.iter().enumerate() {
        s[i + 1] = torus.step(root, m);
    }
    s
}

/// Cells recorded in the loop's trace so far (where its rollout starts).
pub(crate) fn trace_len(env: &LoopEnv<'_>) -> u32 {
    env.trace.as_deref().map_or(0, |t| t.len() as u32)
}

/// Notes the rollout in `rec`: where it starts in the trace, its steps
/// and whether it found the practice target.
pub(crate) fn note_rollout(rec: Option<&mut PhaseRecord>, from: u32, steps: u32, detected: bool) {
    if let Some(r) = rec {
        r.rollout_from = from;
        r.rollout_steps = steps;
        r.detected = detected;
        r.truncated = !detected;
    }
}
