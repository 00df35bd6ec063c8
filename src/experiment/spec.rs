//! What an experiment request says: which experiment, how many trials, the
//! seed, a preset, and parameter overrides (a sweep and series for `custom`).
//!
//! A spec arrives as JSON (the page, a result file) or from CLI flags (which
//! the CLI turns into the same JSON). Reading it checks every field and
//! writes every value in its canonical text, so two specs that ask for the
//! same thing serialise to the same bytes (the merge of shards relies on it).

use super::defs::{self, Definition};
use crate::config::preset::Preset;
use crate::config::{self, TRIALS};
use crate::param::ParamError;

/// The preset of a spec that names none: the authors' code, which is what
/// produced the paper's figures (`EXPERIMENTS.md` compares it with their
/// numbers); `paper-text` and no preset are a flag away.
pub const DEFAULT_PRESET: Preset = super::defs::PAPER;
use serde_json::Value;
use std::collections::BTreeMap;
use std::fmt;

/// The fields a spec may have.
pub const SPEC_FIELDS: &[&str] = &[
    "name", "trials", "seed", "preset", "params", "sweep", "series",
];

/// Most values a sweep may have, and most series a custom experiment may have.
pub const MAX_SWEEP_VALUES: usize = 1000;
/// Most series a custom experiment may have.
pub const MAX_SERIES: usize = 100;

/// A spec that cannot be used, with what is wrong in words.
#[derive(Clone, Debug, PartialEq)]
pub enum SpecError {
    /// The text is not JSON, or the spec is not an object.
    Json(String),
    /// A field with a value of the wrong kind.
    Field {
        /// The field, e.g. `trials` or `sweep.values`.
        field: String,
        /// What it must be.
        allowed: String,
        /// What was given.
        got: String,
    },
    /// A field the spec does not have.
    UnknownField(String),
    /// No experiment by this name.
    Name(String),
    /// A parameter value out of range, or an unknown parameter.
    Param {
        /// Where it was given: "params", "sweep", `series "A"`.
        place: String,
        /// The parameter's own error.
        error: ParamError,
    },
    /// A point whose configuration does not validate.
    Point {
        /// Which point: its series and x value.
        point: String,
        /// The first invalid field.
        error: ParamError,
    },
    /// A parameter no point (of its series) reads, refused as `run`
    /// refuses a flag that does not apply.
    NotApplying {
        /// The parameter key.
        key: String,
        /// The series that sets it; `None` for the spec's params or sweep.
        series: Option<String>,
        /// Why it does not apply.
        why: String,
    },
    /// A request the experiment cannot honour (a sweep on a named
    /// experiment, an override of the swept parameter, ...).
    Conflict(String),
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpecError::Json(e) => write!(f, "the experiment spec is not a JSON object: {e}"),
            SpecError::Field {
                field,
                allowed,
                got,
            } => write!(f, "spec field {field} must be {allowed}, got {got}"),
            SpecError::UnknownField(name) => write!(
                f,
                "spec has an unknown field {name:?}; the fields are {}",
                SPEC_FIELDS.join(", ")
            ),
            SpecError::Name(name) => write!(
                f,
                "experiment must be one of {}, got {name:?}",
                defs::names().join(", ")
            ),
            SpecError::Param { place, error } => write!(f, "{error} (in {place})"),
            SpecError::Point { point, error } => write!(f, "{error} (at point {point})"),
            SpecError::NotApplying { key, series, why } => match series {
                Some(label) => write!(f, "{key} does not apply to series {label:?}: {why}"),
                None => write!(f, "{key} does not apply to any point of {why}"),
            },
            SpecError::Conflict(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for SpecError {}

/// A sweep of one parameter over values (custom experiments).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SweepSpec {
    /// The parameter key.
    pub key: String,
    /// Its values, in canonical text, in the order given.
    pub values: Vec<String>,
}

/// One series of a custom experiment: a label and its parameter values.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SeriesSpec {
    /// The label, unique within the spec.
    pub label: String,
    /// Parameter values, canonical text.
    pub params: BTreeMap<String, String>,
}

/// A read and normalised spec: every field present, every value canonical.
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// The experiment's name.
    pub name: String,
    /// Trials (samples, for `priors`) per point.
    pub trials: u64,
    /// The seed every point's configuration keeps.
    pub seed: u64,
    /// The reading of the paper applied first, if any.
    pub preset: Option<Preset>,
    /// Overrides applied after the preset and the experiment's defaults.
    pub params: BTreeMap<String, String>,
    /// The swept parameter (custom only).
    pub sweep: Option<SweepSpec>,
    /// The series (custom only).
    pub series: Option<Vec<SeriesSpec>>,
}

