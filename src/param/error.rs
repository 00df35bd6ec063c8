//! The error of a parameter value: the key, what was given and what is allowed.

use std::fmt;

/// A parameter value outside its allowed range.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// The parameter key.
    pub field: &'static str,
    /// What was given, as text.
    pub value: String,
    /// The allowed range or set, e.g. "an integer in 3..=1024".
    pub allowed: String,
}

impl ParamError {
    /// An error for `field` with the offending `value` and the `allowed` range.
    pub fn new(
        field: &'static str,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> ParamError {
        ParamError {
            field,
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} must be {}, got {}",
            self.field, self.allowed, self.value
        )
    }
}

impl std::error::Error for ParamError {}
