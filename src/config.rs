//! The full, validated configuration of an episode or a batch of trials.

use crate::lattice::{MAX_N, MIN_N};
use crate::mcts::tree::{DEFAULT_MAX_NODES, MAX_MAX_NODES, MIN_MAX_NODES};
use crate::mcts::{FinalRule, Variant};
use crate::prior::PriorSpec;
use crate::searchers::PolicyKind;
use std::fmt;

/// Who searches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SearcherKind {
    /// Monte Carlo Tree Search with a rollout policy.
    Mcts,
    /// A standalone random walk.
    Rw,
    /// A standalone Lévy flight.
    Levy,
    /// A standalone nearly self-avoiding random walk.
    Nsarw,
}

impl SearcherKind {
    /// All kinds.
    pub const ALL: [SearcherKind; 4] = [
        SearcherKind::Mcts,
        SearcherKind::Rw,
        SearcherKind::Levy,
        SearcherKind::Nsarw,
    ];

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            SearcherKind::Mcts => "mcts",
            SearcherKind::Rw => "rw",
            SearcherKind::Levy => "levy",
            SearcherKind::Nsarw => "nsarw",
        }
    }

    /// Parses a lower-case name.
    pub fn parse(s: &str) -> Option<SearcherKind> {
        SearcherKind::ALL.into_iter().find(|k| k.name() == s)
    }
}

/// Where practice targets come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Belief {
    /// The prior, as in the paper.
    Prior,
    /// The prior with every searched cell set to zero, renormalised.
    Posterior,
}

impl Belief {
    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Belief::Prior => "prior",
            Belief::Posterior => "posterior",
        }
    }

    /// Parses a lower-case name.
    pub fn parse(s: &str) -> Option<Belief> {
        [Belief::Prior, Belief::Posterior]
            .into_iter()
            .find(|b| b.name() == s)
    }
}

/// Everything that defines a run; with a seed it determines the run exactly.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Lattice side N.
    pub n: u32,
    /// Target prior.
    pub prior: PriorSpec,
    /// Detection radius r_v (torus Euclidean distance).
    pub rv: f64,
    /// Start cell, 1-based `[x, y]`.
    pub start: [u32; 2],
    /// A fixed target cell, 1-based `[x, y]` (a delta prior there).
    pub target: Option<[u32; 2]>,
    /// Place the target by the prior but plan with a delta prior on it.
    pub known: bool,
    /// Who searches.
    pub searcher: SearcherKind,
    /// MCTS variant.
    pub variant: Variant,
    /// MCTS rollout (default) policy.
    pub rollout: PolicyKind,
    /// Where practice targets come from. The default is the posterior: with
    /// the paper's prior a `cells` searcher can shuttle between two cells at
    /// the prior's mode for ever (see README, "Where it departs from the paper").
    pub belief: Belief,
    /// MCTS loops per real move (used when `decision_ms` is `None`).
    pub loops: u32,
    /// A decision-time budget in milliseconds instead of a loop count.
    pub decision_ms: Option<f64>,
    /// UCT exploration constant.
    pub c: f64,
    /// Lévy exponent μ in (1, 3].
    pub mu: f64,
    /// Greedy rollout noise ε in [0, 1].
    pub epsilon: f64,
    /// How the real move is chosen.
    pub final_rule: FinalRule,
    /// Rollout step cap (truncated rollouts are counted).
    pub rollout_cap: u32,
    /// Episode step cap (a capped episode is a failure).
    pub step_cap: u32,
    /// `cells`: clear the statistics table before each real move.
    pub reset_each_move: bool,
    /// `tree`: arena cap in nodes.
    pub tree_nodes: u32,
    /// How many recent rollout traces to keep for drawing (0 = none).
    pub keep_traces: u32,
}

/// Limits for the numeric fields.
pub mod limits {
    /// Loops per move.
    pub const LOOPS: (u32, u32) = (1, 10_000_000);
    /// Decision time, ms.
    pub const DECISION_MS: (f64, f64) = (0.001, 600_000.0);
    /// Exploration constant.
    pub const C: (f64, f64) = (0.0, 1e6);
    /// Rollout cap.
    pub const ROLLOUT_CAP: (u32, u32) = (1, 1_000_000_000);
    /// Step cap.
    pub const STEP_CAP: (u32, u32) = (1, 100_000_000);
    /// Kept traces.
    pub const KEEP_TRACES: (u32, u32) = (0, 64);
}

impl Default for Config {
    fn default() -> Config {
        Config {
            n: 40,
            prior: PriorSpec::Gaussian { sigma: 5.0 },
            rv: 1.0,
            start: [1, 1],
            target: None,
            known: false,
            searcher: SearcherKind::Mcts,
            variant: Variant::Cells,
            rollout: PolicyKind::Rw,
            belief: Belief::Posterior,
            loops: 100,
            decision_ms: None,
            c: std::f64::consts::SQRT_2,
            mu: 2.0,
            epsilon: 0.2,
            final_rule: FinalRule::Visits,
            rollout_cap: 10_000,
            step_cap: 100_000,
            reset_each_move: false,
            tree_nodes: DEFAULT_MAX_NODES,
            keep_traces: 0,
        }
    }
}

