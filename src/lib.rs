//! Monte Carlo Tree Search for a single-target search game on a periodic 2-D lattice.
//!
//! The core (everything except [`wasm`]) is plain Rust with no browser
//! dependency. A run is a pure function of a [`config::Config`] (which
//! holds the seed) on every platform. The modules form layers that only
//! point down (`docs/ARCHITECTURE.md`; `tests/suite/layers.rs` checks it):

pub mod game;

pub mod param;

pub mod searchers;

pub mod config;

pub mod run;

pub mod analysis;
pub mod bench;
pub mod display;
pub mod experiment;

#[cfg(not(target_arch = "wasm32"))]
pub mod cli;
pub mod wasm;
