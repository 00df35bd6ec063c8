//! The configuration of a run, and the table that describes it.
//!
//! [`PARAMS`] is the only place that names a parameter and gives its
//! default, range, choices and help text. [`Config::default`] is built from
//! it, [`Config::validate`] checks against it, and text values (CLI flags,
//! URL query values) are parsed and written by it. The CLI builds its flags
//! from it, the facade exports it as [`schema`] for the page's URL parser and
//! controls, and experiment sweeps name parameters by its keys.

pub mod preset;

use crate::config::preset::Preset;
use crate::game::belief::Belief;
use crate::game::lattice::{Torus, MAX_N, MIN_N};
use crate::game::prior::{self, PriorKind, PriorSpec};
use crate::searchers::mcts::cells::DEFAULT_DECAY;
use crate::searchers::mcts::pomcp::{Scale, DEFAULT_POMCP_DEPTH, DEFAULT_POMCP_PLAN};
use crate::searchers::mcts::tree::{DEFAULT_MAX_NODES, MAX_MAX_NODES, MIN_MAX_NODES};
use crate::searchers::mcts::{FinalRule, Variant};
use crate::searchers::{self, Base, PolicyKind, SearcherId, SweepPattern};
use std::borrow::Cow;
use std::fmt;

/// Everything that defines a run: with it, a run is a pure function of the
/// config on every platform (the seed is part of it).
///
/// Field names are the parameter keys of [`PARAMS`] (`final_rule` is
/// spelled `final` outside Rust).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Lattice side N.
    pub n: u32,
    /// Which prior places the target.
    pub prior: PriorKind,
    /// Gaussian standard deviation (0 = delta, inf = uniform).
    #[serde(with = "serde_sigma")]
    pub sigma: f64,
    /// The painted prior, [`prior::encode_paint`] text (prior `paint`).
    pub paint: String,
    /// Detection radius r_v (torus Euclidean distance).
    pub rv: f64,
    /// Start cell, 1-based `[x, y]`.
    pub start: [u32; 2],
    /// A fixed target cell, 1-based `[x, y]` (a delta prior there).
    pub target: Option<[u32; 2]>,
    /// Place the target by the prior but plan with a delta prior on it.
    pub known: bool,
    /// Who searches (a name in the searcher registry).
    pub searcher: SearcherId,
    /// MCTS variant.
    pub variant: Variant,
    /// MCTS rollout (default) policy.
    pub rollout: PolicyKind,
    /// Where practice targets come from. The default is the posterior: with
    /// the paper's prior a `cells` searcher can shuttle between two cells at
    /// the prior's mode for ever (see README, "Where it departs from the paper").
    pub belief: Belief,
    /// MCTS loops per real move (when `ms` is `None`).
    pub loops: u32,
    /// A decision-time budget per real move in milliseconds instead of loops.
    pub ms: Option<f64>,
    /// UCT exploration constant.
    pub c: f64,
    /// Lévy exponent μ in (1, 3].
    pub mu: f64,
    /// Greedy rollout noise ε in [0, 1].
    pub epsilon: f64,
    /// How the real move is chosen.
    #[serde(rename = "final")]
    pub final_rule: FinalRule,
    /// Rollout step cap (truncated rollouts are counted).
    pub rollout_cap: u32,
    /// Episode step cap (a capped episode is a failure).
    pub step_cap: u32,
    /// `cells`: clear the statistics table before each real move.
    pub reset_each_move: bool,
    /// `cells`: the factor the table's counts are multiplied by whenever the
    /// belief changes (1 keeps them for ever, as the paper does).
    pub decay: f64,
    /// MCTS: after this many real moves in a row that
    /// search no new cell, head for the best unsearched cell (0 = never).
    pub escape: u32,
    /// `tree`: arena cap in nodes.
    pub tree_nodes: u32,
    /// `pomcp`: how returns are scaled for UCT.
    pub pomcp_scale: Scale,
    /// `pomcp`: the posterior mass left below which a return stops counting
    /// expected time exactly and samples the practice target's.
    pub pomcp_exact: f64,
    /// pomcp: rollout steps counted before the reference tail stands in.
    pub pomcp_depth: u32,
    /// pomcp: the horizon depth of its first plan (0: no plan).
    pub pomcp_plan: u32,
    /// How many recent rollout traces to keep for drawing (0 = none).
    pub keep_traces: u32,
    /// Planners: the receding horizon's depth h.
    pub horizon: u32,
    /// Rollout improvement: the base policy it completes searches with.
    pub base: Base,
    /// The beam planner: partial paths kept at each depth.
    pub beam_width: u32,
    /// The beam planner: moves planned by beam search.
    pub beam_depth: u32,
    /// The sweep's pattern.
    pub sweep_pattern: SweepPattern,
    /// The seed: trial i of a batch draws from streams derived from (seed, i).
    #[serde(with = "serde_seed")]
    pub seed: u64,
}

/// A configuration value outside its allowed range.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigError {
    /// The parameter key.
    pub field: &'static str,
    /// What was given, as text.
    pub value: String,
    /// The allowed range or set, e.g. "an integer in 3..=1024".
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

