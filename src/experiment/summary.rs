//! Per-point statistics of an experiment's rows.
//!
//! A capped trial keeps its cap as its steps and is counted in `capped`;
//! it is never dropped (dropping the failures would flatter a searcher).

use super::defs::{Kind, Metric};
use super::plan::{Plan, Point};
use super::run::{game_of, Row};
use crate::analysis::stats::{BoxStats, MeanCi};

/// The statistics of one point over the rows it has so far.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PointStats {
    /// A lower bound on the expected metric for any searcher, `None` when
    /// unknown (or for target samples).
    pub lower_bound: Option<f64>,
    /// Rows summarised.
    pub n: u64,
    /// Mean of the metric (NaN, written null, without rows).
    pub mean: f64,
    /// Sample standard deviation (n − 1).
    pub sd: f64,
    /// Lower end of the t-based 95% CI of the mean.
    pub ci_low: f64,
    /// Upper end of the t-based 95% CI of the mean.
    pub ci_high: f64,
    /// Median, quartiles, Tukey whiskers and range (written as flat
    /// fields: `median`, `q1`, `q3`, `whisker_low`, `whisker_high`, `min`,
    /// `max`).
    #[serde(flatten)]
    pub spread: BoxStats,
    /// Trials ended by the step cap (kept at the cap in every statistic).
    pub capped: u64,
    /// Trials that detected the target (every sample, for targets).
    pub found: u64,
    /// Episodes: the mean optimal steps.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_optimal: Option<f64>,
    /// Episodes: the mean of steps − optimal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub excess_mean: Option<f64>,
    /// Episodes: lower end of the 95% CI of the mean excess.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub excess_ci_low: Option<f64>,
    /// Episodes: upper end of the 95% CI of the mean excess.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub excess_ci_high: Option<f64>,
    /// Targets: samples per cell, `y * n + x`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub histogram: Option<Vec<u64>>,
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

/// The statistics of `point` over `rows` (all of them the point's).
pub fn point_stats(
    plan: &Plan,
    point: &Point,
    rows: &[Row],
    lower_bound: Option<f64>,
) -> PointStats {
    let values = MeanCi::of(rows.iter().map(|r| r.value as f64));
    let mut sorted: Vec<f64> = rows.iter().map(|r| r.value as f64).collect();
    sorted.sort_by(f64::total_cmp);
    let episodes = plan.header.kind == Kind::Episodes;
    let excess =
        episodes.then(|| MeanCi::of(rows.iter().map(|r| r.steps as f64 - r.optimal as f64)));
    let histogram = (!episodes).then(|| {
        let n = point.config.n as usize;
        let mut h = vec![0u64; n * n];
        for r in rows {
            h[r.target as usize] += 1;
        }
        h
    });
    PointStats {
        lower_bound,
        n: values.n,
        mean: values.mean,
        sd: values.sd,
        ci_low: values.lo,
        ci_high: values.hi,
        spread: BoxStats::of_sorted(&sorted),
        capped: rows.iter().filter(|r| !r.found).count() as u64,
        found: rows.iter().filter(|r| r.found).count() as u64,
        mean_optimal: episodes.then(|| MeanCi::of(rows.iter().map(|r| r.optimal as f64)).mean),
        excess_mean: excess.map(|e| e.mean),
        excess_ci_low: excess.map(|e| e.lo),
        excess_ci_high: excess.map(|e| e.hi),
        histogram,
    }
}
