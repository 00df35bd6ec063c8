//! Reading a result JSON back, and merging shards into the single-run result.
//!
//! Reading trusts nothing in the file but its spec and rows: the spec is
//! planned again, and the header, the point configurations and the
//! statistics written in the file must agree with what this build derives
//! from them.

use super::plan::Plan;
use super::result::{ResultError, ResultSet};
use super::result::{FORMAT, FORMAT_VERSION};
use super::run::{Row, ROW_FIELDS};
use super::spec::Spec;
use serde_json::Value;
use std::fmt;

fn shown(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s
    }
}

/// Equal as JSON, numbers within a relative 1e-12 (a file re-saved by
/// another JSON writer may respell a number).
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => x == y || (x - y).abs() <= 1e-12 * x.abs().max(y.abs()),
            _ => x == y,
        },
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same(a, b))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

/// The path of the first difference between `a` and `b` below `path`.
fn first_difference(path: &str, a: &Value, b: &Value) -> String {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, v) in x {
                match y.get(k) {
                    Some(w) if same(v, w) => {}
                    Some(w) => return first_difference(&format!("{path}.{k}"), v, w),
                    None => return format!("{path}.{k}"),
                }
            }
            match y.keys().find(|k| !x.contains_key(*k)) {
                Some(k) => format!("{path}.{k}"),
                None => path.to_string(),
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .find(|(_, (v, w))| !same(v, w))
            .map_or_else(
                || path.to_string(),
                |(i, (v, w))| first_difference(&format!("{path}[{i}]"), v, w),
            ),
        _ => path.to_string(),
    }
}

fn field<'a>(
    obj: &'a serde_json::Map<String, Value>,
    name: &str,
) -> Result<&'a Value, ResultError> {
    obj.get(name).ok_or_else(|| ResultError::Field {
        field: name.into(),
        problem: "is missing".into(),
    })
}

fn unsigned(v: &Value, name: &str) -> Result<u64, ResultError> {
    v.as_u64().ok_or_else(|| ResultError::Field {
        field: name.into(),
        problem: format!("must be a non-negative integer, got {}", shown(v)),
    })
}

/// Reads and checks a result JSON.
///
/// # Errors
/// A [`ResultError`] saying what in the text is wrong: not JSON, another
/// format or version, a spec that does not plan, a header, configuration or
/// statistic that disagrees with the spec and rows, a bad unit range, or a
/// bad, misplaced or repeated row.
pub fn read(text: &str) -> Result<ResultSet, ResultError> {
    read_with_json(text).map(|(set, _)| set)
}

/// [`read`], with the result's JSON as this build writes it (computed to
/// check the file's statistics, so a caller that wants it pays once).
///
/// # Errors
/// As [`read`].
pub fn read_with_json(text: &str) -> Result<(ResultSet, String), ResultError> {
    let v: Value = serde_json::from_str(text).map_err(|e| {
        ResultError::Json(if e.is_eof() {
            format!("{e}: the text ends early, so the file is truncated (an interrupted write or copy?)")
        } else {
            e.to_string()
        })
    })?;
    let obj = v
        .as_object()
        .ok_or_else(|| ResultError::Foreign(format!("the top level is {}", shown(&v))))?;
    match obj.get("format") {
        Some(Value::String(f)) if f == FORMAT => {}
        Some(other) => {
            return Err(ResultError::Foreign(format!(
                "its format is {}",
                shown(other)
            )))
        }
        None => return Err(ResultError::Foreign("it has no format field".into())),
    }
    let fv = field(obj, "format_version")?;
    if fv.as_u64() != Some(FORMAT_VERSION) {
        return Err(ResultError::FormatVersion(shown(fv)));
    }
    match field(obj, "version")? {
        Value::String(s) if s == env!("CARGO_PKG_VERSION") => {}
        Value::String(s) => return Err(ResultError::Version(s.clone())),
        other => return Err(ResultError::Version(shown(other))),
    }
    let spec = Spec::from_value(field(obj, "spec")?).map_err(ResultError::Spec)?;
    let plan = Plan::new(&spec).map_err(ResultError::Spec)?;
    let header = serde_json::to_value(&plan.header).expect("a header serialises");
    let theirs = field(obj, "experiment")?;
    if !same(theirs, &header) {
        return Err(ResultError::Mismatch(format!(
            "the experiment header ({})",
            first_difference("experiment", theirs, &header)
        )));
    }
    let units = field(obj, "units")?
        .as_object()
        .ok_or_else(|| ResultError::Field {
            field: "units".into(),
            problem: "must be an object {total, from, to}".into(),
        })?;
    let unit = |k: &str| {
        units
            .get(k)
            .ok_or_else(|| ResultError::Field {
                field: format!("units.{k}"),
                problem: "is missing".into(),
            })
            .and_then(|v| unsigned(v, &format!("units.{k}")))
    };
    let (total, from, to) = (unit("total")?, unit("from")?, unit("to")?);
    if total != plan.total_units() {
        return Err(ResultError::Units(format!(
            "units.total is {total} but the spec plans {} units ({} points × {} trials)",
            plan.total_units(),
            plan.points.len(),
            plan.trials()
        )));
    }
    let raw_rows = field(obj, "rows")?
        .as_array()
        .ok_or_else(|| ResultError::Field {
            field: "rows".into(),
            problem: "must be a list".into(),
        })?;
    let mut rows = Vec::with_capacity(raw_rows.len());
    for (index, r) in raw_rows.iter().enumerate() {
        let nums: Option<Vec<f64>> = r.as_array().and_then(|a| {
            a.iter()
                .map(|x| {
                    x.as_i64()
                        .map(|i| i as f64)
                        .or_else(|| x.as_u64().map(|u| u as f64))
                })
                .collect()
        });
        let row = nums
            .as_deref()
            .and_then(Row::from_fields)
            .ok_or_else(|| ResultError::Row {
                index,
                problem: format!(
                    "must be [{}] as integers, got {}",
                    ROW_FIELDS.join(", "),
                    shown(r)
                ),
            })?;
        rows.push(row);
    }
    let set = ResultSet::new(plan, from, to, rows)?;
    let json = set.to_json();
    let mine: Value = serde_json::from_str(&json).expect("our JSON parses");
    for part in ["points", "paired"] {
        let theirs = field(obj, part)?;
        if !same(theirs, &mine[part]) {
            return Err(ResultError::Mismatch(
                first_difference(part, theirs, &mine[part])
                    + " (statistics are derived from the rows)",
            ));
        }
    }
    Ok((set, json))
}

