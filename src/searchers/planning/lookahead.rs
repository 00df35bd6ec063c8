//! The lookahead: every move sequence of depth `h` (reversals pruned) from
//! a cell, scored by how early it covers planning mass. The horizon
//! planner, the beam planner, rollout improvement and the belief MCTS's
//! plan all decide with it.
//!
//! # Rule
//! A sequence covering new planning mass `g_1, …, g_h` at its moves scores
//! `Σ_k (h − k + 1)·g_k`. Minimising the expected time `E[T] = Σ_t R_t`
//! (`R_t`: mass left after `t` moves) over the horizon is the same as
//! maximising this score, since `Σ_{k≤h} R_k = h·R_0 − score`: mass found
//! earlier counts more. Ties go to going straight on, then `Move::ALL`
//! order. There are `4·3^(h−1)` sequences, about `2·3^h` simulated moves
//! per decision (hence [`MAX_HORIZON`]). Sequences that cannot beat the
//! best found are left out, so the result is that of trying them all.

use super::far_goal::FarScan;
use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::param::{Param, ParamKind, Value};

/// The largest horizon: `2·3^h` simulated moves per decision stays under
/// 10⁵ (about 1 ms natively at r_v = 1).
pub const MAX_HORIZON: u32 = 9;

/// The default horizon.
pub const DEFAULT_HORIZON: u32 = 6;

/// The receding horizon's depth h, for the planners that look ahead.
pub static HORIZON: Param = Param {
    key: "horizon",
    label: "Horizon depth h",
    kind: ParamKind::Int {
        min: 1,
        max: MAX_HORIZON as u64,
    },
    default: Value::Int(DEFAULT_HORIZON as u64),
    help: "planners: the receding horizon's depth h (4·3^(h−1) move sequences, about 2·3^h simulated moves per decision, so at most 9)",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// Work units a lookahead's search costs besides its simulated moves (the
/// bound's box, the first moves' discs): a depth-1 search, the greedy
/// step of a plan's tail, took about 180 ns a move at N = 256 when it was
/// charged only its 4 first moves, against about 25 ns a unit for the
/// depth-5 lookahead at N = 40.
pub const SEARCH_WORK: u64 = 4;

/// The depth-`h` search over move sequences, with its scratch.
#[derive(Clone, Debug)]
pub struct Lookahead {
    h: u32,
    cur: Vec<u32>,
    run_seq: Vec<u32>,
    best_seq: Vec<u32>,
    best: f64,
    best_gain: f64,
    /// `tail[k]`: a bound on what moves `k + 1 ..= h` may add to a
    /// sequence's score, with room for rounding. Move `j` adds at most its
    /// front of cells, each within ℓ1 distance `j` + the disc's of the
    /// searcher, times the move's weight `h − j + 1`.
    tail: Vec<f64>,
    /// Scratch: the largest live mass at each ℓ1 distance from the searcher.
    rings: Vec<f64>,
    /// Simulated moves made since the work was last taken.
    work: u64,
    /// Scratch for the fallback scan, with its work.
    pub(crate) scan: FarScan,
}

/// Which first moves a [`Lookahead::search`] scores exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scored {
    /// Every first move, for the decision panel.
    Every,
    /// Only the chosen one (the others' scores are NaN): a first move's
    /// sequences are then left out once they cannot beat an earlier first
    /// move's best, which the moves, gain and sequence do not depend on.
    Winner,
}

/// What a [`Lookahead`] found.
#[derive(Clone, Copy, Debug)]
pub struct Found {
    /// The best sequence's first move.
    pub first: Move,
    /// Score of the best sequence starting with each move (NaN for a move
    /// [`Scored::Winner`] did not score).
    pub score: [f64; 4],
    /// Mass the best sequence covers (unweighted).
    pub gain: f64,
}

/// `last` first (going straight wins ties), then the others in `Move::ALL`
/// order.
#[inline]
fn order(last: Option<Move>) -> impl Iterator<Item = Move> {
    last.into_iter()
        .chain(Move::ALL.into_iter().filter(move |&m| Some(m) != last))
}

