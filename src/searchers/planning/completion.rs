//! Completing a search by the horizon rule: a lookahead's move each step,
//! or a step toward the far goal when that is better, made in slices of
//! bounded work so that the page stays responsive.
//!
//! **Fallback.** Beyond the horizon the lookahead is blind, so the rule
//! compares the best sequence's rate `G/h` (`G`: the mass it covers) with
//! the best far goal: the cell maximising (uncovered mass in its disc) ÷
//! (distance + 1), a scan of the lattice that skips the rows that cannot
//! beat the rate ([`fallback_target`]). When the goal's value is larger (in
//! particular when nothing within reach adds mass) it steps straight toward
//! the goal.

use super::far_goal::{fallback_target, toward, FarScan};
use super::lookahead::{Found, Lookahead, Scored};
use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};

/// One decision of the horizon rule from `pos` over `cov` (left as it
/// was): the lookahead's move, or a step toward the fallback goal when
/// nothing within the horizon adds mass, or, with `far` at
/// [`FarGoal::Compared`], when the goal is better. Returns the move, the
/// lookahead's result (scored as `scored` says) and the goal it headed for,
/// if any. `run`, if given, says that the far-goal scan continues that run
/// ([`FarScan`]).
#[allow(clippy::too_many_arguments)]
pub fn decide(
    look: &mut Lookahead,
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    cov: &mut Coverage,
    pos: u32,
    last: Option<Move>,
    far: FarGoal,
    scored: Scored,
    run: Option<u64>,
) -> (Move, Found, Option<u32>) {
    let found = look.search(torus, sensor, belief, cov, pos, last, scored);
    if found.gain > 0.0 && far == FarGoal::Stuck {
        return (found.first, found, None);
    }
    // Only a goal worth more than the lookahead's rate is taken, so the scan
    // may skip every row that cannot beat it.
    let beat = (found.gain > 0.0).then(|| found.gain / look.depth() as f64);
    match fallback_target(torus, sensor, belief, cov, pos, beat, &mut look.scan, run) {
        Some((goal, _)) => (toward(torus, pos, goal, found.first), found, Some(goal)),
        None => (found.first, found, None),
    }
}

/// When a horizon-rule completion heads for its far goal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FarGoal {
    /// Whenever the goal's value beats the lookahead's rate, as the horizon
    /// searcher plays: one scan of the cells a move. On a prior much wider
    /// than the sensor the lookahead nearly always finds a little mass,
    /// and without this comparison the path crawls through the tail (exact
    /// means at h = 5: 693.47 against 945.64 at N = 128, σ = 16).
    Compared,
    /// Only when nothing within the horizon adds mass: no scan while the
    /// lookahead finds mass, the cheap rule of the rollout bases, which
    /// complete a search at every candidate move.
    Stuck,
}

/// Completes the search from `pos` by the horizon rule, heading for its far
/// goal as `far` says, writing the cells entered into `out`: until every
/// unsearched cell with planning mass is covered, or `cap` moves. `cov`
/// must hold no simulation, and is left holding none.
#[allow(clippy::too_many_arguments)]
pub fn completion(
    look: &mut Lookahead,
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    cov: &mut Coverage,
    pos: u32,
    last: Option<Move>,
    cap: usize,
    far: FarGoal,
    out: &mut Vec<u32>,
) {
    out.clear();
    let mut run = Completion::new(belief, pos, last, cap, far);
    while !run.moves(look, torus, sensor, belief, cov, out, u64::MAX) {}
}

/// A [`completion`] made in slices: [`Completion::moves`] adds a few moves
/// at a time. Between slices `cov` holds the simulation so far, so it must
/// not be used for anything else until the completion is done.
#[derive(Clone, Debug)]
pub struct Completion {
    left: u32,
    p: u32,
    last: Option<Move>,
    /// Moves made so far, and the most allowed.
    made: usize,
    cap: usize,
    far: FarGoal,
    /// The planning mass not yet covered (a running difference), and the
    /// mass left at which the completion may end early (−∞: it covers
    /// every cell with mass).
    mass_left: f64,
    enough: f64,
    /// The mass left at or below which each move is the greedy one, and
    /// the depth-1 lookahead that makes it ([`Completion::greedy_below`]).
    greedy: Option<(f64, Lookahead)>,
    /// This completion's number in the process: its far-goal scans, move
    /// after move, tell the scan that only cells were covered since the
    /// last ([`FarScan`]).
    run: u64,
}

