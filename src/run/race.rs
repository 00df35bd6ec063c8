//! One episode, or several racing: each on its own configuration, stepped
//! together. The page shows a race side by side; with the same seed the
//! runs share their target. Each run keeps its timeline, so the race can
//! seek back to any point it has reached.

use crate::config::Config;
use crate::param::ParamError;
use crate::run::branch::{self, BranchError};
use crate::run::episode::{Episode, Status, TimePoint};
use crate::run::timeline::{BackUnit, SeekError, Timeline, TimelineMemory, DEFAULT_CAP_BYTES};
use crate::searchers::phase::PhaseStep;

/// Episodes stepped together. A searcher that does not deliberate, racing
/// one that does, makes no more real moves than it while it runs, so the
/// boards compare paths rather than speed; once it is done the walker runs
/// free.
pub struct Race {
    runs: Vec<Episode>,
    /// For each run, the run whose moves pace it.
    pacer: Vec<Option<usize>>,
    /// For each run, the moves "Step move" has asked it to have made.
    asked: Vec<u32>,
    /// For each run, its snapshots and furthest point.
    timelines: Vec<Timeline>,
    /// For each run, where it branched from its parents, oldest first.
    lineage: Vec<Vec<BranchPoint>>,
}

/// Where a run branched: the move, and the configuration of the run it
/// branched from (see [`crate::run::branch`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BranchPoint {
    /// The moves shared with the parent.
    #[serde(rename = "move")]
    pub at: u32,
    /// The parent's configuration.
    pub config: Config,
}

/// For each run, the run whose moves pace it: a walker racing a run that
/// deliberates.
fn pacers(runs: &[Episode]) -> Vec<Option<usize>> {
    let deliberates: Vec<bool> = runs.iter().map(|r| r.searcher_info().deliberates).collect();
    (0..runs.len())
        .map(|i| {
            (!deliberates[i])
                .then(|| (0..runs.len()).find(|&j| j != i && deliberates[j]))
                .flatten()
        })
        .collect()
}

/// How many runs a race holds at most.
pub const MAX_RUNS: usize = 2;

impl Race {
    /// Trial 0 of each config.
    ///
    /// # Errors
    /// A [`ParamError`] for the first invalid config, or for a count of
    /// configs outside 1..=[`MAX_RUNS`].
    pub fn new(configs: &[Config]) -> Result<Race, ParamError> {
        if configs.is_empty() || configs.len() > MAX_RUNS {
            return Err(ParamError::new(
                "race",
                format!("{} configs", configs.len()),
                format!("1 to {MAX_RUNS} configs"),
            ));
        }
        let runs = configs
            .iter()
            .map(Episode::new)
            .collect::<Result<Vec<_>, _>>()?;
        let pacer = pacers(&runs);
        let asked = vec![0; runs.len()];
        let timelines = runs
            .iter()
            .map(|r| Timeline::new(r, DEFAULT_CAP_BYTES))
            .collect();
        Ok(Race {
            lineage: vec![Vec::new(); runs.len()],
            runs,
            pacer,
            asked,
            timelines,
        })
    }

    /// Branches every run at move `at` of the first run's timeline (see
    /// [`crate::run::branch`]): run i continues with `configs[i]` from
    /// where it stands at point (`at`, loop 0), its path so far kept; a
    /// run that had not reached `at` (a walker paced behind, or one that
    /// ended) branches where it ended. The branched runs stand at that
    /// point; their timelines reach back to move 0.
    ///
    /// # Errors
    /// A [`BranchError`]: a count of configs other than the runs', a
    /// world parameter changed, `at` past the first run's furthest move,
    /// or a timed run (it does not replay). Nothing changes then.
    pub fn branch(&mut self, configs: &[Config], at: u32) -> Result<(), BranchError> {
        if configs.len() != self.runs.len() {
            return Err(BranchError::Runs {
                given: configs.len(),
                runs: self.runs.len(),
            });
        }
        let reached = self.timelines[0].end().mv;
        if at > reached {
            return Err(BranchError::PastEnd { at, reached });
        }
        let mut fresh = Vec::with_capacity(self.runs.len());
        for (i, cfg) in configs.iter().enumerate() {
            let replayed = match self.runs[i].steps() == at {
                true => None,
                false => Some(
                    self.timelines[i]
                        .replay_at_most(&self.runs[i], TimePoint::at(at, 0))
                        .map_err(|e| BranchError::Seek(e.to_string()))?,
                ),
            };
            let parent = replayed.as_ref().unwrap_or(&self.runs[i]);
            let shared = parent.steps();
            let ep = branch::forced(parent, shared, cfg)?;
            let mut tl = Timeline::new(&ep, DEFAULT_CAP_BYTES);
            let ep = branch::follow(ep, shared, |e| tl.note(e));
            let from = BranchPoint {
                at: shared,
                config: parent.config().clone(),
            };
            fresh.push((ep, tl, from));
        }
        for (i, (ep, tl, from)) in fresh.into_iter().enumerate() {
            self.asked[i] = ep.steps();
            self.runs[i] = ep;
            self.timelines[i] = tl;
            self.lineage[i].push(from);
        }
        self.pacer = pacers(&self.runs);
        Ok(())
    }