/// A merge that cannot be made: the file at fault (if one is) and why.
#[derive(Clone, Debug, PartialEq)]
pub struct MergeError {
    /// The offending file's name, as given.
    pub file: Option<String>,
    /// What is wrong.
    pub problem: String,
}

impl fmt::Display for MergeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{file}: {}", self.problem),
            None => f.write_str(&self.problem),
        }
    }
}

impl std::error::Error for MergeError {}

/// The first field in which two normalised specs differ, as "field a vs b".
fn spec_difference(a: &Spec, b: &Spec) -> String {
    let (x, y) = (
        serde_json::to_value(a).expect("a spec serialises"),
        serde_json::to_value(b).expect("a spec serialises"),
    );
    let path = first_difference("spec", &x, &y);
    let at = |v: &Value| {
        path.trim_start_matches("spec")
            .split('.')
            .filter(|s| !s.is_empty())
            .try_fold(v, |v, k| v.get(k))
            .map_or_else(|| "absent".to_string(), shown)
    };
    format!("{path} is {} there, {} here", at(&x), at(&y))
}

/// Merges complete shard results `(file name, text)` of one spec into the
/// result of all units, which is byte for byte the single run's.
///
/// # Errors
/// A [`MergeError`] naming the file that cannot be read, is partial, has
/// another spec, or overlaps another; or the units no file covers.
pub fn merge(files: &[(&str, &str)]) -> Result<ResultSet, MergeError> {
    let mut sets: Vec<(&str, ResultSet)> = Vec::with_capacity(files.len());
    for &(name, text) in files {
        let fail = |problem: String| MergeError {
            file: Some(name.to_string()),
            problem,
        };
        let set = read(text).map_err(|e| fail(e.to_string()))?;
        if let Some(u) = set.first_missing() {
            return Err(fail(format!(
                "covers units {}..{} but has no row for unit {u}: a partial result cannot be merged",
                set.from, set.to
            )));
        }
        if let Some((first, s)) = sets.first() {
            if s.plan.spec.to_text() != set.plan.spec.to_text() {
                return Err(fail(format!(
                    "its spec differs from {first}'s ({})",
                    spec_difference(&s.plan.spec, &set.plan.spec)
                )));
            }
        }
        sets.push((name, set));
    }
    let Some((_, first)) = sets.first() else {
        return Err(MergeError {
            file: None,
            problem: "no result files to merge".into(),
        });
    };
    let plan = first.plan.clone();
    let total = plan.total_units();
    let mut order: Vec<&(&str, ResultSet)> = sets.iter().filter(|(_, s)| s.from < s.to).collect();
    order.sort_by_key(|(_, s)| (s.from, s.to));
    let mut covered = 0u64;
    let mut last: Option<&(&str, ResultSet)> = None;
    for item in &order {
        let (name, s) = item;
        if s.from < covered {
            let (prev, p) = last.expect("covered > 0 follows a file");
            return Err(MergeError {
                file: Some(name.to_string()),
                problem: format!(
                    "its units {}..{} overlap {prev}'s units {}..{}",
                    s.from, s.to, p.from, p.to
                ),
            });
        }
        if s.from > covered {
            return Err(missing(covered, s.from, total));
        }
        covered = s.to;
        last = Some(item);
    }
    if covered < total {
        return Err(missing(covered, total, total));
    }
    let rows = sets.into_iter().flat_map(|(_, s)| s.rows).collect();
    ResultSet::new(plan, 0, total, rows).map_err(|e| MergeError {
        file: None,
        problem: e.to_string(),
    })
}

fn missing(from: u64, to: u64, total: u64) -> MergeError {
    MergeError {
        file: None,
        problem: format!(
            "units {from}..{to} of 0..{total} are in none of the files (a shard is missing)"
        ),
    }
}
