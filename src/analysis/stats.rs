//! Summaries over trials: means with bootstrap intervals, medians with
//! order-statistic intervals, the paper's ASOO, ratios, quartiles; and the
//! t-interval that tests compare with.

pub use super::quantiles::{quantile, t975};

use super::bootstrap::{bca_mean, bca_means};
use super::interval::Interval;
use super::median::median_interval;
use crate::game::counters::Counters;
use crate::run::episode::TrialResult;

/// Mean, standard deviation and t-based 95% CI of a sample: for tests
/// and comparisons (outputs give [`Interval`]s, which suit capped,
/// heavy-tailed trials).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MeanCi {
    /// Sample size.
    pub n: u64,
    /// Sample mean (NaN when empty).
    pub mean: f64,
    /// Sample standard deviation (n − 1 denominator; NaN below 2).
    pub sd: f64,
    /// Lower end of the t-based 95% CI.
    pub lo: f64,
    /// Upper end of the t-based 95% CI.
    pub hi: f64,
}

impl MeanCi {
    /// Summarises `xs`.
    pub fn of(xs: impl IntoIterator<Item = f64>) -> MeanCi {
        // Welford: stable for long runs of large step counts.
        let (mut n, mut mean, mut m2) = (0u64, 0.0f64, 0.0f64);
        for x in xs {
            n += 1;
            let d = x - mean;
            mean += d / n as f64;
            m2 += d * (x - mean);
        }
        if n == 0 {
            return MeanCi {
                n,
                mean: f64::NAN,
                sd: f64::NAN,
                lo: f64::NAN,
                hi: f64::NAN,
            };
        }
        if n == 1 {
            return MeanCi {
                n,
                mean,
                sd: f64::NAN,
                lo: f64::NAN,
                hi: f64::NAN,
            };
        }
        let sd = (m2 / (n - 1) as f64).sqrt();
        let half = t975(n - 1) * sd / (n as f64).sqrt();
        MeanCi {
            n,
            mean,
            sd,
            lo: mean - half,
            hi: mean + half,
        }
    }

    /// Standard error of the mean.
    pub fn se(&self) -> f64 {
        self.sd / (self.n as f64).sqrt()
    }
}

/// Quartiles, Tukey whiskers and range of a sample: what a box plot draws.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BoxStats {
    /// The median.
    pub median: f64,
    /// First quartile.
    pub q1: f64,
    /// Third quartile.
    pub q3: f64,
    /// The smallest value at or above q1 − 1.5 IQR.
    pub whisker_low: f64,
    /// The largest value at or below q3 + 1.5 IQR.
    pub whisker_high: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl BoxStats {
    /// Summarises `sorted` (ascending, no NaN); every field is NaN when it is empty.
    pub fn of_sorted(sorted: &[f64]) -> BoxStats {
        let (Some(&min), Some(&max)) = (sorted.first(), sorted.last()) else {
            return BoxStats {
                median: f64::NAN,
                q1: f64::NAN,
                q3: f64::NAN,
                whisker_low: f64::NAN,
                whisker_high: f64::NAN,
                min: f64::NAN,
                max: f64::NAN,
            };
        };
        let q1 = quantile(sorted, 0.25);
        let q3 = quantile(sorted, 0.75);
        let iqr = q3 - q1;
        // Tukey's fences, with the whiskers drawn to the data inside them
        // (q1 and q3 lie between data points, so the whiskers always exist).
        let lo = sorted.partition_point(|&x| x < q1 - 1.5 * iqr);
        let hi = sorted.partition_point(|&x| x <= q3 + 1.5 * iqr);
        BoxStats {
            median: quantile(sorted, 0.5),
            q1,
            q3,
            whisker_low: sorted[lo.min(sorted.len() - 1)],
            whisker_high: sorted[hi.max(1) - 1],
            min,
            max,
        }
    }
}

