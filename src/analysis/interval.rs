//! The one shape every output gives an interval: an estimate, the ends of
//! its 95% interval, the level and the method that made it.

use crate::game::named::named_enum;

/// The level of every interval the crate reports.
pub const LEVEL: f64 = 0.95;

named_enum! {
    /// How an interval was computed.
    pub enum IntervalMethod {
        /// A seeded bias-corrected and accelerated bootstrap of the mean,
        /// its tails expanded for small samples (`analysis::bootstrap`).
        Bootstrap = "expanded-bca-bootstrap",
        /// Order statistics around the median, from the binomial law of
        /// how many trials fall below it: distribution-free
        /// (`analysis::median`).
        OrderStatistic = "order-statistic",
    }
}

/// An estimate with its 95% interval. Written in every output as
/// `{"estimate", "lo", "hi", "level", "method"}`; a CSV flattens an
/// interval field `f` into the columns `f`, `f_lo` and `f_hi`. An end that
/// cannot be computed (too few trials) is NaN, written `null` in JSON and
/// empty in CSV.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Interval {
    /// The point estimate (the sample mean or median).
    pub estimate: f64,
    /// The lower end.
    pub lo: f64,
    /// The upper end.
    pub hi: f64,
    /// The nominal coverage, [`LEVEL`].
    pub level: f64,
    /// How it was computed.
    pub method: IntervalMethod,
}

impl Interval {
    /// An estimate without an interval (both ends NaN).
    pub fn bare(estimate: f64, method: IntervalMethod) -> Interval {
        Interval {
            estimate,
            lo: f64::NAN,
            hi: f64::NAN,
            level: LEVEL,
            method,
        }
    }

    /// True when both ends are known and `x` lies between them.
    pub fn covers(&self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }
}