impl serde::Serialize for Spec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct Out<'a> {
            name: &'a str,
            trials: u64,
            seed: String,
            preset: Option<&'static str>,
            params: &'a BTreeMap<String, String>,
            sweep: &'a Option<SweepSpec>,
            series: &'a Option<Vec<SeriesSpec>>,
        }
        Out {
            name: &self.name,
            trials: self.trials,
            seed: self.seed.to_string(),
            preset: self.preset.map(Preset::name),
            params: &self.params,
            sweep: &self.sweep,
            series: &self.series,
        }
        .serialize(s)
    }
}

fn shown(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 60 {
        format!("{}…", s.chars().take(60).collect::<String>())
    } else {
        s
    }
}

fn field_error(field: &str, allowed: impl Into<String>, got: &Value) -> SpecError {
    SpecError::Field {
        field: field.to_string(),
        allowed: allowed.into(),
        got: shown(got),
    }
}

/// A JSON scalar as parameter text (strings as they are, numbers in JSON's
/// spelling, booleans as 1/0).
fn scalar_text(v: &Value) -> Option<String> {
    match v {
        Value::String(s) => Some(s.clone()),
        Value::Number(n) => Some(n.to_string()),
        Value::Bool(b) => Some(if *b { "1" } else { "0" }.to_string()),
        _ => None,
    }
}

/// Checks parameter `key` and its `raw` text; returns the key and the
/// canonical text. The seed is the spec's own field, never a parameter.
///
/// # Errors
/// A [`SpecError::Param`] naming `place`, the key and the allowed values.
pub fn canonical_param(place: &str, key: &str, raw: &str) -> Result<(String, String), SpecError> {
    let bad = |error| SpecError::Param {
        place: place.to_string(),
        error,
    };
    if key == "seed" {
        return Err(SpecError::Conflict(format!(
            "seed is the spec's own field, not a parameter (in {place})"
        )));
    }
    let p = config::param(key).ok_or_else(|| {
        bad(config::Config::default()
            .set(key, raw)
            .expect_err("an unknown key is refused"))
    })?;
    let v = p.kind.parse(p.key, raw).map_err(bad)?;
    Ok((p.key.to_string(), v.text()))
}

fn params_of(
    place: &str,
    field: &str,
    v: Option<&Value>,
) -> Result<BTreeMap<String, String>, SpecError> {
    let mut out = BTreeMap::new();
    match v {
        None | Some(Value::Null) => {}
        Some(Value::Object(map)) => {
            for (k, v) in map {
                let raw = scalar_text(v).ok_or_else(|| {
                    field_error(&format!("{field}.{k}"), "a string, number or boolean", v)
                })?;
                let (key, text) = canonical_param(place, k, &raw)?;
                out.insert(key, text);
            }
        }
        Some(other) => {
            return Err(field_error(
                field,
                "an object of parameter keys and values",
                other,
            ))
        }
    }
    Ok(out)
}

fn only_fields(
    field: &str,
    map: &serde_json::Map<String, Value>,
    allowed: &[&str],
) -> Result<(), SpecError> {
    match map.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(SpecError::Field {
            field: format!("{field}.{k}"),
            allowed: format!("absent: {field} has only {}", allowed.join(", ")),
            got: shown(&map[k]),
        }),
        None => Ok(()),
    }
}

fn sweep_of(v: Option<&Value>) -> Result<Option<SweepSpec>, SpecError> {
    let map = match v {
        None | Some(Value::Null) => return Ok(None),
        Some(Value::Object(map)) => map,
        Some(other) => {
            return Err(field_error(
                "sweep",
                "an object {\"key\": KEY, \"values\": [...]} or null",
                other,
            ))
        }
    };
    only_fields("sweep", map, &["key", "values"])?;
    let key = match map.get("key") {
        Some(Value::String(k)) => k.clone(),
        other => {
            return Err(field_error(
                "sweep.key",
                "a parameter key",
                other.unwrap_or(&Value::Null),
            ))
        }
    };
    let values = match map.get("values") {
        Some(Value::Array(a)) if !a.is_empty() && a.len() <= MAX_SWEEP_VALUES => a,
        other => {
            return Err(field_error(
                "sweep.values",
                format!("a list of 1 to {MAX_SWEEP_VALUES} values"),
                other.unwrap_or(&Value::Null),
            ))
        }
    };
    let mut out: Vec<String> = Vec::with_capacity(values.len());
    let mut canonical_key = key.clone();
    for v in values {
        let raw = scalar_text(v)
            .ok_or_else(|| field_error("sweep.values", "strings, numbers or booleans", v))?;
        let (k, text) = canonical_param("sweep", &key, &raw)?;
        if out.contains(&text) {
            return Err(SpecError::Conflict(format!(
                "sweep value {text} of {k} is given twice"
            )));
        }
        canonical_key = k;
        out.push(text);
    }
    Ok(Some(SweepSpec {
        key: canonical_key,
        values: out,
    }))
}

