//! What `run --json` prints for a batch: the summary, the bound, and how it
//! ran.

use crate::analysis::stats::Summary;
use crate::config::Config;

/// What a batch reports: the summary's fields, the bound, then how it ran.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Report<'a> {
    /// The statistics.
    #[serde(flatten)]
    pub summary: &'a Summary,
    /// The lower bound on the mean steps of any searcher for this prior, N,
    /// r_v, start and step cap ([`crate::analysis::bound::lower_bound_capped`]).
    pub lower_bound: f64,
    /// Mean steps ÷ the lower bound (`None` when the bound is 0).
    pub mean_over_bound: Option<f64>,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Threads or workers used (results do not depend on it).
    pub threads: usize,
    /// The seed (also in `config`).
    pub seed: u64,
    /// The full resolved configuration.
    pub config: &'a Config,
}