/// A configuration value outside its allowed range.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigError {
    /// The field (CLI flag / URL parameter name without dashes).
    pub field: &'static str,
    /// What was given.
    pub value: String,
    /// The allowed range or set.
    pub allowed: String,
}

impl ConfigError {
    /// An error for `field` with the offending `value` and the `allowed` range.
    pub fn new(
        field: &'static str,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> ConfigError {
        ConfigError {
            field,
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} must be {}, got {}",
            self.field, self.allowed, self.value
        )
    }
}

impl std::error::Error for ConfigError {}

fn check_u32(field: &'static str, v: u32, (lo, hi): (u32, u32)) -> Result<(), ConfigError> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(ConfigError::new(
            field,
            v,
            format!("an integer in {lo}..={hi}"),
        ))
    }
}

fn check_f64(
    field: &'static str,
    v: f64,
    (lo, hi): (f64, f64),
    allowed: &str,
) -> Result<(), ConfigError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(ConfigError::new(field, v, allowed))
    }
}

impl Config {
    /// Checks every field against its range.
    ///
    /// # Errors
    /// The first [`ConfigError`] found, naming the field and its allowed range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_u32("n", self.n, (MIN_N, MAX_N))?;
        let n = self.n;
        check_f64(
            "rv",
            self.rv,
            (0.0, 2.0 * MAX_N as f64),
            "a number in [0, 2048]",
        )?;
        for (name, cell) in [("start", Some(self.start)), ("target", self.target)] {
            if let Some([x, y]) = cell {
                if !(1..=n).contains(&x) || !(1..=n).contains(&y) {
                    return Err(ConfigError::new(
                        name,
                        format!("{x},{y}"),
                        format!("x,y with each in 1..={n}"),
                    ));
                }
            }
        }
        match &self.prior {
            PriorSpec::Gaussian { sigma } if sigma.is_nan() || *sigma < 0.0 => {
                return Err(ConfigError::new(
                    "sigma",
                    sigma,
                    "a number >= 0 (inf means uniform)",
                ));
            }
            PriorSpec::Delta { cell: Some(c) } if *c >= n * n => {
                return Err(ConfigError::new(
                    "prior",
                    c,
                    format!("a delta cell index in 0..{}", n * n),
                ));
            }
            PriorSpec::Weights { weights } => {
                let want = (n * n) as usize;
                if weights.len() != want {
                    return Err(ConfigError::new(
                        "prior",
                        format!("{} weights", weights.len()),
                        format!("{want} weights (n*n)"),
                    ));
                }
                if let Some((i, w)) = weights
                    .iter()
                    .enumerate()
                    .find(|(_, w)| !w.is_finite() || **w < 0.0)
                {
                    return Err(ConfigError::new(
                        "prior",
                        format!("weight {i} = {w}"),
                        "finite weights >= 0",
                    ));
                }
                if weights.iter().sum::<f64>() <= 0.0 {
                    return Err(ConfigError::new(
                        "prior",
                        "all-zero weights",
                        "weights with a positive sum",
                    ));
                }
            }
            _ => {}
        }
        check_u32("loops", self.loops, limits::LOOPS)?;
        if let Some(ms) = self.decision_ms {
            check_f64(
                "ms",
                ms,
                limits::DECISION_MS,
                "a number of milliseconds in [0.001, 600000]",
            )?;
        }
        check_f64("c", self.c, limits::C, "a number in [0, 1000000]")?;
        if !(self.mu > 1.0 && self.mu <= 3.0) {
            return Err(ConfigError::new("mu", self.mu, "a number in (1, 3]"));
        }
        check_f64("epsilon", self.epsilon, (0.0, 1.0), "a number in [0, 1]")?;
        check_u32("rollout-cap", self.rollout_cap, limits::ROLLOUT_CAP)?;
        check_u32("step-cap", self.step_cap, limits::STEP_CAP)?;
        check_u32(
            "tree-nodes",
            self.tree_nodes,
            (MIN_MAX_NODES, MAX_MAX_NODES),
        )?;
        check_u32("keep-traces", self.keep_traces, limits::KEEP_TRACES)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_errors_name_the_field() {
        Config::default().validate().unwrap();
        let e = Config {
            n: 0,
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.to_string(), "n must be an integer in 3..=1024, got 0");
        let e = Config {
            mu: 1.0,
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "mu");
        let e = Config {
            start: [41, 1],
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "start");
        let e = Config {
            prior: PriorSpec::Gaussian { sigma: f64::NAN },
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "sigma");
        let e = Config {
            loops: 0,
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "loops");
        let e = Config {
            rv: -1.0,
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "rv");
    }
}
