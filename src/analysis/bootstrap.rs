//! A seeded, deterministic bootstrap interval for the mean: BCa with
//! expanded tails.
//!
//! Why BCa (bias-corrected and accelerated, Efron 1987) rather than a
//! t-interval or the studentised bootstrap: the trials are heavy-tailed and
//! capped. A BCa interval is a pair of quantiles of the resampled means, so
//! it never leaves the trials' range (a mean of trials lies between their
//! least and greatest); it corrects the percentile interval for the bias
//! and the skew of the mean's law, which are large here, so that it misses
//! about as often above as below. A t-interval is symmetric about the mean:
//! on skewed trials it misses mostly above, and it leaves the range when one
//! trial dominates. The studentised bootstrap divides by each resample's
//! standard error, which a heavy tail makes unstable, and can leave the
//! range too.
//!
//! Expanded tails (Hesterberg 2015, "What teachers should know about the
//! bootstrap"): a bootstrap's spread is the plug-in one, `(n − 1)/n` of the
//! sample variance, and its quantiles are normal where a studentised mean's
//! are Student's. So the normal quantile ±1.96 of the BCa formula is replaced
//! by `±√(n/(n−1)) · t₀.₉₇₅(n − 1)`. It matters below a few dozen trials
//! and vanishes as n grows; EXPERIMENTS.md ("Intervals and paired
//! comparisons") gives the calibration.
//!
//! Determinism: the resampling stream is seeded by a hash of the values in
//! the order given (trial order), so the same trials give the same bits on
//! every platform and however the trials were run (threads, Web Workers,
//! merged shards). Sums are in a fixed order; Φ and Φ⁻¹ come from `libm`.

use super::interval::{Interval, IntervalMethod, LEVEL};
use super::normal;
use super::quantiles::{quantile, t975};
use crate::game::fnv::Fnv;
use crate::game::rng::{self, Rng};
use rand::SeedableRng;

/// Resamples per interval: enough that the BCa ends move by less than a
/// tenth of the interval's width from one seed to another (Efron and
/// Tibshirani advise 1000 or more for percentile ends).
pub const RESAMPLES: usize = 2000;

/// The seed of the resampling stream of `columns`: FNV-1a of their length
/// and their values' bits, column by column, mixed.
pub fn seed_of(columns: &[&[f64]]) -> u64 {
    let mut h = Fnv::default();
    h.word(columns.first().map_or(0, |c| c.len()) as u64);
    for xs in columns {
        for x in xs.iter() {
            h.word(x.to_bits());
        }
    }
    rng::splitmix64(h.finish())
}

/// A uniform index in `0..n` from 32 random bits (Lemire's method; on the
/// rare rejection, with probability below n/2³², fresh bits are drawn).
/// Inline, with no call, so that a caller's sums stay in registers.
#[inline(always)]
fn index(bits: u32, n: u32, rng: &mut Rng) -> usize {
    let mut m = bits as u64 * n as u64;
    if (m as u32) < n {
        let threshold = n.wrapping_neg() % n;
        while (m as u32) < threshold {
            m = (rng::bits(rng) >> 32) * n as u64;
        }
    }
    (m >> 32) as usize
}

/// The sum of one resample of `xs` (n = `xs.len()` draws): two sums, of
/// the even and the odd draws, added at the end in a fixed order, so the
/// bits are the same everywhere and the additions do not form one long
/// chain. A function of its own so that the sums stay in registers.
#[inline(never)]
fn sums(xs: &[f64], n32: u32, rng: &mut Rng) -> f64 {
    let (mut s0, mut s1) = (0.0f64, 0.0f64);
    for _ in 0..xs.len() / 2 {
        let w = rng::bits(rng);
        s0 += xs[index(w as u32, n32, rng)];
        s1 += xs[index((w >> 32) as u32, n32, rng)];
    }
    if xs.len() % 2 == 1 {
        s0 += xs[index(rng::bits(rng) as u32, n32, rng)];
    }
    s0 + s1
}