/// A parameter's value, as [`Kind::parse`] reads it from text.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// An unsigned integer.
    Int(u64),
    /// A number.
    Float(f64),
    /// A number, or none (written as 0).
    OptFloat(Option<f64>),
    /// One of a set of names.
    Name(Cow<'static, str>),
    /// On or off.
    Bool(bool),
    /// A 1-based cell `[x, y]`.
    Cell([u32; 2]),
    /// A 1-based cell, or none (written as an empty value).
    OptCell(Option<[u32; 2]>),
    /// Free text (a painted prior).
    Text(Cow<'static, str>),
}

impl Value {
    /// The value as text, the form the CLI and the URL read back.
    pub fn text(&self) -> String {
        match self {
            Value::Int(v) => v.to_string(),
            Value::Float(v) => fmt_float(*v),
            Value::OptFloat(v) => v.map_or_else(|| "0".into(), fmt_float),
            Value::Name(s) | Value::Text(s) => s.to_string(),
            Value::Bool(b) => if *b { "1" } else { "0" }.into(),
            Value::Cell([x, y]) => format!("{x},{y}"),
            Value::OptCell(c) => c.map_or_else(String::new, |[x, y]| format!("{x},{y}")),
        }
    }
}

/// Shortest text that reads back as the same `f64` ("inf" for infinity).
fn fmt_float(v: f64) -> String {
    if v == f64::INFINITY {
        "inf".into()
    } else {
        v.to_string()
    }
}

/// What values a parameter takes.
#[derive(Clone, Copy)]
pub enum Kind {
    /// An integer in `min..=max`.
    Int {
        /// Smallest allowed.
        min: u64,
        /// Largest allowed.
        max: u64,
    },
    /// A number in `[min, max]` (`(min, max]` when `min_open`); `max` may be inf.
    Float {
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
        /// The lower bound itself is excluded.
        min_open: bool,
    },
    /// 0 (none), or a number in `[min, max]`.
    OptFloat {
        /// Smallest allowed other than 0.
        min: f64,
        /// Largest allowed.
        max: f64,
    },
    /// One of the names the function lists.
    Choice(fn() -> Vec<&'static str>),
    /// On or off: 1/0, true/false, yes/no, on/off.
    Bool,
    /// A 1-based cell "x,y", each in 1..=n.
    Cell,
    /// A cell "x,y", or empty for none.
    OptCell,
    /// A painted prior ([`prior::encode_paint`] text; checked against n).
    Paint,
}

impl Kind {
    /// The kind's name in the exported schema.
    pub fn name(&self) -> &'static str {
        match self {
            Kind::Int { .. } => "int",
            Kind::Float { .. } => "float",
            Kind::OptFloat { .. } => "optfloat",
            Kind::Choice(_) => "choice",
            Kind::Bool => "bool",
            Kind::Cell => "cell",
            Kind::OptCell => "optcell",
            Kind::Paint => "paint",
        }
    }

    /// The allowed values, as an error message states them.
    pub fn allowed(&self) -> String {
        match *self {
            Kind::Int { min, max } => format!("an integer in {min}..={max}"),
            Kind::Float { min, max, .. } if max.is_infinite() => {
                format!("a number >= {min} (inf allowed)")
            }
            Kind::Float {
                min,
                max,
                min_open: true,
            } => format!("a number in ({min}, {max}]"),
            Kind::Float { min, max, .. } => format!("a number in [{min}, {max}]"),
            Kind::OptFloat { min, max } => format!("a number in [{min}, {max}], or 0 for none"),
            Kind::Choice(names) => format!("one of {}", names().join(", ")),
            Kind::Bool => "one of 1, 0, true, false, yes, no, on, off".into(),
            Kind::Cell => "x,y with each in 1..=n".into(),
            Kind::OptCell => "x,y with each in 1..=n, or empty for none".into(),
            Kind::Paint => "a painted prior (run-length encoded levels 0-15, n*n cells)".into(),
        }
    }

    /// Reads a text value and checks it against the range.
    ///
    /// # Errors
    /// A [`ConfigError`] for `key` naming the text and the allowed range.
    pub fn parse(&self, key: &'static str, raw: &str) -> Result<Value, ConfigError> {
        let s = raw.trim();
        let bad = || ConfigError::new(key, shown(raw), self.allowed());
        let v = match self {
            Kind::Int { .. } => Value::Int(s.parse().map_err(|_| bad())?),
            Kind::Float { .. } => Value::Float(parse_float(s).ok_or_else(bad)?),
            Kind::OptFloat { .. } => Value::OptFloat(match parse_float(s).ok_or_else(bad)? {
                0.0 => None,
                v => Some(v),
            }),
            Kind::Choice(names) => Value::Name(Cow::Borrowed(
                names().into_iter().find(|&n| n == s).ok_or_else(bad)?,
            )),
            Kind::Bool => Value::Bool(match s {
                "1" | "true" | "yes" | "on" => true,
                "0" | "false" | "no" | "off" => false,
                _ => return Err(bad()),
            }),
            Kind::Cell => Value::Cell(parse_cell(s).ok_or_else(bad)?),
            Kind::OptCell => Value::OptCell(match s {
                "" | "none" => None,
                _ => Some(parse_cell(s).ok_or_else(bad)?),
            }),
            Kind::Paint => {
                let ok = s.len() % 3 == 0
                    && s.bytes()
                        .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_');
                if !ok {
                    return Err(bad());
                }
                Value::Text(Cow::Owned(s.to_string()))
            }
        };
        self.check(key, &v)?;
        Ok(v)
    }

    /// Checks a value against the range (cells and paint against n are
    /// checked by [`Config::validate`], which knows n).
    ///
    /// # Errors
    /// A [`ConfigError`] for `key` naming the value and the allowed range.
    pub fn check(&self, key: &'static str, v: &Value) -> Result<(), ConfigError> {
        let ok = match (*self, v) {
            (Kind::Int { min, max }, Value::Int(x)) => (min..=max).contains(x),
            (Kind::Float { min, max, min_open }, &Value::Float(x)) => {
                !x.is_nan() && (if min_open { x > min } else { x >= min }) && x <= max
            }
            (Kind::OptFloat { min, max }, &Value::OptFloat(x)) => {
                x.is_none_or(|x| x.is_finite() && x >= min && x <= max)
            }
            (Kind::Choice(names), Value::Name(s)) => names().contains(&s.as_ref()),
            (Kind::Bool, Value::Bool(_)) => true,
            // Cells are checked against n by Config::validate.
            (Kind::Cell, Value::Cell(_)) | (Kind::OptCell, Value::OptCell(_)) => true,
            (Kind::Paint, Value::Text(_)) => true,
            _ => false,
        };
        if ok {
            Ok(())
        } else {
            Err(ConfigError::new(key, v.text(), self.allowed()))
        }
    }
}

/// Shortens a user-supplied value for an error message.
fn shown(raw: &str) -> String {
    if raw.chars().count() > 40 {
        format!("{}…", raw.chars().take(40).collect::<String>())
    } else {
        raw.to_string()
    }
}

fn parse_float(s: &str) -> Option<f64> {
    // Rust's parser also takes "infinity" and "NaN"; NaN fails every range.
    s.parse::<f64>().ok()
}

fn parse_cell(s: &str) -> Option<[u32; 2]> {
    let (x, y) = s.split_once(',')?;
    Some([x.trim().parse().ok()?, y.trim().parse().ok()?])
}

/// When a parameter affects a run.
#[derive(Clone, Copy)]
pub enum Applies {
    /// Always.
    Always,
    /// When the searcher reads it (the registry entry's `uses`).
    Searcher,
    /// When the predicate holds; the text says when, for messages.
    When(fn(&Config) -> bool, &'static str),
}

/// One parameter: its key, kind, default, help text and field access.
pub struct Param {
    /// The key: the URL parameter, the JSON field, and (with `-` for `_`) the CLI flag.
    pub key: &'static str,
    /// What values it takes.
    pub kind: Kind,
    /// The default value.
    pub default: Value,
    /// One line of help.
    pub help: &'static str,
    /// When it matters.
    pub applies: Applies,
    /// Other CLI flag names accepted (without dashes).
    pub aliases: &'static [&'static str],
    /// Reads the field.
    pub get: fn(&Config) -> Value,
    /// Writes the field (the value has this parameter's kind).
    pub set: fn(&mut Config, &Value),
}

impl Param {
    /// The CLI flag without its dashes (`step_cap` → `step-cap`).
    pub fn flag(&self) -> String {
        self.key.replace('_', "-")
    }

    /// An integer parameter's value read from `raw`, or its default when
    /// `raw` is `None`.
    ///
    /// # Errors
    /// A [`ConfigError`] for text out of range, or for a parameter that is
    /// not an integer.
    pub fn int_value(&self, raw: Option<&str>) -> Result<u64, ConfigError> {
        let v = match raw {
            Some(raw) => self.kind.parse(self.key, raw)?,
            None => self.default.clone(),
        };
        match v {
            Value::Int(x) => Ok(x),
            other => Err(ConfigError::new(
                self.key,
                other.text(),
                self.kind.allowed(),
            )),
        }
    }

    /// True when this parameter affects a run of `cfg`.
    pub fn applies_to(&self, cfg: &Config) -> bool {
        match self.applies {
            Applies::Always => true,
            Applies::Searcher => (cfg.searcher.info().uses)(cfg, self.key),
            Applies::When(f, _) => f(cfg),
        }
    }

    /// Why this parameter does not affect a run of `cfg`.
    pub fn not_applying(&self, cfg: &Config) -> String {
        match self.applies {
            Applies::When(_, when) => format!("it applies {when}"),
            _ => format!("searcher {} does not read it here", cfg.searcher),
        }
    }
}

fn int(v: &Value) -> u64 {
    match v {
        Value::Int(x) => *x,
        _ => 0,
    }
}

fn u32_of(v: &Value) -> u32 {
    int(v).min(u32::MAX as u64) as u32
}

fn float(v: &Value) -> f64 {
    match v {
        Value::Float(x) => *x,
        _ => f64::NAN,
    }
}

fn name(v: &Value) -> &str {
    match v {
        Value::Name(s) => s,
        _ => "",
    }
}

fn flag(v: &Value) -> bool {
    matches!(v, Value::Bool(true))
}

fn no_target(c: &Config) -> bool {
    c.target.is_none()
}

/// Every parameter, in the order the CLI's help and the URL list them.
pub static PARAMS: &[Param] = &[
    Param {
        key: "n",
        kind: Kind::Int {
            min: MIN_N as u64,
            max: MAX_N as u64,
        },
        default: Value::Int(40),
        help: "lattice side N (an N×N torus)",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::Int(c.n as u64),
        set: |c, v| c.n = u32_of(v),
    },
    Param {
        key: "prior",
        kind: Kind::Choice(|| PriorKind::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("gaussian")),
        help: "target prior: gaussian (the paper's rounded, wrapped normal), delta (the centre), uniform, or paint (a painted grid)",
        applies: Applies::When(no_target, "without a fixed target"),
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.prior.name())),
        set: |c, v| c.prior = PriorKind::parse(name(v)).unwrap_or(c.prior),
    },
    Param {
        key: "sigma",
        kind: Kind::Float {
            min: 0.0,
            max: f64::INFINITY,
            min_open: false,
        },
        default: Value::Float(5.0),
        help: "Gaussian standard deviation σ (0 = a delta at the centre, inf = uniform)",
        applies: Applies::When(
            |c| c.prior == PriorKind::Gaussian && no_target(c),
            "with prior gaussian and no fixed target",
        ),
        aliases: &[],
        get: |c| Value::Float(c.sigma),
        set: |c, v| c.sigma = float(v),
    },
    Param {
        key: "paint",
        kind: Kind::Paint,
        default: Value::Text(Cow::Borrowed("")),
        help: "painted prior: run-length encoded weights 0–15 per cell, as the page writes it",
        applies: Applies::When(
            |c| c.prior == PriorKind::Paint && no_target(c),
            "with prior paint and no fixed target",
        ),
        aliases: &[],
        get: |c| Value::Text(Cow::Owned(c.paint.clone())),
        set: |c, v| {
            if let Value::Text(s) = v {
                c.paint = s.to_string();
            }
        },
    },
    Param {
        key: "rv",
        kind: Kind::Float {
            min: 0.0,
            max: 2.0 * MAX_N as f64,
            min_open: false,
        },
        default: Value::Float(1.0),
        help: "detection radius r_v (torus Euclidean distance; 1 = the cell and its four neighbours)",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::Float(c.rv),
        set: |c, v| c.rv = float(v),
    },
    Param {
        key: "start",
        kind: Kind::Cell,
        default: Value::Cell([1, 1]),
        help: "start cell x,y (1-based)",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::Cell(c.start),
        set: |c, v| {
            if let Value::Cell(x) = v {
                c.start = *x;
            }
        },
    },
    Param {
        key: "target",
        kind: Kind::OptCell,
        default: Value::OptCell(None),
        help: "a fixed target cell x,y (1-based) instead of one drawn from the prior",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::OptCell(c.target),
        set: |c, v| {
            if let Value::OptCell(x) = v {
                c.target = *x;
            }
        },
    },
    Param {
        key: "known",
        kind: Kind::Bool,
        default: Value::Bool(false),
        help: "draw the target from the prior, then plan with a delta prior on it",
        applies: Applies::When(no_target, "without a fixed target"),
        aliases: &[],
        get: |c| Value::Bool(c.known),
        set: |c, v| c.known = flag(v),
    },
    Param {
        key: "searcher",
        kind: Kind::Choice(searchers::names),
        default: Value::Name(Cow::Borrowed("mcts")),
        help: "who searches: MCTS, or a walk that moves without deliberating",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.searcher.name())),
        set: |c, v| c.searcher = SearcherId::parse(name(v)).unwrap_or(c.searcher),
    },
    Param {
        key: "variant",
        kind: Kind::Choice(|| Variant::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("cells")),
        help: "MCTS statistics: cells (the paper's per-cell table), tree (a search tree with subtree reuse), code (the authors' MATLAB statistics, for the paper-code preset) or pomcp (a belief MCTS on the posterior, beyond the paper)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.variant.name())),
        set: |c, v| c.variant = Variant::parse(name(v)).unwrap_or(c.variant),
    },
    Param {
        key: "rollout",
        kind: Kind::Choice(|| PolicyKind::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("rw")),
        help: "MCTS rollout policy: rw, levy, nsarw or greedy (toward the practice target)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.rollout.name())),
        set: |c, v| c.rollout = PolicyKind::parse(name(v)).unwrap_or(c.rollout),
    },
    Param {
        key: "belief",
        kind: Kind::Choice(|| Belief::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("posterior")),
        help: "where practice targets come from: prior (the paper) or posterior (the prior with searched cells removed)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.belief.name())),
        set: |c, v| c.belief = Belief::parse(name(v)).unwrap_or(c.belief),
    },
    Param {
        key: "loops",
        kind: Kind::Int {
            min: 1,
            max: 10_000_000,
        },
        default: Value::Int(100),
        help: "MCTS loops per real move (when ms is 0)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.loops as u64),
        set: |c, v| c.loops = u32_of(v),
    },
    Param {
        key: "ms",
        kind: Kind::OptFloat {
            min: 0.001,
            max: 600_000.0,
        },
        default: Value::OptFloat(None),
        help: "MCTS decision time per real move in milliseconds instead of loops (0 = use loops; timed runs depend on the machine)",
        applies: Applies::Searcher,
        aliases: &["decision-ms"],
        get: |c| Value::OptFloat(c.ms),
        set: |c, v| {
            if let Value::OptFloat(x) = v {
                c.ms = *x;
            }
        },
    },
    Param {
        key: "c",
        kind: Kind::Float {
            min: 0.0,
            max: 1e6,
            min_open: false,
        },
        default: Value::Float(std::f64::consts::SQRT_2),
        help: "UCT exploration constant c",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Float(c.c),
        set: |c, v| c.c = float(v),
    },
    Param {
        key: "mu",
        kind: Kind::Float {
            min: 1.0,
            max: 3.0,
            min_open: true,
        },
        default: Value::Float(2.0),
        help: "Lévy exponent μ: flight lengths follow P(l) ∝ l^−μ",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Float(c.mu),
        set: |c, v| c.mu = float(v),
    },
    Param {
        key: "epsilon",
        kind: Kind::Float {
            min: 0.0,
            max: 1.0,
            min_open: false,
        },
        default: Value::Float(0.2),
        help: "greedy rollout noise ε: the chance of a random move",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Float(c.epsilon),
        set: |c, v| c.epsilon = float(v),
    },
    Param {
        key: "final",
        kind: Kind::Choice(|| FinalRule::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("visits")),
        help: "how the real move is chosen: visits (picked most this decision), mean (best mean reward) or uct (best UCT value)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.final_rule.name())),
        set: |c, v| c.final_rule = FinalRule::parse(name(v)).unwrap_or(c.final_rule),
    },
    Param {
        key: "rollout_cap",
        kind: Kind::Int {
            min: 1,
            max: 1_000_000_000,
        },
        default: Value::Int(10_000),
        help: "rollout step cap (a truncated rollout earns 0 and is counted)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.rollout_cap as u64),
        set: |c, v| c.rollout_cap = u32_of(v),
    },
    Param {
        key: "step_cap",
        kind: Kind::Int {
            min: 1,
            max: 100_000_000,
        },
        default: Value::Int(100_000),
        help: "episode step cap (a capped episode is a failure, counted as such)",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::Int(c.step_cap as u64),
        set: |c, v| c.step_cap = u32_of(v),
    },
    Param {
        key: "reset_each_move",
        kind: Kind::Bool,
        default: Value::Bool(false),
        help: "cells: clear the statistics table before each real move",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Bool(c.reset_each_move),
        set: |c, v| c.reset_each_move = flag(v),
    },
    Param {
        key: "decay",
        kind: Kind::Float {
            min: 0.0,
            max: 1.0,
            min_open: false,
        },
        default: Value::Float(DEFAULT_DECAY),
        help: "cells: when a move searches new cells, each table count is multiplied by this (rounded down, the mean kept), so stale statistics fade; 1 keeps them for ever (the paper), 0 clears them",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Float(c.decay),
        set: |c, v| c.decay = float(v),
    },
    Param {
        key: "escape",
        kind: Kind::Int {
            min: 0,
            max: 1_000_000,
        },
        default: Value::Int(crate::searchers::mcts::DEFAULT_ESCAPE as u64),
        help: "MCTS: after this many real moves in a row that search no new cell, walk straight to the cell with the most unsearched mass per step of distance, then search again (not while the belief MCTS follows its plan, which cannot trap it); 0 never (the paper)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.escape as u64),
        set: |c, v| c.escape = int(v) as u32,
    },
    Param {
        key: "tree_nodes",
        kind: Kind::Int {
            min: MIN_MAX_NODES as u64,
            max: MAX_MAX_NODES as u64,
        },
        default: Value::Int(DEFAULT_MAX_NODES as u64),
        help: "tree: arena cap in nodes (32 bytes each, twice)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.tree_nodes as u64),
        set: |c, v| c.tree_nodes = u32_of(v),
    },
    Param {
        key: "pomcp_scale",
        kind: Kind::Choice(|| Scale::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("best")),
        help: "pomcp: a child's value for UCT and for the real move: best (the best return found through it, scaled by the spread of returns this decision), range (its mean return, scaled the same way) or left (its mean return as a fraction of the expected steps left)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.pomcp_scale.name())),
        set: |c, v| c.pomcp_scale = Scale::parse(name(v)).unwrap_or(c.pomcp_scale),
    },
    Param {
        key: "pomcp_exact",
        kind: Kind::Float {
            min: 0.0,
            max: 1.0,
            min_open: false,
        },
        default: Value::Float(0.0),
        help: "pomcp: a return counts the expected steps exactly until this share of the posterior is left, then adds the practice target's sampled remaining steps (1 = the sampled return of plain POMCP, 0 = expected steps only)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Float(c.pomcp_exact),
        set: |c, v| c.pomcp_exact = float(v),
    },
    Param {
        key: "pomcp_depth",
        kind: Kind::Int { min: 1, max: 100_000 },
        default: Value::Int(DEFAULT_POMCP_DEPTH as u64),
        help: "pomcp: rollout steps counted exactly; the rest of a return is then estimated from one coverage walk to the end, made at the start of the decision",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.pomcp_depth as u64),
        set: |c, v| c.pomcp_depth = u32_of(v),
    },
    Param {
        key: "pomcp_plan",
        kind: Kind::Int {
            min: 0,
            max: searchers::MAX_HORIZON as u64,
        },
        default: Value::Int(DEFAULT_POMCP_PLAN as u64),
        help: "pomcp: the horizon depth of the plan it starts from (rollouts rejoin the plan, and a move leaves it only for a line checked exactly to be cheaper); 0 = no plan, coverage-walk rollouts",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.pomcp_plan as u64),
        set: |c, v| c.pomcp_plan = u32_of(v),
    },
    Param {
        key: "keep_traces",
        kind: Kind::Int { min: 0, max: 64 },
        default: Value::Int(0),
        help: "how many recent rollout traces to keep for drawing",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.keep_traces as u64),
        set: |c, v| c.keep_traces = u32_of(v),
    },
    Param {
        key: "horizon",
        kind: Kind::Int {
            min: 1,
            max: searchers::MAX_HORIZON as u64,
        },
        default: Value::Int(searchers::DEFAULT_HORIZON as u64),
        help: "planners: the receding horizon's depth h (4·3^(h−1) move sequences, about 2·3^h simulated moves per decision, so at most 9)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.horizon as u64),
        set: |c, v| c.horizon = u32_of(v),
    },
    Param {
        key: "base",
        kind: Kind::Choice(|| Base::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("cover")),
        help: "rollout improvement's base policy: cover (greedy coverage, the cheapest), sweep (the lawnmower, covered stretches skipped), horizon (depth horizon; slow), or best (all three; slow)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.base.name())),
        set: |c, v| c.base = Base::parse(name(v)).unwrap_or(c.base),
    },
    Param {
        key: "beam_width",
        kind: Kind::Int {
            min: 1,
            max: searchers::MAX_BEAM as u64,
        },
        default: Value::Int(searchers::DEFAULT_BEAM_WIDTH as u64),
        help: "beam planner: partial paths kept at each depth (at most 2 ending on one cell)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.beam_width as u64),
        set: |c, v| c.beam_width = u32_of(v),
    },
    Param {
        key: "beam_depth",
        kind: Kind::Int {
            min: 1,
            max: searchers::MAX_BEAM as u64,
        },
        default: Value::Int(searchers::DEFAULT_BEAM_DEPTH as u64),
        help: "beam planner: moves planned by beam search before the horizon rule finishes the path",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Int(c.beam_depth as u64),
        set: |c, v| c.beam_depth = u32_of(v),
    },
    Param {
        key: "sweep_pattern",
        kind: Kind::Choice(|| SweepPattern::NAMES.to_vec()),
        default: Value::Name(Cow::Borrowed("lawnmower")),
        help: "the sweep's pattern: lawnmower (passes alternately right and left) or helix (always right)",
        applies: Applies::Searcher,
        aliases: &[],
        get: |c| Value::Name(Cow::Borrowed(c.sweep_pattern.name())),
        set: |c, v| c.sweep_pattern = SweepPattern::parse(name(v)).unwrap_or(c.sweep_pattern),
    },
    Param {
        key: "seed",
        kind: Kind::Int {
            min: 0,
            max: u64::MAX,
        },
        default: Value::Int(1),
        help: "seed: a run is a pure function of the config and the seed",
        applies: Applies::Always,
        aliases: &[],
        get: |c| Value::Int(c.seed),
        set: |c, v| c.seed = int(v),
    },
];

