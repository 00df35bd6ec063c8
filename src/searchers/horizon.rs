//! The receding-horizon planner: every move sequence of depth `h`
//! (reversals pruned), scored by how early it covers planning mass; the
//! first move of the best sequence is taken, then the search repeats.
//!
//! # Rule
//! A sequence covering new planning mass `g_1, …, g_h` at its moves scores
//! `Σ_k (h − k + 1)·g_k`. Minimising the expected time `E[T] = Σ_t R_t`
//! (`R_t`: mass left after `t` moves) over the horizon is the same as
//! maximising this score, since `Σ_{k≤h} R_k = h·R_0 − score`: mass found
//! earlier counts more. Ties go to going straight on, then `Move::ALL`
//! order. There are `4·3^(h−1)` sequences, about `2·3^h` simulated moves
//! per decision (hence [`MAX_HORIZON`]).
//!
//! **Fallback.** Beyond the horizon the planner is blind, so it compares
//! the best sequence's rate `G/h` (`G`: the mass it covers) with the best
//! far goal: the cell maximising (uncovered mass in its disc) ÷
//! (distance + 1), a scan of the lattice that skips the rows that cannot beat
//! the rate (`plan::fallback_target`). When the goal's value is larger (in
//! particular when nothing within reach adds mass) it steps straight toward
//! the goal.
//!
//! The planner is deterministic: its path depends only on the belief, so
//! `run --exact` evaluates it exactly.

use super::plan::{fallback_target, toward, FarScan};
use super::{MoveScores, Searcher, SearcherInfo, World};
use crate::config::Config;
use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};

/// The largest horizon: `2·3^h` simulated moves per decision stays under
/// 10⁵ (about 1 ms natively at r_v = 1).
pub const MAX_HORIZON: u32 = 9;

/// The default horizon.
pub const DEFAULT_HORIZON: u32 = 6;

/// What the decision panel says the scores are.
const MEANING: &str =
    "mass covered over the horizon, earlier moves weighted more: Σ_k (h−k+1)·gain_k";

/// The receding-horizon planner as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "horizon",
    label: "Receding horizon",
    help: "tries every move sequence of depth h and takes the first move of the one that covers planning mass earliest; heads for the best far cell when that is better; on priors much wider than the sensor (σ of 30 cells or more) it runs on into the tail, where the spiral planner does better",
    deterministic: true,
    deliberates: false,
    uses: |_, key| key == "horizon",
    build: |s| Box::new(Horizon::new(s.cfg, s.torus)),
};

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
    scan: FarScan,
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

    /// The work done since it was last taken, in [`SLICE_WORK`]'s units: the
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

/// Work units a lookahead's search costs besides its simulated moves (the
/// bound's box, the first moves' discs): a depth-1 search, the greedy
/// step of a plan's tail, took about 180 ns a move at N = 256 when it was
/// charged only its 4 first moves, against about 25 ns a unit for the
/// depth-5 lookahead at N = 40.
pub const SEARCH_WORK: u64 = 4;

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

/// The receding-horizon searcher.
pub struct Horizon {
    look: Lookahead,
    cov: Coverage,
    last: Option<Move>,
    intent: Vec<u32>,
    scores: Option<MoveScores>,
    /// Its number among the process's runs of far-goal scans: a searcher
    /// plays one episode, whose searched cells only grow, so each scan
    /// may keep what the one before read ([`FarScan`]).
    run: u64,
}

impl Horizon {
    /// A planner with `cfg.horizon` for a lattice like `torus`.
    pub fn new(cfg: &Config, torus: &Torus) -> Horizon {
        Horizon {
            look: Lookahead::new(cfg.horizon),
            cov: Coverage::new(torus.cells()),
            last: None,
            intent: Vec::with_capacity(2 * torus.n() as usize + cfg.horizon as usize),
            scores: None,
            run: FarScan::new_run(),
        }
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

impl Searcher for Horizon {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        self.cov.clear();
        let (m, found, goal) = decide(
            &mut self.look,
            w.torus,
            w.sensor,
            w.belief,
            &mut self.cov,
            w.pos,
            self.last,
            FarGoal::Compared,
            Scored::Every,
            Some(self.run),
        );
        self.intent.clear();
        match goal {
            Some(g) => walk_to(w.torus, w.pos, g, &mut self.intent),
            None => self.intent.extend_from_slice(self.look.best_seq()),
        }
        self.scores = Some(MoveScores {
            meaning: MEANING,
            higher_is_better: true,
            score: found.score,
            chosen: m as u8,
        });
        Some(m)
    }

    fn observe(&mut self, _torus: &Torus, m: Move, _pos: u32) {
        self.last = Some(m);
        if !self.intent.is_empty() {
            self.intent.remove(0);
        }
    }

    fn intent(&self) -> &[u32] {
        &self.intent
    }

    fn scores(&self) -> Option<MoveScores> {
        self.scores
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::prior::{PriorSpec, TargetPrior};
    use crate::game::rng;
    use crate::searchers::plan::reverse;

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