    /// For each run, where it branched from its parents, oldest first
    /// (empty for a run of its own).
    pub fn lineage(&self) -> &[Vec<BranchPoint>] {
        &self.lineage
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
            let tl = &mut self.timelines[i];
            self.runs[i].advance_observed(k, limit, |e| tl.note(e));
            tl.note(&self.runs[i]);
        }
    }

    /// One loop on every unfinished run (one move for a walker).
    pub fn step_loop(&mut self) {
        for (r, tl) in self.runs.iter_mut().zip(&mut self.timelines) {
            r.step_loops(1);
            tl.note(r);
        }
    }

    /// One phase of the loop in flight on every unfinished run (see
    /// [`Episode::step_phase`]); a walker racing an MCTS run moves only
    /// while behind it. Returns what each run did (`None`: nothing).
    pub fn step_phase(&mut self) -> Vec<Option<PhaseStep>> {
        (0..self.runs.len())
            .map(|i| {
                if let Some(j) = self.pacer[i] {
                    let pacer = &self.runs[j];
                    if pacer.status() == Status::Running && self.runs[i].steps() >= pacer.steps() {
                        return None;
                    }
                }
                let step = self.runs[i].step_phase();
                self.timelines[i].note(&self.runs[i]);
                step
            })
            .collect()
    }

    /// Each run's point and the furthest point it has reached.
    pub fn timeline(&self) -> Vec<(TimePoint, TimePoint)> {
        self.runs
            .iter()
            .zip(&self.timelines)
            .map(|(r, tl)| (r.point(), tl.end()))
            .collect()
    }

    /// What each run's snapshots hold.
    pub fn memory(&self) -> Vec<TimelineMemory> {
        self.timelines.iter().map(Timeline::memory).collect()
    }

    /// Moves every run to point `to` of its timeline, the state reached
    /// going forward. `to` must be a point one of the runs has reached;
    /// a run that has not reached it, or whose decision there ran fewer
    /// loops, shows its latest point before it.
    ///
    /// # Errors
    /// A [`SeekError`] naming the point and the points allowed when no run
    /// has it (the run that went furthest names its range); nothing changes.
    pub fn seek(&mut self, to: TimePoint) -> Result<(), SeekError> {
        self.seek_each(&vec![to; self.runs.len()])
    }

    /// Moves run `i` to point `to[i]` of its own timeline, as [`Race::seek`]
    /// does (a race stepped loop by loop leaves its runs at different
    /// moves: a link holds each one's point).
    ///
    /// # Errors
    /// As [`Race::seek`]; also a [`SeekError`] when `to` does not hold one
    /// point per run. Nothing changes then.
    pub fn seek_each(&mut self, to: &[TimePoint]) -> Result<(), SeekError> {
        if to.len() != self.runs.len() {
            return Err(SeekError::Param(crate::param::ParamError::new(
                "seek",
                format!("{} points", to.len()),
                format!("one point, or one per run ({})", self.runs.len()),
            )));
        }
        let mut exact: Vec<Result<Episode, SeekError>> = self
            .runs
            .iter()
            .zip(&self.timelines)
            .zip(to)
            .map(|((r, tl), &to)| tl.replay(r, to))
            .collect();
        if exact.iter().all(Result::is_err) {
            let furthest = (0..self.runs.len())
                .max_by_key(|&i| (self.timelines[i].end(), std::cmp::Reverse(i)))
                .unwrap_or(0);
            return Err(exact
                .swap_remove(furthest)
                .err()
                .expect("every replay failed"));
        }
        let mut landed = Vec::with_capacity(self.runs.len());
        for (i, r) in exact.into_iter().enumerate() {
            landed.push(match r {
                Ok(ep) => ep,
                Err(_) => self.timelines[i].replay_at_most(&self.runs[i], to[i])?,
            });
        }
        for (i, ep) in landed.into_iter().enumerate() {
            self.asked[i] = ep.steps();
            self.runs[i] = ep;
        }
        Ok(())
    }

    /// Moves every run one `unit` back from where the first run stands
    /// (see [`Timeline::back`]); false at the start, where nothing moves.
    ///
    /// # Errors
    /// As [`Race::seek`]; nothing changes then.
    pub fn back(&mut self, unit: BackUnit) -> Result<bool, SeekError> {
        match self.timelines[0].back(&self.runs[0], unit)? {
            Some(to) => self.seek(to).map(|()| true),
            None => Ok(false),
        }
    }

    /// Finishes the decision under way and makes one real move, on every
    /// unfinished run, in one call however long a plan takes to make.
    pub fn step_move(&mut self) {
        self.ask_move();
        while !self.make_asked_moves() {}
    }

    /// Asks every unfinished run for one more real move than it has made or
    /// was already asked for; [`Race::make_asked_moves`] makes them.
    pub fn ask_move(&mut self) {
        for (r, asked) in self.runs.iter().zip(&mut self.asked) {
            if r.status() == Status::Running {
                *asked = (*asked).max(r.steps()) + 1;
            }
        }
    }

    /// One call of bounded length toward the moves asked for (see
    /// [`Episode::step_move_bounded`]): a planner makes at most
    /// [`crate::run::episode::PLAN_CALL_SLICES`] slices of its plan, so the page's
    /// worker can answer between calls. Returns true once every run has
    /// made them or ended.
    pub fn make_asked_moves(&mut self) -> bool {
        let mut done = true;
        for ((r, &asked), tl) in self
            .runs
            .iter_mut()
            .zip(&self.asked)
            .zip(&mut self.timelines)
        {
            while r.status() == Status::Running && r.steps() < asked {
                let moved = r.step_move_bounded();
                tl.note(r);
                if !moved {
                    done = false;
                    break;
                }
            }
        }
        done
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
            ..Config::default()
        }
        .with(&[("loops", "10")]);
        let beam = mcts.clone().with(&[
            ("searcher", "beam"),
            ("beam_width", "8"),
            ("beam_depth", "20"),
        ]);
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
    fn step_move_is_made_in_calls_of_bounded_length_while_a_plan_is_made() {
        // "Step move" on a race of MCTS and a planner that has yet to make
        // its plan: the page's worker answers between calls, so no call may
        // make the whole plan. (A configuration no other test plans: plans
        // are kept for the process.)
        let mcts = Config {
            n: 13,
            ..Config::default()
        }
        .with(&[("loops", "10")]);
        let beam = mcts.clone().with(&[
            ("searcher", "beam"),
            ("beam_width", "6"),
            ("beam_depth", "17"),
        ]);
        let mut race = Race::new(&[mcts.clone(), beam.clone()]).unwrap();
        // A clock that stands still: only the slice count ends a call.
        for r in race.runs_mut() {
            r.set_clock(|| 0.0);
        }
        race.ask_move();
        let mut calls = 0;
        let mut last = None;
        while !race.make_asked_moves() {
            calls += 1;
            let [a, b] = [&race.runs()[0], &race.runs()[1]];
            assert_eq!(
                a.steps(),
                1,
                "the MCTS run makes its move in the first call"
            );
            assert_eq!(b.steps(), 0, "no move before the plan is made");
            let p = b.planning().expect("still planning");
            let at = Some((p.stage, p.done));
            assert_ne!(at, last, "each call works on the plan");
            last = at;
        }
        assert!(calls >= 3, "the plan took {calls} calls");
        assert_eq!(race.runs()[0].steps(), 1);
        assert_eq!(race.runs()[1].steps(), 1);
        assert!(race.runs()[1].planning().is_none());
        // Asked twice, two moves; with the plan made, in one call.
        race.ask_move();
        race.ask_move();
        assert!(race.make_asked_moves());
        assert_eq!(race.runs()[0].steps(), 3);
        assert_eq!(race.runs()[1].steps(), 3);
        // The same moves as step_move, which makes them in one call.
        let mut whole = Race::new(&[mcts, beam]).unwrap();
        for _ in 0..3 {
            whole.step_move();
        }
        for i in 0..2 {
            assert_eq!(whole.runs()[i].path(), race.runs()[i].path(), "run {i}");
        }
    }

    #[test]
    fn a_walker_keeps_pace_with_mcts_and_shares_its_target() {
        let mcts = Config {
            n: 15,
            ..Config::default()
        }
        .with(&[("loops", "10")]);
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