fn series_of(v: Option<&Value>) -> Result<Option<Vec<SeriesSpec>>, SpecError> {
    let list = match v {
        None | Some(Value::Null) => return Ok(None),
        Some(Value::Array(a)) if !a.is_empty() && a.len() <= MAX_SERIES => a,
        Some(other) => {
            return Err(field_error(
                "series",
                format!("a list of 1 to {MAX_SERIES} {{\"label\", \"params\"}} objects, or null"),
                other,
            ))
        }
    };
    let mut out: Vec<SeriesSpec> = Vec::with_capacity(list.len());
    for (i, item) in list.iter().enumerate() {
        let field = format!("series[{i}]");
        let map = item
            .as_object()
            .ok_or_else(|| field_error(&field, "an object {\"label\", \"params\"}", item))?;
        only_fields(&field, map, &["label", "params"])?;
        let label = match map.get("label") {
            Some(Value::String(s))
                if !s.trim().is_empty()
                    && s.chars().count() <= 80
                    && !s.chars().any(char::is_control) =>
            {
                s.trim().to_string()
            }
            other => {
                return Err(field_error(
                    &format!("{field}.label"),
                    "a label of 1 to 80 characters without control characters",
                    other.unwrap_or(&Value::Null),
                ))
            }
        };
        if out.iter().any(|s| s.label == label) {
            return Err(SpecError::Conflict(format!(
                "series label {label:?} is given twice"
            )));
        }
        let params = params_of(
            &format!("series {label:?}"),
            &format!("{field}.params"),
            map.get("params"),
        )?;
        out.push(SeriesSpec { label, params });
    }
    Ok(Some(out))
}

impl Spec {
    /// Reads a spec from JSON text.
    ///
    /// # Errors
    /// A [`SpecError`] naming the first bad field or value.
    pub fn from_text(text: &str) -> Result<Spec, SpecError> {
        let v: Value = serde_json::from_str(text).map_err(|e| SpecError::Json(e.to_string()))?;
        Spec::from_value(&v)
    }

    /// Reads a spec from a JSON value: unknown fields are refused, missing
    /// ones take the experiment's defaults (trials), seed 1, preset
    /// [`DEFAULT_PRESET`] (`null` or `"none"` means no preset).
    ///
    /// # Errors
    /// A [`SpecError`] naming the first bad field or value.
    pub fn from_value(v: &Value) -> Result<Spec, SpecError> {
        let obj = v
            .as_object()
            .ok_or_else(|| SpecError::Json(format!("expected an object, got {}", shown(v))))?;
        if let Some(k) = obj.keys().find(|k| !SPEC_FIELDS.contains(&k.as_str())) {
            return Err(SpecError::UnknownField(k.clone()));
        }
        let name = match obj.get("name") {
            Some(Value::String(s)) => s.clone(),
            other => {
                return Err(field_error(
                    "name",
                    format!("one of {}", defs::names().join(", ")),
                    other.unwrap_or(&Value::Null),
                ))
            }
        };
        let def: &Definition = defs::find(&name).ok_or_else(|| SpecError::Name(name.clone()))?;
        let trials = match obj.get("trials") {
            None | Some(Value::Null) => def.default_trials,
            Some(v) => {
                let raw = scalar_text(v).unwrap_or_else(|| v.to_string());
                TRIALS.int_value(Some(&raw)).map_err(|e| SpecError::Field {
                    field: "trials".into(),
                    allowed: e.allowed,
                    got: e.value,
                })?
            }
        };
        let seed = match obj.get("seed") {
            None | Some(Value::Null) => config::Config::default().seed,
            Some(v @ (Value::String(_) | Value::Number(_))) => {
                let raw = scalar_text(v).expect("a scalar");
                let p = config::param("seed").expect("seed is a parameter");
                p.int_value(Some(&raw)).map_err(|e| SpecError::Field {
                    field: "seed".into(),
                    allowed: format!("{} (a decimal string)", e.allowed),
                    got: e.value,
                })?
            }
            Some(v) => return Err(field_error("seed", "an integer as a decimal string", v)),
        };
        let preset_allowed = || format!("one of {}, none, or null", Preset::NAMES.join(", "));
        let preset = match obj.get("preset") {
            None => def.default_preset,
            Some(Value::Null) => None,
            Some(Value::String(s)) if s == "none" => None,
            Some(v @ Value::String(s)) => {
                Some(Preset::parse(s).ok_or_else(|| field_error("preset", preset_allowed(), v))?)
            }
            Some(v) => return Err(field_error("preset", preset_allowed(), v)),
        };
        let params = params_of("params", "params", obj.get("params"))?;
        let sweep = sweep_of(obj.get("sweep"))?;
        let series = series_of(obj.get("series"))?;
        if !def.is_custom() {
            for (field, given) in [("sweep", sweep.is_some()), ("series", series.is_some())] {
                if given {
                    return Err(SpecError::Conflict(format!(
                        "{field} is for the custom experiment only; {name} defines its own"
                    )));
                }
            }
        }
        Ok(Spec {
            name,
            trials,
            seed,
            preset,
            params,
            sweep,
            series,
        })
    }

