//! Batches of trials, and run fingerprints. The CLI, the
//! page's worker pool and the tests all run trials through [`trial`].

use crate::config::Config;
use crate::game::fnv::Fnv;
use crate::param::ParamError;
use crate::run::episode::{Episode, TrialResult};

/// Runs trial `index` of `cfg` to the end.
///
/// Trial `i` depends only on `(cfg, i)` (the seed is part of the config),
/// so any split of a batch (threads, workers, chunks) gives the same results.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn trial(cfg: &Config, index: u64) -> Result<TrialResult, ParamError> {
    Ok(Episode::trial(cfg, index)?.run())
}

/// Runs trials `first..first + count` of `cfg`, in order.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn run_trials(cfg: &Config, first: u64, count: u64) -> Result<Vec<TrialResult>, ParamError> {
    cfg.validate()?;
    (first..first + count).map(|i| trial(cfg, i)).collect()
}

/// A fingerprint of `trials` trials: every path cell, target and rollout
/// counter. Equal fingerprints on two platforms mean identical runs.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn fingerprint(cfg: &Config, trials: u64) -> Result<u64, ParamError> {
    fingerprint_driven(cfg, trials, |e| {
        e.run();
    })
}

/// The fingerprint of `trials` trials each run to its end by `drive`
/// (stepped in any way: by moves, loops or phases), as [`fingerprint`]
/// hashes them.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn fingerprint_driven(
    cfg: &Config,
    trials: u64,
    mut drive: impl FnMut(&mut Episode),
) -> Result<u64, ParamError> {
    let mut h = Fnv::default();
    for i in 0..trials {
        let mut e = Episode::trial(cfg, i)?;
        drive(&mut e);
        let r = e.result();
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
