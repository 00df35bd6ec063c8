//! Searchers: who decides each real move, behind one
//! [`searcher::Searcher`] trait, and the [`registry`] that names them.
//!
//! * [`searcher`]: the trait and what a searcher works with.
//! * [`info`]: what the registry knows of a searcher: its parameters and
//!   how to build it.
//! * [`registry`]: every searcher by name.
//! * [`decision`]: what a searcher reports about its decision.
//! * [`phase`]: an MCTS loop a phase at a time, with what each phase did.
//! * [`tree_export`]: the decision's search tree as data, cut for drawing.
//! * [`walks`]: the random walk, the Lévy flight, NSARW and the greedy
//!   walk, as searchers and as rollout policies.
//! * [`planning`]: the parts the belief planners share (the lookahead, the
//!   horizon rule's completion, the far-goal scans, the coverage walk, the
//!   plan cache, path refinement).
//! * [`planners`]: the belief planners (sweep, horizon, rollout
//!   improvement, beam, spiral).
//! * [`mcts`]: UCT Monte Carlo Tree Search and its variants.

pub mod decision;
pub mod info;
pub mod mcts;
pub mod phase;
pub mod planners;
pub mod planning;
pub mod registry;
pub mod searcher;
pub mod tree_export;
pub mod walks;

#[cfg(test)]
mod registry_tests;

pub use decision::{ChildStat, DecisionView, MoveScores, Planning};
pub use info::SearcherInfo;
pub use registry::{SearcherId, REGISTRY};
pub use searcher::{Searcher, Setup, World};