    /// The normalised spec as JSON text (compact): equal requests give equal bytes.
    pub fn to_text(&self) -> String {
        serde_json::to_string(self).expect("a spec serialises")
    }

    /// The experiment's definition.
    pub fn definition(&self) -> &'static Definition {
        defs::find(&self.name).expect("a spec names a defined experiment")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_fill_in_and_values_become_canonical() {
        let s = Spec::from_text(r#"{"name": "loops", "params": {"c": "2.50", "n": 30}}"#).unwrap();
        assert_eq!(s.trials, 100);
        assert_eq!(s.seed, 1);
        assert_eq!(s.preset, Some(DEFAULT_PRESET));
        assert_eq!(s.params["c"], "2.5");
        assert_eq!(s.params["n"], "30");
        let text = s.to_text();
        assert_eq!(
            text,
            r#"{"name":"loops","trials":100,"seed":"1","preset":"paper-code","params":{"c":"2.5","n":"30"},"sweep":null,"series":null}"#
        );
        // The normalised text reads back as itself.
        assert_eq!(Spec::from_text(&text).unwrap(), s);
        assert_eq!(
            Spec::from_text(r#"{"name":"priors","preset":null}"#)
                .unwrap()
                .preset,
            None
        );
        assert_eq!(
            Spec::from_text(r#"{"name":"priors"}"#).unwrap().trials,
            10_000
        );
        let big = Spec::from_text(r#"{"name":"delta","seed":"18446744073709551615"}"#).unwrap();
        assert_eq!(big.seed, u64::MAX);
    }

    #[test]
    fn bad_specs_name_the_field_and_value() {
        let err = |t: &str| Spec::from_text(t).unwrap_err().to_string();
        assert!(
            err(r#"{"name":"sigma"}"#).starts_with("experiment must be one of priors, sigma-sweep")
        );
        assert!(err(r#"{"name":"delta","trails":5}"#).contains("unknown field \"trails\""));
        assert_eq!(
            err(r#"{"name":"delta","trials":0}"#),
            "spec field trials must be an integer in 1..=100000000, got 0"
        );
        assert_eq!(
            err(r#"{"name":"delta","params":{"n":"2"}}"#),
            "n must be an integer in 3..=1024, got 2 (in params)"
        );
        assert!(err(r#"{"name":"delta","params":{"bogus":"2"}}"#)
            .starts_with("parameter must be one of n, prior"));
        assert!(err(r#"{"name":"delta","params":{"seed":"2"}}"#)
            .contains("seed is the spec's own field"));
        assert!(
            err(r#"{"name":"delta","sweep":{"key":"n","values":["10"]}}"#)
                .contains("custom experiment only")
        );
        assert!(
            err(r#"{"name":"custom","sweep":{"key":"mu","values":["1"]}}"#)
                .starts_with("mu must be a number in (1, 3], got 1 (in sweep)")
        );
        assert_eq!(
            err(r#"{"name":"custom","sweep":{"key":"n","values":["10","10.0"]}}"#),
            "n must be an integer in 3..=1024, got 10.0 (in sweep)"
        );
        assert!(
            err(r#"{"name":"custom","sweep":{"key":"c","values":["1","1.0"]}}"#)
                .contains("sweep value 1 of c is given twice")
        );
        assert!(err(
            r#"{"name":"custom","series":[{"label":"a","params":{}},{"label":"a","params":{}}]}"#
        )
        .contains("series label \"a\" is given twice"));
        assert!(err(r#"{"name":"delta","preset":"paper"}"#)
            .starts_with("spec field preset must be one of paper-text, paper-code, none, or null"));
        assert!(err("[1]").starts_with("the experiment spec is not a JSON object"));
        assert!(err("{").starts_with("the experiment spec is not a JSON object"));
    }
}
