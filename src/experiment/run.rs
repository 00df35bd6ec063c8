//! Units and rows: the flat numbering of an experiment's work, a shard's
//! slice of it, and running units into rows.
//!
//! Unit u is trial `u / points` of point `u % points`: trial-major, so
//! that any contiguous range (a shard, a worker's chunk, the first units of
//! a live run) holds every point, and shards of an experiment whose points
//! differ a hundredfold in cost still take about the same time. A unit
//! depends only on (plan, u), so any split (threads, Web Workers, cluster
//! shards) gives the same rows.

use super::defs::{Kind, Metric};
use super::plan::Plan;
use crate::game::lattice::Torus;
use crate::game::rng;
use crate::run::episode::Episode;
use std::fmt;

/// The numbers of a row, in order: what [`Row::fields`] gives and the
/// facade's `experimentRun` returns, `ROW_FIELDS.len()` numbers per row.
///
/// For a targets experiment (`priors`) steps and optimal are 0, found is 1,
/// target is the sampled cell and value its ℓ1 distance from the prior's
/// centre cell.
pub const ROW_FIELDS: [&str; 7] = [
    "point", "trial", "steps", "optimal", "found", "target", "value",
];

/// What one unit gave.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Row {
    /// The point.
    pub point: u32,
    /// The trial within the point.
    pub trial: u64,
    /// Real moves made (the step cap for a capped trial).
    pub steps: u32,
    /// Fewest moves that would have detected the target.
    pub optimal: u32,
    /// False for a capped trial.
    pub found: bool,
    /// The target cell, `y * n + x`.
    pub target: u32,
    /// The experiment's metric for this row.
    pub value: i64,
}

impl Row {
    /// The unit this row is, in a plan of `points` points.
    pub fn unit(&self, points: u64) -> u64 {
        self.trial * points + self.point as u64
    }

    /// The row as numbers, in [`ROW_FIELDS`] order.
    pub fn fields(&self) -> [f64; 7] {
        [
            self.point as f64,
            self.trial as f64,
            self.steps as f64,
            self.optimal as f64,
            self.found as u8 as f64,
            self.target as f64,
            self.value as f64,
        ]
    }

    /// Reads [`Row::fields`] back; `None` unless each number is an integer
    /// in its field's range (the value may be negative).
    pub fn from_fields(f: &[f64]) -> Option<Row> {
        if f.len() != ROW_FIELDS.len() {
            return None;
        }
        let int = |v: f64, lo: f64, hi: f64| (v >= lo && v <= hi && v.fract() == 0.0).then_some(v);
        let u32max = u32::MAX as f64;
        let u53 = (1u64 << 53) as f64;
        Some(Row {
            point: int(f[0], 0.0, u32max)? as u32,
            trial: int(f[1], 0.0, u53)? as u64,
            steps: int(f[2], 0.0, u32max)? as u32,
            optimal: int(f[3], 0.0, u32max)? as u32,
            found: int(f[4], 0.0, 1.0)? == 1.0,
            target: int(f[5], 0.0, u32max)? as u32,
            value: int(f[6], -u53, u53)? as i64,
        })
    }

    /// The metric of a row with these numbers, as [`run_unit`] computes it.
    pub fn metric(metric: Metric, steps: u32, optimal: u32) -> i64 {
        match metric {
            Metric::Steps => steps as i64,
            Metric::Excess => steps as i64 - optimal as i64,
            Metric::Distance => 0,
        }
    }
}

/// A unit range that does not fit the plan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RangeError {
    /// The first unit asked for.
    pub from: u64,
    /// One past the last unit asked for.
    pub to: u64,
    /// The plan's number of units.
    pub total: u64,
}

impl fmt::Display for RangeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "units must be a range from..to with 0 <= from <= to <= {} (points × trials), got {}..{}",
            self.total, self.from, self.to
        )
    }
}

impl std::error::Error for RangeError {}

/// Shard `index` of `count`, numbered from 1: a contiguous slice of the units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, 1..=count.
    pub index: u64,
    /// How many shards.
    pub count: u64,
}

/// Most shards a run may be split into.
pub const MAX_SHARDS: u64 = 1_000_000;

