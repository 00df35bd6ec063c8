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
use crate::searchers::phase::{PhaseKind, PhaseRecord, PhaseStep};
use crate::searchers::tree_export::{TreeError, TreeExport, TreeQuery};
use crate::searchers::{MoveScores, Planning, Searcher, SearcherInfo, Setup, World};
use std::sync::Arc;

pub use crate::run::trial_result::{TrialResult, TRIAL_FIELDS};

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

/// A point of an episode's timeline: loop `loop_` (0-based) of the
/// decision that makes real move `mv` + 1, and the last phase of it done.
/// With no phase, the state before that loop: `loop_` loops of the
/// decision done, none in flight. Points order as the run passes them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct TimePoint {
    /// Real moves made before the decision.
    #[serde(rename = "move")]
    pub mv: u32,
    /// Loops of the decision before this one (under `code`, its expansion
    /// rollouts count too).
    #[serde(rename = "loop")]
    pub loop_: u32,
    /// The last phase of loop `loop_` done (`None`: none of it yet).
    pub phase: Option<PhaseKind>,
}

impl TimePoint {
    /// The point before loop `loop_` of decision `mv`.
    pub fn at(mv: u32, loop_: u32) -> TimePoint {
        TimePoint {
            mv,
            loop_,
            phase: None,
        }
    }

    fn rank(self) -> (u32, u32, u8) {
        let p = self.phase.map_or(0, |k| k as u8 + 1);
        (self.mv, self.loop_, p)
    }
}

impl Ord for TimePoint {
    fn cmp(&self, other: &TimePoint) -> std::cmp::Ordering {
        self.rank().cmp(&other.rank())
    }
}