/// Work units one slice of a decision or plan made in slices may spend (it
/// ends after the move that reaches them): a horizon move costs the
/// simulated moves its lookahead made (at most about `2·3^h`; fewer where
/// its bound leaves sequences out), [`SEARCH_WORK`] and the far-goal
/// scan's work ([`FarScan`]), all as counted. About half a millisecond
/// natively.
pub const SLICE_WORK: u64 = 20_000;

impl Completion {
    /// A completion from `pos` after `last`, of at most `cap` moves,
    /// heading for the far goal as `far` says.
    pub fn new(
        belief: &BeliefState,
        pos: u32,
        last: Option<Move>,
        cap: usize,
        far: FarGoal,
    ) -> Completion {
        Completion {
            left: belief.cells_left(),
            p: pos,
            last,
            made: 0,
            cap,
            far,
            mass_left: belief.remaining(),
            enough: f64::NEG_INFINITY,
            greedy: None,
            run: FarScan::new_run(),
        }
    }

    /// The same completion, ending once the planning mass it has not
    /// covered is at most `mass` (as a running difference from the
    /// belief's unsearched mass, so within its rounding): for a caller
    /// that never follows a plan into a tail that thin.
    pub fn ending_at(self, mass: f64) -> Completion {
        Completion {
            enough: mass,
            ..self
        }
    }

    /// The same completion, taking the greedy step once the planning mass
    /// it has not covered is at most `mass`: the neighbour whose disc adds
    /// the most (the horizon rule of depth 1), and only when none adds,
    /// toward the far goal ([`FarGoal::Stuck`]). For a plan whose thin
    /// tail is worth too little to pay for the deeper lookahead and a scan
    /// a move (the belief MCTS's first plan).
    pub fn greedy_below(self, mass: f64) -> Completion {
        Completion {
            greedy: Some((mass, Lookahead::new(1))),
            ..self
        }
    }

    /// Appends moves to `out`, with the arguments of [`completion`], until
    /// they have cost `max_work` units of [`SLICE_WORK`]'s kind (every move
    /// costs at least one). True when the completion is done (and `cov` is
    /// cleared).
    #[allow(clippy::too_many_arguments)]
    pub fn moves(
        &mut self,
        look: &mut Lookahead,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &mut Coverage,
        out: &mut Vec<u32>,
        max_work: u64,
    ) -> bool {
        let mut work = 0;
        while self.left > 0
            && self.mass_left > self.enough
            && self.made < self.cap
            && work < max_work
        {
            let (look, far) = match &mut self.greedy {
                Some((thin, step)) if self.mass_left <= *thin => (step, FarGoal::Stuck),
                _ => (&mut *look, self.far),
            };
            let (m, _, _) = decide(
                look,
                torus,
                sensor,
                belief,
                cov,
                self.p,
                self.last,
                far,
                Scored::Winner,
                Some(self.run),
            );
            work += look.take_work();
            self.p = torus.step(self.p, m);
            let (gain, cells) = cov.cover_counted(sensor, belief, self.p);
            self.left -= cells;
            self.mass_left -= gain;
            out.push(self.p);
            self.made += 1;
            self.last = Some(m);
        }
        let done = self.left == 0 || self.mass_left <= self.enough || self.made >= self.cap;
        if done {
            cov.clear();
        }
        done
    }

    /// Moves made so far.
    pub fn made(&self) -> usize {
        self.made
    }
}