/// The parameter named `key`.
pub fn param(key: &str) -> Option<&'static Param> {
    PARAMS.iter().find(|p| p.key == key)
}

impl Default for Config {
    fn default() -> Config {
        // Placeholders only: every field is then set from its PARAMS default
        // (a test checks that every field has a parameter).
        let mut c = Config {
            n: 0,
            prior: PriorKind::Gaussian,
            sigma: 0.0,
            paint: String::new(),
            rv: 0.0,
            start: [0, 0],
            target: None,
            known: false,
            searcher: SearcherId::parse("mcts").expect("mcts is registered"),
            variant: Variant::Cells,
            rollout: PolicyKind::Rw,
            belief: Belief::Prior,
            loops: 0,
            ms: None,
            c: 0.0,
            mu: 0.0,
            epsilon: 0.0,
            final_rule: FinalRule::Visits,
            rollout_cap: 0,
            step_cap: 0,
            reset_each_move: false,
            decay: 1.0,
            escape: 0,
            tree_nodes: 0,
            pomcp_scale: Scale::Best,
            pomcp_exact: 0.0,
            pomcp_depth: 0,
            pomcp_plan: 0,
            keep_traces: 0,
            horizon: 0,
            base: Base::Cover,
            beam_width: 0,
            beam_depth: 0,
            sweep_pattern: SweepPattern::Lawnmower,
            seed: 0,
        };
        for p in PARAMS {
            (p.set)(&mut c, &p.default);
        }
        c
    }
}

