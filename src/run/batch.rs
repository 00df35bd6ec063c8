//! Batches of trials, their report, and run fingerprints. The CLI, the
//! page's worker pool and the tests all run trials through [`trial`].

use crate::analysis::stats::Summary;
use crate::config::{Config, ConfigError};
use crate::run::episode::{Episode, TrialResult};

/// Runs trial `index` of `cfg` to the end.
///
/// Trial `i` depends only on `(cfg, i)` (the seed is part of the config),
/// so any split of a batch (threads, workers, chunks) gives the same results.
///
/// # Errors
/// A [`ConfigError`] naming the first invalid field.
pub fn trial(cfg: &Config, index: u64) -> Result<TrialResult, ConfigError> {
    Ok(Episode::trial(cfg, index)?.run())
}

/// Runs trials `first..first + count` of `cfg`, in order.
///
/// # Errors
/// A [`ConfigError`] naming the first invalid field.
pub fn run_trials(cfg: &Config, first: u64, count: u64) -> Result<Vec<TrialResult>, ConfigError> {
    cfg.validate()?;
    (first..first + count).map(|i| trial(cfg, i)).collect()
}

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

/// FNV-1a over 64-bit words.
#[derive(Clone, Copy, Debug)]
pub struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    /// Mixes in one word.
    pub fn word(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }

    /// The hash.
    pub fn finish(self) -> u64 {
        self.0
    }
}

/// A fingerprint of `trials` trials: every path cell, target and rollout
/// counter. Equal fingerprints on two platforms mean identical runs.
///
/// # Errors
/// A [`ConfigError`] naming the first invalid field.
pub fn fingerprint(cfg: &Config, trials: u64) -> Result<u64, ConfigError> {
    let mut h = Fnv::default();
    for i in 0..trials {
        let mut e = Episode::trial(cfg, i)?;
        let r = e.run();
        for &c in e.path() {
            h.word(c as u64);
        }
        h.word(r.target as u64);
        h.word(r.counters.rollouts);
        h.word(r.counters.rollout_steps);
        h.word(r.counters.truncated);
    }
    Ok(h.finish())
}