/// Everything reported over a batch of trials. It serialises flat, with
/// the field names the CLI's `--json` and the page's batch panel use:
/// `trials, mean_steps, mean_optimal, asoo, mean_ratio,
/// steps_over_mean_optimal, median_steps, q1_steps, q3_steps, zero_optimal,
/// capped, rollouts, rollout_steps, truncated_rollouts`, where the means and
/// the median are intervals (`{estimate, lo, hi, level, method}`).
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Trials run.
    pub trials: u64,
    /// Mean steps per trial, with its bootstrap interval.
    pub steps: Interval,
    /// Mean optimal steps per trial.
    pub optimal: Interval,
    /// ASOO as the authors' code computes it: the mean of (steps − optimal).
    pub asoo: Interval,
    /// Mean of steps/optimal over trials with optimal > 0.
    pub ratio: Interval,
    /// Mean steps / mean optimal.
    pub steps_over_mean_optimal: f64,
    /// Median steps, with its order-statistic interval.
    pub median_steps: Interval,
    /// First quartile of steps.
    pub q1_steps: f64,
    /// Third quartile of steps.
    pub q3_steps: f64,
    /// Trials excluded from the ratio because optimal = 0.
    pub zero_optimal: u64,
    /// Episodes ended by the step cap (failures, still counted above).
    pub capped: u64,
    /// Summed rollout counters.
    pub counters: Counters,
}

impl Summary {
    /// Summarises `results` (in trial order: the intervals' resampling is
    /// seeded by the values in order).
    pub fn of(results: &[TrialResult]) -> Summary {
        let column = |f: &dyn Fn(&TrialResult) -> f64| results.iter().map(f).collect::<Vec<_>>();
        // Steps and steps − optimal from the same resamples.
        let [steps, asoo] = bca_means(&[
            &column(&|r| r.steps as f64),
            &column(&|r| r.steps as f64 - r.optimal as f64),
        ])[..] else {
            unreachable!("two columns give two intervals")
        };
        let optimal = bca_mean(&column(&|r| r.optimal as f64));
        let ratios: Vec<f64> = results.iter().filter_map(TrialResult::ratio).collect();
        let mut sorted: Vec<f64> = results.iter().map(|r| r.steps as f64).collect();
        sorted.sort_by(f64::total_cmp);
        let mut counters = Counters::default();
        for r in results {
            counters += r.counters;
        }
        Summary {
            trials: results.len() as u64,
            steps,
            optimal,
            asoo,
            ratio: bca_mean(&ratios),
            steps_over_mean_optimal: steps.estimate / optimal.estimate,
            median_steps: median_interval(&sorted),
            q1_steps: quantile(&sorted, 0.25),
            q3_steps: quantile(&sorted, 0.75),
            zero_optimal: results.iter().filter(|r| r.optimal == 0).count() as u64,
            capped: results.iter().filter(|r| !r.found).count() as u64,
            counters,
        }
    }
}

