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
//! 4 × (bases) completions of up to N²/3 moves each at r_v = 1.

use super::horizon::{decide, Lookahead};
use super::plan::{toward, CoverWalk, Sum};
use super::sweep::{sweep_path, SweepPattern};
use super::{MoveScores, Searcher, SearcherInfo, World};
use crate::belief::BeliefState;
use crate::config::Config;
use crate::coverage::Coverage;
use crate::lattice::{Move, Sensor, Torus};
use crate::mcts::DecisionView;
use crate::named::named_enum;
use crate::view::Layer;

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

/// Rollout improvement as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "improve",
    label: "Rollout improvement",
    help: "completes the search with a base policy after each of the four moves and follows the completion with the least expected time (never worse than its base)",
    deterministic: true,
    deliberates: false,
    uses: |c, key| key == "base" || (key == "horizon" && matches!(c.base, Base::Horizon | Base::Best)),
    build: |s| Box::new(Improve::new(s.cfg, s.torus, &s.sensor(), s.start)),
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
    best: Vec<u32>,
    scores: Option<MoveScores>,
}

/// The belief at a decision: mass left and cells with mass left.
#[derive(Clone, Copy)]
struct Left {
    mass: f64,
    cells: u32,
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
    // Exactly 0 once every cell with mass is covered (no rounding dust).
    sum.add(if left.cells == 0 { 0.0 } else { left.mass });
}

impl Improve {
    /// A rollout improver for `cfg` on `torus` from `start`.
    pub fn new(cfg: &Config, torus: &Torus, sensor: &Sensor, start: u32) -> Improve {
        let mut sweep = Vec::new();
        sweep_path(torus, sensor, start, SweepPattern::Lawnmower, &mut sweep);
        let room = sweep.len() + 4 * torus.n() as usize;
        Improve {
            base: cfg.base,
            look: Lookahead::new(cfg.horizon),
            sweep,
            sweep_from: 0,
            cov: Coverage::new(torus.cells()),
            step_cap: cfg.step_cap,
            steps: 0,
            last: None,
            incumbent: Vec::with_capacity(room),
            inc_at: 0,
            scratch: Vec::with_capacity(room),
            best: Vec::with_capacity(room),
            scores: None,
        }
    }

    /// Completes the search from `pos` with `base` after the move `first`
    /// (`None`: the base's own move), writing the cells into `self.scratch`
    /// and returning `Σ R_t` over them. At most `limit` moves.
    #[allow(clippy::too_many_arguments)]
    fn complete(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        pos: u32,
        first: Option<Move>,
        base: Base,
        start: Left,
        limit: usize,
    ) -> f64 {
        self.cov.clear();
        self.scratch.clear();
        let mut left = start;
        let mut sum = Sum::default();
        let mut p = pos;
        let mut last = self.last;
        let mut walk = CoverWalk::new(last);
        let mut waypoint = self.sweep_from;
        if let Some(m) = first {
            let q = torus.step(p, m);
            advance(
                sensor,
                belief,
                &mut self.cov,
                &mut left,
                &mut sum,
                &mut self.scratch,
                q,
            );
            p = q;
            last = Some(m);
            walk = CoverWalk::new(last);
        }
        while left.cells > 0 && self.scratch.len() < limit {
            let m = match base {
                Base::Cover | Base::Best => walk.next_move(torus, sensor, belief, &self.cov, p),
                Base::Sweep => {
                    while waypoint < self.sweep.len()
                        && self.cov.gain(sensor, belief, self.sweep[waypoint]) <= 0.0
                    {
                        waypoint += 1;
                    }
                    match self.sweep.get(waypoint) {
                        Some(&w) => toward(torus, p, w, Move::Right),
                        None => walk.next_move(torus, sensor, belief, &self.cov, p),
                    }
                }
                Base::Horizon => {
                    decide(
                        &mut self.look,
                        torus,
                        sensor,
                        belief,
                        &mut self.cov,
                        p,
                        last,
                        false,
                    )
                    .0
                }
            };
            let q = torus.step(p, m);
            advance(
                sensor,
                belief,
                &mut self.cov,
                &mut left,
                &mut sum,
                &mut self.scratch,
                q,
            );
            p = q;
            last = Some(m);
        }
        sum.value()
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
            sum.add(if left.cells == 0 { 0.0 } else { left.mass });
        }
        sum.value()
    }

    fn adopt_best(&mut self) {
        std::mem::swap(&mut self.incumbent, &mut self.best);
        self.inc_at = 0;
    }
}

