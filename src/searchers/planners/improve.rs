//! Rollout improvement of a base policy (Bertsekas, Tsitsiklis & Wu 1997):
//! for each of the four moves, finish the search with the base policy,
//! compute the completed path's `Σ R_t` exactly, and take the cheapest.
//!
//! # Rule
//! A completion runs from the current cell until every cell with planning
//! mass is covered or the step cap, and costs `Σ_{t<cap} R_t` over its
//! moves (`R_t`: planning mass left), the exact expected number of further
//! moves (times the mass left now) if the searcher followed it. The
//! searcher keeps the cheapest completion found so far, its *incumbent*,
//! and follows it; at each move it completes each of the four moves with
//! the base (each base, with `base = best`) and adopts a completion only
//! when it is strictly cheaper than what is left of the incumbent. At the
//! first move the incumbent is the base's own path, so the searcher's
//! exact mean is never above its base's (the "fortified" rollout: the
//! guarantee then needs nothing of the base).
//!
//! Bases (parameter `base`): `cover`, the greedy coverage walk (the
//! neighbour that covers the most mass, else straight to the cell with the
//! most mass per step of distance; O(disc) per move); `sweep`, the fixed
//! lawnmower from the start with covered stretches skipped (it heads for
//! the first waypoint still adding mass); `horizon`, the receding-horizon
//! rule of depth `horizon` (its far-goal fallback only when nothing within
//! the horizon adds mass); `best`, all three. A decision costs
//! 4 × (bases) completions of up to N²/3 moves each at r_v = 1, so it is
//! made in slices of bounded work ([`SLICE_WORK`]), each completion resumed
//! where a slice stopped: the page's worker answers between slices, and the
//! moves do not depend on where the slices fall.

use super::sweep::{sweep_path, SweepPattern};
use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::named::named_enum;
use crate::game::sum::Sum;
use crate::param::{Param, ParamKind, Value};
use crate::searchers::decision::{MoveScores, Planning};
use crate::searchers::info::{Reads, SearcherInfo};
use crate::searchers::planning::completion::{decide, FarGoal, SLICE_WORK};
use crate::searchers::planning::coverage_walk::CoverageWalk;
use crate::searchers::planning::far_goal::{toward, FarScan};
use crate::searchers::planning::lookahead::{Lookahead, Scored, HORIZON};
use crate::searchers::searcher::{Searcher, World};
use std::borrow::Cow;

named_enum! {
    /// The base policy that rollout improvement completes searches with.
    pub enum Base {
        /// The greedy coverage walk.
        Cover = "cover",
        /// The lawnmower sweep from the start, covered stretches skipped.
        Sweep = "sweep",
        /// The receding-horizon rule (depth `horizon`).
        Horizon = "horizon",
        /// Every base above: the cheapest completion of any.
        Best = "best",
    }
}

const SINGLE: [Base; 3] = [Base::Cover, Base::Sweep, Base::Horizon];

/// What the decision panel says the scores are.
const MEANING: &str =
    "Σ R_t of the search completed by the base after this move (expected further moves × mass left)";

/// The base policy rollout improvement completes searches with.
pub static BASE: Param = Param {
    key: "base",
    label: "Base policy",
    kind: ParamKind::Choice(|| Base::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("cover")),
    help: "rollout improvement's base policy: cover (greedy coverage, the cheapest), sweep (the lawnmower, covered stretches skipped), horizon (depth horizon; slow), or best (all three; slow)",
    aliases: &[],
    choice_labels: &["coverage walk", "sweep", "horizon rule", "best of the three"],
    advanced: false,
};

/// Rollout improvement as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "improve",
    label: "Rollout improvement",
    help: "completes the search with a base policy after each of the four moves and follows the completion with the least expected time (never worse than its base)",
    deterministic: true,
    deliberates: false,
    params: &[
        Reads::always(&BASE),
        Reads::when(
            &HORIZON,
            |s| matches!(s.choice::<Base>(&BASE), Base::Horizon | Base::Best),
            "with base horizon or best",
        ),
    ],
    build: |s| {
        let base = s.settings.choice(&BASE);
        let h = s.settings.u32(&HORIZON);
        Box::new(Improve::new(base, h, s.step_cap, s.torus, s.sensor, s.start))
    },
};

