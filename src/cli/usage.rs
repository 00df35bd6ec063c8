//! Usage errors: a one-line message for stderr, and exit code 2.

use crate::config;
use crate::param::ParamError;

/// A message for stderr; the process exits with code 2.
pub(super) struct UsageError(pub(super) String);

/// The flag of parameter `key`, with its dashes.
pub(super) fn flag(key: &str) -> String {
    config::param(key).map_or_else(|| format!("--{key}"), |p| format!("--{}", p.flag()))
}

/// A configuration error worded for the command line.
pub(super) fn usage(e: ParamError) -> UsageError {
    UsageError(format!(
        "{} must be {}, got {}",
        flag(e.field),
        e.allowed,
        e.value
    ))
}
