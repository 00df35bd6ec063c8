//! The registry: every searcher by name.
//!
//! A searcher is its file plus one line in [`REGISTRY`]: its parameters are
//! statics in that file, listed in its [`SearcherInfo::params`], and the
//! configuration's schema is assembled from them, so the CLI flag, the URL
//! key, the page's control, the JSON field and the schema snapshot follow.

use super::info::SearcherInfo;
use super::mcts::search as mcts;
use super::planners::{beam, horizon, improve, spiral, sweep};
use super::walks::walker;
use crate::param::Param;
use std::fmt;

/// Every searcher, in the order the CLI and the page list them.
pub static REGISTRY: &[&SearcherInfo] = &[
    &mcts::INFO,
    &walker::RW,
    &walker::LEVY,
    &walker::NSARW,
    &sweep::INFO,
    &horizon::INFO,
    &improve::INFO,
    &beam::INFO,
    &spiral::INFO,
    #[cfg(test)]
    &super::registry_tests::SHUTTLE,
];

/// The names of the registered searchers.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|s| s.name).collect()
}

/// Every parameter the registered searchers read, each once, in registry
/// order.
pub fn params() -> Vec<&'static Param> {
    let mut out: Vec<&'static Param> = Vec::new();
    for r in REGISTRY.iter().flat_map(|s| s.params) {
        if !out.iter().any(|p| **p == *r.param) {
            out.push(r.param);
        }
    }
    out
}

/// A registered searcher, by name.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct SearcherId(&'static str);

impl SearcherId {
    /// The registered searcher called `name`.
    pub fn parse(name: &str) -> Option<SearcherId> {
        REGISTRY
            .iter()
            .find(|s| s.name == name)
            .map(|s| SearcherId(s.name))
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        self.0
    }

    /// Its registry entry.
    pub fn info(self) -> &'static SearcherInfo {
        // An id is only made from a registry name.
        REGISTRY
            .iter()
            .find(|s| s.name == self.0)
            .copied()
            .unwrap_or(REGISTRY[0])
    }
}

impl fmt::Debug for SearcherId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "SearcherId({})", self.0)
    }
}

impl fmt::Display for SearcherId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

impl serde::Serialize for SearcherId {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

impl<'de> serde::Deserialize<'de> for SearcherId {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<SearcherId, D::Error> {
        let s = String::deserialize(d)?;
        SearcherId::parse(&s).ok_or_else(|| {
            serde::de::Error::custom(format!("expected one of {}, got {s:?}", names().join(", ")))
        })
    }
}
