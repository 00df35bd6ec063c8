//! Experiments: the paper's figures (and studies beyond them) as named
//! definitions that the CLI and the page run through the same code.
//!
//! * A [`Spec`] says what is asked (experiment, trials, seed, preset,
//!   overrides; a sweep and series for `custom`).
//! * A [`Plan`] resolves it: a header (axes, series, references) and the
//!   points, series × x values, each with its full validated configuration.
//! * Units `0..points × trials` are the work; unit u is trial `u / points`
//!   of point `u % points` (trial-major), and depends on (plan, u) only. [`run_units`]
//!   runs any range of them into [`Row`]s; a [`Shard`] is a contiguous range.
//! * A [`ResultSet`] holds a plan, a unit range and its rows; it gives the
//!   per-point statistics, the paired comparisons, the result JSON, the
//!   per-point, paired and per-trial CSVs. [`read`] checks a
//!   result JSON back; [`merge`] joins shards into the single-run result,
//!   byte for byte.
//!
//! Nothing here does I/O: the CLI writes the files, the facade hands the
//! text to the page.

mod defs;
mod output;
mod pairs;
mod plan;
pub mod provenance;
mod read;
mod result;
mod run;
mod spec;
mod summary;
mod tidy;

#[cfg(not(target_arch = "wasm32"))]
mod chart;

#[cfg(not(target_arch = "wasm32"))]
pub use chart::{png_stamped, svg, svg_stamped};

pub use defs::{
    series_style, Chart, Definition, Kind, Marker, Metric, SeriesStyle, COMMON_DEFAULTS,
    DEFINITIONS, PALETTE,
};
pub use output::{CSV_HEADER, PAIRED_CSV_HEADER};
pub use pairs::PairStats;
pub use plan::{common_base, Axis, Header, Plan, Point, PointView, Reference, YAxis, MAX_UNITS};
pub use provenance::Provenance;
pub use read::{merge, read, read_with_json, MergeError};
pub use result::{ResultError, ResultSet};
pub use result::{FORMAT, FORMAT_VERSION};
pub use run::{
    check_range, run_unit, run_units, run_units_clocked, RangeError, Row, Shard, MAX_SHARDS,
    ROW_FIELDS,
};
pub use spec::{
    canonical_param, SeriesSpec, Spec, SpecError, SweepSpec, DEFAULT_PRESET, SPEC_FIELDS,
};
pub use summary::{expected_optimal, PointStats};
pub use tidy::{varying, TRIALS_COLUMNS};

/// An experiment as the CLI's `--list` and the page's picker show it.
#[derive(Clone, Debug, serde::Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ExperimentInfo {
    /// Its name.
    pub name: &'static str,
    /// Its title.
    pub title: &'static str,
    /// What it shows.
    pub help: &'static str,
    /// `episodes` or `targets`.
    pub kind: Kind,
    /// Trials per point unless a spec says otherwise.
    pub default_trials: u64,
    /// The preset a spec without one gets (`None`: no preset).
    pub default_preset: Option<&'static str>,
}

/// Every named experiment.
pub fn list() -> Vec<ExperimentInfo> {
    DEFINITIONS
        .iter()
        .map(|d| ExperimentInfo {
            name: d.name,
            title: d.title,
            help: d.help,
            kind: d.kind,
            default_trials: d.default_trials,
            default_preset: d.default_preset.map(|p| p.name()),
        })
        .collect()
}

/// A plan as the page sees it: the normalised spec, the header, the points
/// with their configurations, the number of units and the row layout.
#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
pub struct PlanSummary<'a> {
    /// The normalised spec.
    pub spec: &'a Spec,
    /// The header.
    pub experiment: &'a Header,
    /// The points.
    pub points: Vec<PointView<'a>>,
    /// points × trials.
    pub total_units: u64,
    /// The numbers of each row, in order ([`ROW_FIELDS`]).
    pub row_fields: [&'static str; 7],
}

impl Plan {
    /// The plan as the page sees it.
    pub fn summary(&self) -> PlanSummary<'_> {
        PlanSummary {
            spec: &self.spec,
            experiment: &self.header,
            points: self.point_views(),
            total_units: self.total_units(),
            row_fields: ROW_FIELDS,
        }
    }

    /// Plans the spec in JSON text.
    ///
    /// # Errors
    /// A [`SpecError`] for a bad spec.
    pub fn from_spec_text(text: &str) -> Result<Plan, SpecError> {
        Plan::new(&Spec::from_text(text)?)
    }
}

impl ResultSet {
    /// The result of `rows` given as [`Row::fields`] numbers, concatenated
    /// (the facade's form), spanning the units they hold.
    ///
    /// # Errors
    /// A [`ResultError`] for a length that is not a multiple of the row
    /// size, a bad row, or a repeated one.
    pub fn from_flat(plan: Plan, flat: &[f64]) -> Result<ResultSet, ResultError> {
        let k = ROW_FIELDS.len();
        if flat.len() % k != 0 {
            return Err(ResultError::Field {
                field: "rows".into(),
                problem: format!("must hold {k} numbers per row, got {} numbers", flat.len()),
            });
        }
        let rows = flat
            .chunks(k)
            .enumerate()
            .map(|(index, f)| {
                Row::from_fields(f).ok_or_else(|| ResultError::Row {
                    index,
                    problem: format!(
                        "must be {k} integers ({}), got {f:?}",
                        ROW_FIELDS.join(", ")
                    ),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        ResultSet::spanning(plan, rows)
    }
}
