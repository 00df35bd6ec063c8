//! Analysis: the lower bound, theory, statistics and exact means.

pub mod bootstrap;
pub mod bound;
pub mod exact;
pub mod interval;
pub mod median;
pub mod normal;
pub mod paired;
pub mod paired_runs;
pub mod quantiles;
pub mod report;
pub mod stats;
pub mod theory;
