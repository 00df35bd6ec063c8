//! Analysis: the lower bound, theory, statistics and exact means.

pub mod bound;
pub mod exact;
pub mod report;
pub mod stats;
pub mod theory;