/// [`sums`] of two columns over the same draws.
#[inline(never)]
fn sums_of_two(a: &[f64], b: &[f64], n32: u32, rng: &mut Rng) -> (f64, f64) {
    let (mut a0, mut a1, mut b0, mut b1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for _ in 0..a.len() / 2 {
        let w = rng::bits(rng);
        let (i, j) = (index(w as u32, n32, rng), index((w >> 32) as u32, n32, rng));
        a0 += a[i];
        a1 += a[j];
        b0 += b[i];
        b1 += b[j];
    }
    if a.len() % 2 == 1 {
        let i = index(rng::bits(rng) as u32, n32, rng);
        a0 += a[i];
        b0 += b[i];
    }
    (a0 + a1, b0 + b1)
}

/// For each of `columns` (one or two, equally long, not empty), the sorted
/// means of the same [`RESAMPLES`] resamples of the trials with
/// replacement, drawn from `rng`: two trial indices from each 64 random
/// bits, the low half first.
///
/// # Panics
/// With no columns or more than two (a caller bug).
pub fn resampled_means(columns: &[&[f64]], rng: &mut Rng) -> Vec<Vec<f64>> {
    let (a, b) = match *columns {
        [a] => (a, None),
        [a, b] => (a, Some(b)),
        _ => panic!(
            "a bootstrap resamples one or two columns, got {}",
            columns.len()
        ),
    };
    let n = a.len();
    let n32 = u32::try_from(n).expect("at most 2^32 trials per interval");
    let mut means = vec![Vec::with_capacity(RESAMPLES); columns.len()];
    for _ in 0..RESAMPLES {
        let (sa, sb) = match b {
            None => (sums(a, n32, rng), 0.0),
            Some(b) => sums_of_two(a, b, n32, rng),
        };
        means[0].push(sa / n as f64);
        if b.is_some() {
            means[1].push(sb / n as f64);
        }
    }
    for m in &mut means {
        m.sort_by(f64::total_cmp);
    }
    means
}

/// The quantile `z` that the BCa formula of `n` trials uses in place of the
/// normal 97.5% point: `√(n/(n−1)) · t₀.₉₇₅(n − 1)` (NaN below 2 trials).
pub fn expanded_z(n: usize) -> f64 {
    let n = n as f64;
    (n / (n - 1.0)).sqrt() * t975(n as u64 - 1)
}

/// The mean of `xs` with its expanded BCa 95% interval. The ends lie within
/// `[min, max]` of `xs`; both are NaN with fewer than two values, and both
/// equal the mean when every value is the same.
pub fn bca_mean(xs: &[f64]) -> Interval {
    bca_means(&[xs])[0]
}

/// [`bca_mean`] of each of `columns` (one or two, values of the same
/// trials, equally long), from one set of resamples of the trials: a
/// point's steps and excess cost one stream of draws, not two.
///
/// # Panics
/// When the columns differ in length, or there are more than two (a
/// caller bug).
pub fn bca_means(columns: &[&[f64]]) -> Vec<Interval> {
    let n = columns.first().map_or(0, |c| c.len());
    assert!(
        columns.iter().all(|c| c.len() == n),
        "columns of one bootstrap must be equally long"
    );
    let means: Vec<f64> = columns
        .iter()
        .map(|xs| xs.iter().sum::<f64>() / n as f64)
        .collect();
    if n < 2 {
        return means
            .iter()
            .map(|&m| Interval::bare(m, IntervalMethod::Bootstrap))
            .collect();
    }
    let boot = resampled_means(columns, &mut Rng::seed_from_u64(seed_of(columns)));
    let z = expanded_z(n);
    columns
        .iter()
        .zip(means)
        .zip(&boot)
        .map(|((xs, mean), boot)| {
            let (min, max) = xs
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            // Every value the same: the bootstrap's law is a point.
            let (lo, hi) = if min == max {
                (mean, mean)
            } else {
                bca_ends(xs, mean, boot, (-z, z))
            };
            Interval {
                estimate: mean,
                lo: lo.clamp(min, max),
                hi: hi.clamp(min, max),
                level: LEVEL,
                method: IntervalMethod::Bootstrap,
            }
        })
        .collect()
}

/// The BCa ends from the sorted resampled means, with `zs` in place of the
/// normal quantiles of the two tails (`(−1.96, 1.96)` for the textbook BCa).
pub fn bca_ends(xs: &[f64], mean: f64, means: &[f64], zs: (f64, f64)) -> (f64, f64) {
    let b = means.len() as f64;
    // Bias: the share of resampled means below the mean (ties count half,
    // as the data are integers), kept off 0 and 1.
    let below = means.partition_point(|&m| m < mean) as f64;
    let equal = means.partition_point(|&m| m <= mean) as f64 - below;
    let share = ((below + equal / 2.0) / b).clamp(0.5 / b, 1.0 - 0.5 / b);
    let z0 = normal::quantile(share);
    // Acceleration from the jackknife, which for the mean is the skewness
    // of the values: Σd³ / (6 (Σd²)^{3/2}) with d = x − mean.
    let (mut s2, mut s3) = (0.0, 0.0);
    for &x in xs {
        let d = x - mean;
        s2 += d * d;
        s3 += d * d * d;
    }
    let a = s3 / (6.0 * s2 * libm::sqrt(s2));
    let end = |zq: f64| {
        let z = z0 + zq;
        let denom = 1.0 - a * z;
        // |a| < 1/6 for a mean and |z| < 6 here, so denom > 0; guard anyway.
        let p = if denom > 0.0 {
            normal::cdf(z0 + z / denom)
        } else if z > 0.0 {
            1.0
        } else {
            0.0
        };
        quantile(means, p)
    };
    (end(zs.0), end(zs.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::stats::MeanCi;

    /// 29 trials between 29 and 141 and one at 4238: the shape of the
    /// committed `belief.csv` point whose t-interval was [−52.8, 514.8].
    fn skewed() -> Vec<f64> {
        let mut xs: Vec<f64> = (0..29).map(|i| (29 + 4 * i) as f64).collect();
        xs.insert(11, 4238.0);
        xs
    }

    #[test]
    fn intervals_stay_in_the_range_where_t_intervals_leave_it() {
        let xs = skewed();
        let t = MeanCi::of(xs.iter().copied());
        assert!(t.lo < 29.0, "the t-interval leaves the range: {t:?}");
        let b = bca_mean(&xs);
        assert_eq!(b.estimate, xs.iter().sum::<f64>() / 30.0);
        assert!(
            29.0 <= b.lo && b.lo < b.estimate && b.estimate < b.hi && b.hi <= 4238.0,
            "{b:?}"
        );
        // The one large trial makes the mean's law skewed to the right:
        // the interval reaches further above the mean than below it.
        assert!(b.hi - b.estimate > b.estimate - b.lo, "{b:?}");
        assert_eq!((b.level, b.method), (0.95, IntervalMethod::Bootstrap));
    }

    #[test]
    fn the_same_values_give_the_same_interval() {
        let xs = skewed();
        assert_eq!(bca_mean(&xs), bca_mean(&xs.clone()));
        // The stream is the values': other values, another stream.
        let mut ys = xs.clone();
        ys.swap(0, 1);
        assert_ne!(seed_of(&[&xs]), seed_of(&[&ys]));
        assert_ne!(bca_mean(&xs).lo, bca_mean(&ys).lo);
        // tests/suite/determinism.rs pins the bits natively and in wasm.
    }

    #[test]
    fn degenerate_samples() {
        assert!(bca_mean(&[]).estimate.is_nan());
        let one = bca_mean(&[7.0]);
        assert_eq!(one.estimate, 7.0);
        assert!(one.lo.is_nan() && one.hi.is_nan());
        let same = bca_mean(&[39.0; 20]);
        assert_eq!((same.lo, same.estimate, same.hi), (39.0, 39.0, 39.0));
        // Two values: the expanded tails reach both ends.
        let two = bca_mean(&[0.0, 10.0]);
        assert_eq!((two.lo, two.hi), (0.0, 10.0));
    }

    #[test]
    fn columns_share_resamples_but_not_results() {
        // Steps and steps − optimal of the same trials: one stream of
        // resamples, each column its own interval.
        let steps = skewed();
        let excess: Vec<f64> = steps.iter().map(|s| s - 29.0).collect();
        let both = bca_means(&[&steps, &excess]);
        assert_eq!(both[0].estimate, bca_mean(&steps).estimate);
        // Shifting every value shifts the shared resamples' means alike.
        assert!((both[1].lo - (both[0].lo - 29.0)).abs() < 1e-9, "{both:?}");
        assert!((both[1].hi - (both[0].hi - 29.0)).abs() < 1e-9, "{both:?}");
        assert!(both[1].lo >= 0.0);
    }

    #[test]
    fn expanded_quantiles() {
        // √(n/(n−1)) t₀.₉₇₅(n−1): 1.0541 × 2.262 at n = 10, → 1.96 for large n.
        assert!((expanded_z(10) - (10f64 / 9.0).sqrt() * 2.262).abs() < 1e-12);
        assert!((expanded_z(100_000) - 1.96).abs() < 1e-3);
        assert!(expanded_z(30) > expanded_z(31));
    }
}
