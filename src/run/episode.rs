//! One trial: a target, a searcher, and the moves until detection or the step cap.

use crate::config::{Config, Game};
use crate::game::belief::BeliefState;
use crate::game::budget::Budget;
use crate::game::counters::Counters;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::layer::Layer;
use crate::game::prior::{PriorSpec, TargetPrior};
use crate::game::rng::{self, Rng};
use crate::game::traces::Traces;
use crate::param::ParamError;
use crate::searchers::decision::DecisionView;
use crate::searchers::mcts::search::{BELIEF, KEEP_TRACES, LOOPS, MS};
use crate::searchers::{MoveScores, Planning, Searcher, SearcherInfo, Setup, World};

/// Where an episode stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Still searching.
    Running,
    /// The target was detected.
    Found,
    /// The step cap ended the episode first (a failure).
    Capped,
}

/// The result of one trial.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TrialResult {
    /// Real moves made.
    pub steps: u32,
    /// Fewest moves that would have detected the target.
    pub optimal: u32,
    /// True when the target was detected.
    pub found: bool,
    /// The target cell.
    pub target: u32,
    /// Rollout counters over the whole episode.
    pub counters: Counters,
}

/// How many numbers [`TrialResult::fields`] gives.
pub const TRIAL_FIELDS: usize = 7;

impl TrialResult {
    /// steps / optimal, `None` when optimal is 0.
    pub fn ratio(&self) -> Option<f64> {
        (self.optimal > 0).then(|| self.steps as f64 / self.optimal as f64)
    }

    /// The result as numbers, for passing between workers:
    /// `[steps, optimal, found (0/1), target, rollouts, rollout_steps, truncated]`.
    pub fn fields(&self) -> [f64; TRIAL_FIELDS] {
        [
            self.steps as f64,
            self.optimal as f64,
            self.found as u8 as f64,
            self.target as f64,
            self.counters.rollouts as f64,
            self.counters.rollout_steps as f64,
            self.counters.truncated as f64,
        ]
    }

    /// Reads [`TrialResult::fields`] back; `None` unless every number is a
    /// non-negative integer in range.
    pub fn from_fields(f: &[f64]) -> Option<TrialResult> {
        let int = |v: f64, max: f64| (v >= 0.0 && v <= max && v.fract() == 0.0).then_some(v);
        let u32max = u32::MAX as f64;
        let u53 = 9_007_199_254_740_992.0;
        if f.len() != TRIAL_FIELDS {
            return None;
        }
        Some(TrialResult {
            steps: int(f[0], u32max)? as u32,
            optimal: int(f[1], u32max)? as u32,
            found: int(f[2], 1.0)? == 1.0,
            target: int(f[3], u32max)? as u32,
            counters: Counters {
                rollouts: int(f[4], u53)? as u64,
                rollout_steps: int(f[5], u53)? as u64,
                truncated: int(f[6], u53)? as u64,
            },
        })
    }
}

/// Slices of a plan being made (about a millisecond each at N = 40) after
/// which a call of [`Episode::advance`] stops, at any `k`: at a set speed
/// (k moves a frame) a frame's worth of planning.
pub const PLAN_CALL_SLICES: u32 = 8;

/// Milliseconds on the episode's clock after which a call of
/// [`Episode::advance`] makes no further slice of a plan (slices are longer
/// on large lattices).
pub const PLAN_CALL_MS: f64 = 8.0;

/// The most moves of a searcher that does not deliberate between readings
/// of the clock in [`Episode::advance`]; the stride doubles while a stride
/// of moves takes under PLAN_CALL_MS ÷ 64.
const MAX_STRIDE: u64 = 1024;

/// One call's share of the slices of a plan being made (or of the work
/// before a decision's loops): [`PLAN_CALL_SLICES`] of them, or as many as
/// fit in [`PLAN_CALL_MS`] from the start of the call.
struct CallShare {
    slices: u32,
    t0: f64,
}

