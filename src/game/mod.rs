//! The game: the lattice, the target prior, what the searcher knows, and
//! the small parts every layer above uses.

pub mod belief;
pub mod budget;
pub mod counters;
pub mod coverage;
pub mod fnv;
pub mod lattice;
pub mod layer;
pub mod named;
pub mod prior;
pub mod rng;
pub mod sum;
pub mod traces;
