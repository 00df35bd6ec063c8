//! Monte Carlo Tree Search for a single-target search game on a periodic 2-D lattice.
//!
//! The core (everything except [`wasm`]) is plain Rust with no browser
//! dependency. A run is a pure function of a [`config::Config`] (which
//! holds the seed) on every platform. `docs/ARCHITECTURE.md` maps the
//! modules and the data flow from a URL or CLI flag to a drawn frame.

mod named;

pub mod batch;
pub mod belief;
pub mod bench;
pub mod bound;
pub mod budget;
pub mod config;
pub mod coverage;
pub mod episode;
pub mod exact;
pub mod experiment;
pub mod lattice;
pub mod mcts;
pub mod preset;
pub mod prior;
pub mod race;
pub mod render;
pub mod rng;
pub mod searchers;
pub mod stats;
pub mod theory;
pub mod traces;
pub mod view;
pub mod wasm;
