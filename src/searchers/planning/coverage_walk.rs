//! The greedy coverage walk: each step goes to the neighbour whose sensor
//! disc newly covers the most planning mass, given what has been searched
//! for real and what a simulation has covered ([`Coverage`]); when going
//! on is not worth it, it heads for a goal cell, the uncovered cell with the
//! best (planning mass) ÷ (distance + 1), kept until it is covered.
//!
//! It comes in two flavours, which differ only where chance may enter:
//! * **ordered** ([`CoverageWalk::ordered`]), for the planners (rollout
//!   improvement's cheap base): ties keep the last direction, then go in
//!   `Move::ALL` order; the goal is sought only when no neighbour adds
//!   mass, found by the far-goal scan ([`cell_goal`], ties to the lower
//!   cell) and approached along the longer axis first ([`toward`]). Its
//!   path is a function of the belief, as a planner's must be for exact
//!   means.
//! * **randomised** ([`CoverageWalk::randomised`]), the belief MCTS's
//!   rollout: ties keep the last direction when it is among them (so an
//!   even prior is swept in straight lines rather than in a meander that
//!   leaves holes), else are broken at random, so rollouts sample rather
//!   than repeat one path. Far from a Gaussian's mode every neighbour adds
//!   a sliver of tail mass, so it compares the local gain with the goal's
//!   ratio and heads for the goal whenever the goal is better; the goal
//!   search walks ℓ1 rings outward and stops once no farther cell could
//!   beat the best found, using the cells sorted by mass with a pointer
//!   past the covered ones that only moves forward within a rollout.
//!
//! Nothing here allocates after the first decision.

use super::far_goal::{cell_goal, toward, FarScan};
use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::rng::{self, Rng};

/// The coverage walk's state: the last move and the goal, and for the
/// randomised flavour the mass order of the cells.
#[derive(Clone, Debug, Default)]
pub struct CoverageWalk {
    last: Option<Move>,
    /// The goal cell, kept until it is covered.
    goal: Option<u32>,
    /// Cells with positive planning mass, heaviest first (built on first use:
    /// the planning prior is fixed for a trial; randomised flavour only).
    order: Vec<u32>,
    /// Index in `order` of the first cell not searched for real.
    real: usize,
    /// Index in `order` of the first cell not covered in this rollout.
    sim: usize,
}

/// How the walk breaks a tie among allowed moves that the last move is not
/// among.
enum Tie<'a> {
    /// The first in `Move::ALL` order.
    First,
    /// One at random.
    Random(&'a mut Rng),
}

/// The disc gain of each neighbour of `cell`, in `Move::ALL` order.
fn gains(
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    cov: &Coverage,
    cell: u32,
) -> [f64; 4] {
    Move::ALL.map(|m| cov.gain(sensor, belief, torus.step(cell, m)))
}

/// `last` when allowed, else an allowed move as `tie` says.
fn prefer_last(last: Option<Move>, ok: [bool; 4], tie: Tie<'_>) -> Move {
    if let Some(m) = last.filter(|&m| ok[m as usize]) {
        return m;
    }
    let mut pick = match tie {
        Tie::First => 0,
        Tie::Random(rng) => {
            let k = ok.iter().filter(|&&b| b).count() as u32;
            rng::below(rng, k.max(1))
        }
    };
    for (i, &b) in ok.iter().enumerate() {
        if b {
            if pick == 0 {
                return Move::ALL[i];
            }
            pick -= 1;
        }
    }
    Move::Up
}

/// The cells a straight step newly covers at r_v = 1: a local gain is
/// divided by this before it is compared with a goal's per-cell ratio.
const FRONT: f64 = 3.0;

/// No goal is searched for while the (per-cell) local gain is at least
/// this share of the heaviest uncovered cell: the search is the walk's
/// dearest part, and a good local gain rarely loses to a remote cell.
const SEARCH_BELOW: f64 = 0.125;

/// Up to this many cells with mass left, the goal search scans them
/// instead of walking rings (a ring walk to a far delta crosses the lattice).
const FEW: usize = 64;

/// The best goal found so far, ties kept uniformly at random.
#[derive(Default)]
struct Best {
    ratio: f64,
    pick: Option<u32>,
    ties: u32,
}

impl Best {
    fn offer(&mut self, cell: u32, ratio: f64, rng: &mut Rng) {
        if ratio > self.ratio {
            *self = Best {
                ratio,
                pick: Some(cell),
                ties: 1,
            };
        } else if ratio == self.ratio && self.pick.is_some() {
            self.ties += 1;
            if rng::below(rng, self.ties) == 0 {
                self.pick = Some(cell);
            }
        }
    }
}

impl CoverageWalk {
    /// The ordered walk, for planners: it last moved `last` (its preferred
    /// direction), with no goal.
    pub fn ordered(last: Option<Move>) -> CoverageWalk {
        CoverageWalk {
            last,
            ..CoverageWalk::default()
        }
    }

    /// The randomised walk, for rollouts: it sorts the cells on first use.
    pub fn randomised() -> CoverageWalk {
        CoverageWalk::default()
    }