impl serde::Serialize for Summary {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct Flat {
            trials: u64,
            mean_steps: Interval,
            mean_optimal: Interval,
            asoo: Interval,
            mean_ratio: Interval,
            steps_over_mean_optimal: f64,
            median_steps: Interval,
            q1_steps: f64,
            q3_steps: f64,
            zero_optimal: u64,
            capped: u64,
            rollouts: u64,
            rollout_steps: u64,
            truncated_rollouts: u64,
        }
        Flat {
            trials: self.trials,
            mean_steps: self.steps,
            mean_optimal: self.optimal,
            asoo: self.asoo,
            mean_ratio: self.ratio,
            steps_over_mean_optimal: self.steps_over_mean_optimal,
            median_steps: self.median_steps,
            q1_steps: self.q1_steps,
            q3_steps: self.q3_steps,
            zero_optimal: self.zero_optimal,
            capped: self.capped,
            rollouts: self.counters.rollouts,
            rollout_steps: self.counters.rollout_steps,
            truncated_rollouts: self.counters.truncated,
        }
        .serialize(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_ci_and_quartiles() {
        let m = MeanCi::of([1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(m.mean, 3.0);
        assert!((m.sd - 2.5f64.sqrt()).abs() < 1e-12);
        let half = 2.776 * m.sd / 5f64.sqrt();
        assert!((m.hi - 3.0 - half).abs() < 1e-9);
        let s = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(quantile(&s, 0.5), 2.5);
        assert_eq!(quantile(&s, 0.25), 1.75);
    }

    #[test]
    fn box_stats_whiskers_include_values_on_the_fences() {
        // q1 = 4 and q3 = 10 (type 7 on 9 values), IQR 6: fences at −5 and
        // 19, on which data lie, so the whiskers end there; −20 and 30 are
        // outliers. An IQR of q3 / q1, fences 1.5 + IQR out, or a strict
        // fence test all move a whisker.
        let xs = [-20.0, -5.0, 4.0, 6.0, 6.0, 8.0, 10.0, 19.0, 30.0];
        let b = BoxStats::of_sorted(&xs);
        assert_eq!((b.q1, b.median, b.q3), (4.0, 6.0, 10.0));
        assert_eq!((b.whisker_low, b.whisker_high), (-5.0, 19.0));
        assert_eq!((b.min, b.max), (-20.0, 30.0));
    }

    #[test]
    fn summary_of_trials_by_hand() {
        let trial = |steps, optimal, found, rollouts, rollout_steps, truncated| TrialResult {
            steps,
            optimal,
            found,
            target: 0,
            counters: Counters {
                rollouts,
                rollout_steps,
                truncated,
            },
        };
        let results = [
            trial(10, 5, true, 3, 30, 1),
            trial(20, 0, true, 2, 10, 0),
            trial(30, 10, false, 1, 5, 1),
            trial(40, 5, true, 0, 0, 0),
        ];
        let s = Summary::of(&results);
        assert_eq!(s.trials, 4);
        assert_eq!((s.steps.estimate, s.optimal.estimate), (25.0, 5.0));
        // ASOO: the mean of steps − optimal (5, 20, 20, 35).
        assert_eq!(s.asoo.estimate, 20.0);
        let joint = bca_means(&[&[10.0, 20.0, 30.0, 40.0], &[5.0, 20.0, 20.0, 35.0]]);
        assert_eq!((s.steps, s.asoo), (joint[0], joint[1]));
        assert_eq!(s.optimal, bca_mean(&[5.0, 0.0, 10.0, 5.0]));
        // The ratio leaves out the trial with optimal 0: (2 + 3 + 8) / 3.
        assert_eq!(s.zero_optimal, 1);
        assert_eq!(s.ratio, bca_mean(&[2.0, 3.0, 8.0]));
        assert!((s.ratio.estimate - 13.0 / 3.0).abs() < 1e-12);
        assert_eq!(s.steps_over_mean_optimal, 5.0);
        assert_eq!(
            (s.q1_steps, s.median_steps.estimate, s.q3_steps),
            (17.5, 25.0, 32.5)
        );
        // Intervals stay within the trials' range.
        assert!(s.steps.lo >= 10.0 && s.steps.hi <= 40.0, "{:?}", s.steps);
        assert_eq!(s.capped, 1, "the one trial not found");
        assert_eq!(
            s.counters,
            Counters {
                rollouts: 6,
                rollout_steps: 45,
                truncated: 2
            }
        );
    }

    #[test]
    fn box_stats_whiskers_stop_at_the_fences() {
        // q1 = 2, q3 = 4 (type 7 on 9 values), IQR 2: fences -1 and 7, so
        // the whiskers end at the last data inside them (1 and 5), not at
        // the outlier 50. Whiskers drawn to min/max (a plausible bug) give
        // 50 and fail.
        let mut xs = vec![1.0, 2.0, 2.0, 3.0, 3.0, 3.0, 4.0, 5.0, 50.0];
        xs.sort_by(f64::total_cmp);
        let b = BoxStats::of_sorted(&xs);
        assert_eq!((b.q1, b.median, b.q3), (2.0, 3.0, 4.0));
        assert_eq!((b.whisker_low, b.whisker_high), (1.0, 5.0));
        assert_eq!((b.min, b.max), (1.0, 50.0));
        let one = BoxStats::of_sorted(&[7.0]);
        assert_eq!(
            (one.whisker_low, one.median, one.whisker_high),
            (7.0, 7.0, 7.0)
        );
        assert!(BoxStats::of_sorted(&[]).median.is_nan());
    }
}