/// [`order`]`(Some(last))` without the reversal, by `last`'s index: `last`,
/// then the two turns in `Move::ALL` order. A table, for the lookahead's
/// inner loops.
const ONWARD: [[Move; 3]; 4] = {
    use Move::{Down, Left, Right, Up};
    [
        [Up, Right, Left],
        [Right, Up, Down],
        [Down, Right, Left],
        [Left, Up, Down],
    ]
};

impl Lookahead {
    /// A lookahead of depth `h` (at least 1).
    pub fn new(h: u32) -> Lookahead {
        let h = h.max(1);
        Lookahead {
            h,
            cur: vec![0; h as usize],
            run_seq: vec![0; h as usize],
            best_seq: vec![0; h as usize],
            best: 0.0,
            best_gain: 0.0,
            tail: vec![0.0; h as usize + 1],
            rings: Vec::new(),
            work: 0,
            scan: FarScan::default(),
        }
    }

    /// The depth.
    pub fn depth(&self) -> u32 {
        self.h
    }

    /// The work done since it was last taken, in `completion::SLICE_WORK`'s units: the
    /// simulated moves, and the far-goal scans' work ([`FarScan`]).
    pub fn take_work(&mut self) -> u64 {
        std::mem::take(&mut self.work) + std::mem::take(&mut self.scan.work)
    }

    /// The best sequence's cells (after [`search`](Lookahead::search)).
    pub fn best_seq(&self) -> &[u32] {
        &self.best_seq
    }

    /// Tries every sequence from `pos` over `cov` (left as it was); `last`
    /// is the move that led to `pos`, preferred on ties. `scored` says
    /// which first moves get their exact score.
    #[allow(clippy::too_many_arguments)]
    pub fn search(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &mut Coverage,
        pos: u32,
        last: Option<Move>,
        scored: Scored,
    ) -> Found {
        let mut score = [f64::NAN; 4];
        let mut overall = f64::NEG_INFINITY;
        let mut first = last.unwrap_or(Move::Up);
        let mut gain = 0.0;
        // Past the first move a step's disc only adds its front to the
        // covered disc it came from; from `pos` that holds when its disc
        // is covered (it is wherever a searcher has stood).
        let stood = cov.disc_covered(sensor, belief, pos);
        // Move j's new cells lie within ℓ1 distance j + the disc's ℓ1 reach
        // of `pos` (and within h + reach rows and columns), so it adds at
        // most its front times the heaviest live cell that near: the first
        // moves, which weigh most, see only the cells next to `pos`. The
        // margin covers the rounding of the sums the bound stands for
        // (non-negative terms, a few dozen roundings).
        let half = self.h + sensor.reach();
        self.rings.resize(2 * half as usize + 1, 0.0);
        cov.live_max_rings(belief, torus.n(), pos, half, &mut self.rings);
        let reach1 = sensor.reach_l1() as usize;
        let front = sensor.front_len() as f64 * (1.0 + 1e-9);
        let (h, mut upto, mut most) = (self.h as usize, 0, 0.0f64);
        for j in 1..=h {
            while upto < self.rings.len() && upto <= j + reach1 {
                most = most.max(self.rings[upto]);
                upto += 1;
            }
            self.tail[j - 1] = (h - j + 1) as f64 * front * most;
        }
        self.tail[h] = 0.0;
        for k in (0..h).rev() {
            self.tail[k] += self.tail[k + 1];
        }
        self.work += SEARCH_WORK;
        for m in order(last) {
            // A later first move is taken only when strictly better, so
            // without its own score only what beats the best so far counts.
            self.best = match scored {
                Scored::Every => f64::NEG_INFINITY,
                Scored::Winner => overall,
            };
            self.work += 1;
            let q = torus.step(pos, m);
            let cp = cov.checkpoint();
            let g = if stood {
                cov.cover_step(sensor, belief, m, q)
            } else {
                cov.cover(sensor, belief, q)
            };
            self.cur[0] = q;
            let w = self.h as f64;
            self.dfs(torus, sensor, belief, cov, q, m, 1, w * g, g);
            cov.undo(cp);
            if scored == Scored::Every {
                score[m as usize] = self.best;
            }
            if self.best > overall {
                overall = self.best;
                first = m;
                gain = self.best_gain;
                self.best_seq.copy_from_slice(&self.run_seq);
            }
        }
        score[first as usize] = overall;
        Found { first, score, gain }
    }