    /// The ordered walk's next move from `pos` over the simulated coverage
    /// `cov`: the neighbour that adds the most mass, or when none adds, a
    /// step toward the goal. `scan` is scratch for its goal scans, which
    /// continue `run` if given ([`FarScan`]) and count their work in it.
    ///
    /// O(disc) per move, plus an O(N²) scan each time it has to pick a new
    /// goal.
    #[allow(clippy::too_many_arguments)]
    pub fn next_ordered(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &Coverage,
        pos: u32,
        scan: &mut FarScan,
        run: Option<u64>,
    ) -> Move {
        let g = gains(torus, sensor, belief, cov, pos);
        let local = g.iter().copied().fold(0.0, f64::max);
        let m = if local > 0.0 {
            prefer_last(self.last, g.map(|x| x == local), Tie::First)
        } else {
            let stale = self.goal.is_none_or(|g| cov.gain(sensor, belief, g) <= 0.0);
            if stale {
                self.goal = cell_goal(torus, belief, cov, pos, scan, run);
            }
            let straight = self.last.unwrap_or(Move::Up);
            match self.goal {
                Some(g) => toward(torus, pos, g, straight),
                None => straight,
            }
        };
        self.last = Some(m);
        m
    }

    /// Starts a decision: skips the cells searched for real since the last one.
    pub fn begin_decision(&mut self, belief: &BeliefState) {
        let mass = belief.plan_mass();
        if self.order.is_empty() {
            self.order = (0..mass.len() as u32)
                .filter(|&c| mass[c as usize] > 0.0)
                .collect();
            // Stable and total: equal masses keep index order, so every
            // platform sorts alike.
            self.order
                .sort_by(|&a, &b| mass[b as usize].total_cmp(&mass[a as usize]));
            self.real = 0;
        }
        let searched = belief.searched();
        while self.real < self.order.len() && searched[self.order[self.real] as usize] != 0 {
            self.real += 1;
        }
    }

    /// Starts a rollout from a simulated position (the simulation's coverage
    /// is whatever `Coverage` holds now).
    pub fn begin_rollout(&mut self) {
        self.sim = self.real;
        self.goal = None;
        self.last = None;
    }

    /// The largest planning mass not yet covered (0 when all is covered).
    fn peak(&mut self, belief: &BeliefState, cov: &Coverage) -> f64 {
        while self.sim < self.order.len() && cov.covered(belief, self.order[self.sim]) {
            self.sim += 1;
        }
        self.order
            .get(self.sim)
            .map_or(0.0, |&c| belief.plan_mass()[c as usize])
    }

    /// The uncovered cell with the best mass ÷ (ℓ1 distance + 1) from
    /// `cell` and that ratio, ties at random, if that ratio beats `floor`.
    /// The search ends at the distance where even the heaviest uncovered
    /// cell could not beat it, so a good local gain (`floor`) keeps it short.
    fn find_goal(
        &mut self,
        torus: &Torus,
        belief: &BeliefState,
        cov: &Coverage,
        rng: &mut Rng,
        cell: u32,
        floor: f64,
    ) -> Option<(u32, f64)> {
        let peak = self.peak(belief, cov);
        if peak <= 0.0 {
            return None;
        }
        let mass = belief.plan_mass();
        if self.order.len() - self.sim <= FEW {
            // Few cells hold mass (a delta prior): scan them, not rings.
            let mut best = Best {
                ratio: floor,
                pick: None,
                ties: 0,
            };
            for &c in &self.order[self.sim..] {
                if !cov.covered(belief, c) {
                    let r = mass[c as usize] / (torus.l1(cell, c) + 1) as f64;
                    best.offer(c, r, rng);
                }
            }
            return best.pick.map(|c| (c, best.ratio));
        }
        let n = torus.n() as i64;
        let (lo, hi) = (-((n - 1) / 2), n / 2);
        let (x, y) = torus.xy(cell);
        let (x, y) = (x as i64, y as i64);
        let mut best = Best {
            ratio: floor,
            pick: None,
            ties: 0,
        };
        let consider = |best: &mut Best, c: u32, d: i64, rng: &mut Rng| {
            let m = mass[c as usize];
            if m > 0.0 && !cov.covered(belief, c) {
                best.offer(c, m / (d + 1) as f64, rng);
            }
        };
        // Each torus cell at ℓ1 distance d has one offset with both
        // coordinates in [lo, hi]; the largest distance is hi − lo.
        for d in 0..=(hi - lo) {
            for dx in (-d).max(lo)..=d.min(hi) {
                let a = d - dx.abs();
                if a <= hi {
                    consider(&mut best, torus.cell(x + dx, y + a), d, rng);
                }
                if a != 0 && -a >= lo {
                    consider(&mut best, torus.cell(x + dx, y - a), d, rng);
                }
            }
            // No cell farther out can reach the best ratio found.
            if peak / ((d + 2) as f64) < best.ratio {
                break;
            }
        }
        best.pick.map(|c| (c, best.ratio))
    }

