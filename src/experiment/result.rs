//! A result: a plan, the unit range it covers, and the rows of those units,
//! checked against the plan. Its statistics and files come from here only.

use super::defs::Kind;
use super::plan::Plan;
use super::run::{centre, check_range, Row};
use super::spec::SpecError;
use super::summary::{self, PointStats};
use crate::game::lattice::Torus;
use std::fmt;

/// The `format` field of a result file.
pub const FORMAT: &str = "torus-search-experiment";
/// The `format_version` this build writes and reads. Version 2: intervals
/// as `{estimate, lo, hi, level, method}` objects from the bootstrap and
/// order statistics (version 1 had t-intervals as `ci_low`, `ci_high`), and
/// the paired comparisons (`paired`).
pub const FORMAT_VERSION: u64 = 2;

/// A result (or a result file) that cannot be used, with what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub enum ResultError {
    /// The text is not JSON.
    Json(String),
    /// JSON, but not an experiment result of this program.
    Foreign(String),
    /// A format version this build does not read.
    FormatVersion(String),
    /// Made by another version of the program.
    Version(String),
    /// A field missing or of the wrong kind.
    Field {
        /// The field, e.g. `units.from`.
        field: String,
        /// What is wrong with it.
        problem: String,
    },
    /// The spec inside does not plan here.
    Spec(SpecError),
    /// A part that disagrees with what the spec plans.
    Mismatch(String),
    /// A unit range that does not fit.
    Units(String),
    /// A row that does not fit the plan or its range.
    Row {
        /// Its position among the rows.
        index: usize,
        /// What is wrong with it.
        problem: String,
    },
}

impl fmt::Display for ResultError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ResultError::Json(e) => write!(f, "not JSON: {e}"),
            ResultError::Foreign(what) => {
                write!(f, "not a torus-search experiment result ({what})")
            }
            ResultError::FormatVersion(v) => write!(
                f,
                "format_version {v} is not supported (this build reads format_version {}): rerun the experiment with this build",
                FORMAT_VERSION
            ),
            ResultError::Version(v) => write!(
                f,
                "made by torus-search {v}, but this is {}: another version may give other results, so rerun it with this one",
                env!("CARGO_PKG_VERSION")
            ),
            ResultError::Field { field, problem } => write!(f, "field {field} {problem}"),
            ResultError::Spec(e) => write!(f, "its spec does not plan here: {e}"),
            ResultError::Mismatch(what) => write!(
                f,
                "{what} does not match what its spec plans (the file was edited, or made by another build)"
            ),
            ResultError::Units(m) => f.write_str(m),
            ResultError::Row { index, problem } => write!(f, "rows[{index}] {problem}"),
        }
    }
}

impl std::error::Error for ResultError {}

/// Rows of units `from..to` of a plan, sorted by unit, each checked.
#[derive(Clone, Debug, PartialEq)]
pub struct ResultSet {
    /// The plan.
    pub plan: Plan,
    /// The first unit covered.
    pub from: u64,
    /// One past the last unit covered.
    pub to: u64,
    /// The rows, sorted by unit, at most one per unit.
    pub rows: Vec<Row>,
}

/// Why `row` cannot be a row of `plan`, if it cannot.
fn row_problem(plan: &Plan, row: &Row) -> Option<String> {
    let Some(point) = plan.points.get(row.point as usize) else {
        return Some(format!(
            "names point {} but the plan has {} points",
            row.point,
            plan.points.len()
        ));
    };
    if row.trial >= plan.trials() {
        return Some(format!(
            "names trial {} but points have {} trials",
            row.trial,
            plan.trials()
        ));
    }
    let cfg = &point.config;
    let cells = cfg.n as u64 * cfg.n as u64;
    if row.target as u64 >= cells {
        return Some(format!(
            "has target cell {} outside the {}×{} lattice",
            row.target, cfg.n, cfg.n
        ));
    }
    let want = match plan.header.kind {
        Kind::Episodes => {
            if row.steps > cfg.step_cap || (!row.found && row.steps != cfg.step_cap) {
                return Some(format!(
                    "has {} steps, {}, with step cap {}",
                    row.steps,
                    if row.found { "found" } else { "capped" },
                    cfg.step_cap
                ));
            }
            if row.optimal > cfg.n {
                return Some(format!("has optimal {} > N = {}", row.optimal, cfg.n));
            }
            Row::metric(plan.header.metric, row.steps, row.optimal)
        }
        Kind::Targets => {
            if row.steps != 0 || row.optimal != 0 || !row.found {
                return Some("is a target sample with steps or optimal set, or not found".into());
            }
            let torus = Torus::new(cfg.n).expect("plan configs are validated");
            torus.l1(centre(&torus), row.target) as i64
        }
    };
    (row.value != want).then(|| format!("has value {} but its numbers give {want}", row.value))
}