/// The rollout improver.
pub struct Improve {
    base: Base,
    look: Lookahead,
    /// The sweep from the start (waypoints for the sweep base).
    sweep: Vec<u32>,
    /// Every sweep waypoint before this one adds no mass any more.
    sweep_from: usize,
    cov: Coverage,
    step_cap: u32,
    steps: u32,
    last: Option<Move>,
    /// The incumbent completion (cells after the current one) from `inc_at`.
    incumbent: Vec<u32>,
    inc_at: usize,
    scratch: Vec<u32>,
    /// Scratch for the cover walk's far-goal scans.
    goals: FarScan,
    best: Vec<u32>,
    scores: Option<MoveScores>,
    /// The decision under way, between slices.
    pending: Option<Pending>,
    /// The work one slice may spend ([`SLICE_WORK`]).
    slice: u64,
    /// The work and the simulated moves of each slice made, and each
    /// decision's incumbent cost and cheapest completion (tests check them).
    #[cfg(test)]
    log: TestLog,
}

/// What tests read of an improver's work.
#[cfg(test)]
#[derive(Default)]
struct TestLog {
    /// Each slice's work, and the moves it simulated (besides each
    /// completion's first move) and sweep waypoints it skipped.
    slices: Vec<(u64, u64)>,
    /// The same count for the slice under way.
    simulated: u64,
    /// Each decision: whether it started afresh (no incumbent), the
    /// incumbent's cost, and the cheapest completion (what it follows).
    decisions: Vec<(bool, f64, f64)>,
}

/// The belief at a decision: mass left and cells with mass left.
#[derive(Clone, Copy)]
struct Left {
    mass: f64,
    cells: u32,
}

impl Left {
    /// `R_t` with this much left: the mass, exactly 0 once every cell with
    /// mass is covered (the running difference would leave rounding dust).
    fn r(self) -> f64 {
        if self.cells == 0 {
            0.0
        } else {
            self.mass
        }
    }
}

fn left_of(belief: &BeliefState) -> Left {
    let mut mass = Sum::default();
    let mut cells = 0;
    for (&m, &s) in belief.plan_mass().iter().zip(belief.searched()) {
        if s == 0 && m > 0.0 {
            mass.add(m);
            cells += 1;
        }
    }
    Left {
        mass: mass.value(),
        cells,
    }
}

/// One simulated move's bookkeeping: covers `q`, pushes it, adds `R`.
#[inline]
#[allow(clippy::too_many_arguments)]
fn advance(
    sensor: &Sensor,
    belief: &BeliefState,
    cov: &mut Coverage,
    left: &mut Left,
    sum: &mut Sum,
    path: &mut Vec<u32>,
    q: u32,
) {
    let (g, c) = cov.cover_counted(sensor, belief, q);
    left.mass -= g;
    left.cells -= c;
    path.push(q);
    sum.add(left.r());
}

impl Improve {
    /// A rollout improver over `base` (with horizon `h` where the base
    /// plays the horizon rule) on `torus` from `start`, planning no further
    /// than `step_cap`.
    pub fn new(
        base: Base,
        h: u32,
        step_cap: u32,
        torus: &Torus,
        sensor: &Sensor,
        start: u32,
    ) -> Improve {
        let mut sweep = Vec::new();
        sweep_path(torus, sensor, start, SweepPattern::Lawnmower, &mut sweep);
        let room = sweep.len() + 4 * torus.n() as usize;
        Improve {
            base,
            look: Lookahead::new(h),
            sweep,
            sweep_from: 0,
            cov: Coverage::new(torus.cells()),
            step_cap,
            steps: 0,
            last: None,
            incumbent: Vec::with_capacity(room),
            inc_at: 0,
            scratch: Vec::with_capacity(room),
            goals: FarScan::default(),
            best: Vec::with_capacity(room),
            scores: None,
            pending: None,
            slice: SLICE_WORK,
            #[cfg(test)]
            log: TestLog::default(),
        }
    }

