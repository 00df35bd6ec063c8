//! Paired comparisons of two series over the same trials.
//!
//! Trial `i` of every point of an experiment draws its target from the
//! same stream (common random numbers), so two series at one x value face
//! the same targets trial by trial. Comparing them trial by trial removes
//! the target's share of the noise, which unpaired intervals keep: the
//! difference of means gets an interval from the per-trial differences, and
//! the counts say in how many trials each side did better.

use super::bootstrap::bca_mean;
use super::interval::Interval;

/// One trial of a series: its index, its value (lower is better) and its
/// target cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairedTrial {
    /// The trial index.
    pub trial: u64,
    /// The value compared (steps, or steps − optimal).
    pub value: f64,
    /// The target cell.
    pub target: u32,
}

/// A series against a reference over the trials both have.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Paired {
    /// Trials present in both.
    pub n: u64,
    /// The mean of (series − reference) over those trials, with its
    /// bootstrap interval (which lies between the least and the greatest
    /// difference).
    pub difference: Interval,
    /// Trials in which the series' value is lower than the reference's.
    pub wins: u64,
    /// Trials in which they are equal.
    pub ties: u64,
    /// Trials in which the series' value is higher.
    pub losses: u64,
    /// Trials in which both had the same target (all of them when the two
    /// share the prior and the seed).
    pub same_target: u64,
}

/// Compares `series` with `reference`, each sorted by trial with at most
/// one entry per trial, over the trials both have, in trial order.
pub fn paired(series: &[PairedTrial], reference: &[PairedTrial]) -> Paired {
    let mut diffs = Vec::with_capacity(series.len().min(reference.len()));
    let mut same_target = 0;
    let (mut i, mut j) = (0, 0);
    while i < series.len() && j < reference.len() {
        let (a, b) = (&series[i], &reference[j]);
        match a.trial.cmp(&b.trial) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                diffs.push(a.value - b.value);
                same_target += (a.target == b.target) as u64;
                i += 1;
                j += 1;
            }
        }
    }
    let count = |f: fn(&f64) -> bool| diffs.iter().filter(|d| f(d)).count() as u64;
    Paired {
        n: diffs.len() as u64,
        difference: bca_mean(&diffs),
        wins: count(|&d| d < 0.0),
        ties: count(|&d| d == 0.0),
        losses: count(|&d| d > 0.0),
        same_target,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::interval::IntervalMethod;

    fn trials(values: &[(u64, f64, u32)]) -> Vec<PairedTrial> {
        values
            .iter()
            .map(|&(trial, value, target)| PairedTrial {
                trial,
                value,
                target,
            })
            .collect()
    }

    #[test]
    fn paired_arithmetic_by_hand() {
        // Trials 0..5 of the series, 1..6 of the reference: trials 1–4 pair.
        // Differences: 30 − 50 = −20, 40 − 40 = 0, 100 − 60 = 40, 20 − 70 =
        // −50; mean −7.5; 2 wins, 1 tie, 1 loss; targets agree in trials 1,
        // 2 and 4.
        let a = trials(&[
            (0, 9.0, 5),
            (1, 30.0, 7),
            (2, 40.0, 8),
            (3, 100.0, 9),
            (4, 20.0, 3),
        ]);
        let b = trials(&[
            (1, 50.0, 7),
            (2, 40.0, 8),
            (3, 60.0, 1),
            (4, 70.0, 3),
            (5, 1.0, 0),
        ]);
        let p = paired(&a, &b);
        assert_eq!(p.n, 4);
        assert_eq!(p.difference.estimate, -7.5);
        assert_eq!((p.wins, p.ties, p.losses), (2, 1, 1));
        assert_eq!(p.same_target, 3);
        assert_eq!(p.difference.method, IntervalMethod::Bootstrap);
        // The interval is the bootstrap of exactly these differences, and
        // lies within their range. Pairing by position instead of by trial
        // (a plausible bug) gives 9 − 50, 30 − 40, … and another mean.
        assert_eq!(p.difference, bca_mean(&[-20.0, 0.0, 40.0, -50.0]));
        assert!(p.difference.lo >= -50.0 && p.difference.hi <= 40.0);
        // Swapping the sides negates the difference and swaps wins and losses.
        let q = paired(&b, &a);
        assert_eq!(q.difference.estimate, 7.5);
        assert_eq!((q.wins, q.ties, q.losses), (1, 1, 2));
        // Nothing in common: no trials, no estimate.
        let none = paired(&a[..1], &b[..1]);
        assert_eq!(none.n, 0);
        assert!(none.difference.estimate.is_nan());
    }
}
