//! What the registry knows of a searcher: its name, the parameters it
//! reads and when, and how to build it.

use super::searcher::{Searcher, Setup};
use crate::param::{Param, Settings};

/// When a searcher reads one of its parameters.
#[derive(Clone, Copy)]
pub enum When {
    /// Whenever the searcher runs.
    Always,
    /// When the predicate holds on the settings; the text says when, for
    /// messages ("with variant cells").
    If(fn(&Settings) -> bool, &'static str),
}

/// A parameter a searcher reads, and when.
#[derive(Clone, Copy)]
pub struct Reads {
    /// The parameter (a static of the file that declares it).
    pub param: &'static Param,
    /// When it is read.
    pub when: When,
}

impl Reads {
    /// `param`, read whenever the searcher runs.
    pub const fn always(param: &'static Param) -> Reads {
        Reads {
            param,
            when: When::Always,
        }
    }

    /// `param`, read when `f` holds (`text` says when, for messages).
    pub const fn when(
        param: &'static Param,
        f: fn(&Settings) -> bool,
        text: &'static str,
    ) -> Reads {
        Reads {
            param,
            when: When::If(f, text),
        }
    }
}

/// A registry entry: a searcher's name, what it reads and how to build it.
pub struct SearcherInfo {
    /// The `searcher` value that selects it.
    pub name: &'static str,
    /// A short name for people.
    pub label: &'static str,
    /// How it moves, in one sentence.
    pub help: &'static str,
    /// True when it runs MCTS loops before each move.
    pub deliberates: bool,
    /// True when its path does not depend on chance: until it detects the
    /// target the path is a function of the configuration alone, so one
    /// pass along it gives its exact mean (`crate::analysis::exact`).
    /// Random walks and MCTS draw random numbers.
    pub deterministic: bool,
    /// The parameters it reads, in the order its settings are listed.
    pub params: &'static [Reads],
    /// Builds it for a trial.
    pub build: fn(&Setup<'_>) -> Box<dyn Searcher>,
}

impl SearcherInfo {
    /// True when it reads `p` under `settings`.
    pub fn reads(&self, p: &Param, settings: &Settings) -> bool {
        self.params.iter().any(|r| {
            *r.param == *p
                && match r.when {
                    When::Always => true,
                    When::If(f, _) => f(settings),
                }
        })
    }

    /// Why it does not read `p` under `settings`, for messages.
    pub fn not_reading(&self, p: &Param) -> String {
        match self.params.iter().find(|r| *r.param == *p).map(|r| r.when) {
            Some(When::If(_, text)) => format!("it applies {text}"),
            _ => format!("searcher {} does not read it", self.name),
        }
    }
}
