//! Runs: one trial, runs stepped together, batches of trials.

pub mod batch;
pub mod episode;
pub mod paired;
pub mod race;
pub mod timeline;
pub mod trial_result;
