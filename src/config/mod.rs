//! The configuration of a run, and the schema that describes it.
//!
//! The schema ([`schema::params`]) is the only place that lists the
//! parameters: the game's own ([`fields::FIELDS`]) and the ones each
//! searcher declares in its file (assembled from the registry). The CLI
//! builds its flags from it, the facade exports it for the page's URL
//! parser and controls, and experiment sweeps name parameters by its keys.

pub mod edit;
pub mod fields;
pub mod game;
pub mod json;
pub mod preset;
pub mod schema;

#[cfg(test)]
mod tests;

pub use edit::from_params;
pub use fields::Config;
pub use game::Game;
pub use json::from_json;
pub use schema::{param, params, schema, Schema, PRESET, TRIALS};
