//! The schema: every parameter of a configuration, assembled from the
//! game's fields and the registry's searchers, and exported as data for the
//! CLI's help and the page.

use super::fields::{Config, Field, FIELDS};
use super::preset::Preset;
use crate::param::kind::fmt_float;
use crate::param::{Param, ParamKind, Value};
use crate::searchers::registry::{self, REGISTRY};
use std::sync::OnceLock;

/// The key that names a preset in `Config::set`, URLs and `--preset`.
pub const PRESET: &str = "preset";

/// One parameter of a configuration: a game field, or a setting a searcher
/// declares.
#[derive(Clone, Copy)]
pub enum ConfigParam {
    /// A field of [`Config`].
    Field(&'static Field),
    /// A searcher's parameter, held in `Config::settings`.
    Setting(&'static Param),
}

impl ConfigParam {
    /// The parameter.
    pub fn param(self) -> &'static Param {
        match self {
            ConfigParam::Field(f) => &f.param,
            ConfigParam::Setting(p) => p,
        }
    }

    /// Its value in `cfg`.
    pub fn value(self, cfg: &Config) -> Value {
        match self {
            ConfigParam::Field(f) => (f.get)(cfg),
            ConfigParam::Setting(p) => cfg.settings.get(p).clone(),
        }
    }

    /// Writes `v` (a value of its kind, already checked) into `cfg`.
    pub fn assign(self, cfg: &mut Config, v: Value) {
        match self {
            ConfigParam::Field(f) => (f.set)(cfg, &v),
            ConfigParam::Setting(p) => cfg.settings.set(p, v),
        }
    }

    /// True when it affects a run of `cfg`.
    pub fn applies_to(self, cfg: &Config) -> bool {
        match self {
            ConfigParam::Field(f) => f.applies.is_none_or(|(when, _)| when(cfg)),
            ConfigParam::Setting(p) => cfg.searcher.info().reads(p, &cfg.settings),
        }
    }

    /// Why it does not affect a run of `cfg`, for messages.
    pub fn not_applying(self, cfg: &Config) -> String {
        match self {
            ConfigParam::Field(f) => match f.applies {
                Some((_, when)) => format!("it applies {when}"),
                None => "it always applies".into(),
            },
            ConfigParam::Setting(p) => cfg.searcher.info().not_reading(p),
        }
    }

    /// Where it belongs, for grouping controls: `game` for a field, else
    /// the first registered searcher that reads it.
    pub fn group(self) -> &'static str {
        match self {
            ConfigParam::Field(_) => "game",
            ConfigParam::Setting(p) => REGISTRY
                .iter()
                .find(|s| s.params.iter().any(|r| *r.param == *p))
                .map_or("game", |s| s.name),
        }
    }
}

/// Every parameter, in the order the CLI's help, the URL, the JSON and the
/// page's form list them: the game's fields, then the searchers'
/// parameters in registry order.
pub fn params() -> &'static [ConfigParam] {
    static ALL: OnceLock<Vec<ConfigParam>> = OnceLock::new();
    ALL.get_or_init(|| {
        FIELDS
            .iter()
            .map(ConfigParam::Field)
            .chain(registry::params().into_iter().map(ConfigParam::Setting))
            .collect()
    })
}

/// The parameter whose key is `key`.
pub fn entry(key: &str) -> Option<ConfigParam> {
    params().iter().copied().find(|p| p.param().key == key)
}

/// The parameter whose key is `key`, as every surface shows it.
pub fn param(key: &str) -> Option<&'static Param> {
    entry(key).map(ConfigParam::param)
}

/// The number of trials a batch may run.
pub static TRIALS: Param = Param {
    key: "trials",
    label: "Trials",
    kind: ParamKind::Int {
        min: 1,
        max: 100_000_000,
    },
    default: Value::Int(1000),
    help: "number of trials; trial i depends only on (config, i)",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// The schema as data: what the facade exports to the page and the CLI's
/// help lists.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Schema {
    /// Every parameter.
    pub params: Vec<ParamInfo>,
    /// The groups parameters belong to, in order: `game`, then each
    /// searcher that declares parameters, with names for people.
    pub groups: Vec<GroupInfo>,
    /// The searcher registry.
    pub searchers: Vec<SearcherSummary>,
    /// Limits of a batch of trials.
    pub trials: ParamInfo,
    /// The named presets.
    pub presets: Vec<PresetInfo>,
    /// The key that sets a preset ([`PRESET`]).
    pub preset_key: &'static str,
}

/// A group of parameters as data.
#[derive(Clone, Debug, serde::Serialize)]
pub struct GroupInfo {
    /// Its name, as a parameter's `group` gives it.
    pub name: &'static str,
    /// A name for people.
    pub label: &'static str,
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
    /// A short name for people (the page's control label).
    pub label: &'static str,
    /// `game`, or the searcher that declares it.
    pub group: &'static str,
    /// A setting most people leave alone.
    pub advanced: bool,
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
    /// Names for people of the choices, in their order (choices that
    /// give them only; `searcher`'s are the registry's labels).
    pub choice_labels: Option<Vec<&'static str>>,
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
    /// The keys of the parameters it may read.
    pub params: Vec<&'static str>,
}

impl ParamInfo {
    fn of(p: &'static Param, group: &'static str) -> ParamInfo {
        let (min, max, min_open) = match p.kind {
            ParamKind::Int { min, max } => (Some(min.to_string()), Some(max.to_string()), false),
            ParamKind::Float { min, max, min_open } => {
                (Some(fmt_float(min)), Some(fmt_float(max)), min_open)
            }
            ParamKind::OptFloat { min, max } => (Some(fmt_float(min)), Some(fmt_float(max)), false),
            _ => (None, None, false),
        };
        ParamInfo {
            key: p.key,
            label: p.label,
            group,
            advanced: p.advanced,
            flag: format!("--{}", p.flag()),
            aliases: p.aliases.iter().map(|a| format!("--{a}")).collect(),
            kind: p.kind.name(),
            default: p.default.text(),
            min,
            max,
            min_open,
            choices: match p.kind {
                ParamKind::Choice(names) => Some(names()),
                _ => None,
            },
            choice_labels: (!p.choice_labels.is_empty()).then(|| p.choice_labels.to_vec()),
            allowed: p.kind.allowed(),
            help: p.help,
        }
    }
}

/// The whole schema.
pub fn schema() -> Schema {
    let params: Vec<ParamInfo> = params()
        .iter()
        .map(|p| ParamInfo::of(p.param(), p.group()))
        .collect();
    let mut groups = vec![GroupInfo {
        name: "game",
        label: "Game",
    }];
    for s in REGISTRY {
        if params.iter().any(|p| p.group == s.name) {
            groups.push(GroupInfo {
                name: s.name,
                label: s.label,
            });
        }
    }
    Schema {
        params,
        groups,
        searchers: REGISTRY
            .iter()
            .map(|s| SearcherSummary {
                name: s.name,
                label: s.label,
                help: s.help,
                deliberates: s.deliberates,
                params: s.params.iter().map(|r| r.param.key).collect(),
            })
            .collect(),
        trials: ParamInfo::of(&TRIALS, "batch"),
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