impl Shard {
    /// Reads `i/n` (1 <= i <= n <= 1 000 000).
    ///
    /// # Errors
    /// A message naming the text and the allowed form.
    pub fn parse(text: &str) -> Result<Shard, String> {
        let bad = || {
            format!("--shard must be i/n with integers 1 <= i <= n <= {MAX_SHARDS} (shards are numbered from 1), got {text:?}")
        };
        let (i, n) = text.trim().split_once('/').ok_or_else(bad)?;
        let (index, count): (u64, u64) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if index < 1 || index > count || count > MAX_SHARDS {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The units `[⌊(i−1)·U/n⌋, ⌊i·U/n⌋)` of `total` = U: the shards of one
    /// count tile `0..U` without gaps or overlaps, sizes differing by at most one.
    pub fn range(&self, total: u64) -> (u64, u64) {
        let at = |k: u64| ((k as u128 * total as u128) / self.count as u128) as u64;
        (at(self.index - 1), at(self.index))
    }
}

/// Checks `from..to` against the plan.
///
/// # Errors
/// A [`RangeError`] unless `from <= to <= total`.
pub fn check_range(plan: &Plan, from: u64, to: u64) -> Result<(), RangeError> {
    let total = plan.total_units();
    if from <= to && to <= total {
        Ok(())
    } else {
        Err(RangeError { from, to, total })
    }
}

/// Runs unit `unit` of `plan` (which must be below `plan.total_units()`),
/// timing decision budgets with `clock` when given.
///
/// # Panics
/// When `unit` is out of range (a caller bug; the public runners check).
pub fn run_unit(plan: &Plan, unit: u64, clock: Option<fn() -> f64>) -> Row {
    let points = plan.points.len() as u64;
    let point = &plan.points[(unit % points) as usize];
    let trial = unit / points;
    let cfg = &point.config;
    match plan.header.kind {
        Kind::Episodes => {
            let mut ep = Episode::trial(cfg, trial).expect("plan configs are validated");
            if let Some(clock) = clock {
                ep.set_clock(clock);
            }
            let r = ep.run();
            Row {
                point: point.index as u32,
                trial,
                steps: r.steps,
                optimal: r.optimal,
                found: r.found,
                target: r.target,
                value: Row::metric(plan.header.metric, r.steps, r.optimal),
            }
        }
        Kind::Targets => {
            let crate::config::Game { torus, prior, .. } = game_of(cfg);
            // The episode's world stream: sample i is exactly the target
            // trial i of an episode with this configuration draws.
            let target = prior.sample(&mut rng::stream(cfg.seed, 2 * trial));
            Row {
                point: point.index as u32,
                trial,
                steps: 0,
                optimal: 0,
                found: true,
                target,
                value: torus.l1(centre(&torus), target) as i64,
            }
        }
    }
}

/// The game of a plan's configuration (validated when the plan was made).
pub(crate) fn game_of(cfg: &crate::config::Config) -> crate::config::Game {
    cfg.game().expect("plan configs are validated")
}

/// The prior's centre cell, `(N/2, N/2)` 0-based (the Gaussian's mean).
pub(crate) fn centre(torus: &Torus) -> u32 {
    let h = (torus.n() / 2) as i64;
    torus.cell(h, h)
}

/// Runs units `from..to` in order.
///
/// # Errors
/// A [`RangeError`] when the range does not fit the plan.
pub fn run_units(plan: &Plan, from: u64, to: u64) -> Result<Vec<Row>, RangeError> {
    run_units_clocked(plan, from, to, None)
}

/// [`run_units`] with a host clock for time budgets (the facade's `performance.now`).
///
/// # Errors
/// A [`RangeError`] when the range does not fit the plan.
pub fn run_units_clocked(
    plan: &Plan,
    from: u64,
    to: u64,
    clock: Option<fn() -> f64>,
) -> Result<Vec<Row>, RangeError> {
    check_range(plan, from, to)?;
    Ok((from..to).map(|u| run_unit(plan, u, clock)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_tile_the_units() {
        for total in [0u64, 1, 7, 100, 101] {
            for count in [1u64, 2, 3, 7, 150] {
                let mut next = 0;
                for index in 1..=count {
                    let (a, b) = Shard { index, count }.range(total);
                    assert_eq!(a, next, "{index}/{count} of {total}");
                    assert!(b - a <= total / count + 1);
                    next = b;
                }
                assert_eq!(next, total);
            }
        }
        assert_eq!(Shard::parse(" 2/3 ").unwrap(), Shard { index: 2, count: 3 });
        for bad in ["0/3", "4/3", "1", "a/b", "1/0", "-1/3", "1/2000000"] {
            assert!(
                Shard::parse(bad)
                    .unwrap_err()
                    .contains("--shard must be i/n"),
                "{bad}"
            );
        }
    }

    #[test]
    fn fields_round_trip_and_refuse_junk() {
        let r = Row {
            point: 3,
            trial: 9,
            steps: 100,
            optimal: 39,
            found: false,
            target: 820,
            value: -4,
        };
        assert_eq!(Row::from_fields(&r.fields()), Some(r));
        assert_eq!(Row::from_fields(&[0.0; 6]), None);
        let mut f = r.fields();
        f[4] = 2.0;
        assert_eq!(Row::from_fields(&f), None);
        f[4] = 1.0;
        f[2] = 1.5;
        assert_eq!(Row::from_fields(&f), None);
    }
}