impl Config {
    /// Checks every parameter against its range, the cells against n and a
    /// painted prior against the lattice.
    ///
    /// # Errors
    /// The first [`ConfigError`] found, naming the parameter and its range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        for p in PARAMS {
            p.kind.check(p.key, &(p.get)(self))?;
        }
        let n = self.n;
        for (key, cell) in [("start", Some(self.start)), ("target", self.target)] {
            if let Some([x, y]) = cell {
                if !(1..=n).contains(&x) || !(1..=n).contains(&y) {
                    return Err(ConfigError::new(
                        key,
                        format!("{x},{y}"),
                        format!("x,y with each in 1..={n}"),
                    ));
                }
            }
        }
        if self.prior == PriorKind::Paint && self.target.is_none() {
            // Without a painting the prior is at fault (a URL's fallback
            // then resets the prior, not the empty paint).
            if self.paint.is_empty() {
                return Err(ConfigError::new(
                    "prior",
                    "paint",
                    "gaussian, delta or uniform unless a paint is given",
                ));
            }
            prior::decode_paint(&self.paint, n)
                .map_err(|e| ConfigError::new("paint", e, Kind::Paint.allowed()))?;
        }
        Ok(())
    }

    /// Sets parameter `key` from text, checking its range (not its relation
    /// to other parameters: [`Config::validate`] does that).
    ///
    /// # Errors
    /// A [`ConfigError`] for an unknown key or a value out of range.
    ///
    /// The key [`PRESET`] is not a field: it sets every value of that
    /// preset (`crate::config::preset`), so a URL or a form can name one.
    pub fn set(&mut self, key: &str, raw: &str) -> Result<(), ConfigError> {
        if key == PRESET {
            Preset::from_name(raw)?.apply(self);
            return Ok(());
        }
        let p = param(key).ok_or_else(|| unknown(key))?;
        let v = p.kind.parse(p.key, raw)?;
        (p.set)(self, &v);
        Ok(())
    }

    /// Sets `key` as an editor does: a new n also moves the start and target
    /// inside the lattice and rescales a painted prior.
    ///
    /// # Errors
    /// As [`Config::set`].
    pub fn edit(&mut self, key: &str, raw: &str) -> Result<(), ConfigError> {
        let old_n = self.n;
        self.set(key, raw)?;
        let n = self.n;
        if n != old_n {
            let inside = |[x, y]: [u32; 2]| [x.min(n), y.min(n)];
            self.target = self.target.map(inside);
            self.start = inside(self.start);
            if let Ok(levels) = prior::decode_paint(&self.paint, old_n) {
                self.paint = prior::encode_paint(&prior::resize_paint(&levels, old_n, n));
            }
        }
        Ok(())
    }

    /// Parameter `key` as text.
    ///
    /// # Errors
    /// A [`ConfigError`] for an unknown key.
    pub fn get(&self, key: &str) -> Result<String, ConfigError> {
        let p = param(key).ok_or_else(|| unknown(key))?;
        Ok((p.get)(self).text())
    }

    /// `(key, text)` pairs for a URL: every parameter with `full`, else those
    /// that differ from the default, and the seed always (a link reproduces
    /// the run). Values that do not apply are kept too: switching back to
    /// what reads them restores them.
    pub fn params(&self, full: bool) -> Vec<(&'static str, String)> {
        let d = Config::default();
        PARAMS
            .iter()
            .filter(|p| full || p.key == "seed" || (p.get)(self) != (p.get)(&d))
            .map(|p| (p.key, (p.get)(self).text()))
            .collect()
    }

    /// The keys of the parameters that affect a run of this config.
    pub fn applicable(&self) -> Vec<&'static str> {
        PARAMS
            .iter()
            .filter(|p| p.applies_to(self))
            .map(|p| p.key)
            .collect()
    }

    /// The prior that places the target on `torus`, from `prior`, `sigma`,
    /// `paint` and `target`.
    ///
    /// # Errors
    /// A [`ConfigError`] for `paint` when it does not decode for this n.
    pub fn prior_spec(&self, torus: &Torus) -> Result<PriorSpec, ConfigError> {
        let n = self.n;
        Ok(match (self.target, self.prior) {
            (Some([x, y]), _) => PriorSpec::Delta {
                cell: Some(torus.cell(x as i64 - 1, y as i64 - 1)),
            },
            (None, PriorKind::Gaussian) => PriorSpec::Gaussian { sigma: self.sigma },
            (None, PriorKind::Delta) => PriorSpec::Delta { cell: None },
            (None, PriorKind::Uniform) => PriorSpec::Uniform,
            (None, PriorKind::Paint) => PriorSpec::Weights {
                weights: prior::decode_paint(&self.paint, n)
                    .map_err(|e| ConfigError::new("paint", e, Kind::Paint.allowed()))?
                    .into_iter()
                    .map(f64::from)
                    .collect(),
            },
        })
    }

    /// A short human label of who searches and how, e.g.
    /// "MCTS cells · rw rollouts · L=100".
    pub fn label(&self) -> String {
        let info = self.searcher.info();
        if !info.deliberates {
            return info.label.to_string();
        }
        let budget = self
            .ms
            .map_or_else(|| format!("L={}", self.loops), |ms| format!("{ms} ms"));
        // The belief MCTS rolls out with its own walks: along its plan, or
        // the coverage walk without one.
        let rollout = match self.variant {
            Variant::Pomcp if self.pomcp_plan > 0 => "plan",
            Variant::Pomcp => "coverage",
            _ => self.rollout.name(),
        };
        format!(
            "{} {} · {rollout} rollouts · {budget}",
            info.label, self.variant
        )
    }

    /// A line that describes the prior, e.g. "gaussian sigma=5".
    pub fn prior_label(&self) -> String {
        match (self.target, self.prior) {
            (Some([x, y]), _) => format!("target ({x},{y})"),
            (None, PriorKind::Gaussian) => format!("gaussian sigma={}", fmt_float(self.sigma)),
            (None, k) => k.name().to_string(),
        }
    }
}

