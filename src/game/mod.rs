//! The game: the lattice, the target prior, what the searcher knows, and
//! the small parts every layer above uses.

pub mod belief;
pub mod budget;
pub mod coverage;
pub mod lattice;
pub(crate) mod named;
pub mod prior;
pub mod rng;
pub mod traces;
