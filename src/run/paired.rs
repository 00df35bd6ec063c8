//! Two configurations on the same trials: each trial's target comes from
//! the seed and the game (lattice, prior, start), so two configurations
//! that share them search for the same target, and their steps can be
//! compared trial by trial (common random numbers). Here: the paired trial,
//! the paired difference of steps with a bootstrap interval and the
//! win/tie/loss counts, and what differs between the two configurations.

use crate::config::{self, Config};
use crate::game::rng;
use crate::param::ParamError;
use crate::run::episode::{Episode, TrialResult};

/// The keys that decide a trial's target and start: two configurations
/// are paired only when these agree.
pub const WORLD_KEYS: &[&str] = &["seed", "n", "prior", "sigma", "paint", "target", "start"];

/// Bootstrap resamples of the mean difference.
pub const BOOTSTRAP_RESAMPLES: usize = 2000;

/// The seed of the bootstrap's resampling (fixed: a summary is a function
/// of its trials).
const BOOTSTRAP_SEED: u64 = 0x7061_6972;

/// Why two configurations cannot be paired.
#[derive(Clone, Debug, PartialEq)]
pub enum PairError {
    /// A configuration is invalid.
    Param(ParamError),
    /// The two sides of a trial search for different targets (or start
    /// from different cells).
    Unpaired {
        /// The trial.
        index: u64,
        /// The world keys whose values differ, with both values.
        differ: Vec<ConfigDifference>,
    },
    /// No trials to summarise.
    Empty,
}

impl std::fmt::Display for PairError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PairError::Param(e) => e.fmt(f),
            PairError::Unpaired { index, differ } => {
                write!(
                    f,
                    "trial {index}: the two sides search for different targets; a paired comparison needs the same {}",
                    WORLD_KEYS.join(", ")
                )?;
                if !differ.is_empty() {
                    let d: Vec<String> = differ
                        .iter()
                        .map(|d| format!("{} {} ≠ {}", d.key, d.a, d.b))
                        .collect();
                    write!(f, " (here {})", d.join(", "))?;
                }
                Ok(())
            }
            PairError::Empty => f.write_str("a paired summary needs at least one trial"),
        }
    }
}

impl std::error::Error for PairError {}

impl From<ParamError> for PairError {
    fn from(e: ParamError) -> PairError {
        PairError::Param(e)
    }
}

/// A parameter whose values differ between two configurations.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct ConfigDifference {
    /// Its key.
    pub key: &'static str,
    /// Its label, for people.
    pub label: &'static str,
    /// Its value in the first configuration, as text.
    pub a: String,
    /// Its value in the second.
    pub b: String,
}

/// The parameters whose values differ between `a` and `b`, among those
/// that affect a run of either (a board's title names them).
pub fn differences(a: &Config, b: &Config) -> Vec<ConfigDifference> {
    let (used_a, used_b) = (a.applicable(), b.applicable());
    a.params(true)
        .into_iter()
        .zip(b.params(true))
        .filter(|((k, va), (_, vb))| va != vb && (used_a.contains(k) || used_b.contains(k)))
        .map(|((key, va), (_, vb))| ConfigDifference {
            key,
            label: config::param(key).map_or(key, |p| p.label),
            a: va,
            b: vb,
        })
        .collect()
}

/// Trial `index` of `a` and of `b`, run to the end, on the same target.
///
/// # Errors
/// A [`PairError`] when a configuration is invalid or the two sides'
/// targets or starts differ.
pub fn paired_trial(
    a: &Config,
    b: &Config,
    index: u64,
) -> Result<(TrialResult, TrialResult), PairError> {
    let (mut ea, mut eb) = (Episode::trial(a, index)?, Episode::trial(b, index)?);
    if ea.target() != eb.target() || ea.start() != eb.start() {
        return Err(unpaired(a, b, index));
    }
    Ok((ea.run(), eb.run()))
}

fn unpaired(a: &Config, b: &Config, index: u64) -> PairError {
    let differ = differences(a, b)
        .into_iter()
        .filter(|d| WORLD_KEYS.contains(&d.key))
        .collect();
    PairError::Unpaired { index, differ }
}

/// The paired comparison of two configurations' steps over common trials.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PairedSummary {
    /// Trials compared.
    pub trials: usize,
    /// Mean steps of each side (a capped trial counts its step cap).
    pub mean_a: f64,
    /// Mean steps of the second side.
    pub mean_b: f64,
    /// Mean of the differences, steps of A − steps of B (negative: A is faster).
    pub mean_difference: f64,
    /// Standard deviation of the differences.
    pub sd_difference: f64,
    /// 95% bootstrap percentile interval of the mean difference.
    pub ci: [f64; 2],
    /// The interval's level.
    pub level: f64,
    /// How the interval was made.
    pub method: &'static str,
    /// Trials where A took fewer steps (detected first), as many, more.
    pub a_wins: usize,
    /// Trials of equal steps.
    pub ties: usize,
    /// Trials where B took fewer steps.
    pub b_wins: usize,
    /// Trials each side detected the target in (the rest hit the step cap).
    pub found_a: usize,
    /// Trials B detected the target in.
    pub found_b: usize,
}

