//! What one trial gives: its steps, the fewest that would have done, and
//! its rollout counters; as numbers, for passing between workers.

use crate::game::counters::Counters;

/// The result of one trial.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TrialResult {
    /// Real moves made.
    pub steps: u32,
    /// Fewest moves that would have detected the target.
    pub optimal: u32,
    /// True when the target was detected.
    pub found: bool,
    /// The target cell.
    pub target: u32,
    /// Rollout counters over the whole episode.
    pub counters: Counters,
}

/// How many numbers [`TrialResult::fields`] gives.
pub const TRIAL_FIELDS: usize = 7;

impl TrialResult {
    /// steps / optimal, `None` when optimal is 0.
    pub fn ratio(&self) -> Option<f64> {
        (self.optimal > 0).then(|| self.steps as f64 / self.optimal as f64)
    }

    /// The result as numbers, for passing between workers:
    /// `[steps, optimal, found (0/1), target, rollouts, rollout_steps, truncated]`.
    pub fn fields(&self) -> [f64; TRIAL_FIELDS] {
        [
            self.steps as f64,
            self.optimal as f64,
            self.found as u8 as f64,
            self.target as f64,
            self.counters.rollouts as f64,
            self.counters.rollout_steps as f64,
            self.counters.truncated as f64,
        ]
    }

    /// Reads [`TrialResult::fields`] back; `None` unless every number is a
    /// non-negative integer in range.
    pub fn from_fields(f: &[f64]) -> Option<TrialResult> {
        let int = |v: f64, max: f64| (v >= 0.0 && v <= max && v.fract() == 0.0).then_some(v);
        let u32max = u32::MAX as f64;
        let u53 = 9_007_199_254_740_992.0;
        if f.len() != TRIAL_FIELDS {
            return None;
        }
        Some(TrialResult {
            steps: int(f[0], u32max)? as u32,
            optimal: int(f[1], u32max)? as u32,
            found: int(f[2], 1.0)? == 1.0,
            target: int(f[3], u32max)? as u32,
            counters: Counters {
                rollouts: int(f[4], u53)? as u64,
                rollout_steps: int(f[5], u53)? as u64,
                truncated: int(f[6], u53)? as u64,
            },
        })
    }
}
