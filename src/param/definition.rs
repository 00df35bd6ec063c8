//! One parameter: its key, label, kind, default and help.

use super::error::ParamError;
use super::kind::{ParamKind, Value};

/// One parameter as every surface shows it: the CLI flag, the URL key, the
/// JSON field, the page's control and an experiment's sweep.
#[derive(Debug)]
pub struct Param {
    /// The key: the URL parameter, the JSON field, and (with `-` for `_`)
    /// the CLI flag.
    pub key: &'static str,
    /// A short name for people, as the page's control is labelled.
    pub label: &'static str,
    /// What values it takes.
    pub kind: ParamKind,
    /// The default value.
    pub default: Value,
    /// One line of help.
    pub help: &'static str,
    /// Other CLI flag names accepted (without dashes).
    pub aliases: &'static [&'static str],
    /// Names for people of a choice's values, in the order of its choices
    /// (empty: the values' own names serve).
    pub choice_labels: &'static [&'static str],
    /// True for a setting most people leave alone (the page folds it away).
    pub advanced: bool,
}

impl Param {
    /// The CLI flag without its dashes (`step_cap` → `step-cap`).
    pub fn flag(&self) -> String {
        self.key.replace('_', "-")
    }

    /// Reads a text value and checks it against the range.
    ///
    /// # Errors
    /// A [`ParamError`] naming this key, the text and the allowed range.
    pub fn parse(&self, raw: &str) -> Result<Value, ParamError> {
        self.kind.parse(self.key, raw)
    }

    /// An integer parameter's value read from `raw`, or its default when
    /// `raw` is `None`.
    ///
    /// # Errors
    /// A [`ParamError`] for text out of range, or for a parameter that is
    /// not an integer.
    pub fn int_value(&self, raw: Option<&str>) -> Result<u64, ParamError> {
        let v = match raw {
            Some(raw) => self.parse(raw)?,
            None => self.default.clone(),
        };
        match v {
            Value::Int(x) => Ok(x),
            other => Err(ParamError::new(self.key, other.text(), self.kind.allowed())),
        }
    }
}

impl PartialEq for Param {
    /// Parameters are statics: two are the same when they are the same
    /// static (keys are unique, which the schema checks).
    fn eq(&self, other: &Param) -> bool {
        std::ptr::eq(self, other)
    }
}
