//! What the belief planners (sweep, horizon, rollout improvement) share:
//! simulated moves over a [`Coverage`], the fallback target, and the cheap
//! greedy coverage walk that completes searches in rollouts.
//!
//! Every quantity here is a planning quantity: mass is the belief's
//! planning mass, "covered" means searched for real or by the simulation.
//! For a path `p_0, p_1, …` from the current cell the expected number of
//! further moves until detection, given no detection so far, is
//! proportional to `Σ_{t≥1} R_t` (`R_t`: planning mass left after `t`
//! simulated moves): see `crate::bound`. Planners compare paths by that sum.

use crate::belief::BeliefState;
use crate::coverage::Coverage;
use crate::lattice::{Move, Sensor, Torus};

/// The planning mass of each cell, 0 where searched: what a plan made
/// from here has left to find.
pub fn mass_left(belief: &BeliefState) -> Vec<f64> {
    belief
        .plan_mass()
        .iter()
        .zip(belief.searched())
        .map(|(&m, &s)| if s == 0 { m } else { 0.0 })
        .collect()
}

/// The planning mass in the disc around `cell` that is not covered yet.
#[inline]
pub fn disc_gain(sensor: &Sensor, belief: &BeliefState, cov: &Coverage, cell: u32) -> f64 {
    cov.gain(sensor, belief, cell)
}

/// The fallback target: the cell maximising (uncovered planning mass in its
/// disc) ÷ (torus ℓ1 distance from `pos` + 1), with that value; `None` when
/// no mass is left. Ties go to the lower cell index. O(N² · disc), a row
/// of gains at a time ([`Coverage::gains_row`]) in `row`, scratch the
/// caller keeps so the scan allocates nothing.
pub fn fallback_target(
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    cov: &Coverage,
    pos: u32,
    row: &mut Vec<f64>,
) -> Option<(u32, f64)> {
    let n = torus.n();
    // The row's gains, then each column's distance from `pos` (small
    // integers, so sums of them as f64 are exact).
    row.resize(2 * n as usize, 0.0);
    let (px, py) = torus.xy(pos);
    let (gains, cols) = row.split_at_mut(n as usize);
    for (x, d) in (0..n).zip(cols.iter_mut()) {
        *d = torus.axis_dist(px, x) as f64;
    }
    let mut best: Option<(u32, f64)> = None;
    for y in 0..n {
        cov.gains_row(sensor, belief, y, gains);
        let dy = torus.axis_dist(py, y) as f64 + 1.0;
        for ((x, &g), &dx) in (0..n).zip(gains.iter()).zip(cols.iter()) {
            if g <= 0.0 {
                continue;
            }
            let v = g / (dx + dy);
            if best.is_none_or(|(_, b)| v > b) {
                best = Some((y * n + x, v));
            }
        }
    }
    best
}

/// A move from `pos` that shortens the torus ℓ1 distance to `target`: along
/// the axis with the longer way to go (x on a tie); `fallback` when already
/// there.
#[inline]
pub fn toward(torus: &Torus, pos: u32, target: u32, fallback: Move) -> Move {
    let (dx, dy) = torus.delta(pos, target);
    if dx == 0 && dy == 0 {
        fallback
    } else if dx.abs() >= dy.abs() {
        if dx > 0 {
            Move::Right
        } else {
            Move::Left
        }
    } else if dy > 0 {
        Move::Down
    } else {
        Move::Up
    }
}

/// The move that undoes `m`.
#[inline]
pub fn reverse(m: Move) -> Move {
    Move::from_index(m as u32 + 2)
}

/// The greedy coverage walk: the neighbour whose disc newly covers the most
/// planning mass (ties: keep going straight, then `Move::ALL` order); when no
/// neighbour adds mass, straight toward the cell with the most uncovered mass
/// per step of distance, kept as the goal until it no longer adds mass.
///
/// It is the rollout improver's cheap base: O(disc) per move, plus an
/// O(N²) scan each time it has to pick a new goal.
#[derive(Clone, Debug, Default)]
pub struct CoverWalk {
    last: Option<Move>,
    goal: Option<u32>,
    /// Far-goal scans made, for callers that account for work.
    scans: u32,
}