#[cfg(test)]
impl Config {
    /// This configuration with each `(name, value)` set as the CLI and URL
    /// would set it, for tests that read best as a list of settings.
    ///
    /// # Panics
    /// If a name is unknown or a value out of its range.
    pub(crate) fn with(mut self, settings: &[(&str, &str)]) -> Config {
        for (k, v) in settings {
            self.set(k, v).unwrap_or_else(|e| panic!("{k} = {v}: {e}"));
        }
        self
    }
}

/// The lattice, sensor, target prior and start cell a configuration describes.
#[derive(Clone, Debug)]
pub struct Game {
    /// The lattice.
    pub torus: Torus,
    /// The sensor of radius r_v.
    pub sensor: crate::game::lattice::Sensor,
    /// The target prior.
    pub prior: prior::TargetPrior,
    /// The start cell.
    pub start: u32,
}

impl Config {
    /// Builds the game this configuration describes: what an episode, the
    /// bound and an experiment's target samples all start from.
    ///
    /// # Errors
    /// A [`ConfigError`] naming the first invalid field.
    pub fn game(&self) -> Result<Game, ConfigError> {
        self.validate()?;
        // Past validation the lattice, the sensor and the prior build:
        // n, r_v, the cells and the paint were checked against their ranges.
        let torus = Torus::new(self.n).expect("n was validated");
        let spec = self.prior_spec(&torus)?;
        let sensor = crate::game::lattice::Sensor::new(&torus, self.rv).expect("rv was validated");
        let prior = prior::TargetPrior::new(&torus, &spec).expect("the prior was validated");
        let start = torus.cell(self.start[0] as i64 - 1, self.start[1] as i64 - 1);
        Ok(Game {
            torus,
            sensor,
            prior,
            start,
        })
    }
}