    /// The randomised walk's next move from `cell`.
    pub fn next_random(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &Coverage,
        rng: &mut Rng,
        cell: u32,
    ) -> Move {
        let gains = gains(torus, sensor, belief, cov, cell);
        let local = gains.iter().copied().fold(0.0, f64::max);
        // A step's gain is a disc front (3 new cells at r_v = 1); a goal
        // ratio is one cell's mass per step: compare like with like.
        let lw = local / FRONT;
        if self.goal.is_some_and(|w| cov.covered(belief, w)) {
            self.goal = None;
        }
        // A kept goal is compared afresh; without one, look for one that
        // beats the local gain (the search stops where no cell could).
        let peak = self.peak(belief, cov);
        let remote = match self.goal {
            Some(w) => belief.plan_mass()[w as usize] / (torus.l1(cell, w) + 1) as f64,
            None if local > 0.0 && lw >= SEARCH_BELOW * peak => 0.0,
            None => match self.find_goal(torus, belief, cov, rng, cell, lw) {
                Some((w, r)) => {
                    self.goal = Some(w);
                    r
                }
                None => 0.0,
            },
        };
        let m = if local > 0.0 && lw >= remote {
            let ok = gains.map(|g| g == local);
            prefer_last(self.last, ok, Tie::Random(rng))
        } else if let Some(w) = self.goal {
            let (dx, dy) = torus.delta(cell, w);
            let mut ok = [false; 4];
            ok[Move::Up as usize] = dy < 0;
            ok[Move::Down as usize] = dy > 0;
            ok[Move::Left as usize] = dx < 0;
            ok[Move::Right as usize] = dx > 0;
            if ok == [false; 4] {
                // At the goal yet it is uncovered: only with r_v < 0 — or
                // a sensor that misses its own cell — so any move will do.
                ok = [true; 4];
            }
            prefer_last(self.last, ok, Tie::Random(rng))
        } else {
            Move::from_index(rng::below(rng, 4))
        };
        self.last = Some(m);
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::prior::{PriorSpec, TargetPrior};

    fn setup(n: u32, spec: PriorSpec) -> (Torus, Sensor, BeliefState) {
        let torus = Torus::new(n).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let prior = TargetPrior::new(&torus, &spec).unwrap();
        (
            torus,
            sensor,
            BeliefState::new(Belief::Posterior, prior, None),
        )
    }

    /// Walks until all planning mass is covered; returns the steps.
    fn cover_all(torus: &Torus, sensor: &Sensor, belief: &BeliefState, start: u32) -> u32 {
        let mut walk = CoverageWalk::randomised();
        walk.begin_decision(belief);
        walk.begin_rollout();
        let mut cov = Coverage::new(torus.cells());
        let mut rng = crate::game::rng::stream(7, 0);
        let mut left = belief.remaining();
        let mut cell = start;
        let mut steps = 0;
        while left > 1e-12 {
            let m = walk.next_random(torus, sensor, belief, &cov, &mut rng, cell);
            cell = torus.step(cell, m);
            left -= cov.cover(sensor, belief, cell);
            steps += 1;
            assert!(steps < 10 * torus.cells() as u32, "the walk stalls");
        }
        steps
    }

    #[test]
    fn heads_straight_for_a_delta_target() {
        let (torus, sensor, mut belief) = setup(40, PriorSpec::Delta { cell: None });
        let start = torus.cell(0, 0);
        belief.search_around(&sensor, start);
        let target = torus.cell(20, 20);
        // A shortest path to the target's disc: 39 moves.
        assert_eq!(cover_all(&torus, &sensor, &belief, start), 39);
        assert_eq!(sensor.optimal_steps(&torus, start, target), 39);
    }

    #[test]
    fn covers_an_even_prior_without_many_repeats() {
        // A perfect sweep covers 3 new cells a move; N² / 5 moves is a floor
        // no walk beats. Straight ties make it a sweep with some overlap: a
        // meander (random ties, which this test fails at about 1.3× this
        // bound when tried) revisits far more.
        let (torus, sensor, mut belief) = setup(30, PriorSpec::Uniform);
        belief.search_around(&sensor, 0);
        let steps = cover_all(&torus, &sensor, &belief, 0);
        assert!(steps <= 900 / 3 + 120, "{steps} moves to cover 900 cells");
    }

    #[test]
    fn leaves_the_tail_for_the_mode() {
        // From a corner far out in a Gaussian's tail, the first moves go
        // toward the mode (both shorten the distance), not along the tail.
        let (torus, sensor, mut belief) = setup(40, PriorSpec::Gaussian { sigma: 3.0 });
        let start = torus.cell(0, 0);
        belief.search_around(&sensor, start);
        let mut walk = CoverageWalk::randomised();
        walk.begin_decision(&belief);
        walk.begin_rollout();
        let cov = Coverage::new(torus.cells());
        let mut rng = crate::game::rng::stream(1, 0);
        for _ in 0..20 {
            let m = walk.next_random(&torus, &sensor, &belief, &cov, &mut rng, start);
            assert!(matches!(m, Move::Right | Move::Down), "{m:?}");
        }
    }
}