impl ResultSet {
    /// The rows of units `from..to` (any order, any subset of the range).
    ///
    /// # Errors
    /// A [`ResultError`] for a range that does not fit the plan, or a row
    /// outside it, repeated, or inconsistent with its point.
    pub fn new(
        plan: Plan,
        from: u64,
        to: u64,
        mut rows: Vec<Row>,
    ) -> Result<ResultSet, ResultError> {
        check_range(&plan, from, to).map_err(|e| ResultError::Units(e.to_string()))?;
        let points = plan.points.len() as u64;
        for (index, row) in rows.iter().enumerate() {
            if let Some(problem) = row_problem(&plan, row) {
                return Err(ResultError::Row { index, problem });
            }
            let u = row.unit(points);
            if !(from..to).contains(&u) {
                return Err(ResultError::Row {
                    index,
                    problem: format!(
                        "is unit {u}, outside the units {from}..{to} the result covers"
                    ),
                });
            }
        }
        rows.sort_by_key(|r| r.unit(points));
        if let Some(w) = rows
            .windows(2)
            .find(|w| w[0].unit(points) == w[1].unit(points))
        {
            return Err(ResultError::Units(format!(
                "unit {} (point {}, trial {}) has two rows",
                w[0].unit(points),
                w[0].point,
                w[0].trial
            )));
        }
        Ok(ResultSet {
            plan,
            from,
            to,
            rows,
        })
    }

    /// The rows given, covering the units from the least to the greatest
    /// (nothing when there are none): a live snapshot of a run.
    ///
    /// # Errors
    /// As [`ResultSet::new`].
    pub fn spanning(plan: Plan, rows: Vec<Row>) -> Result<ResultSet, ResultError> {
        let points = plan.points.len() as u64;
        let total = plan.total_units();
        let units = rows.iter().map(|r| r.unit(points).min(total));
        let (from, to) = match (units.clone().min(), units.max()) {
            (Some(a), Some(b)) => (a, (b + 1).min(total)),
            _ => (0, 0),
        };
        ResultSet::new(plan, from, to, rows)
    }

    /// True when every unit of the range has its row.
    pub fn is_complete(&self) -> bool {
        self.rows.len() as u64 == self.to - self.from
    }

    /// The first unit of the range without a row, if any.
    pub fn first_missing(&self) -> Option<u64> {
        let points = self.plan.points.len() as u64;
        (self.from..self.to)
            .zip(
                self.rows
                    .iter()
                    .map(|r| r.unit(points))
                    .chain(std::iter::repeat(u64::MAX)),
            )
            .find(|(want, got)| want != got)
            .map(|(want, _)| want)
    }

    /// The rows of each point, in trial order (the rows are stored by
    /// unit, which interleaves the points).
    pub fn rows_by_point(&self) -> Vec<Vec<Row>> {
        let mut out = vec![Vec::new(); self.plan.points.len()];
        for r in &self.rows {
            out[r.point as usize].push(*r);
        }
        out
    }

    /// Each point's statistics over the rows present.
    pub fn stats(&self) -> Vec<PointStats> {
        self.plan
            .points
            .iter()
            .zip(self.rows_by_point())
            .map(|(point, mine)| {
                let lb = summary::lower_bound(&self.plan, point);
                summary::point_stats(&self.plan, point, &mine, lb)
            })
            .collect()
    }
}
