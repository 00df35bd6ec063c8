//! Per-point statistics of an experiment's rows.
//!
//! A capped trial keeps its cap as its steps and is counted in `capped`;
//! it is never dropped (dropping the failures would flatter a searcher).

use super::defs::{Kind, Metric};
use super::plan::{Plan, Point};
use super::run::{game_of, Row};
use crate::analysis::bootstrap::{bca_mean, bca_means};
use crate::analysis::interval::Interval;
use crate::analysis::median::median_interval;
use crate::analysis::stats::{BoxStats, MeanCi};

/// The statistics of one point over the rows it has so far.
///
/// In the result JSON the fields are, in order: `lower_bound`, `n`,
/// `mean` (an interval), `sd`, `median` (an interval), `q1`, `q3`,
/// `whisker_low`, `whisker_high`, `min`, `max`, `capped`, `found`, and for
/// episodes `mean_optimal` and `excess_mean` (an interval), for targets
/// `histogram`. An interval is `{estimate, lo, hi, level, method}`.
#[derive(Clone, Debug, PartialEq)]
pub struct PointStats {
    /// A lower bound on the expected metric for any searcher, `None` when
    /// unknown (or for target samples).
    pub lower_bound: Option<f64>,
    /// Rows summarised.
    pub n: u64,
    /// Mean of the metric with its bootstrap interval (NaN, written null,
    /// without rows).
    pub mean: Interval,
    /// Sample standard deviation (n − 1).
    pub sd: f64,
    /// Median of the metric with its order-statistic interval.
    pub median: Interval,
    /// Quartiles, Tukey whiskers and range (its median is `median`'s
    /// estimate).
    pub spread: BoxStats,
    /// Trials ended by the step cap (kept at the cap in every statistic).
    pub capped: u64,
    /// Trials that detected the target (every sample, for targets).
    pub found: u64,
    /// Episodes: the mean optimal steps.
    pub mean_optimal: Option<f64>,
    /// Episodes: the mean of steps − optimal, with its bootstrap interval.
    pub excess_mean: Option<Interval>,
    /// Targets: samples per cell, `y * n + x`.
    pub histogram: Option<Vec<u64>>,
}

impl serde::Serialize for PointStats {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct Flat<'a> {
            lower_bound: Option<f64>,
            n: u64,
            mean: Interval,
            sd: f64,
            median: Interval,
            q1: f64,
            q3: f64,
            whisker_low: f64,
            whisker_high: f64,
            min: f64,
            max: f64,
            capped: u64,
            found: u64,
            #[serde(skip_serializing_if = "Option::is_none")]
            mean_optimal: Option<f64>,
            #[serde(skip_serializing_if = "Option::is_none")]
            excess_mean: Option<Interval>,
            #[serde(skip_serializing_if = "Option::is_none")]
            histogram: Option<&'a [u64]>,
        }
        let b = &self.spread;
        Flat {
            lower_bound: self.lower_bound,
            n: self.n,
            mean: self.mean,
            sd: self.sd,
            median: self.median,
            q1: b.q1,
            q3: b.q3,
            whisker_low: b.whisker_low,
            whisker_high: b.whisker_high,
            min: b.min,
            max: b.max,
            capped: self.capped,
            found: self.found,
            mean_optimal: self.mean_optimal,
            excess_mean: self.excess_mean,
            histogram: self.histogram.as_deref(),
        }
        .serialize(s)
    }
}

/// A lower bound on the expected metric of `point` for any searcher:
/// `bound::lower_bound` for steps; for the excess, that bound minus the
/// exact expected optimal steps under the prior (E[steps − optimal] =
/// E[steps] − E[optimal]). `None` when the bound is not finite.
pub fn lower_bound(plan: &Plan, point: &Point) -> Option<f64> {
    if plan.header.kind != Kind::Episodes {
        return None;
    }
    let cfg = &point.config;
    let lb = crate::analysis::bound::lower_bound(cfg)
        .ok()
        .filter(|b| b.is_finite())?;
    match plan.header.metric {
        Metric::Excess => Some(lb - expected_optimal(cfg)),
        _ => Some(lb),
    }
}

/// The exact mean optimal steps when the target is drawn from the prior.
pub fn expected_optimal(cfg: &crate::config::Config) -> f64 {
    let crate::config::Game {
        torus,
        sensor,
        prior,
        start,
    } = game_of(cfg);
    prior
        .mass()
        .iter()
        .enumerate()
        .filter(|(_, &m)| m > 0.0)
        .map(|(c, &m)| m * sensor.optimal_steps(&torus, start, c as u32) as f64)
        .sum()
}

/// The statistics of `point` over `rows` (all of them the point's, in
/// trial order: the intervals' resampling is seeded by the values in order).
pub fn point_stats(
    plan: &Plan,
    point: &Point,
    rows: &[Row],
    lower_bound: Option<f64>,
) -> PointStats {
    let values: Vec<f64> = rows.iter().map(|r| r.value as f64).collect();
    let mut sorted = values.clone();
    sorted.sort_by(f64::total_cmp);
    let episodes = plan.header.kind == Kind::Episodes;
    let excess: Vec<f64> = rows
        .iter()
        .map(|r| r.steps as f64 - r.optimal as f64)
        .collect();
    let histogram = (!episodes).then(|| {
        let n = point.config.n as usize;
        let mut h = vec![0u64; n * n];
        for r in rows {
            h[r.target as usize] += 1;
        }
        h
    });
    // Episodes: the metric and the excess from the same resamples.
    let (mean, excess_mean) = if episodes {
        let both = bca_means(&[&values, &excess]);
        (both[0], Some(both[1]))
    } else {
        (bca_mean(&values), None)
    };
    PointStats {
        lower_bound,
        n: values.len() as u64,
        mean,
        sd: MeanCi::of(values.iter().copied()).sd,
        median: median_interval(&sorted),
        spread: BoxStats::of_sorted(&sorted),
        capped: rows.iter().filter(|r| !r.found).count() as u64,
        found: rows.iter().filter(|r| r.found).count() as u64,
        mean_optimal: episodes.then(|| MeanCi::of(rows.iter().map(|r| r.optimal as f64)).mean),
        excess_mean,
        histogram,
    }
}
