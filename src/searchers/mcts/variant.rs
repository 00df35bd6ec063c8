//! What an MCTS variant provides: its statistics ([`Stats`]), one loop's
//! environment and report, and the rollout every variant runs.

use crate::game::belief::BeliefState;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::named::named_enum;
use crate::game::rng::Rng;
use crate::searchers::decision::{DecisionView, Planning};
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
pub trait Stats {
    /// True when practice targets come from the posterior whatever the
    /// `belief` parameter says.
    const POSTERIOR_TARGETS: bool = false;
    /// Starts a decision at `root`; `reset` clears persistent statistics.
    fn begin_decision(&mut self, root: u32, reset: bool);
    /// One loop from `root`: select, roll out, backpropagate.
    fn iterate(&mut self, env: &mut LoopEnv<'_>, root: u32) -> LoopReport;
    /// The decision statistics at `root`.
    fn view(&self, torus: &Torus, root: u32, c: f64) -> DecisionView;
    /// The real move `m` was made (a tree keeps that subtree).
    fn advance(&mut self, m: Move);
    /// Visit counts per cell of a lattice of `cells` cells (`scratch` is
    /// room to project a tree into).
    fn visits<'a>(&'a self, cells: usize, scratch: &'a mut Vec<u32>) -> &'a [u32];
    /// The belief changed since the last decision (a move searched new
    /// cells): statistics gathered for the old belief are now stale.
    fn belief_changed(&mut self) {}
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

/// Runs the rollout policy from `from` and returns the outcome.
pub(crate) fn rollout<V: Visit>(env: &mut LoopEnv<'_>, from: u32, visit: &mut V) -> Outcome {
    env.policy.begin(from, env.practice);
    env.policy
        .rollout(env.torus, env.mask, env.rng, from, env.rollout_cap, visit)
}
