//! Monte Carlo Tree Search for a single-target search game on a periodic 2-D lattice.
//!
//! The core (everything except [`wasm`]) is plain Rust with no browser
//! dependency: [`lattice`], [`prior`], [`searchers`], [`mcts`], [`episode`],
//! [`stats`] and [`theory`]. A run is a pure function of a [`config::Config`]
//! and a `u64` seed on every platform.

pub mod batch;
pub mod bench;
pub mod config;
pub mod episode;
pub mod lattice;
pub mod mcts;
pub mod prior;
pub mod render;
pub mod rng;
pub mod searchers;
pub mod stats;
pub mod theory;
pub mod wasm;