impl CallShare {
    fn new(budget: &Budget) -> CallShare {
        CallShare {
            slices: 0,
            t0: budget.now(),
        }
    }

    /// Counts one more slice; true when the call has had its share.
    fn slice(&mut self, budget: &Budget) -> bool {
        self.slices += 1;
        self.slices == PLAN_CALL_SLICES || budget.now() - self.t0 >= PLAN_CALL_MS
    }
}

/// One trial, advanced move by move or loop by loop.
pub struct Episode {
    cfg: Config,
    info: &'static SearcherInfo,
    torus: Torus,
    sensor: Sensor,
    belief: BeliefState,
    searcher: Box<dyn Searcher>,
    rng: Rng,
    budget: Budget,
    traces: Traces,
    counters: Counters,
    target: u32,
    optimal: u32,
    path: Vec<u32>,
    status: Status,
    /// Detection switched off (see [`Episode::blind`]).
    blind: bool,
}

impl Episode {
    /// Trial 0 of `cfg` (the trial the page shows).
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field.
    pub fn new(cfg: &Config) -> Result<Episode, ParamError> {
        Episode::trial(cfg, 0)
    }

    /// Trial `index` of a batch: its streams derive from `(cfg.seed, index)`
    /// only (the world's from stream 2·index, the searcher's from 2·index + 1),
    /// so any split of a batch gives the same trials.
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field.
    pub fn trial(cfg: &Config, index: u64) -> Result<Episode, ParamError> {
        let Game {
            torus,
            sensor,
            prior,
            start,
        } = cfg.game()?;
        let mut world = rng::stream(cfg.seed, 2 * index);
        let target = prior.sample(&mut world);
        let plan = cfg.known.then(|| {
            TargetPrior::new(&torus, &PriorSpec::Delta { cell: Some(target) })
                .expect("the target is on the lattice")
        });
        let info = cfg.searcher.info();
        let searcher = (info.build)(&Setup {
            settings: &cfg.settings,
            torus: &torus,
            sensor: &sensor,
            start,
            rv: cfg.rv,
            step_cap: cfg.step_cap,
        });
        let s = &cfg.settings;
        let mut ep = Episode {
            cfg: cfg.clone(),
            info,
            belief: BeliefState::new(s.choice(&BELIEF), prior, plan),
            searcher,
            rng: rng::stream(cfg.seed, 2 * index + 1),
            budget: Budget::new(s.u32(&LOOPS), s.opt_float(&MS)),
            traces: Traces::new(s.u32(&KEEP_TRACES) as usize),
            counters: Counters::default(),
            target,
            optimal: sensor.optimal_steps(&torus, start, target),
            path: vec![start],
            status: Status::Running,
            blind: false,
            sensor,
            torus,
        };
        ep.belief.search_around(&ep.sensor, start);
        if ep.sensor.detects(&ep.torus, start, target) {
            ep.status = Status::Found;
        }
        Ok(ep)
    }

    /// Trial 0 of `cfg` with detection switched off: the searcher moves
    /// until the step cap as if the target were nowhere it looked. Until
    /// detection a searcher learns nothing of the target, so this is the
    /// path every trial follows up to its detection (for a deterministic
    /// searcher: `crate::analysis::exact`).
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field.
    pub fn blind(cfg: &Config) -> Result<Episode, ParamError> {
        Episode::blind_trial(cfg, 0)
    }

    /// Trial `i` of `cfg` with detection switched off (see [`Episode::blind`]):
    /// for a searcher that draws random numbers, the path trial `i` follows
    /// up to its detection.
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field.
    pub fn blind_trial(cfg: &Config, i: u64) -> Result<Episode, ParamError> {
        let mut ep = Episode::trial(cfg, i)?;
        ep.blind = true;
        ep.status = Status::Running;
        Ok(ep)
    }

    /// Sets the millisecond clock that time budgets read.
    pub fn set_clock(&mut self, clock: fn() -> f64) {
        self.budget.set_clock(clock);
    }