/// Writes into `out` the cells a straight walk from `pos` to `goal` enters.
pub(crate) fn walk_to(torus: &Torus, pos: u32, goal: u32, out: &mut Vec<u32>) {
    let mut p = pos;
    while p != goal {
        p = torus.step(p, toward(torus, p, goal, Move::Up));
        out.push(p);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::prior::{PriorSpec, TargetPrior};

    /// A completion given [`Completion::greedy_below`] makes the moves of
    /// the horizon rule while more than its mass is left, then the greedy
    /// step: a neighbour whose disc adds the most, and when none adds, a
    /// step toward the far goal. Tried: a rule greedy from the start fails
    /// on a move of the horizon rule's part, one that never turns greedy
    /// fails the first check, and one that compares the far goal in the
    /// tail fails on a greedy move.
    #[test]
    fn a_completion_takes_the_greedy_step_once_its_mass_is_thin() {
        for (n, sigma) in [(40u32, 2.5), (40, 5.0), (24, 3.0)] {
            let torus = Torus::new(n).unwrap();
            let sensor = Sensor::new(&torus, 1.0).unwrap();
            let prior = TargetPrior::new(&torus, &PriorSpec::Gaussian { sigma }).unwrap();
            let mut belief = BeliefState::new(Belief::Posterior, prior, None);
            let start = torus.cell(1, 1);
            belief.search_around(&sensor, start);
            let mass = belief.remaining();
            let thin = mass * 1e-3;
            let make = |run: &mut Completion| {
                let (mut look, mut cov) = (Lookahead::new(5), Coverage::new(torus.cells()));
                let mut out = Vec::new();
                while !run.moves(&mut look, &torus, &sensor, &belief, &mut cov, &mut out, 97) {}
                out
            };
            let new = || Completion::new(&belief, start, None, 5000, FarGoal::Compared);
            let plain = make(&mut new());
            let greedy = make(&mut new().greedy_below(thin));
            assert_ne!(
                plain, greedy,
                "n {n}, σ {sigma}: the tail rule changes the plan"
            );
            let mut cov = Coverage::new(torus.cells());
            let mut scan = FarScan::default();
            let (mut left, mut p, mut tail) = (mass, start, 0);
            for (i, &c) in greedy.iter().enumerate() {
                if left > thin {
                    assert_eq!(
                        c, plain[i],
                        "n {n}, σ {sigma}: move {i} is the horizon rule's"
                    );
                } else {
                    let gains = Move::ALL.map(|m| cov.gain(&sensor, &belief, torus.step(p, m)));
                    let most = gains.iter().cloned().fold(0.0, f64::max);
                    if most > 0.0 {
                        assert_eq!(cov.gain(&sensor, &belief, c), most, "move {i}");
                    } else {
                        let (goal, _) = fallback_target(
                            &torus, &sensor, &belief, &cov, p, None, &mut scan, None,
                        )
                        .expect("mass is left");
                        assert!(torus.l1(c, goal) < torus.l1(p, goal), "move {i}");
                    }
                    tail += 1;
                }
                assert_eq!(torus.l1(p, c), 1);
                left -= cov.cover(&sensor, &belief, c);
                p = c;
            }
            assert!(tail > 50, "n {n}, σ {sigma}: {tail} greedy moves");
        }
    }

    /// Mass out of the lookahead's reach: a decision heads for it even when
    /// the far goal is taken only once nothing within reach adds mass, and a
    /// completion walks there, stopping at its cap, once every cell with
    /// mass is covered, or once the mass it has not covered is down to what
    /// `ending_at` allows. Two cells of mass 1/2 on a row, 6 and 13 columns
    /// from the start.
    #[test]
    fn a_completion_heads_for_mass_out_of_reach_and_stops_where_it_is_told() {
        let torus = Torus::new(20).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let mut weights = vec![0.0; torus.cells()];
        let (near, far) = (torus.cell(8, 10), torus.cell(15, 10));
        weights[near as usize] = 1.0;
        weights[far as usize] = 1.0;
        let prior = TargetPrior::new(&torus, &PriorSpec::Weights { weights }).unwrap();
        let mut belief = BeliefState::new(Belief::Posterior, prior, None);
        let start = torus.cell(2, 10);
        belief.search_around(&sensor, start);
        let mut cov = Coverage::new(torus.cells());
        for far_goal in [FarGoal::Stuck, FarGoal::Compared] {
            let mut look = Lookahead::new(3);
            let (m, found, goal) = decide(
                &mut look,
                &torus,
                &sensor,
                &belief,
                &mut cov,
                start,
                Some(Move::Left),
                far_goal,
                Scored::Winner,
                None,
            );
            assert_eq!(found.gain, 0.0, "nothing within 3 moves");
            assert_eq!(
                (m, goal),
                (Move::Right, Some(torus.cell(7, 10))),
                "{far_goal:?}"
            );
            assert!(cov.is_empty());
        }
        let mut run = |c: Completion| {
            let (mut c, mut look, mut out) = (c, Lookahead::new(3), Vec::new());
            while !c.moves(&mut look, &torus, &sensor, &belief, &mut cov, &mut out, 50) {}
            assert_eq!(c.made(), out.len());
            assert!(out
                .iter()
                .enumerate()
                .all(|(i, &p)| p == torus.cell(3 + i as i64, 10)));
            out.len()
        };
        let completion = |cap| Completion::new(&belief, start, None, cap, FarGoal::Stuck);
        assert_eq!(
            run(completion(1000)),
            12,
            "to (14, 10), whose disc holds the far cell"
        );
        for cap in [0, 1, 5, 11] {
            assert_eq!(run(completion(cap)), cap);
        }
        assert_eq!(
            run(completion(1000).ending_at(0.5)),
            5,
            "the near cell found"
        );
        assert_eq!(run(completion(1000).ending_at(1.0)), 0, "enough already");
    }
}
