//! Batches of trials and run fingerprints.

use crate::config::{Config, ConfigError};
use crate::episode::{Episode, TrialResult};

/// Runs trials `first..first + count` of `cfg` with `seed`, in order.
///
/// Trial `i` depends only on `(cfg, seed, i)`, so any split of a batch
/// (threads, workers, chunks) gives the same results.
///
/// # Errors
/// A [`ConfigError`] naming the first invalid field.
pub fn run_trials(
    cfg: &Config,
    seed: u64,
    first: u64,
    count: u64,
) -> Result<Vec<TrialResult>, ConfigError> {
    cfg.validate()?;
    (first..first + count)
        .map(|i| Episode::trial(cfg, seed, i).map(|mut e| e.run()))
        .collect()
}

/// FNV-1a over 32-bit words.
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
pub fn fingerprint(cfg: &Config, seed: u64, trials: u64) -> Result<u64, ConfigError> {
    let mut h = Fnv::default();
    for i in 0..trials {
        let mut e = Episode::trial(cfg, seed, i)?;
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