impl Searcher for Improve {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        let (torus, sensor, belief, pos) = (w.torus, &*w.sensor, &*w.belief, w.pos);
        while self.sweep_from < self.sweep.len() && {
            self.cov.clear();
            self.cov.gain(sensor, belief, self.sweep[self.sweep_from]) <= 0.0
        } {
            self.sweep_from += 1;
        }
        let start = left_of(belief);
        // Terms t = steps+1 ..= step_cap−1 of Σ_{t<cap} R_t remain.
        let limit = self.step_cap.saturating_sub(self.steps + 1) as usize;
        let bases: &[Base] = match self.base {
            Base::Best => &SINGLE,
            Base::Cover => &SINGLE[0..1],
            Base::Sweep => &SINGLE[1..2],
            Base::Horizon => &SINGLE[2..3],
        };
        let fresh =
            self.inc_at >= self.incumbent.len() || torus.l1(pos, self.incumbent[self.inc_at]) != 1;
        let mut inc = f64::INFINITY;
        if fresh {
            // The base's own path (the cheapest base's, with `best`).
            for &b in bases {
                let c = self.complete(torus, sensor, belief, pos, None, b, start, limit);
                if c < inc && !self.scratch.is_empty() {
                    inc = c;
                    std::mem::swap(&mut self.scratch, &mut self.best);
                }
            }
            if inc.is_finite() {
                self.adopt_best();
            }
        } else {
            inc = self.incumbent_cost(sensor, belief, start);
        }
        let mut score = [f64::NAN; 4];
        let mut cheapest = inc;
        let mut improved = false;
        if start.cells > 0 && limit > 0 {
            for m in Move::ALL {
                for &b in bases {
                    let c = self.complete(torus, sensor, belief, pos, Some(m), b, start, limit);
                    if score[m as usize].is_nan() || c < score[m as usize] {
                        score[m as usize] = c;
                    }
                    if c < cheapest {
                        cheapest = c;
                        improved = true;
                        std::mem::swap(&mut self.scratch, &mut self.best);
                    }
                }
            }
        }
        if improved {
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
            score,
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

    fn counts<'a>(&'a self, _layer: Layer, _scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        None
    }

    fn decision(&self, _torus: &Torus, _pos: u32) -> Option<DecisionView> {
        None
    }

    fn intent(&self) -> &[u32] {
        &self.incumbent[self.inc_at.min(self.incumbent.len())..]
    }

    fn scores(&self) -> Option<MoveScores> {
        self.scores
    }
}

/// The exact `Σ_{t<cap} R_t` of `base` alone from the start of `cfg` (what
/// rollout improvement is never worse than), with the base's path.
///
/// # Errors
/// The [`crate::config::ConfigError`] of [`Config::game`].
pub fn base_mean(cfg: &Config, base: Base) -> Result<f64, crate::config::ConfigError> {
    let g = cfg.game()?;
    let belief = {
        let mut b = BeliefState::new(cfg.belief, g.prior.clone(), None);
        b.search_around(&g.sensor, g.start);
        b
    };
    let mut imp = Improve::new(
        &Config {
            base,
            ..cfg.clone()
        },
        &g.torus,
        &g.sensor,
        g.start,
    );
    let start = left_of(&belief);
    let limit = cfg.step_cap.saturating_sub(1) as usize;
    let bases: &[Base] = match base {
        Base::Best => &SINGLE,
        Base::Cover => &SINGLE[0..1],
        Base::Sweep => &SINGLE[1..2],
        Base::Horizon => &SINGLE[2..3],
    };
    let mut best = f64::INFINITY;
    for &b in bases {
        best = best.min(imp.complete(&g.torus, &g.sensor, &belief, g.start, None, b, start, limit));
    }
    // R_0, the term before any move.
    Ok(best + if start.cells == 0 { 0.0 } else { start.mass })
}
