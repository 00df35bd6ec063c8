//! Monte Carlo Tree Search for a single-target search game on a periodic 2-D lattice.
//!
//! The core (everything except [`wasm`]) is plain Rust with no browser dependency.

pub mod wasm;
