//! A result as text: the result JSON and the per-point CSV.
//!
//! The JSON holds nothing about how the run went (no timings, no thread
//! counts), so the merge of shards is byte for byte the single run.
//! Non-finite numbers (a mean without rows, an unknown bound) are `null`.

use super::plan::{Header, PointView};
use super::provenance::Provenance;
use super::result::{ResultSet, FORMAT, FORMAT_VERSION};
use super::run::{Row, ROW_FIELDS};
use super::spec::Spec;
use super::summary::PointStats;

impl serde::Serialize for Row {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        (
            self.point,
            self.trial,
            self.steps,
            self.optimal,
            self.found as u8,
            self.target,
            self.value,
        )
            .serialize(s)
    }
}

#[derive(serde::Serialize)]
struct Units {
    total: u64,
    from: u64,
    to: u64,
}

#[derive(serde::Serialize)]
struct PointOut<'a> {
    #[serde(flatten)]
    view: PointView<'a>,
    #[serde(flatten)]
    stats: PointStats,
}

#[derive(serde::Serialize)]
struct Out<'a> {
    format: &'static str,
    format_version: u64,
    version: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    provenance: Option<&'a Provenance>,
    spec: &'a Spec,
    experiment: &'a Header,
    units: Units,
    row_fields: [&'static str; 7],
    points: Vec<PointOut<'a>>,
    rows: &'a [Row],
}

impl ResultSet {
    /// The result JSON (compact, one line), without provenance: the bytes
    /// that compare equal (shards merged and one run; the page and the CLI).
    pub fn to_json(&self) -> String {
        self.json_with(None)
    }

    /// The result JSON, with `provenance` after `version` when given.
    pub(super) fn json_with(&self, provenance: Option<&Provenance>) -> String {
        let points = self
            .plan
            .point_views()
            .into_iter()
            .zip(self.stats())
            .map(|(view, stats)| PointOut { view, stats })
            .collect();
        serde_json::to_string(&Out {
            format: FORMAT,
            format_version: FORMAT_VERSION,
            version: env!("CARGO_PKG_VERSION"),
            provenance,
            spec: &self.plan.spec,
            experiment: &self.plan.header,
            units: Units {
                total: self.plan.total_units(),
                from: self.from,
                to: self.to,
            },
            row_fields: ROW_FIELDS,
            points,
            rows: &self.rows,
        })
        .expect("a result serialises")
    }

    /// One CSV line per point with its statistics, after a header line.
    pub fn csv(&self) -> String {
        let mut out = String::from(CSV_HEADER);
        out.push('\n');
        for (p, s) in self.plan.points.iter().zip(self.stats()) {
            let num = |v: f64| {
                if v.is_finite() {
                    v.to_string()
                } else {
                    String::new()
                }
            };
            let opt = |v: Option<f64>| v.map_or_else(String::new, num);
            let fields = [
                p.index.to_string(),
                quote(self.plan.series_label(p)),
                quote(self.plan.x_text(p)),
                s.n.to_string(),
                num(s.mean),
                num(s.sd),
                num(s.ci_low),
                num(s.ci_high),
                num(s.spread.median),
                num(s.spread.q1),
                num(s.spread.q3),
                num(s.spread.whisker_low),
                num(s.spread.whisker_high),
                num(s.spread.min),
                num(s.spread.max),
                s.capped.to_string(),
                s.found.to_string(),
                opt(s.lower_bound),
                opt(s.mean_optimal),
                opt(s.excess_mean),
                opt(s.excess_ci_low),
                opt(s.excess_ci_high),
            ];
            out.push_str(&fields.join(","));
            out.push('\n');
        }
        out
    }
}

/// The CSV's header line.
pub const CSV_HEADER: &str = "index,series,x,n,mean,sd,ci_low,ci_high,median,q1,q3,whisker_low,whisker_high,min,max,capped,found,lower_bound,mean_optimal,excess_mean,excess_ci_low,excess_ci_high";

/// A CSV text field: always quoted, inner quotes doubled (RFC 4180).
fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}
