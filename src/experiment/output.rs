//! A result as text: the result JSON, the per-point CSV and the paired
//! comparisons' CSV (the per-trial CSV is `tidy.rs`'s).
//!
//! The JSON holds nothing about how the run went (no timings, no thread
//! counts), so the merge of shards is byte for byte the single run.
//! Non-finite numbers (a mean without rows, an unknown bound) are `null`
//! in JSON and empty in CSV. A CSV flattens an interval field `f` into the
//! columns `f`, `f_lo`, `f_hi` (the estimate and the ends; every interval is
//! 95%, its method fixed by the field: see EXPERIMENTS.md).

use super::pairs::PairStats;
use super::plan::{Header, PointView};
use super::provenance::Provenance;
use super::result::{ResultSet, FORMAT, FORMAT_VERSION};
use super::run::{Row, ROW_FIELDS};
use super::spec::Spec;
use super::summary::PointStats;
use crate::analysis::interval::Interval;

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
    paired: Vec<PairStats>,
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
            paired: self.paired(),
            rows: &self.rows,
        })
        .expect("a result serialises")
    }

    /// One CSV line per point with its statistics, after a header line
    /// ([`CSV_HEADER`]).
    pub fn csv(&self) -> String {
        let mut out = String::from(CSV_HEADER);
        out.push('\n');
        for (p, s) in self.plan.points.iter().zip(self.stats()) {
            let opt = |v: Option<f64>| v.map_or_else(String::new, num);
            let b = &s.spread;
            let mut fields = vec![
                p.index.to_string(),
                quote(self.plan.series_label(p)),
                quote(self.plan.x_text(p)),
                s.n.to_string(),
            ];
            fields.extend(interval_fields(Some(&s.mean)));
            fields.push(num(s.sd));
            fields.extend(interval_fields(Some(&s.median)));
            fields.extend([b.q1, b.q3, b.whisker_low, b.whisker_high, b.min, b.max].map(num));
            fields.extend([
                s.capped.to_string(),
                s.found.to_string(),
                opt(s.lower_bound),
                opt(s.mean_optimal),
            ]);
            fields.extend(interval_fields(s.excess_mean.as_ref()));
            out.push_str(&fields.join(","));
            out.push('\n');
        }
        out
    }

    /// One CSV line per paired comparison ([`ResultSet::paired`]), after a
    /// header line ([`PAIRED_CSV_HEADER`]).
    pub fn paired_csv(&self) -> String {
        let mut out = String::from(PAIRED_CSV_HEADER);
        out.push('\n');
        for c in self.paired() {
            let q = &c.paired;
            let mut fields = vec![
                quote(&c.series),
                quote(&c.reference),
                quote(&c.x),
                c.point.to_string(),
                c.reference_point.to_string(),
                q.n.to_string(),
            ];
            fields.extend(interval_fields(Some(&q.difference)));
            fields.extend([q.wins, q.ties, q.losses, q.same_target].map(|v| v.to_string()));
            out.push_str(&fields.join(","));
            out.push('\n');
        }
        out
    }
}

/// The per-point CSV's header line.
pub const CSV_HEADER: &str = "index,series,x,n,mean,mean_lo,mean_hi,sd,median,median_lo,median_hi,q1,q3,whisker_low,whisker_high,min,max,capped,found,lower_bound,mean_optimal,excess_mean,excess_mean_lo,excess_mean_hi";

/// The paired comparisons' CSV header line.
pub const PAIRED_CSV_HEADER: &str = "series,reference,x,point,reference_point,n,difference,difference_lo,difference_hi,wins,ties,losses,same_target";

/// A number for a CSV field: empty when not finite.
pub(super) fn num(v: f64) -> String {
    if v.is_finite() {
        v.to_string()
    } else {
        String::new()
    }
}

/// An interval's estimate and ends as three CSV fields (three empty ones
/// for none).
fn interval_fields(i: Option<&Interval>) -> [String; 3] {
    match i {
        Some(i) => [num(i.estimate), num(i.lo), num(i.hi)],
        None => Default::default(),
    }
}

/// A CSV text field: always quoted, inner quotes doubled (RFC 4180).
pub(super) fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}
