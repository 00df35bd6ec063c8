//! A distribution-free interval for the median, from order statistics.
//!
//! Whatever the law of the trials, the number of them below its median is
//! Binomial(n, ½) (for a continuous law; with ties, at most that many are
//! strictly below and at least that many at or below, which only widens
//! the coverage). So `[x₍ₖ₎, x₍ₙ₋ₖ₊₁₎]` covers the median with probability at
//! least `1 − 2·P(Bin(n, ½) ≤ k − 1)`; the largest `k` that keeps this at
//! or above 95% gives the narrowest such interval. Its ends are trials, so
//! it never leaves the data's range.

use super::interval::{Interval, IntervalMethod, LEVEL};
use super::quantiles::quantile;

/// The rank `k` (1-based) of the lower end of the order-statistic interval
/// of `n` trials, the largest with `P(Bin(n, ½) ≤ k − 1) ≤ (1 − level)/2`;
/// `None` when even `[x₍₁₎, x₍ₙ₎]` covers less than `level` (n ≤ 5 at 95%).
pub fn lower_rank(n: u64, level: f64) -> Option<u64> {
    let tail = (1.0 - level) / 2.0;
    // P(Bin = j) in logs: log C(n, j) − n log 2, by the ratio (n − j)/(j + 1).
    let mut log_pmf = -(n as f64) * std::f64::consts::LN_2;
    let mut cdf = 0.0;
    let mut k = 0;
    for j in 0..=n / 2 {
        cdf += libm::exp(log_pmf);
        if cdf > tail {
            break;
        }
        k = j + 1;
        log_pmf += libm::log((n - j) as f64 / (j + 1) as f64);
    }
    (k >= 1).then_some(k)
}

/// The median of `sorted` (ascending, no NaN; R's type 7, as
/// [`quantile`]) with its order-statistic 95% interval: NaN ends for five
/// trials or fewer, all NaN without trials.
pub fn median_interval(sorted: &[f64]) -> Interval {
    let estimate = quantile(sorted, 0.5);
    let n = sorted.len() as u64;
    match lower_rank(n, LEVEL) {
        Some(k) => Interval {
            estimate,
            lo: sorted[(k - 1) as usize],
            hi: sorted[(n - k) as usize],
            level: LEVEL,
            method: IntervalMethod::OrderStatistic,
        },
        None => Interval::bare(estimate, IntervalMethod::OrderStatistic),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranks_match_the_binomial_table() {
        // The classical table of the sign-test interval (e.g. Conover,
        // Practical Nonparametric Statistics, table A3): n = 6 → (1, 6),
        // 10 → (2, 9), 20 → (6, 15), 30 → (10, 21), 100 → (40, 61).
        // P(Bin(30, ½) ≤ 9) = 0.02139 ≤ 0.025 < P(≤ 10) = 0.04937.
        for (n, k) in [(6, 1), (10, 2), (20, 6), (30, 10), (100, 40), (1000, 469)] {
            assert_eq!(lower_rank(n, 0.95), Some(k), "n = {n}");
        }
        for n in 0..=5 {
            assert_eq!(lower_rank(n, 0.95), None, "n = {n}");
        }
        // Large n: the normal approximation n/2 − 1.96 √n / 2, within one rank.
        let n = 100_000u64;
        let k = lower_rank(n, 0.95).unwrap() as f64;
        assert!(
            (k - (n as f64 / 2.0 - 1.96 * (n as f64).sqrt() / 2.0)).abs() < 1.5,
            "{k}"
        );
    }

    #[test]
    fn the_interval_is_made_of_trials() {
        let xs: Vec<f64> = (1..=30).map(|i| (i * i) as f64).collect();
        let m = median_interval(&xs);
        assert_eq!(m.estimate, (225.0 + 256.0) / 2.0);
        assert_eq!((m.lo, m.hi), (100.0, 441.0), "x₍₁₀₎ and x₍₂₁₎");
        assert_eq!(m.method, IntervalMethod::OrderStatistic);
        let few = median_interval(&[1.0, 2.0, 9.0]);
        assert_eq!(few.estimate, 2.0);
        assert!(few.lo.is_nan() && few.hi.is_nan());
        assert!(median_interval(&[]).estimate.is_nan());
    }
}
