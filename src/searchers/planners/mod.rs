//! The belief planners: searchers that plan paths over the belief instead
//! of sampling, each deterministic, so `run --exact` evaluates it exactly.

pub mod beam;
pub mod horizon;
pub mod improve;
pub mod spiral;
pub mod sweep;
