//! The configuration of a run: the game's own parameters as fields, and
//! the values of the searchers' parameters.

use crate::game::lattice::{MAX_N, MIN_N};
use crate::game::prior::PriorKind;
use crate::param::{Param, ParamKind, Settings, Value};
use crate::searchers::registry::{self, SearcherId};
use std::borrow::Cow;

/// Everything that defines a run: with it, a run is a pure function of the
/// config on every platform (the seed is part of it).
///
/// The fields are the game's parameters ([`FIELDS`]); `settings` holds the
/// values of the parameters the searchers declare. Field names are the
/// parameter keys.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// Lattice side N.
    pub n: u32,
    /// Which prior places the target.
    pub prior: PriorKind,
    /// Gaussian standard deviation (0 = delta, inf = uniform).
    pub sigma: f64,
    /// The painted prior, `game::prior::encode_paint` text (prior `paint`).
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
    /// Episode step cap (a capped episode is a failure).
    pub step_cap: u32,
    /// The seed: trial i of a batch draws from streams derived from (seed, i).
    pub seed: u64,
    /// The values of the searchers' own parameters.
    pub settings: Settings,
}

/// When a field applies, and the text that says when (for messages).
pub type Condition = (fn(&Config) -> bool, &'static str);

/// A game parameter: a field of [`Config`], when it applies, and how to
/// read and write it.
pub struct Field {
    /// The parameter as every surface shows it.
    pub param: Param,
    /// `None` when it always applies, else when it does (the text says when,
    /// for messages).
    pub applies: Option<Condition>,
    /// Reads the field.
    pub get: fn(&Config) -> Value,
    /// Writes the field (the value has this parameter's kind).
    pub set: fn(&mut Config, &Value),
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

/// The game's parameters, in the order the schema lists them.
pub static FIELDS: &[Field] = &[
    Field {
        param: Param {
            key: "n",
            label: "Lattice side N",
            kind: ParamKind::Int {
                min: MIN_N as u64,
                max: MAX_N as u64,
            },
            default: Value::Int(40),
            help: "lattice side N (an N×N torus)",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: None,
        get: |c| Value::Int(c.n as u64),
        set: |c, v| c.n = u32_of(v),
    },
    Field {
        param: Param {
            key: "prior",
            label: "Prior",
            kind: ParamKind::Choice(|| PriorKind::NAMES.to_vec()),
            default: Value::Name(Cow::Borrowed("gaussian")),
            help: "target prior: gaussian (the paper's rounded, wrapped normal), delta (the centre), uniform, paint (a painted grid), or code (the authors' gausstarget on their (N+1)-lattice: under the paper-code preset with n = N+1 it reproduces MCTSgaussian.m at side N)",
            aliases: &[],
            choice_labels: &[
                "Gaussian",
                "Delta (the centre)",
                "Uniform",
                "Painted",
                "Gaussian as the authors' code draws it (N = n − 1)",
            ],
            advanced: false,
        },
        applies: Some((no_target, "without a fixed target")),
        get: |c| Value::Name(Cow::Borrowed(c.prior.name())),
        set: |c, v| c.prior = PriorKind::parse(name(v)).unwrap_or(c.prior),
    },
    Field {
        param: Param {
            key: "sigma",
            label: "Prior spread σ",
            kind: ParamKind::Float {
                min: 0.0,
                max: f64::INFINITY,
                min_open: false,
            },
            default: Value::Float(5.0),
            help: "Gaussian standard deviation σ (0 = a delta at the centre, inf = uniform)",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: Some((
            |c| matches!(c.prior, PriorKind::Gaussian | PriorKind::Code) && no_target(c),
            "with prior gaussian or code and no fixed target",
        )),
        get: |c| Value::Float(c.sigma),
        set: |c, v| c.sigma = float(v),
    },
    Field {
        param: Param {
            key: "paint",
            label: "Painted prior",
            kind: ParamKind::Paint,
            default: Value::Text(Cow::Borrowed("")),
            help: "painted prior: run-length encoded weights 0–15 per cell, as the page writes it",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: Some((
            |c| c.prior == PriorKind::Paint && no_target(c),
            "with prior paint and no fixed target",
        )),
        get: |c| Value::Text(Cow::Owned(c.paint.clone())),
        set: |c, v| {
            if let Value::Text(s) = v {
                c.paint = s.to_string();
            }
        },
    },
    Field {
        param: Param {
            key: "rv",
            label: "Detection radius r_v",
            kind: ParamKind::Float {
                min: 0.0,
                max: 2.0 * MAX_N as f64,
                min_open: false,
            },
            default: Value::Float(1.0),
            help: "detection radius r_v (torus Euclidean distance; 1 = the cell and its four neighbours)",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: None,
        get: |c| Value::Float(c.rv),
        set: |c, v| c.rv = float(v),
    },
    Field {
        param: Param {
            key: "start",
            label: "Start cell",
            kind: ParamKind::Cell,
            default: Value::Cell([1, 1]),
            help: "start cell x,y (1-based)",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: None,
        get: |c| Value::Cell(c.start),
        set: |c, v| {
            if let Value::Cell(x) = v {
                c.start = *x;
            }
        },
    },
    Field {
        param: Param {
            key: "target",
            label: "Fixed target",
            kind: ParamKind::OptCell,
            default: Value::OptCell(None),
            help: "a fixed target cell x,y (1-based) instead of one drawn from the prior",
            aliases: &[],
            choice_labels: &[],
            advanced: true,
        },
        applies: None,
        get: |c| Value::OptCell(c.target),
        set: |c, v| {
            if let Value::OptCell(x) = v {
                c.target = *x;
            }
        },
    },
    Field {
        param: Param {
            key: "known",
            label: "Known target",
            kind: ParamKind::Bool,
            default: Value::Bool(false),
            help: "draw the target from the prior, then plan with a delta prior on it",
            aliases: &[],
            choice_labels: &[],
            advanced: true,
        },
        applies: Some((no_target, "without a fixed target")),
        get: |c| Value::Bool(c.known),
        set: |c, v| c.known = flag(v),
    },
    Field {
        param: Param {
            key: "searcher",
            label: "Searcher",
            kind: ParamKind::Choice(registry::names),
            default: Value::Name(Cow::Borrowed("mcts")),
            help: "who searches: MCTS, or a walk that moves without deliberating",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: None,
        get: |c| Value::Name(Cow::Borrowed(c.searcher.name())),
        set: |c, v| c.searcher = SearcherId::parse(name(v)).unwrap_or(c.searcher),
    },
    Field {
        param: Param {
            key: "step_cap",
            label: "Step cap",
            kind: ParamKind::Int {
                min: 1,
                max: 100_000_000,
            },
            default: Value::Int(100_000),
            help: "episode step cap (a capped episode is a failure, counted as such)",
            aliases: &[],
            choice_labels: &[],
            advanced: true,
        },
        applies: None,
        get: |c| Value::Int(c.step_cap as u64),
        set: |c, v| c.step_cap = u32_of(v),
    },
    Field {
        param: Param {
            key: "seed",
            label: "Seed",
            kind: ParamKind::Int {
                min: 0,
                max: u64::MAX,
            },
            default: Value::Int(1),
            help: "seed: a run is a pure function of the config and the seed",
            aliases: &[],
            choice_labels: &[],
            advanced: false,
        },
        applies: None,
        get: |c| Value::Int(c.seed),
        set: |c, v| c.seed = int(v),
    },
];
