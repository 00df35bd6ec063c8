//! Exact evaluation of a deterministic searcher: one pass along its path
//! gives its mean with no sampling noise.
//!
//! A searcher learns nothing about the target until it detects it, so a
//! deterministic searcher follows one fixed path `p_0, p_1, …` in every
//! trial up to detection, whatever the target. With `R_t` the prior mass
//! outside the cells covered by `p_0 … p_t`, a trial's `min(T, cap)` has
//! mean `Σ_{t<cap} R_t` ([`crate::analysis::bound::path_mean`]): exactly what a batch
//! of infinitely many trials would report (a capped trial counted at its
//! cap). The path is driven by a blind [`Episode`] until every cell with
//! prior mass is covered or the step cap.

use crate::analysis::bound;
use crate::config::Config;
use crate::game::belief::BeliefState;
use crate::param::ParamError;
use crate::run::episode::Episode;
use crate::searchers;
use crate::searchers::mcts::search::BELIEF;
use crate::searchers::planners::improve::{base_alone, Base};
use crate::searchers::planning::lookahead::HORIZON;
use std::fmt;

/// Why a configuration cannot be evaluated exactly.
#[derive(Clone, Debug, PartialEq)]
pub enum ExactError {
    /// The searcher draws random numbers: its path is not fixed.
    NotDeterministic {
        /// The searcher's name.
        searcher: &'static str,
    },
    /// With `known` the searcher plans with the target's cell, so its path
    /// depends on the target.
    Known {
        /// The flag that asked: `--exact` or `--blind`.
        flag: &'static str,
    },
    /// The configuration is invalid.
    Config(ParamError),
}

impl fmt::Display for ExactError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExactError::NotDeterministic { searcher } => write!(
                f,
                "--exact needs a deterministic searcher ({}), got {searcher}",
                deterministic_names().join(", ")
            ),
            ExactError::Known { flag } => write!(
                f,
                "{flag} cannot evaluate --known: the path then depends on the target"
            ),
            ExactError::Config(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for ExactError {}

impl From<ParamError> for ExactError {
    fn from(e: ParamError) -> ExactError {
        ExactError::Config(e)
    }
}

/// The registered searchers that can be evaluated exactly.
pub fn deterministic_names() -> Vec<&'static str> {
    let mut cfg = Config::default();
    searchers::REGISTRY
        .iter()
        .filter(|s| {
            cfg.searcher = searchers::SearcherId::parse(s.name).expect("registered");
            cfg.searcher.info().deterministic
        })
        .map(|s| s.name)
        .collect()
}

/// The exact mean of a deterministic searcher.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Exact {
    /// `E[min(T, step_cap)] = Σ_{t<cap} R_t`: the mean steps a batch of
    /// trials estimates.
    pub mean: f64,
    /// Prior mass the path leaves uncovered before the cap: the probability
    /// that a trial is capped.
    pub capped_probability: f64,
    /// Moves driven: until every cell with prior mass was covered, or the
    /// step cap.
    pub moves: u32,
}

/// Drives the searcher of `cfg` along its whole path with detection off
/// and sums `R_t` exactly.
///
/// # Errors
/// [`ExactError::NotDeterministic`] for a searcher that draws random
/// numbers, [`ExactError::Known`] with `known`, [`ExactError::Config`] for
/// an invalid configuration.
pub fn exact_mean(cfg: &Config) -> Result<Exact, ExactError> {
    cfg.validate()?;
    if !cfg.searcher.info().deterministic {
        return Err(ExactError::NotDeterministic {
            searcher: cfg.searcher.name(),
        });
    }
    if cfg.known {
        return Err(ExactError::Known { flag: "--exact" });
    }
    Ok(blind_mean(cfg, 0)?)
}