    #[allow(clippy::too_many_arguments)]
    fn dfs(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &mut Coverage,
        pos: u32,
        last: Move,
        k: u32,
        acc: f64,
        gain: f64,
    ) {
        // Moves k.. weigh h − k, …, 1: a subtree that cannot beat the best
        // sequence found is left out, which leaves the result as it was (a
        // later sequence only replaces the best when strictly better).
        if acc + self.tail[k as usize] <= self.best {
            return;
        }
        if k == self.h {
            if acc > self.best {
                self.best = acc;
                self.best_gain = gain;
                self.run_seq.copy_from_slice(&self.cur);
            }
            return;
        }
        let w = (self.h - k) as f64;
        self.work += 3;
        if k + 1 == self.h {
            // The last move: its gain is all that is needed, so nothing is
            // marked or undone (two thirds of the sequences' moves).
            for &m in &ONWARD[last as usize] {
                let q = torus.step(pos, m);
                let g = cov.step_gain(sensor, belief, m, q);
                let total = acc + w * g;
                if total > self.best {
                    self.cur[k as usize] = q;
                    self.best = total;
                    self.best_gain = gain + g;
                    self.run_seq.copy_from_slice(&self.cur);
                }
            }
            return;
        }
        for &m in &ONWARD[last as usize] {
            let q = torus.step(pos, m);
            let cp = cov.checkpoint();
            let g = cov.cover_step(sensor, belief, m, q);
            self.cur[k as usize] = q;
            self.dfs(
                torus,
                sensor,
                belief,
                cov,
                q,
                m,
                k + 1,
                acc + w * g,
                gain + g,
            );
            cov.undo(cp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::prior::{PriorSpec, TargetPrior};
    use crate::game::rng;
    use crate::searchers::planning::far_goal::reverse;

    /// The best total and its sequence below a node, by the rule without
    /// bounds or shortcuts: every sequence covered and undone, first
    /// found kept on ties.
    #[allow(clippy::too_many_arguments)]
    fn best_below(
        h: u32,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &mut Coverage,
        pos: u32,
        last: Move,
        k: u32,
        acc: f64,
        gain: f64,
        seq: &mut Vec<u32>,
        best: &mut (f64, f64, Vec<u32>),
    ) {
        if k == h {
            if acc > best.0 {
                *best = (acc, gain, seq.clone());
            }
            return;
        }
        let w = (h - k) as f64;
        for m in order(Some(last)).filter(|&m| m != reverse(last)) {
            let q = torus.step(pos, m);
            let cp = cov.checkpoint();
            let g = cov.cover(sensor, belief, q);
            seq.push(q);
            best_below(
                h,
                torus,
                sensor,
                belief,
                cov,
                q,
                m,
                k + 1,
                acc + w * g,
                gain + g,
                seq,
                best,
            );
            seq.pop();
            cov.undo(cp);
        }
    }

    #[test]
    fn the_onward_table_is_the_order_without_the_reversal() {
        for last in Move::ALL {
            let want: Vec<Move> = order(Some(last)).filter(|&m| m != reverse(last)).collect();
            assert_eq!(ONWARD[last as usize].to_vec(), want, "{last:?}");
        }
    }

    /// The lookahead, with its bound on what the moves left can add and its
    /// unmarked last move, finds what trying every sequence finds: each
    /// first move's score, the move, the gain and the sequence, bit for bit.
    /// Random searched sets and simulations, positions that have and have
    /// not been stood on, depths 1–5, sensor radii 0 to 2.5, and priors
    /// with ties (uniform, painted levels) and without; a bound one move
    /// short (tried) fails it. Scoring only the winner finds the same.
    #[test]
    fn the_bounded_lookahead_finds_what_every_sequence_finds() {
        let mut r = rng::stream(5, 0);
        let mut checked = 0;
        for n in [5u32, 12, 24] {
            let torus = Torus::new(n).unwrap();
            let cells = torus.cells();
            let paint: Vec<f64> = (0..cells).map(|_| rng::below(&mut r, 3) as f64).collect();
            for spec in [
                PriorSpec::Uniform,
                PriorSpec::Weights { weights: paint },
                PriorSpec::Gaussian {
                    sigma: n as f64 / 5.0,
                },
            ] {
                for rv in [0.0, 1.0, 1.5, 2.5] {
                    let sensor = Sensor::new(&torus, rv).unwrap();
                    let prior = TargetPrior::new(&torus, &spec).unwrap();
                    let mut belief = BeliefState::new(Belief::Posterior, prior, None);
                    let mut cov = Coverage::new(cells);
                    for round in 0..40 {
                        let h = 1 + round % 5;
                        let pos = rng::below(&mut r, cells as u32);
                        if round % 3 == 0 {
                            belief.search_around(&sensor, pos);
                        }
                        let last =
                            (round % 4 != 0).then(|| Move::from_index(rng::below(&mut r, 4)));
                        let mut look = Lookahead::new(h);
                        let before = cov.len();
                        let found = look.search(
                            &torus,
                            &sensor,
                            &belief,
                            &mut cov,
                            pos,
                            last,
                            Scored::Every,
                        );
                        assert_eq!(cov.len(), before, "the simulation is left as it was");
                        // Work is the search's own and the simulated moves
                        // made: at most the 4 + 12 + … + 4·3^(h−1) of the
                        // whole tree, then 0.
                        let work = look.take_work() - SEARCH_WORK;
                        assert!((1..=2 * (3u64.pow(h) - 1)).contains(&work), "h {h}: {work}");
                        assert_eq!(look.take_work(), 0);
                        // Scoring only the winner finds the same move, gain
                        // and sequence, and leaves more out.
                        let mut alone = Lookahead::new(h);
                        let won = alone.search(
                            &torus,
                            &sensor,
                            &belief,
                            &mut cov,
                            pos,
                            last,
                            Scored::Winner,
                        );
                        assert_eq!(cov.len(), before);
                        assert_eq!((won.first, won.gain), (found.first, found.gain));
                        assert_eq!(alone.best_seq(), look.best_seq());
                        assert_eq!(
                            won.score[won.first as usize],
                            found.score[found.first as usize]
                        );
                        let unscored = Move::ALL
                            .iter()
                            .filter(|&&m| won.score[m as usize].is_nan());
                        assert_eq!(unscored.count(), 3);
                        assert!(alone.take_work() - SEARCH_WORK <= work);
                        let mut overall: Option<(Move, f64, f64, Vec<u32>)> = None;
                        for m in order(last) {
                            let q = torus.step(pos, m);
                            let cp = cov.checkpoint();
                            let g = cov.cover(&sensor, &belief, q);
                            let mut best = (f64::NEG_INFINITY, 0.0, Vec::new());
                            let mut seq = vec![q];
                            let w = h as f64;
                            best_below(
                                h,
                                &torus,
                                &sensor,
                                &belief,
                                &mut cov,
                                q,
                                m,
                                1,
                                w * g,
                                g,
                                &mut seq,
                                &mut best,
                            );
                            cov.undo(cp);
                            assert_eq!(
                                found.score[m as usize], best.0,
                                "n {n} {spec:?} r_v {rv} h {h} {m:?}"
                            );
                            if overall.as_ref().is_none_or(|o| best.0 > o.1) {
                                overall = Some((m, best.0, best.1, best.2));
                            }
                        }
                        let (m, _, gain, seq) = overall.unwrap();
                        assert_eq!((found.first, found.gain), (m, gain));
                        assert_eq!(look.best_seq(), &seq[..]);
                        checked += 1;
                        for _ in 0..rng::below(&mut r, 8) {
                            let c = rng::below(&mut r, cells as u32);
                            if rng::below(&mut r, 2) == 0 {
                                belief.search_around(&sensor, c);
                            } else {
                                cov.cover(&sensor, &belief, c);
                            }
                        }
                    }
                }
            }
        }
        assert_eq!(checked, 3 * 3 * 4 * 40);
    }
}
