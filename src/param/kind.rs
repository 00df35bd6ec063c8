//! What values a parameter takes, and a value read from text.

use super::error::ParamError;
use std::borrow::Cow;

/// A parameter's value, as [`ParamKind::parse`] reads it from text.
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
pub fn fmt_float(v: f64) -> String {
    if v == f64::INFINITY {
        "inf".into()
    } else {
        v.to_string()
    }
}

/// What values a parameter takes.
#[derive(Clone, Copy, Debug)]
pub enum ParamKind {
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
    /// A painted prior (`game::prior::encode_paint` text; checked against n
    /// by the configuration).
    Paint,
}

impl ParamKind {
    /// The kind's name in the exported schema.
    pub fn name(&self) -> &'static str {
        match self {
            ParamKind::Int { .. } => "int",
            ParamKind::Float { .. } => "float",
            ParamKind::OptFloat { .. } => "optfloat",
            ParamKind::Choice(_) => "choice",
            ParamKind::Bool => "bool",
            ParamKind::Cell => "cell",
            ParamKind::OptCell => "optcell",
            ParamKind::Paint => "paint",
        }
    }

    /// The allowed values, as an error message states them.
    pub fn allowed(&self) -> String {
        match *self {
            ParamKind::Int { min, max } => format!("an integer in {min}..={max}"),
            ParamKind::Float { min, max, .. } if max.is_infinite() => {
                format!("a number >= {min} (inf allowed)")
            }
            ParamKind::Float {
                min,
                max,
                min_open: true,
            } => format!("a number in ({min}, {max}]"),
            ParamKind::Float { min, max, .. } => format!("a number in [{min}, {max}]"),
            ParamKind::OptFloat { min, max } => {
                format!("a number in [{min}, {max}], or 0 for none")
            }
            ParamKind::Choice(names) => format!("one of {}", names().join(", ")),
            ParamKind::Bool => "one of 1, 0, true, false, yes, no, on, off".into(),
            ParamKind::Cell => "x,y with each in 1..=n".into(),
            ParamKind::OptCell => "x,y with each in 1..=n, or empty for none".into(),
            ParamKind::Paint => {
                "a painted prior (run-length encoded levels 0-15, n*n cells)".into()
            }
        }
    }

    /// Reads a text value and checks it against the range.
    ///
    /// # Errors
    /// A [`ParamError`] for `key` naming the text and the allowed range.
    pub fn parse(&self, key: &'static str, raw: &str) -> Result<Value, ParamError> {
        let s = raw.trim();
        let bad = || ParamError::new(key, shown(raw), self.allowed());
        let v = match self {
            ParamKind::Int { .. } => Value::Int(s.parse().map_err(|_| bad())?),
            ParamKind::Float { .. } => Value::Float(parse_float(s).ok_or_else(bad)?),
            ParamKind::OptFloat { .. } => {
                Value::OptFloat(match parse_float(s).ok_or_else(bad)? {
                    0.0 => None,
                    v => Some(v),
                })
            }
            ParamKind::Choice(names) => Value::Name(Cow::Borrowed(
                names().into_iter().find(|&n| n == s).ok_or_else(bad)?,
            )),
            ParamKind::Bool => Value::Bool(match s {
                "1" | "true" | "yes" | "on" => true,
                "0" | "false" | "no" | "off" => false,
                _ => return Err(bad()),
            }),
            ParamKind::Cell => Value::Cell(parse_cell(s).ok_or_else(bad)?),
            ParamKind::OptCell => Value::OptCell(match s {
                "" | "none" => None,
                _ => Some(parse_cell(s).ok_or_else(bad)?),
            }),
            ParamKind::Paint => {
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
    /// checked by the configuration, which knows n).
    ///
    /// # Errors
    /// A [`ParamError`] for `key` naming the value and the allowed range.
    pub fn check(&self, key: &'static str, v: &Value) -> Result<(), ParamError> {
        let ok = match (*self, v) {
            (ParamKind::Int { min, max }, Value::Int(x)) => (min..=max).contains(x),
            (ParamKind::Float { min, max, min_open }, &Value::Float(x)) => {
                !x.is_nan() && (if min_open { x > min } else { x >= min }) && x <= max
            }
            (ParamKind::OptFloat { min, max }, &Value::OptFloat(x)) => {
                x.is_none_or(|x| x.is_finite() && x >= min && x <= max)
            }
            (ParamKind::Choice(names), Value::Name(s)) => names().contains(&s.as_ref()),
            (ParamKind::Bool, Value::Bool(_)) => true,
            // Cells are checked against n by the configuration, which knows n.
            (ParamKind::Cell, Value::Cell(_)) | (ParamKind::OptCell, Value::OptCell(_)) => true,
            (ParamKind::Paint, Value::Text(_)) => true,
            _ => false,
        };
        if ok {
            Ok(())
        } else {
            Err(ParamError::new(key, v.text(), self.allowed()))
        }
    }
}

/// Shortens a user-supplied value for an error message.
pub fn shown(raw: &str) -> String {
    if raw.chars().count() > 40 {
        format!("{}…", raw.chars().take(40).collect::<String>())
    } else {
        raw.to_string()
    }
}

pub fn parse_float(s: &str) -> Option<f64> {
    // Rust's parser also takes "infinity" and "NaN"; NaN fails every range.
    s.parse::<f64>().ok()
}

fn parse_cell(s: &str) -> Option<[u32; 2]> {
    let (x, y) = s.split_once(',')?;
    Some([x.trim().parse().ok()?, y.trim().parse().ok()?])
}