/// The exact `Σ_{t<cap} R_t` of rollout improvement's `base` alone from
/// the start of `cfg` (what rollout improvement is never worse than), with
/// the cells of the base's path after the start (the cheapest base's, with
/// `best`).
///
/// # Errors
/// The [`ParamError`] of [`Config::game`].
pub fn base_mean(cfg: &Config, base: Base) -> Result<(f64, Vec<u32>), ParamError> {
    let g = cfg.game()?;
    let mut belief = BeliefState::new(cfg.settings.choice(&BELIEF), g.prior.clone(), None);
    belief.search_around(&g.sensor, g.start);
    let h = cfg.settings.u32(&HORIZON);
    Ok(base_alone(
        &g.torus,
        &g.sensor,
        &belief,
        g.start,
        base,
        h,
        cfg.step_cap,
    ))
}

/// The exact mean of trial `i`'s blind path: `Σ_{t<cap} R_t` along the
/// path the searcher of `cfg` follows in trial `i` until it detects the
/// target. For a searcher that draws random numbers (from its own stream,
/// never the target's) this is `E[min(T, cap)]` given trial `i`'s draws,
/// so its mean over trials estimates the searcher's mean with the
/// target's share of the noise removed (Rao-Blackwellised). Ignores
/// `known`.
///
/// # Errors
/// The [`ParamError`] of an invalid configuration.
pub fn blind_mean(cfg: &Config, i: u64) -> Result<Exact, ParamError> {
    let game = cfg.game()?;
    let mass = game.prior.mass();
    let mut covered = vec![false; game.torus.cells()];
    let mut left = mass.iter().filter(|&&m| m > 0.0).count();
    let mut cover = |cell: u32, left: &mut usize| {
        for c in game.sensor.around(cell) {
            if !covered[c as usize] {
                covered[c as usize] = true;
                *left -= (mass[c as usize] > 0.0) as usize;
            }
        }
    };
    let mut ep = Episode::blind_trial(cfg, i)?;
    cover(ep.position(), &mut left);
    // Σ_{t<cap} R_t reads positions 0..cap−1: at most cap − 1 moves.
    while left > 0 && ep.steps() + 1 < cfg.step_cap {
        ep.step_move();
        cover(ep.position(), &mut left);
    }
    let pm = bound::path_mean(&game.torus, &game.sensor, mass, ep.path());
    Ok(Exact {
        mean: pm.mean,
        capped_probability: pm.uncovered,
        moves: ep.steps(),
    })
}

/// What `run --blind` reports: trials' blind paths counted exactly.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BlindReport<'a> {
    /// Trials counted.
    pub trials: u64,
    /// The mean of the trials' blind paths' exact means, which estimates
    /// `E[min(T, step_cap)]`, with its bootstrap interval over trials.
    pub blind_mean: crate::analysis::interval::Interval,
    /// The standard deviation of the trials' exact means (n − 1).
    pub sd: f64,
    /// The smallest and largest trial's exact mean.
    pub min: f64,
    /// See `min`.
    pub max: f64,
    /// The mean probability that a trial is capped.
    pub capped_probability: f64,
    /// Moves driven per trial, on average.
    pub mean_moves: f64,
    /// The lower bound on the mean steps of any searcher.
    pub lower_bound: f64,
    /// The mean ÷ the lower bound (`None` when the bound is 0).
    pub mean_over_bound: Option<f64>,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Threads used (results do not depend on it).
    pub threads: usize,
    /// The seed (also in `config`).
    pub seed: u64,
    /// The full resolved configuration.
    pub config: &'a Config,
}

/// Checks that trials' blind paths estimate the mean of `cfg`: they do
/// unless the searcher knows the target.
///
/// # Errors
/// [`ExactError::Known`] with `known`, [`ExactError::Config`] for an
/// invalid configuration.
pub fn check_blind(cfg: &Config) -> Result<(), ExactError> {
    cfg.game()?;
    if cfg.known {
        return Err(ExactError::Known { flag: "--blind" });
    }
    Ok(())
}

/// What `run --exact` reports.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ExactReport<'a> {
    /// The exact evaluation.
    pub exact: Exact,
    /// The lower bound on the mean steps of any searcher
    /// ([`bound::lower_bound_capped`]).
    pub lower_bound: f64,
    /// The exact mean ÷ the lower bound (`None` when the bound is 0).
    pub mean_over_bound: Option<f64>,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// The seed (also in `config`; the result does not depend on it).
    pub seed: u64,
    /// The full resolved configuration.
    pub config: &'a Config,
}