impl CoverWalk {
    /// A walk that last moved `last` (its preferred direction), with no goal.
    pub fn new(last: Option<Move>) -> CoverWalk {
        CoverWalk {
            last,
            goal: None,
            scans: 0,
        }
    }

    /// The O(N²) scans for a new far goal made so far.
    pub fn scans(&self) -> u32 {
        self.scans
    }

    /// The next move from `pos` over the simulated coverage `cov`.
    pub fn next_move(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &Coverage,
        pos: u32,
    ) -> Move {
        let mut best = (0.0, self.last.unwrap_or(Move::Up));
        for m in self.last.into_iter().chain(Move::ALL) {
            let g = cov.gain(sensor, belief, torus.step(pos, m));
            if g > best.0 {
                best = (g, m);
            }
        }
        let m = if best.0 > 0.0 {
            best.1
        } else {
            let stale = self.goal.is_none_or(|g| cov.gain(sensor, belief, g) <= 0.0);
            if stale {
                self.scans += 1;
                self.goal = cell_goal(torus, belief, cov, pos);
            }
            match self.goal {
                Some(g) => toward(torus, pos, g, best.1),
                None => best.1,
            }
        };
        self.last = Some(m);
        m
    }
}

/// The uncovered cell with positive mass maximising mass ÷ (distance + 1)
/// (cheaper than [`fallback_target`]: one cell, not a disc, per candidate).
fn cell_goal(torus: &Torus, belief: &BeliefState, cov: &Coverage, pos: u32) -> Option<u32> {
    let mass = belief.plan_mass();
    let mut best: Option<(u32, f64)> = None;
    for (c, &m) in mass.iter().enumerate() {
        if m <= 0.0 || cov.covered(belief, c as u32) {
            continue;
        }
        let v = m / (torus.l1(pos, c as u32) as f64 + 1.0);
        if best.is_none_or(|(_, b)| v > b) {
            best = Some((c as u32, v));
        }
    }
    best.map(|(c, _)| c)
}

/// A completed search adds thousands of small terms: compensated.
pub use crate::stats::Sum;

/// The path a planner made and follows (the beam and spiral planners):
/// the cells still to enter, and whether the searcher is on it.
#[derive(Clone, Debug, Default)]
pub struct PlannedPath {
    cells: Vec<u32>,
    next: usize,
    /// False until a plan is made, and again once the searcher leaves it.
    held: bool,
}

impl PlannedPath {
    /// Starts a new plan, followed from its first cell: returns its cells,
    /// cleared, for the caller to fill.
    pub fn start(&mut self) -> &mut Vec<u32> {
        self.cells.clear();
        self.next = 0;
        self.held = true;
        &mut self.cells
    }

    /// True when the plan's next cell is a move away from `pos`.
    pub fn on_plan(&self, torus: &Torus, pos: u32) -> bool {
        self.held && self.next_cell().is_some_and(|c| torus.l1(pos, c) == 1)
    }

    /// True when the whole plan has been walked.
    pub fn walked(&self) -> bool {
        self.held && self.next >= self.cells.len()
    }

    /// The next cell to enter, if the plan has one left.
    pub fn next_cell(&self) -> Option<u32> {
        self.cells.get(self.next).copied()
    }

    /// The searcher entered `pos`: the plan moves on, or is left.
    pub fn observe(&mut self, pos: u32) {
        if self.next_cell() == Some(pos) {
            self.next += 1;
        } else {
            self.held = false;
        }
    }

    /// The cells still to enter.
    pub fn ahead(&self) -> &[u32] {
        &self.cells[self.next.min(self.cells.len())..]
    }
}