    /// Runs up to `max_loops` loops of the current decision (a searcher that
    /// does not deliberate makes its move at once). Returns true when a real
    /// move was made.
    pub fn step_loops(&mut self, max_loops: u32) -> bool {
        if self.status != Status::Running || max_loops == 0 {
            return false;
        }
        let pos = self.position();
        let mut w = World {
            torus: &self.torus,
            sensor: &mut self.sensor,
            belief: &mut self.belief,
            rng: &mut self.rng,
            pos,
            budget: &mut self.budget,
            traces: &mut self.traces,
            counters: &mut self.counters,
        };
        match self.searcher.think(&mut w, max_loops) {
            Some(m) => {
                self.apply(m);
                true
            }
            None => false,
        }
    }

    /// Completes the current decision and makes one real move. Returns the status.
    pub fn step_move(&mut self) -> Status {
        while self.status == Status::Running && !self.step_loops(u32::MAX) {}
        self.status
    }

    /// Works toward one real move in a call of bounded length: a searcher
    /// that deliberates completes its decision (its loops or time budget
    /// bound it), a planner makes its move or at most [`PLAN_CALL_SLICES`]
    /// slices of its plan (see [`Episode::advance`]). Returns true once the
    /// move is made or the episode has ended.
    pub fn step_move_bounded(&mut self) -> bool {
        if self.info.deliberates {
            // Its loops are bounded by its budget; work before them (the
            // belief MCTS's plan) is cut as a planner's plan is.
            let mut share = CallShare::new(&self.budget);
            while self.status == Status::Running && !self.step_loops(u32::MAX) {
                if self.searcher.planning().is_some() && share.slice(&self.budget) {
                    return false;
                }
            }
            return true;
        }
        self.advance_within(1, 1) == 1 || self.status != Status::Running
    }

    /// `k` loops of work, carried across decisions, stopping early if the
    /// episode ends; for a searcher that does not deliberate, up to `k`
    /// moves, where a move may instead be slices of a plan being made, the
    /// call stopping after [`PLAN_CALL_SLICES`] slices or once
    /// [`PLAN_CALL_MS`] have passed (checked after every slice, and after
    /// moves). Returns the real moves made.
    pub fn advance(&mut self, k: u64) -> u64 {
        self.advance_within(k, u64::MAX)
    }