/// The key that names a preset in [`Config::set`], URLs and `--preset`.
pub const PRESET: &str = "preset";

fn unknown(key: &str) -> ConfigError {
    ConfigError {
        field: "parameter",
        value: shown(key),
        allowed: format!(
            "one of {}",
            PARAMS.iter().map(|p| p.key).collect::<Vec<_>>().join(", ")
        ),
    }
}

/// Parses `(key, text)` pairs into a config, as the URL does: a bad value
/// keeps its default and yields an error, so one typo does not lose the
/// rest. Unknown keys are errors too. After the pairs, the cross-field
/// rules of [`Config::validate`] reset what they reject to the default.
pub fn from_params<'a>(
    pairs: impl IntoIterator<Item = (&'a str, &'a str)>,
) -> (Config, Vec<ConfigError>) {
    let mut cfg = Config::default();
    let mut errors = Vec::new();
    // A preset goes first wherever it appears, so that the other pairs
    // override it as flags after `--preset` do.
    let (presets, fields): (Vec<_>, Vec<_>) =
        pairs.into_iter().partition(|&(key, _)| key == PRESET);
    for (key, raw) in presets.into_iter().chain(fields) {
        if let Err(e) = cfg.set(key, raw) {
            errors.push(e);
        }
    }
    // Each rejected cross-field value falls back to its default; a few
    // rounds settle it (start, target and paint are independent).
    for _ in 0..PARAMS.len() {
        match cfg.validate() {
            Ok(()) => break,
            Err(e) => {
                let p = param(e.field).expect("validate names parameters");
                (p.set)(&mut cfg, &p.default);
                errors.push(e);
            }
        }
    }
    (cfg, errors)
}

/// The schema as data: what the facade exports to the page and the CLI's
/// help lists.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Schema {
    /// Every parameter.
    pub params: Vec<ParamInfo>,
    /// The searcher registry.
    pub searchers: Vec<SearcherSummary>,
    /// Limits of a batch of trials.
    pub trials: ParamInfo,
    /// The named presets.
    pub presets: Vec<PresetInfo>,
    /// The key that sets a preset ([`PRESET`]).
    pub preset_key: &'static str,
}

/// A preset as data.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PresetInfo {
    /// Its name.
    pub name: &'static str,
    /// One line of help.
    pub help: &'static str,
    /// The `(key, text)` values it sets.
    pub edits: &'static [(&'static str, &'static str)],
}

/// One parameter as data.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ParamInfo {
    /// The key (URL parameter, JSON field).
    pub key: &'static str,
    /// The CLI flag, with its dashes.
    pub flag: String,
    /// Other CLI flags accepted.
    pub aliases: Vec<String>,
    /// int, float, optfloat, choice, bool, cell, optcell or paint.
    pub kind: &'static str,
    /// The default, as text.
    pub default: String,
    /// Smallest allowed value, as text (numbers only).
    pub min: Option<String>,
    /// Largest allowed value, as text (numbers only).
    pub max: Option<String>,
    /// The lower bound is excluded.
    pub min_open: bool,
    /// The allowed names (choices only).
    pub choices: Option<Vec<&'static str>>,
    /// The allowed values in words, as error messages give them.
    pub allowed: String,
    /// One line of help.
    pub help: &'static str,
}

/// A searcher registry entry as data.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SearcherSummary {
    /// Its `searcher` value.
    pub name: &'static str,
    /// A short name for people.
    pub label: &'static str,
    /// How it moves, in one sentence.
    pub help: &'static str,
    /// True when it runs MCTS loops before each move.
    pub deliberates: bool,
}

impl ParamInfo {
    fn of(p: &Param) -> ParamInfo {
        let (min, max, min_open) = match p.kind {
            Kind::Int { min, max } => (Some(min.to_string()), Some(max.to_string()), false),
            Kind::Float { min, max, min_open } => {
                (Some(fmt_float(min)), Some(fmt_float(max)), min_open)
            }
            Kind::OptFloat { min, max } => (Some(fmt_float(min)), Some(fmt_float(max)), false),
            _ => (None, None, false),
        };
        ParamInfo {
            key: p.key,
            flag: format!("--{}", p.flag()),
            aliases: p.aliases.iter().map(|a| format!("--{a}")).collect(),
            kind: p.kind.name(),
            default: p.default.text(),
            min,
            max,
            min_open,
            choices: match p.kind {
                Kind::Choice(names) => Some(names()),
                _ => None,
            },
            allowed: p.kind.allowed(),
            help: p.help,
        }
    }
}

/// The number of trials a batch may run.
pub static TRIALS: Param = Param {
    key: "trials",
    kind: Kind::Int {
        min: 1,
        max: 100_000_000,
    },
    default: Value::Int(1000),
    help: "number of trials; trial i depends only on (config, i)",
    applies: Applies::Always,
    aliases: &[],
    get: |_| Value::Int(0),
    set: |_, _| {},
};

