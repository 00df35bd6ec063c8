//! Walks: the random walk, the Lévy flight, NSARW and the greedy walk. Each
//! is an MCTS rollout policy ([`policy::Policy`]), and the first three are
//! also searchers ([`walker::Walker`]).

pub mod greedy;
pub mod levy;
pub mod nsarw;
pub mod policy;
pub mod random_walk;
pub mod visit;
pub mod walker;
