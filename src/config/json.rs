//! A configuration as JSON: one field per parameter, in schema order.
//!
//! Each value takes the JSON form of its kind: numbers, names as strings,
//! on/off as booleans, cells as `[x, y]`, none as `null`. Two exceptions
//! keep values exact: an integer that may pass 2^53 (the seed) is a decimal
//! string, since JSON and JS numbers hold only 53 bits, and an infinite
//! number (σ) is the string "inf".

use super::fields::Config;
use super::schema::{entry, params, ConfigParam};
use crate::param::kind::{fmt_float, parse_float};
use crate::param::{ParamError, ParamKind, Value};
use serde::ser::SerializeMap;
use serde_json::Value as Json;
use std::borrow::Cow;

/// The largest integer a JSON number holds exactly.
const EXACT: u64 = 1 << 53;

fn to_json(kind: ParamKind, v: &Value) -> Json {
    let cell = |[x, y]: [u32; 2]| Json::from(vec![x, y]);
    match v {
        Value::Int(x) => match kind {
            ParamKind::Int { max, .. } if max > EXACT => Json::String(x.to_string()),
            _ => Json::from(*x),
        },
        Value::Float(x) if x.is_finite() => Json::from(*x),
        Value::Float(x) => Json::String(fmt_float(*x)),
        Value::OptFloat(x) => x.map_or(Json::Null, Json::from),
        Value::Name(s) | Value::Text(s) => Json::String(s.to_string()),
        Value::Bool(b) => Json::Bool(*b),
        Value::Cell(c) => cell(*c),
        Value::OptCell(c) => c.map_or(Json::Null, cell),
    }
}

/// Reads one parameter's JSON value, or says what it allows.
fn from_json_value(kind: ParamKind, j: &Json) -> Option<Value> {
    let cell = |j: &Json| -> Option<[u32; 2]> {
        let a = j.as_array().filter(|a| a.len() == 2)?;
        let c = |v: &Json| v.as_u64().and_then(|x| u32::try_from(x).ok());
        Some([c(&a[0])?, c(&a[1])?])
    };
    Some(match kind {
        ParamKind::Int { max, .. } => Value::Int(match j {
            Json::String(s) if max > EXACT => s.trim().parse().ok()?,
            // Above 2^53 a float no longer names one integer.
            Json::Number(n) if max > EXACT && n.as_u64().is_none() => {
                let f = n.as_f64()?;
                (f.fract() == 0.0 && (0.0..=EXACT as f64).contains(&f)).then_some(f as u64)?
            }
            _ => j.as_u64()?,
        }),
        ParamKind::Float { max, .. } => Value::Float(match j {
            Json::String(s) if max.is_infinite() => parse_float(s.trim())?,
            _ => j.as_f64()?,
        }),
        ParamKind::OptFloat { .. } => Value::OptFloat(match j {
            Json::Null => None,
            _ => Some(j.as_f64()?),
        }),
        ParamKind::Choice(names) => {
            let s = j.as_str()?;
            Value::Name(Cow::Borrowed(names().into_iter().find(|&n| n == s)?))
        }
        ParamKind::Bool => Value::Bool(j.as_bool()?),
        ParamKind::Cell => Value::Cell(cell(j)?),
        ParamKind::OptCell => Value::OptCell(match j {
            Json::Null => None,
            _ => Some(cell(j)?),
        }),
        ParamKind::Paint => Value::Text(Cow::Owned(j.as_str()?.to_string())),
    })
}

/// What a parameter's JSON form is, for messages.
fn json_form(kind: ParamKind) -> String {
    match kind {
        ParamKind::Int { max, .. } if max > EXACT => {
            format!(
                "{} (a string or a number; numbers above 2^53 must be strings)",
                kind.allowed()
            )
        }
        ParamKind::Float { max, .. } if max.is_infinite() => {
            format!("{} (a number, or \"inf\")", kind.allowed())
        }
        ParamKind::OptFloat { .. } => format!("{} (a number, or null for none)", kind.allowed()),
        ParamKind::Cell => "[x, y] with each in 1..=n".into(),
        ParamKind::OptCell => "[x, y] with each in 1..=n, or null for none".into(),
        ParamKind::Bool => "true or false".into(),
        ParamKind::Choice(_) | ParamKind::Paint => format!("{} (a string)", kind.allowed()),
        _ => kind.allowed(),
    }
}

/// A JSON value shortened for a message.
fn shown(v: &Json) -> String {
    let text = v.to_string();
    match text.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text,
    }
}

/// Reads a configuration from a JSON object without checking ranges: a
/// missing key keeps its default; an unknown key, or a value of the wrong
/// form, is an error naming the key and what it allows.
fn read_object(value: &Json) -> Result<Config, ParamError> {
    let Json::Object(map) = value else {
        return Err(ParamError::new(
            "config",
            shown(value),
            "an object of parameter values",
        ));
    };
    let mut cfg = Config::default();
    for (key, v) in map {
        let Some(p): Option<ConfigParam> = entry(key) else {
            let keys: Vec<&str> = params().iter().map(|p| p.param().key).collect();
            return Err(ParamError::new(
                "config",
                format!("the key {}", shown(&Json::String(key.clone()))),
                format!("an object whose keys are among {}", keys.join(", ")),
            ));
        };
        let param = p.param();
        let value = from_json_value(param.kind, v)
            .ok_or_else(|| ParamError::new(param.key, shown(v), json_form(param.kind)))?;
        p.assign(&mut cfg, value);
    }
    Ok(cfg)
}

/// Reads a config from a JSON value (the page's config objects, files),
/// naming the parameter at fault: a missing key keeps its default, an
/// unknown key or a value of the wrong form is an error naming the key and
/// what it allows, and the whole is then validated.
///
/// # Errors
/// A [`ParamError`] for a value that is not an object, an unknown key, a
/// value of the wrong form, or (after reading) a value out of range.
pub fn from_json(value: serde_json::Value) -> Result<Config, ParamError> {
    let cfg = read_object(&value)?;
    cfg.validate()?;
    Ok(cfg)
}

impl serde::Serialize for Config {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let all = params();
        let mut map = s.serialize_map(Some(all.len()))?;
        for p in all {
            let param = p.param();
            map.serialize_entry(param.key, &to_json(param.kind, &p.value(self)))?;
        }
        map.end()
    }
}

impl<'de> serde::Deserialize<'de> for Config {
    /// Reads the JSON form (ranges are checked by [`Config::validate`]).
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Config, D::Error> {
        let value = Json::deserialize(d)?;
        read_object(&value).map_err(serde::de::Error::custom)
    }
}