/// The paired summary of trials run on both sides (pair `i` the same trial).
///
/// # Errors
/// [`PairError::Empty`] without trials, [`PairError::Unpaired`] (index in
/// `pairs`) when a pair's targets differ.
pub fn paired_summary(pairs: &[(TrialResult, TrialResult)]) -> Result<PairedSummary, PairError> {
    if pairs.is_empty() {
        return Err(PairError::Empty);
    }
    if let Some(i) = pairs.iter().position(|(a, b)| a.target != b.target) {
        return Err(PairError::Unpaired {
            index: i as u64,
            differ: Vec::new(),
        });
    }
    let n = pairs.len();
    let d: Vec<f64> = pairs
        .iter()
        .map(|(a, b)| a.steps as f64 - b.steps as f64)
        .collect();
    let mean = |v: &mut dyn Iterator<Item = f64>| v.sum::<f64>() / n as f64;
    let md = mean(&mut d.iter().copied());
    let sd = if n > 1 {
        (d.iter().map(|x| (x - md) * (x - md)).sum::<f64>() / (n - 1) as f64).sqrt()
    } else {
        0.0
    };
    Ok(PairedSummary {
        trials: n,
        mean_a: mean(&mut pairs.iter().map(|(a, _)| a.steps as f64)),
        mean_b: mean(&mut pairs.iter().map(|(_, b)| b.steps as f64)),
        mean_difference: md,
        sd_difference: sd,
        ci: bootstrap_interval(&d, 0.95),
        level: 0.95,
        method: "bootstrap percentile interval of the mean difference, 2000 resamples (fixed seed)",
        a_wins: d.iter().filter(|&&x| x < 0.0).count(),
        ties: d.iter().filter(|&&x| x == 0.0).count(),
        b_wins: d.iter().filter(|&&x| x > 0.0).count(),
        found_a: pairs.iter().filter(|(a, _)| a.found).count(),
        found_b: pairs.iter().filter(|(_, b)| b.found).count(),
    })
}

/// The percentile bootstrap interval of the mean of `d` at `level`:
/// resampling keeps no normal approximation, which heavy-tailed, capped
/// step counts would break.
fn bootstrap_interval(d: &[f64], level: f64) -> [f64; 2] {
    let n = d.len();
    let mut r = rng::stream(BOOTSTRAP_SEED, n as u64);
    let mut means: Vec<f64> = (0..BOOTSTRAP_RESAMPLES)
        .map(|_| {
            let s: f64 = (0..n)
                .map(|_| d[rng::below(&mut r, n as u32) as usize])
                .sum();
            s / n as f64
        })
        .collect();
    means.sort_by(f64::total_cmp);
    let tail = (1.0 - level) / 2.0;
    let at =
        |q: f64| means[((q * BOOTSTRAP_RESAMPLES as f64) as usize).min(BOOTSTRAP_RESAMPLES - 1)];
    [at(tail), at(1.0 - tail)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::counters::Counters;

    fn result(steps: u32, target: u32) -> TrialResult {
        TrialResult {
            steps,
            optimal: 1,
            found: true,
            target,
            counters: Counters::default(),
        }
    }

    #[test]
    fn the_summary_counts_wins_and_brackets_the_mean_difference() {
        // A is 3 steps faster on each of 30 trials but one (a tie) and
        // one (5 slower).
        let mut pairs: Vec<_> = (0..30)
            .map(|i| (result(10 + i, i), result(13 + i, i)))
            .collect();
        pairs[0].1.steps = pairs[0].0.steps;
        pairs[1].1.steps = pairs[1].0.steps - 5;
        let s = paired_summary(&pairs).unwrap();
        assert_eq!((s.a_wins, s.ties, s.b_wins, s.trials), (28, 1, 1, 30));
        let want = (28.0 * -3.0 + 5.0) / 30.0;
        assert!((s.mean_difference - want).abs() < 1e-12);
        assert!(
            s.ci[0] < s.mean_difference && s.mean_difference < s.ci[1],
            "{s:?}"
        );
        // The interval is about ±2 standard errors wide.
        let se = s.sd_difference / 30f64.sqrt();
        let half = (s.ci[1] - s.ci[0]) / 2.0;
        assert!(half > 1.5 * se && half < 2.5 * se, "{half} vs se {se}");
        // Identical sides: a point interval at 0, all ties.
        let same: Vec<_> = (0..5).map(|i| (result(i, i), result(i, i))).collect();
        let s = paired_summary(&same).unwrap();
        assert_eq!((s.ci, s.ties), ([0.0, 0.0], 5));
        // Different targets cannot be paired; nothing cannot be summarised.
        let mut bad = same.clone();
        bad[3].1.target = 99;
        assert!(matches!(
            paired_summary(&bad),
            Err(PairError::Unpaired { index: 3, .. })
        ));
        assert_eq!(paired_summary(&[]), Err(PairError::Empty));
    }
}