    /// The bases each completion of a decision is made with.
    fn bases(&self) -> &'static [Base] {
        match self.base {
            Base::Best => &SINGLE,
            Base::Cover => &SINGLE[0..1],
            Base::Sweep => &SINGLE[1..2],
            Base::Horizon => &SINGLE[2..3],
        }
    }

    /// Starts the completion `job`: clears the simulation and
    /// `self.scratch`, and makes the job's first move, if it has one.
    fn begin_run(&mut self, torus: &Torus, sensor: &Sensor, belief: &BeliefState, job: Job) -> Run {
        let Job {
            pos,
            first,
            base,
            start,
            limit,
        } = job;
        self.cov.clear();
        self.scratch.clear();
        let mut run = Run {
            base,
            left: start,
            sum: Sum::default(),
            p: pos,
            last: self.last,
            walk: CoverageWalk::ordered(self.last),
            waypoint: self.sweep_from,
            limit,
            scans: FarScan::new_run(),
        };
        if let Some(m) = first {
            let q = torus.step(pos, m);
            advance(
                sensor,
                belief,
                &mut self.cov,
                &mut run.left,
                &mut run.sum,
                &mut self.scratch,
                q,
            );
            run.p = q;
            run.last = Some(m);
            run.walk = CoverageWalk::ordered(run.last);
        }
        run
    }

    /// Continues `run` until it is done (true; `Σ R_t` over its cells is
    /// `run.sum`, the cells are in `self.scratch`) or `work` reaches
    /// `budget` (false). Each simulated move adds its cost to `work`
    /// ([`SLICE_WORK`] says what a unit is), so where a slice ends depends
    /// on the work alone and the completion is the same however it is cut.
    fn proceed(
        &mut self,
        run: &mut Run,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        work: &mut u64,
        budget: u64,
    ) -> bool {
        while run.left.cells > 0 && self.scratch.len() < run.limit {
            if *work >= budget {
                return false;
            }
            let p = run.p;
            let m = match run.base {
                Base::Cover | Base::Best | Base::Sweep => {
                    // The sweep heads for its first waypoint still adding
                    // mass; past the last, and for the cover base, the walk.
                    while run.base == Base::Sweep
                        && run.waypoint < self.sweep.len()
                        && self.cov.gain(sensor, belief, self.sweep[run.waypoint]) <= 0.0
                    {
                        run.waypoint += 1;
                        *work += 1;
                        #[cfg(test)]
                        {
                            self.log.simulated += 1;
                        }
                    }
                    *work += COVER_MOVE_WORK;
                    match self
                        .sweep
                        .get(run.waypoint)
                        .filter(|_| run.base == Base::Sweep)
                    {
                        Some(&w) => toward(torus, p, w, Move::Right),
                        None => {
                            // A new far goal costs a scan, as counted.
                            let (goals, cov) = (&mut self.goals, &self.cov);
                            let at = Some(run.scans);
                            let m = run
                                .walk
                                .next_ordered(torus, sensor, belief, cov, p, goals, at);
                            *work += std::mem::take(&mut goals.work);
                            m
                        }
                    }
                }
                Base::Horizon => {
                    let (m, _, _) = decide(
                        &mut self.look,
                        torus,
                        sensor,
                        belief,
                        &mut self.cov,
                        p,
                        run.last,
                        FarGoal::Stuck,
                        Scored::Winner,
                        Some(run.scans),
                    );
                    *work += self.look.take_work();
                    m
                }
            };
            let q = torus.step(p, m);
            advance(
                sensor,
                belief,
                &mut self.cov,
                &mut run.left,
                &mut run.sum,
                &mut self.scratch,
                q,
            );
            run.p = q;
            run.last = Some(m);
            #[cfg(test)]
            {
                self.log.simulated += 1;
            }
        }
        true
    }

    /// Makes the completion `job` in one go, writing the cells into
    /// `self.scratch` and returning `Σ R_t` over them.
    fn complete(&mut self, torus: &Torus, sensor: &Sensor, belief: &BeliefState, job: Job) -> f64 {
        let mut run = self.begin_run(torus, sensor, belief, job);
        self.proceed(&mut run, torus, sensor, belief, &mut 0, u64::MAX);
        run.sum.value()
    }

    /// `Σ R_t` along what is left of the incumbent.
    fn incumbent_cost(&mut self, sensor: &Sensor, belief: &BeliefState, start: Left) -> f64 {
        self.cov.clear();
        let mut left = start;
        let mut sum = Sum::default();
        for &q in &self.incumbent[self.inc_at..] {
            let (g, c) = self.cov.cover_counted(sensor, belief, q);
            left.mass -= g;
            left.cells -= c;
            sum.add(left.r());
        }
        sum.value()
    }

    fn adopt_best(&mut self) {
        std::mem::swap(&mut self.incumbent, &mut self.best);
        self.inc_at = 0;
    }

    /// Sets up the decision at `pos`: which completions it makes, and the
    /// incumbent's cost when the incumbent still holds.
    fn begin_decision(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        pos: u32,
    ) -> Pending {
        while self.sweep_from < self.sweep.len() && {
            self.cov.clear();
            self.cov.gain(sensor, belief, self.sweep[self.sweep_from]) <= 0.0
        } {
            self.sweep_from += 1;
        }
        let start = left_of(belief);
        // Terms t = steps+1 ..= step_cap−1 of Σ_{t<cap} R_t remain.
        let limit = self.step_cap.saturating_sub(self.steps + 1) as usize;
        let fresh =
            self.inc_at >= self.incumbent.len() || torus.l1(pos, self.incumbent[self.inc_at]) != 1;
        let n = self.bases().len();
        let inc = if fresh {
            f64::INFINITY
        } else {
            self.incumbent_cost(sensor, belief, start)
        };
        let moves = if start.cells > 0 && limit > 0 {
            4 * n
        } else {
            0
        };
        Pending {
            start,
            limit,
            own: if fresh { n } else { 0 },
            jobs: if fresh { n } else { 0 } + moves,
            job: 0,
            inc,
            cheapest: inc,
            improved: false,
            score: [f64::NAN; 4],
            run: None,
        }
    }

    /// Takes in the completion `job` of `d` just finished (cost `c`, cells
    /// in `self.scratch`).
    fn finished(&mut self, d: &mut Pending, c: f64) {
        let bases = self.bases();
        if d.job < d.own {
            // The base's own path (the cheapest base's, with `best`).
            if c < d.inc && !self.scratch.is_empty() {
                d.inc = c;
                std::mem::swap(&mut self.scratch, &mut self.best);
            }
            if d.job + 1 == d.own {
                if d.inc.is_finite() {
                    self.adopt_best();
                }
                d.cheapest = d.inc;
            }
            return;
        }
        let m = Move::ALL[(d.job - d.own) / bases.len()];
        let s = &mut d.score[m as usize];
        if s.is_nan() || c < *s {
            *s = c;
        }
        if c < d.cheapest {
            d.cheapest = c;
            d.improved = true;
            std::mem::swap(&mut self.scratch, &mut self.best);
        }
    }

    /// Completion number `d.job` of the decision `d` at `pos`.
    fn job(&self, d: &Pending, pos: u32) -> Job {
        let bases = self.bases();
        let (first, base) = if d.job < d.own {
            (None, bases[d.job])
        } else {
            let k = d.job - d.own;
            (Some(Move::ALL[k / bases.len()]), bases[k % bases.len()])
        };
        Job {
            pos,
            first,
            base,
            start: d.start,
            limit: d.limit,
        }
    }
}