impl PartialOrd for TimePoint {
    fn partial_cmp(&self, other: &TimePoint) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl std::fmt::Display for TimePoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "move {}, loop {}", self.mv, self.loop_)?;
        match self.phase {
            Some(k) => write!(f, ", phase {k}"),
            None => f.write_str(", no phase"),
        }
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
    /// A bit per cell: the searcher has stood there.
    walked: Vec<u64>,
    /// Moves onto a cell the searcher had already stood on.
    revisits: u32,
    /// Where the last recorded phase step left the run (`None` after any
    /// other step).
    phased: Option<TimePoint>,
    /// Rollouts before the decision under way (the last real move's count).
    decision_rollouts: u64,
    /// The trial's index in its batch.
    index: u64,
    /// Moves made whatever the searcher decides: a branch's shared prefix
    /// (see `crate::run::branch`); empty for a run of its own.
    forced: Arc<[Move]>,
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
            walked: vec![0; torus.cells().div_ceil(64)],
            revisits: 0,
            phased: None,
            decision_rollouts: 0,
            index,
            forced: Arc::from([]),
            sensor,
            torus,
        };
        ep.belief.search_around(&ep.sensor, start);
        ep.walk_on(start);
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
        self.phased = None;
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
        self.advance_observed(k, max_moves, |_| {})
    }

    /// As [`Episode::advance_within`], calling `on_move` after each real move.
    pub fn advance_observed(
        &mut self,
        k: u64,
        max_moves: u64,
        mut on_move: impl FnMut(&Episode),
    ) -> u64 {
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
                on_move(self);
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
                on_move(self);
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

    fn apply(&mut self, decided: Move) {
        // In a branch's shared prefix the searcher decided, but the move
        // made is the parent run's.
        let m = self
            .forced
            .get(self.steps() as usize)
            .map_or(decided, |&f| f);
        self.decision_rollouts = self.counters.rollouts;
        let pos = self.torus.step(self.position(), m);
        self.path.push(pos);
        self.walk_on(pos);
        self.belief.search_around(&self.sensor, pos);
        self.searcher.observe(&self.torus, m, pos);
        if !self.blind && self.sensor.detects(&self.torus, pos, self.target) {
            self.status = Status::Found;
        } else if self.steps() >= self.cfg.step_cap {
            self.status = Status::Capped;
        }
    }

    /// Marks `cell` walked, counting a revisit if it was.
    fn walk_on(&mut self, cell: u32) {
        let (word, bit) = (cell as usize / 64, 1u64 << (cell % 64));
        if self.walked[word] & bit != 0 {
            self.revisits += 1;
        }
        self.walked[word] |= bit;
    }

    /// Moves onto a cell the searcher had already stood on (Theorem 2: a
    /// nearly self-avoiding walk makes few).
    pub fn revisits(&self) -> u32 {
        self.revisits
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
            // Four apart per loop or move, so that a loop's phases have
            // their own (a tree grows at expansion, `code` counts visits
            // as its rollout passes): a function of the timeline's point.
            Layer::Visits | Layer::Walker => {
                let phase = match self.phased.and_then(|p| p.phase) {
                    Some(PhaseKind::Backup) | None => 0,
                    Some(k) => k as u64 + 1,
                };
                4 * (self.counters.rollouts + self.steps() as u64) + phase
            }
        }
    }

    /// One phase of the decision's loop in flight (or one call of a
    /// searcher's work, for one without loops), recorded for
    /// [`Episode::phase`]. Returns what was done, `None` once the episode
    /// has ended. Phase by phase, loops make the same moves as whole.
    pub fn step_phase(&mut self) -> Option<PhaseStep> {
        self.step_phase_with(true)
    }

    /// As [`Episode::step_phase`], recording the phase only when `record`.
    pub fn step_phase_with(&mut self, record: bool) -> Option<PhaseStep> {
        if self.status != Status::Running {
            return None;
        }
        let at = self.point_now();
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
        let step = self.searcher.think_phase(&mut w, record);
        self.phased = match step.phase() {
            Some(k) if record => Some(TimePoint {
                phase: Some(k),
                ..at
            }),
            _ => None,
        };
        if let Some(m) = step.moved() {
            self.apply(m);
        }
        Some(step)
    }

    /// The point before any phase: moves made, loops of the decision done.
    fn point_now(&self) -> TimePoint {
        TimePoint::at(self.steps(), self.loops_of_decision())
    }

    /// Loops of the decision under way done so far (under `code`, its
    /// expansion rollouts too; 0 between decisions).
    pub fn loops_of_decision(&self) -> u32 {
        (self.counters.rollouts - self.decision_rollouts) as u32
    }

    /// Where the run stands on its timeline.
    pub fn point(&self) -> TimePoint {
        self.phased.unwrap_or_else(|| self.point_now())
    }

    /// The loop stepped phase by phase, as far as it has gone (`None`
    /// after any other step, or for a searcher without loops).
    pub fn phase(&self) -> Option<&PhaseRecord> {
        self.phased.and(self.searcher.phase())
    }

    /// The decision's search tree (a table's star), cut by `q`; `None` for
    /// a searcher without one.
    ///
    /// # Errors
    /// A [`TreeError`] for a query the tree cannot answer.
    pub fn tree(&self, q: &TreeQuery) -> Option<Result<TreeExport, TreeError>> {
        self.searcher.tree(&self.torus, self.position(), q)
    }

    /// A copy of the run as it stands, from which stepping gives what
    /// this one would (`None` when its searcher cannot copy itself).
    pub fn snapshot(&self) -> Option<Episode> {
        let searcher = self.searcher.snapshot()?;
        Some(Episode {
            cfg: self.cfg.clone(),
            info: self.info,
            torus: self.torus.clone(),
            sensor: self.sensor.clone(),
            belief: self.belief.clone(),
            searcher,
            rng: self.rng.clone(),
            budget: self.budget.clone(),
            traces: self.traces.clone(),
            counters: self.counters,
            target: self.target,
            optimal: self.optimal,
            path: self.path.clone(),
            status: self.status,
            blind: self.blind,
            walked: self.walked.clone(),
            revisits: self.revisits,
            phased: self.phased,
            decision_rollouts: self.decision_rollouts,
            index: self.index,
            forced: self.forced.clone(),
        })
    }

    /// The run at its start again (the same trial, detection and clock).
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field (none for a config
    /// that built this run).
    pub fn restart(&self) -> Result<Episode, ParamError> {
        let mut ep = Episode::trial(&self.cfg, self.index)?;
        ep.forced = self.forced.clone();
        if self.blind {
            ep.blind = true;
            ep.status = Status::Running;
        }
        ep.set_clock(self.budget.clock());
        Ok(ep)
    }

    /// The trial's index in its batch.
    pub fn index(&self) -> u64 {
        self.index
    }

    /// Makes the first `moves.len()` real moves these, whatever the
    /// searcher decides (it still decides each, and observes the move
    /// made); call before the first move.
    pub(crate) fn force(&mut self, moves: Arc<[Move]>) {
        self.forced = moves;
    }

    /// Real moves forced on the run (a branch's shared prefix; 0 for a
    /// run of its own).
    pub fn forced(&self) -> u32 {
        self.forced.len() as u32
    }

    /// The clock time budgets read.
    pub fn clock(&self) -> fn() -> f64 {
        self.budget.clock()
    }

    /// The time budget of a decision, if decisions are timed (then runs
    /// depend on the machine and do not replay).
    pub fn timed(&self) -> Option<f64> {
        self.budget.ms()
    }

    /// Forgets the phase of the last step (a snapshot at a move keeps the
    /// state, not how it was reached).
    pub(crate) fn forget_phase(&mut self) {
        self.phased = None;
    }

    /// Work done so far, as a count comparable with bytes copied: rollout
    /// steps, and 64 for each rollout and move.
    pub fn work_done(&self) -> u64 {
        self.counters.rollout_steps + 64 * (self.counters.rollouts + self.steps() as u64)
    }

    /// Bytes the run holds (what a snapshot copies), approximately.
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Episode>()
            + self.torus.heap_bytes()
            + self.sensor.heap_bytes()
            + self.belief.heap_bytes()
            + self.searcher.heap_bytes()
            + self.traces.heap_bytes()
            + std::mem::size_of_val(&self.path[..])
            + std::mem::size_of_val(&self.walked[..])
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
#[path = "episode_tests.rs"]
mod tests;
