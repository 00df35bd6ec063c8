//! The values of the parameters that searchers declare, by parameter.

use super::definition::Param;
use super::kind::Value;
use crate::game::named::Named;

/// The values a configuration gives the searchers' own parameters: only
/// those that differ from their defaults are kept, so two settings are
/// equal exactly when every parameter reads the same.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    changed: Vec<(&'static str, Value)>,
}

impl Settings {
    /// The value of `p` (its default unless set).
    pub fn get<'a>(&'a self, p: &'a Param) -> &'a Value {
        self.changed
            .iter()
            .find(|(k, _)| *k == p.key)
            .map_or(&p.default, |(_, v)| v)
    }

    /// Sets `p` to `v`, a value of its kind that the caller has checked.
    pub fn set(&mut self, p: &'static Param, v: Value) {
        self.changed.retain(|(k, _)| *k != p.key);
        if v != p.default {
            self.changed.push((p.key, v));
            self.changed.sort_by_key(|(k, _)| *k);
        }
    }

    /// An integer parameter's value.
    pub fn int(&self, p: &Param) -> u64 {
        match self.get(p) {
            Value::Int(x) => *x,
            other => mismatch(p, other, 0),
        }
    }

    /// An integer parameter's value as a `u32` (every such parameter's
    /// range fits).
    pub fn u32(&self, p: &Param) -> u32 {
        self.int(p).min(u32::MAX as u64) as u32
    }

    /// A number parameter's value.
    pub fn float(&self, p: &Param) -> f64 {
        match self.get(p) {
            Value::Float(x) => *x,
            other => mismatch(p, other, f64::NAN),
        }
    }

    /// An optional number parameter's value (`None` for 0).
    pub fn opt_float(&self, p: &Param) -> Option<f64> {
        match self.get(p) {
            Value::OptFloat(x) => *x,
            other => mismatch(p, other, None),
        }
    }

    /// An on/off parameter's value.
    pub fn flag(&self, p: &Param) -> bool {
        match self.get(p) {
            Value::Bool(b) => *b,
            other => mismatch(p, other, false),
        }
    }

    /// A choice parameter's value, as the named enum `T` whose names are
    /// its choices.
    pub fn choice<T: Named>(&self, p: &Param) -> T {
        let default = || match &p.default {
            Value::Name(n) => T::parse(n.as_ref()),
            _ => None,
        };
        match self.get(p) {
            Value::Name(n) => T::parse(n.as_ref()).or_else(default),
            _ => default(),
        }
        .unwrap_or_else(|| panic!("{}: the choices are not those of the enum asked for", p.key))
    }
}

/// A parameter read as a kind it does not have: a programming error,
/// caught in debug builds (every searcher is built from the defaults by the
/// registry's tests).
fn mismatch<T>(p: &Param, v: &Value, fallback: T) -> T {
    debug_assert!(false, "{} read as the wrong kind: {v:?}", p.key);
    fallback
}
