//! Runs: one trial, runs stepped together, branched, batches of trials.

pub mod batch;
pub mod branch;
pub mod episode;
pub mod paired;
pub mod race;
pub mod timeline;
pub mod trial_result;
