//! Two configurations on the same trials: each trial's target comes from
//! the seed and the game (lattice, prior, start), so two configurations
//! that share them search for the same target, and their steps can be
//! compared trial by trial (common random numbers). Here: the paired trial
//! and what differs between the two configurations; their summary is
//! `analysis::paired_runs`.

use crate::config::{self, Config};
use crate::param::ParamError;
use crate::run::episode::{Episode, TrialResult};

/// The keys that decide a trial's target and start: two configurations
/// are paired only when these agree.
pub const WORLD_KEYS: &[&str] = &["seed", "n", "prior", "sigma", "paint", "target", "start"];

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