#[cfg(test)]
impl TestLog {
    fn end_slice(&mut self, work: u64) {
        let moves = std::mem::take(&mut self.simulated);
        self.slices.push((work, moves));
    }
}

/// A completion to make: from `pos` with `base` after the move `first`
/// (`None`: the base's own move), from the belief `start`, of at most
/// `limit` moves.
#[derive(Clone, Copy)]
struct Job {
    pos: u32,
    first: Option<Move>,
    base: Base,
    start: Left,
    limit: usize,
}

/// A completion under way, between slices (the improver's `cov` and
/// `scratch` hold its simulation and cells).
struct Run {
    base: Base,
    left: Left,
    sum: Sum,
    p: u32,
    last: Option<Move>,
    walk: CoverageWalk,
    waypoint: usize,
    limit: usize,
    /// The run its far-goal scans belong to: within one completion cells
    /// are only covered ([`FarScan`]).
    scans: u64,
}

/// A decision under way: its completions are made one after another, the
/// base's own paths first when the incumbent no longer holds (`own` of
/// them), then each move with each base, in `Move::ALL` order.
struct Pending {
    start: Left,
    limit: usize,
    own: usize,
    jobs: usize,
    /// The completion under way (or next), by index.
    job: usize,
    /// The incumbent's cost, and the cheapest completion so far.
    inc: f64,
    cheapest: f64,
    improved: bool,
    score: [f64; 4],
    run: Option<Run>,
}