/// The whole schema.
pub fn schema() -> Schema {
    Schema {
        params: PARAMS.iter().map(ParamInfo::of).collect(),
        searchers: searchers::REGISTRY
            .iter()
            .map(|s| SearcherSummary {
                name: s.name,
                label: s.label,
                help: s.help,
                deliberates: s.deliberates,
            })
            .collect(),
        trials: ParamInfo::of(&TRIALS),
        presets: Preset::ALL
            .iter()
            .map(|&p| PresetInfo {
                name: p.name(),
                help: p.help(),
                edits: p.edits(),
            })
            .collect(),
        preset_key: PRESET,
    }
}

/// σ as a JSON number, or "inf" (JSON has no infinity).
mod serde_sigma {
    use serde::{de, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if v.is_finite() {
            s.serialize_f64(*v)
        } else {
            s.serialize_str(&super::fmt_float(*v))
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        struct V;
        impl de::Visitor<'_> for V {
            type Value = f64;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number or \"inf\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
                Ok(v)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
                Ok(v as f64)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
                Ok(v as f64)
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<f64, E> {
                super::parse_float(v.trim())
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Str(v), &self))
            }
        }
        d.deserialize_any(V)
    }
}

/// The seed as a decimal string: JSON numbers (and JS numbers) hold only
/// 53 bits, and a seed must never be rounded or wrapped. A number is read
/// too when it is an exact integer in range.
mod serde_seed {
    use serde::{de, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &u64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&v.to_string())
    }

    const ALLOWED: &str = "seed must be an integer in 0..=18446744073709551615";

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
        struct V;
        impl de::Visitor<'_> for V {
            type Value = u64;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an integer in 0..=18446744073709551615, as a string or a number")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<u64, E> {
                Ok(v)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<u64, E> {
                u64::try_from(v).map_err(|_| E::custom(format!("{ALLOWED}, got {v}")))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<u64, E> {
                // Above 2^53 a float no longer names one integer.
                if v.fract() == 0.0 && (0.0..=9_007_199_254_740_992.0).contains(&v) {
                    Ok(v as u64)
                } else {
                    Err(E::custom(format!(
                        "{ALLOWED} (numbers above 2^53 must be strings), got {v}"
                    )))
                }
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<u64, E> {
                v.trim()
                    .parse()
                    .map_err(|_| E::custom(format!("{ALLOWED}, got {v:?}")))
            }
        }
        d.deserialize_any(V)
    }
}