    /// As [`Episode::advance`], making at most `max_moves` real moves (a
    /// searcher that does not deliberate stops there; one that does
    /// finishes the loops).
    pub fn advance_within(&mut self, k: u64, max_moves: u64) -> u64 {
        let mut moves = 0;
        if !self.info.deliberates {
            let mut share = CallShare::new(&self.budget);
            let t0 = share.t0;
            // The call also ends once PLAN_CALL_MS has passed after a move:
            // the caller sizes `k` from the moves it has timed, and a move of
            // a planner on a large lattice (rollout improvement at N = 512)
            // can take a second, so a `k` sized for the cheap first moves
            // held the worker for half a minute. The clock is a host call in
            // wasm, so while moves are cheap it is read every `stride` of them.
            let (mut stride, mut since, mut last) = (1u64, 0u64, t0);
            'calls: for _ in 0..k {
                if moves >= max_moves || self.status != Status::Running {
                    break;
                }
                // A move, or slices of a plan being made until it is made,
                // or the call has done PLAN_CALL_SLICES of them or spent
                // PLAN_CALL_MS: the caller sized `k` for moves of
                // microseconds, not slices of a millisecond (or more on a
                // large lattice), and at the slowest speed (k = 1) one
                // slice a frame would take minutes. Only the pace depends
                // on the clock, never the plan.
                while !self.step_loops(1) {
                    if share.slice(&self.budget) || self.status != Status::Running {
                        break 'calls;
                    }
                }
                moves += 1;
                since += 1;
                if since == stride {
                    since = 0;
                    let now = self.budget.now();
                    if now - t0 >= PLAN_CALL_MS {
                        break;
                    }
                    if now - last < PLAN_CALL_MS / 64.0 && stride < MAX_STRIDE {
                        stride *= 2;
                    }
                    last = now;
                }
            }
            return moves;
        }
        let mut left = k;
        let mut share = CallShare::new(&self.budget);
        while left > 0 && self.status == Status::Running {
            let before = self.counters.rollouts;
            let moved = self.step_loops(left.min(u32::MAX as u64) as u32);
            let did = self.counters.rollouts - before;
            left -= did.min(left);
            if moved {
                moves += 1;
            } else if did == 0 {
                // A slice of the work before the loops (the belief MCTS's
                // plan) is not a loop: as a planner's slices, at most
                // PLAN_CALL_SLICES of them or PLAN_CALL_MS a call.
                if self.searcher.planning().is_none() || share.slice(&self.budget) {
                    break;
                }
            }
        }
        moves
    }

    /// Runs to detection or the step cap.
    pub fn run(&mut self) -> TrialResult {
        while self.step_move() == Status::Running {}
        self.result()
    }

    fn apply(&mut self, m: Move) {
        let pos = self.torus.step(self.position(), m);
        self.path.push(pos);
        self.belief.search_around(&self.sensor, pos);
        self.searcher.observe(&self.torus, m, pos);
        if !self.blind && self.sensor.detects(&self.torus, pos, self.target) {
            self.status = Status::Found;
        } else if self.steps() >= self.cfg.step_cap {
            self.status = Status::Capped;
        }
    }

    /// The configuration.
    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// The searcher's registry entry.
    pub fn searcher_info(&self) -> &'static SearcherInfo {
        self.info
    }

    /// The lattice.
    pub fn torus(&self) -> &Torus {
        &self.torus
    }

    /// Where the episode stands.
    pub fn status(&self) -> Status {
        self.status
    }

    /// Real moves made so far.
    pub fn steps(&self) -> u32 {
        (self.path.len() - 1) as u32
    }

    /// Fewest moves that detect the target from the start.
    pub fn optimal(&self) -> u32 {
        self.optimal
    }

    /// The true target cell.
    pub fn target(&self) -> u32 {
        self.target
    }

    /// The start cell.
    pub fn start(&self) -> u32 {
        self.path[0]
    }

    /// The searcher's cell.
    pub fn position(&self) -> u32 {
        *self.path.last().expect("the path holds the start")
    }

    /// Every cell occupied, start first.
    pub fn path(&self) -> &[u32] {
        &self.path
    }

    /// What is known about the target.
    pub fn belief(&self) -> &BeliefState {
        &self.belief
    }

    /// The searcher's counts for heat layer `layer` (MCTS visits, NSARW's
    /// own counts), if it has them; `scratch` is room to assemble them.
    pub fn counts<'a>(&'a self, layer: Layer, scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        self.searcher.counts(layer, scratch)
    }

    /// The decision under way, for a searcher that deliberates.
    pub fn decision(&self) -> Option<DecisionView> {
        self.searcher.decision(&self.torus, self.position())
    }

    /// The cells the searcher means to enter next, in order (empty unless
    /// it plans a path).
    pub fn intent(&self) -> &[u32] {
        self.searcher.intent()
    }

    /// How a planner scored the four moves at its last decision.
    pub fn scores(&self) -> Option<MoveScores> {
        self.searcher.scores()
    }

    /// How far the plan being made has got (a planner that plans in
    /// slices, while it does).
    pub fn planning(&self) -> Option<Planning> {
        self.searcher.planning()
    }

    /// Loops done in the decision under way (or the last one).
    pub fn loops_done(&self) -> u32 {
        self.budget.loops_done()
    }

    /// Work done so far: loops for a searcher that deliberates, else moves.
    pub fn work(&self) -> u64 {
        if self.info.deliberates {
            self.counters.rollouts
        } else {
            self.steps() as u64
        }
    }

    /// Rollout counters for the whole episode.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// Rollout counters for the decision under way (or the last one).
    pub fn decision_counters(&self) -> Counters {
        self.budget.counters()
    }

    /// Kept rollout traces, newest first, each with its practice target.
    pub fn traces(&self) -> impl Iterator<Item = (&[u32], u32)> + '_ {
        self.traces.iter()
    }

    /// Changes whenever heat layer `layer` may have changed: never for the
    /// priors, with each newly searched cell for the posterior and the
    /// searched area, with each loop or move for the searcher's counts.
    pub fn generation(&self, layer: Layer) -> u64 {
        match layer {
            Layer::Prior | Layer::Plan => 0,
            Layer::Posterior | Layer::Searched => self.belief.generation(),
            Layer::Visits | Layer::Walker => self.counters.rollouts + self.steps() as u64,
        }
    }

    /// The result so far.
    pub fn result(&self) -> TrialResult {
        TrialResult {
            steps: self.steps(),
            optimal: self.optimal,
            found: self.status == Status::Found,
            target: self.target,
            counters: self.counters,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

    /// A blind trial of `searcher` at N = 40 (the default prior).
    fn blind(searcher: &str) -> Episode {
        Episode::blind(&Config::default().with(&[("searcher", searcher)])).unwrap()
    }

    #[test]
    fn a_trial_result_passes_between_workers_as_its_fields_and_back() {
        // A result whose every field differs (the MCTS counts its rollouts),
        // in the documented order, read back unchanged; the worker pool
        // sums batches from these numbers.
        let cfg = Config::default().with(&[("n", "12"), ("sigma", "2"), ("loops", "10")]);
        let r = Episode::trial(&cfg, 3).unwrap().run();
        let c = r.counters;
        assert!(r.found && r.steps > r.optimal && c.rollouts > c.truncated);
        let want = [
            r.steps,
            r.optimal,
            1,
            r.target,
            c.rollouts as u32,
            c.rollout_steps as u32,
            c.truncated as u32,
        ]
        .map(f64::from);
        assert_eq!(r.fields(), want);
        assert_eq!(TrialResult::from_fields(&r.fields()), Some(r));
        let capped = TrialResult { found: false, ..r };
        assert_eq!(capped.fields()[2], 0.0);
        assert_eq!(TrialResult::from_fields(&capped.fields()), Some(capped));
        // Each field at the ends of its range, then just past them.
        let u53 = 9_007_199_254_740_992.0;
        for (i, max) in [
            u32::MAX as f64,
            u32::MAX as f64,
            1.0,
            u32::MAX as f64,
            u53,
            u53,
            u53,
        ]
        .into_iter()
        .enumerate()
        {
            // 2^53 + 1 rounds to 2^53 in f64: the next number past it is 2^53 + 2.
            let past = if max == u53 { max + 2.0 } else { max + 1.0 };
            for (v, ok) in [
                (0.0, true),
                (max, true),
                (-1.0, false),
                (past, false),
                (0.5, false),
            ] {
                let mut f = r.fields();
                f[i] = v;
                assert_eq!(
                    TrialResult::from_fields(&f).is_some(),
                    ok,
                    "field {i} = {v}"
                );
            }
        }
        assert_eq!(TrialResult::from_fields(&r.fields()[..6]), None);
        assert_eq!(TrialResult::from_fields(&[0.0; TRIAL_FIELDS + 1]), None);
    }

    #[test]
    fn the_accessors_report_the_trial_and_its_work_as_it_goes() {
        // Start (3, 5) and target (8, 9), 1-based: 9 apart, so the fewest
        // moves that detect it (r_v = 1) are 8.
        let cfg = Config::default().with(&[
            ("n", "12"),
            ("start", "3,5"),
            ("target", "8,9"),
            ("loops", "10"),
        ]);
        let mut ep = Episode::trial(&cfg, 0).unwrap();
        let t = Torus::new(12).unwrap();
        assert_eq!(ep.config(), &cfg);
        assert_eq!((ep.start(), ep.target()), (t.cell(2, 4), t.cell(7, 8)));
        assert_eq!(ep.optimal(), 8);
        // The decision's loops and rollouts, and the episode's, as loops run
        // (a call's loops stop at the end of the decision).
        let rollouts = |ep: &Episode| (ep.decision_counters().rollouts, ep.counters().rollouts);
        assert!(!ep.step_loops(3));
        assert_eq!((ep.loops_done(), ep.work(), rollouts(&ep)), (3, 3, (3, 3)));
        assert!(ep.step_loops(100));
        assert_eq!(
            (ep.loops_done(), ep.work(), rollouts(&ep)),
            (10, 10, (10, 10))
        );
        assert!(!ep.step_loops(4));
        assert_eq!(
            (ep.loops_done(), ep.work(), rollouts(&ep)),
            (4, 14, (4, 14))
        );
        assert_eq!((ep.steps(), ep.start()), (1, t.cell(2, 4)));
        // The visit counts change with every loop, the one that makes the
        // move too: their generation must, for the page to redraw them.
        for _ in 0..25 {
            let g = ep.generation(Layer::Visits);
            ep.step_loops(1);
            assert!(ep.generation(Layer::Visits) > g, "loop {}", ep.work());
        }
        assert_eq!(ep.steps(), 3);
        // A walk's work is its moves.
        let mut walk = Episode::trial(&cfg.clone().with(&[("searcher", "rw")]), 0).unwrap();
        for _ in 0..5 {
            assert!(walk.step_loops(1));
        }
        assert_eq!(
            (walk.work(), walk.steps(), walk.counters().rollouts),
            (5, 5, 0)
        );
    }

    #[test]
    fn an_ended_episode_and_a_call_for_no_loops_change_nothing() {
        // Found (a walk and an MCTS) and capped (at 2 moves): whatever is
        // called after the end, the result stands.
        for (searcher, cap, status) in [
            ("rw", "500", Status::Found),
            ("mcts", "500", Status::Found),
            ("rw", "2", Status::Capped),
        ] {
            let cfg = Config::default().with(&[
                ("searcher", searcher),
                ("n", "12"),
                ("sigma", "2"),
                ("loops", "10"),
                ("step_cap", cap),
            ]);
            let mut ep = Episode::trial(&cfg, 3).unwrap();
            assert!(!ep.step_loops(0), "{searcher}");
            assert_eq!((ep.steps(), ep.counters()), (0, Counters::default()));
            let r = ep.run();
            assert_eq!(ep.status(), status, "{searcher}");
            assert!(r.steps > 0);
            assert!(!ep.step_loops(1) && !ep.step_loops(u32::MAX), "{searcher}");
            assert_eq!(ep.advance(10), 0);
            assert!(ep.step_move_bounded());
            assert_eq!(ep.step_move(), status);
            assert_eq!((ep.result(), ep.path().len()), (r, r.steps as usize + 1));
        }
    }

    #[test]
    fn a_call_of_moves_makes_all_k_while_time_allows_reading_the_clock_rarely() {
        // Microsecond moves on a clock that gains 1 µs a reading (and
        // stands far from 0, as a page's does: a call counts from its own
        // start): all k moves, with the clock read log2(1024) + k/1024
        // times, not k. One reading as the call starts, one after each
        // stride of 1, 2, 4, …, 512 moves (1023 in all; each doubles the
        // stride), then one after each 1024 moves of the 8977 left.
        static READS: AtomicU64 = AtomicU64::new(0);
        let mut ep = blind("rw");
        ep.set_clock(|| 1e6 + READS.fetch_add(1, Relaxed) as f64 * 1e-3);
        assert_eq!(ep.advance(10_000), 10_000);
        assert_eq!(READS.load(Relaxed), 1 + 10 + 8, "clock readings");
        let mut one = blind("rw");
        for _ in 0..10_000 {
            one.step_move();
        }
        assert_eq!(one.path(), ep.path());
    }

    #[test]
    fn a_call_of_moves_ends_once_its_time_is_spent_and_the_path_is_the_same() {
        // Moves that each take 5 ms on the episode's clock (a slow planner
        // on a large lattice): a call asked for 1000 moves ends after two,
        // the first reading past PLAN_CALL_MS. The moves are the same as
        // made one at a time: only the pace depends on the clock.
        static TICKS: AtomicU64 = AtomicU64::new(0);
        for searcher in ["rw", "horizon"] {
            TICKS.store(0, Relaxed);
            let mut ep = blind(searcher);
            ep.set_clock(|| 5.0 * TICKS.fetch_add(1, Relaxed) as f64);
            let mut calls = 0;
            while ep.steps() < 60 {
                TICKS.store(0, Relaxed);
                assert_eq!(ep.advance(1000), 2, "{searcher}");
                calls += 1;
            }
            assert_eq!(calls, 30);
            let mut one = blind(searcher);
            while one.steps() < 60 {
                one.step_move();
            }
            assert_eq!(one.path(), ep.path(), "{searcher}");
        }
    }

    #[test]
    fn the_belief_mcts_plan_is_cut_into_calls_as_a_planner_plan_is() {
        // pomcp at N = 96 makes a plan of thousands of horizon moves before
        // its first loop. On a clock that stands still a call makes
        // PLAN_CALL_SLICES slices of it, whether it is asked for 1 loop or
        // 10 000 (advance) or for a move (step_move_bounded); once the plan
        // is made, the loops run and count as before.
        // (A configuration no other test plans: plans are kept for the
        // process.)
        let cfg = Config::default().with(&[
            ("variant", "pomcp"),
            ("n", "96"),
            ("sigma", "12"),
            ("rollout_cap", "9999"),
        ]);
        let progress = |ep: &Episode| ep.planning().map(|p| p.done);
        let mut one = Episode::blind(&cfg).unwrap();
        one.set_clock(|| 0.0);
        let mut per_slice = Vec::new();
        for _ in 0..PLAN_CALL_SLICES {
            assert!(!one.step_loops(1));
            per_slice.push(progress(&one).unwrap());
        }
        // A call asked for a move makes as many slices, on a clock that
        // stands at any time (a call counts from its own start).
        let mut bounded = Episode::blind(&cfg).unwrap();
        bounded.set_clock(|| 1e6);
        assert!(!bounded.step_move_bounded());
        assert_eq!(progress(&bounded), per_slice.last().copied());
        let mut ep = Episode::blind(&cfg).unwrap();
        ep.set_clock(|| 0.0);
        assert_eq!(ep.advance(1), 0);
        assert_eq!(progress(&ep), per_slice.last().copied(), "advance(1)");
        assert_eq!(ep.advance(10_000), 0);
        let two = progress(&ep).unwrap();
        assert!(
            two > per_slice[PLAN_CALL_SLICES as usize - 1],
            "advance(10 000)"
        );
        assert!(!ep.step_move_bounded());
        assert!(progress(&ep).unwrap() > two, "step_move_bounded");
        assert_eq!(ep.counters().rollouts, 0);
        // A clock that gains 5 ms a reading (the decision's budget reads it
        // too) ends a call within two slices, by PLAN_CALL_MS. (Before any
        // episode has made the whole plan: it is kept for the process.)
        static TICKS: AtomicU64 = AtomicU64::new(0);
        let mut timed = Episode::blind(&cfg).unwrap();
        timed.set_clock(|| 5.0 * TICKS.fetch_add(1, Relaxed) as f64);
        TICKS.store(0, Relaxed);
        assert_eq!(timed.advance(10_000), 0);
        let p = progress(&timed).unwrap();
        assert!(p == per_slice[0] || p == per_slice[1], "{p}: {per_slice:?}");
        // The plan done, a call runs its k loops (the default L = 100 a move).
        while ep.planning().is_some() {
            ep.advance(1);
        }
        let before = ep.counters().rollouts;
        ep.advance(250);
        assert_eq!(ep.counters().rollouts - before, 250);
        assert_eq!(ep.steps(), 2);
    }
}
