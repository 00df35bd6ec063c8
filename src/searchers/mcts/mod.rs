//! UCT Monte Carlo Tree Search: the searcher and its variants' statistics.
//!
//! * [`search`]: the searcher, its parameters and the escape.
//! * [`uct`]: ties at random and the final rule.
//! * [`variant`]: what a variant provides, and the rollout.
//! * [`cells`] keeps statistics per lattice cell, as the paper does.
//! * [`tree`] keeps a real search tree of move sequences.
//! * [`code`] keeps the per-cell statistics of the authors' MATLAB code.
//! * [`pomcp`] plans on the belief (POMCP-style): posterior practice
//!   targets, a reused tree, exact expected-time returns, rollouts along a
//!   plan ([`plan_walk`]) or the coverage walk.

pub mod cells;
pub mod code;
pub mod plan_walk;
pub mod pomcp;
pub mod search;
pub mod tree;
pub mod uct;
pub mod variant;

pub use uct::FinalRule;
pub use variant::Variant;
