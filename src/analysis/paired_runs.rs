//! The summary of two configurations run on the same trials (the page's
//! race and `runPairedTrial`): the mean steps of each side and the paired
//! difference with the crate's one interval, from [`super::paired`].

use super::interval::Interval;
use super::paired::{paired, PairedTrial};
use crate::run::episode::TrialResult;
use crate::run::paired::PairError;

/// The paired comparison of two configurations' steps over common trials.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PairedRuns {
    /// Trials compared.
    pub trials: usize,
    /// Mean steps of the first side (a capped trial counts its step cap).
    pub mean_a: f64,
    /// Mean steps of the second side.
    pub mean_b: f64,
    /// Steps of A − steps of B, averaged (negative: A is faster), with its
    /// bootstrap interval, which lies within the differences' range.
    pub difference: Interval,
    /// Standard deviation of the differences.
    pub sd_difference: f64,
    /// Trials where A took fewer steps.
    pub a_wins: u64,
    /// Trials of equal steps.
    pub ties: u64,
    /// Trials where B took fewer steps.
    pub b_wins: u64,
    /// Trials A detected the target in (the rest hit the step cap).
    pub found_a: usize,
    /// Trials B detected the target in.
    pub found_b: usize,
}

/// The paired summary of trials run on both sides (pair `i` the same trial).
///
/// # Errors
/// [`PairError::Empty`] without trials, [`PairError::Unpaired`] (index in
/// `pairs`) when a pair's targets differ.
pub fn summarize(pairs: &[(TrialResult, TrialResult)]) -> Result<PairedRuns, PairError> {
    if pairs.is_empty() {
        return Err(PairError::Empty);
    }
    if let Some(i) = pairs.iter().position(|(a, b)| a.target != b.target) {
        return Err(PairError::Unpaired {
            index: i as u64,
            differ: Vec::new(),
        });
    }
    let side = |pick: fn(&(TrialResult, TrialResult)) -> &TrialResult| -> Vec<PairedTrial> {
        (pairs.iter().enumerate())
            .map(|(i, p)| PairedTrial {
                trial: i as u64,
                value: pick(p).steps as f64,
                target: pick(p).target,
            })
            .collect()
    };
    let p = paired(&side(|p| &p.0), &side(|p| &p.1));
    let n = pairs.len() as f64;
    let md = p.difference.estimate;
    let sd = if pairs.len() > 1 {
        let ss: f64 = (pairs.iter())
            .map(|(a, b)| a.steps as f64 - b.steps as f64 - md)
            .map(|x| x * x)
            .sum();
        (ss / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    let mean = |f: fn(&(TrialResult, TrialResult)) -> u32| {
        pairs.iter().map(|p| f(p) as f64).sum::<f64>() / n
    };
    Ok(PairedRuns {
        trials: pairs.len(),
        mean_a: mean(|p| p.0.steps),
        mean_b: mean(|p| p.1.steps),
        difference: p.difference,
        sd_difference: sd,
        a_wins: p.wins,
        ties: p.ties,
        b_wins: p.losses,
        found_a: pairs.iter().filter(|(a, _)| a.found).count(),
        found_b: pairs.iter().filter(|(_, b)| b.found).count(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::counters::Counters;

    fn result(steps: u32, target: u32) -> TrialResult {
        TrialResult {
            steps,
            optimal: 1,
            found: true,
            target,
            counters: Counters::default(),
        }
    }

    #[test]
    fn the_summary_counts_wins_and_brackets_the_mean_difference() {
        // A is 3 steps faster on each of 30 trials but one (a tie) and
        // one (5 slower).
        let mut pairs: Vec<_> = (0..30)
            .map(|i| (result(10 + i, i), result(13 + i, i)))
            .collect();
        pairs[0].1.steps = pairs[0].0.steps;
        pairs[1].1.steps = pairs[1].0.steps - 5;
        let s = summarize(&pairs).unwrap();
        assert_eq!((s.a_wins, s.ties, s.b_wins, s.trials), (28, 1, 1, 30));
        let want = (28.0 * -3.0 + 5.0) / 30.0;
        assert!((s.difference.estimate - want).abs() < 1e-12);
        assert!(s.difference.lo < want && want < s.difference.hi, "{s:?}");
        // The interval is about ±2 standard errors wide, within the range.
        let se = s.sd_difference / 30f64.sqrt();
        let half = (s.difference.hi - s.difference.lo) / 2.0;
        assert!(half > 1.5 * se && half < 3.0 * se, "{half} vs se {se}");
        assert!(s.difference.lo >= -3.0 && s.difference.hi <= 5.0);
        // Identical sides: a point interval at 0, all ties.
        let same: Vec<_> = (0..5).map(|i| (result(i, i), result(i, i))).collect();
        let s = summarize(&same).unwrap();
        assert_eq!((s.difference.lo, s.difference.hi, s.ties), (0.0, 0.0, 5));
        // Different targets cannot be paired; nothing cannot be summarised.
        let mut bad = same.clone();
        bad[3].1.target = 99;
        assert!(matches!(
            summarize(&bad),
            Err(PairError::Unpaired { index: 3, .. })
        ));
        assert_eq!(summarize(&[]), Err(PairError::Empty));
    }
}