/// What a coverage-walk or sweep move costs in [`SLICE_WORK`]'s units (it
/// looks at four neighbours' discs: about as long as one simulated move of
/// the lookahead, `bench --moves` shows).
const COVER_MOVE_WORK: u64 = 1;

impl Searcher for Improve {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        let (torus, sensor, belief, pos) = (w.torus, &*w.sensor, &*w.belief, w.pos);
        let mut d = match self.pending.take() {
            Some(d) => d,
            None => self.begin_decision(torus, sensor, belief, pos),
        };
        let mut work = 0;
        while d.job < d.jobs {
            let mut run = match d.run.take() {
                Some(run) => run,
                None => {
                    let job = self.job(&d, pos);
                    self.begin_run(torus, sensor, belief, job)
                }
            };
            if !self.proceed(&mut run, torus, sensor, belief, &mut work, self.slice) {
                d.run = Some(run);
                self.pending = Some(d);
                #[cfg(test)]
                self.log.end_slice(work);
                return None;
            }
            self.finished(&mut d, run.sum.value());
            d.job += 1;
        }
        #[cfg(test)]
        {
            self.log.end_slice(work);
            self.log.decisions.push((d.own > 0, d.inc, d.cheapest));
        }
        if d.improved {
            self.adopt_best();
        }
        let m = match self.incumbent.get(self.inc_at) {
            Some(&q) => torus.move_to(pos, q).unwrap_or(Move::Up),
            // Nothing left to find (or no move counts before the cap): keep going.
            None => self.last.unwrap_or(Move::Right),
        };
        self.scores = Some(MoveScores {
            meaning: MEANING,
            higher_is_better: false,
            score: d.score,
            chosen: m as u8,
        });
        Some(m)
    }

    fn observe(&mut self, _torus: &Torus, m: Move, pos: u32) {
        self.steps += 1;
        self.last = Some(m);
        if self.incumbent.get(self.inc_at) == Some(&pos) {
            self.inc_at += 1;
        } else {
            self.incumbent.clear();
            self.inc_at = 0;
        }
    }

    fn intent(&self) -> &[u32] {
        &self.incumbent[self.inc_at.min(self.incumbent.len())..]
    }

    fn scores(&self) -> Option<MoveScores> {
        self.scores
    }

    fn planning(&self) -> Option<Planning> {
        let d = self.pending.as_ref()?;
        Some(Planning {
            stage: "completing the search after each move",
            done: d.job as u32,
            total: d.jobs as u32,
            per_move: true,
            // The completion under way has made this many moves so far.
            inner: if d.run.is_some() {
                self.scratch.len() as u32
            } else {
                0
            },
            inner_unit: "moves into the one under way",
        })
    }
}

/// The exact `Σ_{t<cap} R_t` of `base` alone from `start` over `belief`
/// (what rollout improvement is never worse than; `cap` is the step cap),
/// with the cells of the base's path after the start (the cheapest base's,
/// with `best`).
#[allow(clippy::too_many_arguments)]
pub fn base_alone(
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    start: u32,
    base: Base,
    h: u32,
    step_cap: u32,
) -> (f64, Vec<u32>) {
    let mut imp = Improve::new(base, h, step_cap, torus, sensor, start);
    let left = left_of(belief);
    let limit = step_cap.saturating_sub(1) as usize;
    let mut best = (f64::INFINITY, Vec::new());
    for &b in imp.bases() {
        let job = Job {
            pos: start,
            first: None,
            base: b,
            start: left,
            limit,
        };
        let c = imp.complete(torus, sensor, belief, job);
        if c < best.0 {
            best = (c, imp.scratch.clone());
        }
    }
    // R_0, the term before any move.
    best.0 += left.r();
    best
}

#[cfg(test)]
#[path = "improve_tests.rs"]
mod tests;
