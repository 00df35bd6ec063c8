//! The paired comparisons of an experiment: for each pair of series its
//! plan names, at each x value, the per-trial difference of the metric.
//!
//! Every point keeps the spec's seed, so trial i of two series at one x
//! value draws the same target (common random numbers, unless a series
//! changes the prior): their difference trial by trial is free of the
//! target's noise, which the two points' own intervals both carry.

use super::result::ResultSet;
use crate::analysis::paired::{paired, Paired, PairedTrial};

/// One series against a reference at one x value.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PairStats {
    /// The series' label.
    pub series: String,
    /// The reference series' label.
    pub reference: String,
    /// The x value (parameter text; empty with one x value).
    pub x: String,
    /// The series' point.
    pub point: usize,
    /// The reference's point.
    pub reference_point: usize,
    /// `n`, `difference` (series − reference, an interval), `wins`,
    /// `ties`, `losses` (trials where the series' value is lower, equal,
    /// higher) and `same_target`.
    #[serde(flatten)]
    pub paired: Paired,
}

impl ResultSet {
    /// Every paired comparison of the plan over the rows present: pair by
    /// pair, each at every x value in order.
    pub fn paired(&self) -> Vec<PairStats> {
        let by_point: Vec<Vec<PairedTrial>> = self
            .rows_by_point()
            .into_iter()
            .map(|rows| {
                rows.iter()
                    .map(|r| PairedTrial {
                        trial: r.trial,
                        value: r.value as f64,
                        target: r.target,
                    })
                    .collect()
            })
            .collect();
        let header = &self.plan.header;
        let xs = header.x.values.len();
        let mut out = Vec::with_capacity(self.plan.pairs.len() * xs);
        for &(a, b) in &self.plan.pairs {
            for (x, text) in header.x.values.iter().enumerate() {
                // Points are series-major.
                let (pa, pb) = (a * xs + x, b * xs + x);
                out.push(PairStats {
                    series: header.series[a].clone(),
                    reference: header.series[b].clone(),
                    x: text.clone(),
                    point: pa,
                    reference_point: pb,
                    paired: paired(&by_point[pa], &by_point[pb]),
                });
            }
        }
        out
    }
}
