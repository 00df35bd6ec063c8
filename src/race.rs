//! One episode, or several racing: each on its own configuration, stepped
//! together. The page shows a race side by side; with the same seed the
//! runs share their target.

use crate::config::{Config, ConfigError};
use crate::episode::{Episode, Status};

/// Episodes stepped together. A searcher that does not deliberate, racing
/// one that does, makes no more real moves than it while it runs, so the
/// boards compare paths rather than speed; once it is done the walker runs
/// free.
pub struct Race {
    runs: Vec<Episode>,
    /// For each run, the run whose moves pace it.
    pacer: Vec<Option<usize>>,
}

/// How many runs a race holds at most.
pub const MAX_RUNS: usize = 2;

impl Race {
    /// Trial 0 of each config.
    ///
    /// # Errors
    /// A [`ConfigError`] for the first invalid config, or for a count of
    /// configs outside 1..=[`MAX_RUNS`].
    pub fn new(configs: &[Config]) -> Result<Race, ConfigError> {
        if configs.is_empty() || configs.len() > MAX_RUNS {
            return Err(ConfigError::new(
                "race",
                format!("{} configs", configs.len()),
                format!("1 to {MAX_RUNS} configs"),
            ));
        }
        let runs = configs
            .iter()
            .map(Episode::new)
            .collect::<Result<Vec<_>, _>>()?;
        let deliberates: Vec<bool> = runs.iter().map(|r| r.searcher_info().deliberates).collect();
        let pacer = (0..runs.len())
            .map(|i| {
                (!deliberates[i])
                    .then(|| (0..runs.len()).find(|&j| j != i && deliberates[j]))
                    .flatten()
            })
            .collect();
        Ok(Race { runs, pacer })
    }

    /// The runs.
    pub fn runs(&self) -> &[Episode] {
        &self.runs
    }

    /// The runs, to set their clocks.
    pub fn runs_mut(&mut self) -> &mut [Episode] {
        &mut self.runs
    }

    /// How many runs are still searching.
    pub fn running(&self) -> usize {
        self.runs
            .iter()
            .filter(|r| r.status() == Status::Running)
            .count()
    }

    /// `k` loops of work on every unfinished run (see [`Episode::advance`]),
    /// walkers paced.
    pub fn advance(&mut self, k: u64) {
        for i in 0..self.runs.len() {
            let limit = match self.pacer[i] {
                Some(j) if self.runs[j].status() == Status::Running => {
                    (self.runs[j].steps() as u64).saturating_sub(self.runs[i].steps() as u64)
                }
                _ => u64::MAX,
            };
            // The limit is on moves: a planner's slices are not moves.
            self.runs[i].advance_within(k, limit);
        }
    }

    /// One loop on every unfinished run (one move for a walker).
    pub fn step_loop(&mut self) {
        for r in &mut self.runs {
            r.step_loops(1);
        }
    }

    /// Finishes the decision under way and makes one real move, on every unfinished run.
    pub fn step_move(&mut self) {
        for r in &mut self.runs {
            r.step_move();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_planner_makes_its_plan_while_mcts_moves_and_then_keeps_pace() {
        // The beam planner's slices are not moves: it plans while behind
        // the MCTS run, never gets ahead of it, and then follows its plan.
        let mcts = Config {
            n: 12,
            loops: 10,
            ..Config::default()
        };
        let mut beam = mcts.clone();
        for (k, v) in [
            ("searcher", "beam"),
            ("beam_width", "8"),
            ("beam_depth", "20"),
        ] {
            beam.set(k, v).unwrap();
        }
        let mut race = Race::new(&[mcts, beam]).unwrap();
        let mut planned_behind = false;
        for _ in 0..20_000 {
            race.advance(3);
            let [a, b] = [&race.runs()[0], &race.runs()[1]];
            if a.status() == Status::Running {
                assert!(b.steps() <= a.steps(), "{} > {}", b.steps(), a.steps());
            }
            planned_behind |= b.planning().is_some() && a.steps() > b.steps();
            if b.status() != Status::Running {
                break;
            }
        }
        assert!(planned_behind, "the plan was made while the MCTS run moved");
        assert_ne!(race.runs()[1].status(), Status::Running);
    }

    #[test]
    fn a_walker_keeps_pace_with_mcts_and_shares_its_target() {
        let mcts = Config {
            n: 15,
            loops: 10,
            ..Config::default()
        };
        let mut rw = mcts.clone();
        rw.set("searcher", "rw").unwrap();
        let mut race = Race::new(&[mcts.clone(), rw]).unwrap();
        assert_eq!(race.runs()[0].target(), race.runs()[1].target());
        for _ in 0..40 {
            race.advance(7);
            let [a, b] = [&race.runs()[0], &race.runs()[1]];
            if a.status() == Status::Running {
                assert!(b.steps() <= a.steps(), "{} > {}", b.steps(), a.steps());
            }
        }
        // The MCTS run moves exactly as alone.
        let mut alone = Episode::new(&mcts).unwrap();
        alone.advance(280);
        assert_eq!(alone.path(), race.runs()[0].path());
        assert!(Race::new(&[]).is_err());
        assert!(Race::new(&[mcts.clone(), mcts.clone(), mcts]).is_err());
    }
}