/// Reads a config from a JSON value (the page's config objects), naming the
/// parameter at fault: a missing key keeps its default, an unknown key or a
/// value of the wrong type is an error naming the key and what it allows.
///
/// # Errors
/// A [`ConfigError`] for a value that is not an object, an unknown key, a
/// value of the wrong type, or (after reading) a value out of range.
pub fn from_json(value: serde_json::Value) -> Result<Config, ConfigError> {
    fn shown(v: &serde_json::Value) -> String {
        let text = v.to_string();
        match text.char_indices().nth(60) {
            Some((i, _)) => format!("{}…", &text[..i]),
            None => text,
        }
    }
    let serde_json::Value::Object(map) = &value else {
        return Err(ConfigError::new(
            "config",
            shown(&value),
            "an object of parameter values",
        ));
    };
    for (key, v) in map {
        let Some(p) = PARAMS.iter().find(|p| p.key == key.as_str()) else {
            let keys: Vec<&str> = PARAMS.iter().map(|p| p.key).collect();
            return Err(ConfigError::new(
                "config",
                format!(
                    "the key {:?}",
                    shown(&serde_json::Value::String(key.clone()))
                ),
                format!("an object whose keys are among {}", keys.join(", ")),
            ));
        };
        // Reading the key alone tells a type error from a range error, and
        // which key has it (serde's message does not say).
        let one: serde_json::Map<String, serde_json::Value> =
            std::iter::once((key.clone(), v.clone())).collect();
        if let Err(e) = serde_json::from_value::<Config>(serde_json::Value::Object(one)) {
            return Err(ConfigError::new(
                p.key,
                shown(v),
                format!("{} ({e})", p.kind.allowed()),
            ));
        }
    }
    let cfg: Config = serde_json::from_value(value)
        .map_err(|e| ConfigError::new("config", e, "an object of parameter values"))?;
    cfg.validate()?;
    Ok(cfg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_json_names_the_key_at_fault() {
        let ok = from_json(serde_json::json!({"n": 12, "final": "mean"})).unwrap();
        assert_eq!((ok.n, ok.final_rule), (12, FinalRule::Mean));
        let e = from_json(serde_json::json!({"tree_nodes": "xxx"})).unwrap_err();
        assert_eq!(e.field, "tree_nodes");
        assert!(e.to_string().contains("an integer in"), "{e}");
        let e = from_json(serde_json::json!({"n": {"n": 3}})).unwrap_err();
        assert_eq!(e.field, "n");
        let e = from_json(serde_json::json!({"__proto__": {"polluted": 1}})).unwrap_err();
        assert!(e.to_string().contains("__proto__"), "{e}");
        let e = from_json(serde_json::json!({"n": 2})).unwrap_err();
        assert_eq!((e.field, e.value.as_str()), ("n", "2"));
        assert_eq!(
            from_json(serde_json::json!([1])).unwrap_err().field,
            "config"
        );
    }

    #[test]
    fn default_is_valid_and_every_field_has_a_parameter() {
        let d = Config::default();
        d.validate().unwrap();
        let json = serde_json::to_value(&d).unwrap();
        let fields: Vec<&String> = json.as_object().unwrap().keys().collect();
        let keys: Vec<&str> = PARAMS.iter().map(|p| p.key).collect();
        assert_eq!(fields.len(), keys.len(), "{fields:?} vs {keys:?}");
        for f in fields {
            assert!(keys.contains(&f.as_str()), "field {f} has no parameter");
        }
        for p in PARAMS {
            assert_eq!((p.get)(&d), p.default, "{}", p.key);
            // The default's text reads back as the default.
            assert_eq!(
                p.kind.parse(p.key, &p.default.text()).unwrap(),
                p.default,
                "{}",
                p.key
            );
        }
    }

    #[test]
    fn errors_name_the_field_and_range() {
        let bad = |key: &str, raw: &str| Config::default().set(key, raw).unwrap_err();
        assert_eq!(
            bad("n", "0").to_string(),
            "n must be an integer in 3..=1024, got 0"
        );
        assert_eq!(bad("mu", "1").field, "mu");
        assert_eq!(bad("sigma", "NaN").field, "sigma");
        assert_eq!(bad("sigma", "-1").field, "sigma");
        assert_eq!(bad("loops", "0").field, "loops");
        assert_eq!(bad("rv", "-1").field, "rv");
        assert!(bad("searcher", "astar")
            .allowed
            .starts_with("one of mcts, rw, levy, nsarw"));
        assert_eq!(
            bad("seed", "18446744073709551616").to_string(),
            "seed must be an integer in 0..=18446744073709551615, got 18446744073709551616"
        );
        assert_eq!(bad("nope", "1").field, "parameter");
        let e = Config {
            start: [41, 1],
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "start must be x,y with each in 1..=40, got 41,1"
        );
        let e = Config {
            prior: PriorKind::Paint,
            paint: "AAA".into(),
            ..Config::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "paint");
    }

    #[test]
    fn text_round_trips_and_ranges_are_inclusive() {
        let mut c = Config::default();
        for (k, v) in [
            ("n", "1024"),
            ("sigma", "inf"),
            ("ms", "0.001"),
            ("mu", "3"),
            ("seed", "18446744073709551615"),
            ("target", "3,4"),
            ("known", "true"),
            ("c", "0"),
        ] {
            c.set(k, v).unwrap();
        }
        c.validate().unwrap();
        let back = from_params(c.params(true).iter().map(|(k, v)| (*k, v.as_str())));
        assert_eq!(back, (c.clone(), vec![]));
        assert_eq!(c.get("known").unwrap(), "1");
        assert_eq!(c.get("ms").unwrap(), "0.001");
        c.set("ms", "0").unwrap();
        assert_eq!(c.ms, None);
        // JSON keeps the seed and infinity exact.
        let json = serde_json::to_string(&c).unwrap();
        assert!(json.contains("\"seed\":\"18446744073709551615\""), "{json}");
        assert!(json.contains("\"sigma\":\"inf\""), "{json}");
        assert_eq!(serde_json::from_str::<Config>(&json).unwrap(), c);
        assert!(serde_json::from_str::<Config>(r#"{"seed":-1}"#).is_err());
        assert!(serde_json::from_str::<Config>(r#"{"seed":1e300}"#).is_err());
        assert_eq!(
            serde_json::from_str::<Config>(r#"{"seed":7}"#)
                .unwrap()
                .seed,
            7
        );
    }

    #[test]
    fn url_parsing_keeps_good_values_and_defaults_bad_ones() {
        let (c, errs) = from_params([("n", "10"), ("start", "11,1"), ("loops", "x"), ("c", "2")]);
        assert_eq!(c.n, 10);
        assert_eq!(c.c, 2.0);
        assert_eq!(c.start, [1, 1], "start outside the lattice falls back");
        assert_eq!(c.loops, 100);
        let fields: Vec<_> = errs.iter().map(|e| e.field).collect();
        assert_eq!(fields, ["loops", "start"]);
        // prior=paint without a painting falls back to the default prior.
        let (c, errs) = from_params([("prior", "paint")]);
        assert_eq!((c.prior, errs[0].field), (PriorKind::Gaussian, "prior"));
        // Only differing values are written (applying or not), the seed always.
        assert_eq!(
            Config::default().params(false),
            vec![("seed", "1".to_string())]
        );
        let rw = from_params([("searcher", "rw"), ("c", "3")]).0;
        let pairs = vec![
            ("searcher", "rw".into()),
            ("c", "3".into()),
            ("seed", "1".into()),
        ];
        assert_eq!(rw.params(false), pairs);
    }

    #[test]
    fn edit_moves_cells_and_paint_into_a_new_lattice() {
        let mut c = Config {
            start: [30, 40],
            prior: PriorKind::Paint,
            paint: prior::encode_paint(&[3; 1600]),
            ..Config::default()
        };
        c.validate().unwrap();
        c.edit("n", "20").unwrap();
        assert_eq!(c.start, [20, 20]);
        assert_eq!(prior::decode_paint(&c.paint, 20).unwrap(), vec![3; 400]);
        c.validate().unwrap();
    }

    #[test]
    fn the_mcts_parameters_apply_by_variant_and_rollout() {
        // The CLI refuses a flag that does not apply and the page hides its
        // control, so each of these must apply exactly where the searcher
        // reads it. Columns: reset_each_move, tree_nodes, decay, the four
        // pomcp_ parameters, final, rollout, then mu under a Lévy rollout
        // and epsilon under a greedy one (each false under the other).
        let keys = [
            "reset_each_move",
            "tree_nodes",
            "decay",
            "pomcp_scale",
            "pomcp_exact",
            "pomcp_depth",
            "pomcp_plan",
            "final",
            "rollout",
        ];
        let table = [
            (
                "cells",
                [true, false, true, false, false, false, false, true, true],
                true,
            ),
            (
                "tree",
                [false, true, false, false, false, false, false, true, true],
                true,
            ),
            (
                "code",
                [true, false, false, false, false, false, false, true, true],
                true,
            ),
            (
                "pomcp",
                [false, true, false, true, true, true, true, false, false],
                false,
            ),
        ];
        for (variant, applies, reads_policy) in table {
            for (rollout, mu, epsilon) in [
                ("levy", reads_policy, false),
                ("greedy", false, reads_policy),
                ("rw", false, false),
                ("nsarw", false, false),
            ] {
                let c = Config::default().with(&[("variant", variant), ("rollout", rollout)]);
                let a = c.applicable();
                assert_eq!(keys.map(|k| a.contains(&k)), applies, "{variant} {rollout}");
                assert_eq!(
                    (a.contains(&"mu"), a.contains(&"epsilon")),
                    (mu, epsilon),
                    "{variant} {rollout}"
                );
                // What every variant reads.
                for k in ["variant", "c", "rollout_cap", "escape", "loops"] {
                    assert!(a.contains(&k), "{variant} {rollout} {k}");
                }
            }
            // A time budget replaces the loop count.
            let timed = Config::default().with(&[("variant", variant), ("ms", "5")]);
            assert!(!timed.applicable().contains(&"loops"), "{variant}");
        }
    }

    #[test]
    fn applicability_follows_the_searcher() {
        let mut c = Config::default();
        assert!(c.applicable().contains(&"c"));
        assert!(!c.applicable().contains(&"mu"));
        c.set("rollout", "levy").unwrap();
        assert!(c.applicable().contains(&"mu"));
        c.set("searcher", "rw").unwrap();
        let a = c.applicable();
        assert!(!a.contains(&"c") && !a.contains(&"mu") && !a.contains(&"loops"));
        c.set("searcher", "levy").unwrap();
        assert!(c.applicable().contains(&"mu"));
        c.set("prior", "uniform").unwrap();
        assert!(!c.applicable().contains(&"sigma"));
        // The planners: rollout improvement reads the horizon only through
        // a base that plays the horizon rule.
        let planner_keys = [
            "horizon",
            "base",
            "beam_width",
            "beam_depth",
            "sweep_pattern",
        ];
        let uses = |c: &Config| {
            let a = c.applicable();
            planner_keys.map(|k| a.contains(&k))
        };
        c.set("searcher", "horizon").unwrap();
        assert_eq!(uses(&c), [true, false, false, false, false]);
        c.set("searcher", "beam").unwrap();
        assert_eq!(uses(&c), [true, false, true, true, false]);
        c.set("searcher", "sweep").unwrap();
        assert_eq!(uses(&c), [false, false, false, false, true]);
        c.set("searcher", "improve").unwrap();
        for (base, horizon) in [
            ("cover", false),
            ("sweep", false),
            ("horizon", true),
            ("best", true),
        ] {
            c.set("base", base).unwrap();
            assert_eq!(
                uses(&c),
                [horizon, true, false, false, false],
                "base {base}"
            );
        }
    }
}
