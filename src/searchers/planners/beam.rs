//! The beam planner: plans its whole path at the first move and follows it.
//!
//! # Why one path
//! The target does not move and, until detection, the only news is "not
//! found yet", which any path anticipates. So the best a searcher can do is
//! follow one fixed path: the one with the least `Σ_t R_t`.
//!
//! # Rule
//! 1. **Beam search** over the first `beam_depth` moves. A partial path
//!    is ranked by its exact `Σ R_t` so far plus a lower bound on the rest.
//!    The bound is the larger of two:
//!    - each later move covers at most `front` new cells (3 at r_v = 1),
//!      so `R` falls no faster than the heaviest cells taken `front` at a
//!      time;
//!    - no cell is seen before its distance from the searcher less the
//!      sensor's reach.
//!
//!    Both are computed over the heaviest `4 · front · beam_depth` cells
//!    only, which keeps them lower bounds and their cost independent of N. The `beam_width` best partial paths survive each depth, at most
//!    [`PER_CELL`] ending on one cell, so that the beam does not fill with
//!    near-copies.
//! 2. The best partial path is **finished by the horizon rule** (depth
//!    `horizon`), like the horizon planner's own path from here.
//! 3. Both paths are **refined** by exact local search
//!    ([`super::refine`]) over their first `2 · beam_depth` moves. The
//!    cheaper one is the plan. So the plan is never worse than the horizon
//!    rule's path.
//!
//! A plan depends only on the planning mass left, the cell, the last move
//! and the parameters. So the last few plans are kept for the process
//! ([`super::kept`]), and trials of one configuration make the plan once.
//!
//! # Slices
//! The plan is made in slices of about a millisecond (a few horizon moves,
//! partial paths or first moves of refinement), one per loop `think` is
//! asked for, so a page's worker answers between them and shows the
//! progress ([`Searcher::planning`]). Slicing changes nothing in the plan.

use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::rng::splitmix64;
use crate::param::{Param, ParamKind, Value};
use crate::searchers::decision::Planning;
use crate::searchers::info::{Reads, SearcherInfo};
use crate::searchers::planning::completion::{decide, Completion, FarGoal, SLICE_WORK};
use crate::searchers::planning::lookahead::{Lookahead, Scored, HORIZON};
use crate::searchers::planning::plan_cache::{self, PlanKey};
use crate::searchers::planning::planned_path::PlannedPath;
use crate::searchers::planning::refine::Refiner;
use crate::searchers::searcher::{Searcher, Setup, World};
use std::collections::HashSet;

/// The default beam width.
pub const DEFAULT_BEAM_WIDTH: u32 = 100;
/// The default beam depth, in moves.
pub const DEFAULT_BEAM_DEPTH: u32 = 200;
/// The largest beam width and depth: a beam of 400 · 4 · 400 partial
/// paths, whose bounds cost the same at any N.
pub const MAX_BEAM: u32 = 400;
/// Most partial paths that end on one cell at each depth.
pub const PER_CELL: u8 = 2;
/// Refinement tries changes spanning fewer moves than this.
const WINDOW: u32 = 40;

/// Partial paths kept at each depth.
pub static BEAM_WIDTH: Param = Param {
    key: "beam_width",
    label: "Beam width",
    kind: ParamKind::Int {
        min: 1,
        max: MAX_BEAM as u64,
    },
    default: Value::Int(DEFAULT_BEAM_WIDTH as u64),
    help: "beam planner: partial paths kept at each depth (at most 2 ending on one cell)",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// Moves planned by beam search.
pub static BEAM_DEPTH: Param = Param {
    key: "beam_depth",
    label: "Beam depth",
    kind: ParamKind::Int {
        min: 1,
        max: MAX_BEAM as u64,
    },
    default: Value::Int(DEFAULT_BEAM_DEPTH as u64),
    help: "beam planner: moves planned by beam search before the horizon rule finishes the path",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// The beam planner as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "beam",
    label: "Beam planner",
    help: "plans its whole path at the first move: beam search over the first beam_depth moves (exact cost so far plus a lower bound on the rest), finished by the horizon rule and refined by exact local search; never worse than the horizon rule's path",
    deterministic: true,
    deliberates: false,
    params: &[
        Reads::always(&BEAM_WIDTH),
        Reads::always(&BEAM_DEPTH),
        Reads::always(&HORIZON),
    ],
    build: |s| Box::new(Beam::new(s)),
};

/// The beam planner.
pub struct Beam {
    rv: f64,
    width: u32,
    depth: u32,
    horizon: u32,
    step_cap: u32,
    look: Lookahead,
    cov: Coverage,
    /// The plan being followed.
    plan: PlannedPath,
    last: Option<Move>,
    /// The plan being made, between slices.
    job: Option<Box<Job>>,
}

/// First moves of refinement per slice of planning.
const ROWS_PER_SLICE: usize = 2;

/// Where a plan being made stands.
enum Stage {
    /// The horizon rule's own path, into `Job::rule`.
    Rule(Completion),
    /// The beam search.
    Search(Box<BeamSearch>),
    /// The horizon rule finishing the beam's best partial path (the belief
    /// after that path), into `Job::tail`.
    Tail(Box<BeliefState>, Completion),
    /// Refining the rule's path, then the beam's.
    RefineRule,
    RefineBeam,
}

/// A plan being made, in slices (each a bounded piece of work), so a page
/// stays responsive and can show how far it has got.
struct Job {
    key: PlanKey,
    stage: Stage,
    /// The rule's path and the beam's (each from the searcher's cell, and
    /// each growing while it is made).
    rule: Vec<u32>,
    beam: Vec<u32>,
    refiner: Refiner,
    by_rule: f64,
    /// The beam search's best partial path from the searcher's cell, to
    /// draw (the other stages draw the path they work on in place: a copy
    /// a slice would cost the path's length each slice).
    sketch: Vec<u32>,
}

impl Beam {
    /// A beam planner as `setup` describes.
    pub fn new(setup: &Setup<'_>) -> Beam {
        let s = setup.settings;
        let horizon = s.u32(&HORIZON);
        Beam {
            rv: setup.rv,
            width: s.u32(&BEAM_WIDTH),
            depth: s.u32(&BEAM_DEPTH),
            horizon,
            step_cap: setup.step_cap,
            look: Lookahead::new(horizon),
            cov: Coverage::new(setup.torus.cells()),
            plan: PlannedPath::default(),
            last: None,
            job: None,
        }
    }

    /// Recalls the plan from `pos`, or starts making it.
    fn begin(&mut self, belief: &BeliefState, pos: u32) {
        let params = [
            self.rv.to_bits(),
            self.width.into(),
            self.depth.into(),
            self.horizon.into(),
            self.step_cap.into(),
        ];
        let key = PlanKey::new("beam", &params, belief, pos, self.last);
        if let Some(plan) = plan_cache::recall(&key) {
            *self.plan.start() = plan;
            return;
        }
        let run = Completion::new(
            belief,
            pos,
            self.last,
            self.step_cap as usize,
            FarGoal::Stuck,
        );
        self.job = Some(Box::new(Job {
            key,
            stage: Stage::Rule(run),
            rule: vec![pos],
            beam: Vec::new(),
            refiner: Refiner::default(),
            by_rule: 0.0,
            sketch: Vec::new(),
        }));
    }

    /// Works on the plan under way for up to `slices` slices; true once
    /// the plan is made (and kept for the process).
    fn work(&mut self, torus: &Torus, sensor: &Sensor, belief: &BeliefState, slices: u32) -> bool {
        let Some(job) = self.job.as_deref_mut() else {
            return true;
        };
        let cap = self.step_cap as usize;
        let span = 2 * self.depth as usize;
        let pos = job.key.pos();
        let (mass, c) = (job.key.mass(), self.step_cap);
        let look = &mut self.look;
        let cov = &mut self.cov;
        // One slice of the stage under way per turn.
        for _ in 0..slices {
            match &mut job.stage {
                Stage::Rule(run) => {
                    // Horizon moves until they have done a slice's work, as
                    // counted: a move's cost varies a hundredfold with the
                    // lattice and with how much its scan and lookahead skip.
                    if run.moves(look, torus, sensor, belief, cov, &mut job.rule, SLICE_WORK) {
                        let (w, d) = (self.width as usize, self.depth as usize);
                        let search = BeamSearch::new(torus, sensor, mass, pos, w, d);
                        job.stage = Stage::Search(Box::new(search));
                        job.sketch.clear();
                        job.sketch.push(pos);
                    }
                }
                Stage::Search(search) => {
                    let done = search.work(torus, sensor, mass);
                    search.best(&mut job.sketch);
                    if done {
                        // The sketch is the searcher's cell, then the head.
                        let (head, n) = (&job.sketch[1..], job.sketch.len());
                        let mut after = belief.clone();
                        for &c in head {
                            after.search_around(sensor, c);
                        }
                        let end = job.sketch[n - 1];
                        let last = match n {
                            1 => self.last,
                            _ => torus.move_to(job.sketch[n - 2], end),
                        };
                        let rest = cap.saturating_sub(head.len());
                        let run = Completion::new(&after, end, last, rest, FarGoal::Stuck);
                        job.beam.clone_from(&job.sketch);
                        job.stage = Stage::Tail(Box::new(after), run);
                    }
                }
                Stage::Tail(after, run) => {
                    if run.moves(look, torus, sensor, after, cov, &mut job.beam, SLICE_WORK) {
                        job.refiner.start(torus, sensor, mass, c, span, &job.rule);
                        job.stage = Stage::RefineRule;
                    }
                }
                Stage::RefineRule => {
                    let rows = ROWS_PER_SLICE;
                    if job.refiner.work(torus, sensor, mass, c, WINDOW, rows) {
                        job.by_rule = job.refiner.finish(mass, c, &mut job.rule).after;
                        job.refiner.start(torus, sensor, mass, c, span, &job.beam);
                        job.stage = Stage::RefineBeam;
                    }
                }
                Stage::RefineBeam => {
                    let rows = ROWS_PER_SLICE;
                    if job.refiner.work(torus, sensor, mass, c, WINDOW, rows) {
                        let by_beam = job.refiner.finish(mass, c, &mut job.beam).after;
                        let plan = if by_beam < job.by_rule {
                            &job.beam
                        } else {
                            &job.rule
                        };
                        let cells = self.plan.start();
                        cells.extend_from_slice(&plan[1..]);
                        let job = self.job.take().expect("the job under way");
                        plan_cache::keep(job.key, cells);
                        return true;
                    }
                }
            }
        }
        false
    }

    /// How far the plan under way has got.
    fn progress(&self) -> Option<Planning> {
        let job = self.job.as_deref()?;
        let (stage, done, total) = match &job.stage {
            Stage::Rule(_) => ("horizon rule's path", job.rule.len() - 1, 0),
            Stage::Search(s) => ("beam search, depth", s.level, self.depth as usize),
            Stage::Tail(..) => (
                "finishing the beam's path",
                job.beam.len() - job.sketch.len(),
                0,
            ),
            Stage::RefineRule | Stage::RefineBeam => {
                let (pass, i, len) = job.refiner.progress();
                let stage = match (&job.stage, pass) {
                    (Stage::RefineRule, 0) => "refining the rule's path, pass 1",
                    (Stage::RefineRule, _) => "refining the rule's path, later passes",
                    (_, 0) => "refining the beam's path, pass 1",
                    _ => "refining the beam's path, later passes",
                };
                (stage, i, len)
            }
        };
        Some(Planning::plan(stage, done as u32, total as u32))
    }
}

/// A partial path in the beam.
#[derive(Clone, Copy)]
struct Node {
    pos: u32,
    /// `Σ R_t` so far and `R` now.
    cost: f64,
    left_mass: f64,
    /// Cells with mass still uncovered.
    left: u32,
    /// Zobrist hash of the covered set.
    key: u64,
    /// Where its covered set starts in the arena.
    bits: usize,
    /// Its last cell in the history.
    hist: usize,
}

/// A child of a node under test.
#[derive(Clone, Copy)]
struct Child {
    rank: f64,
    key: u64,
    parent: usize,
    cell: u32,
    cost: f64,
    left_mass: f64,
    left: u32,
}

#[inline]
fn zobrist(c: u32) -> u64 {
    splitmix64(c as u64)
}

#[inline]
fn zobrist_pos(c: u32) -> u64 {
    splitmix64(c as u64 ^ 0xA5A5_5A5A_0F0F_F0F0)
}

/// Partial paths expanded per slice of [`BeamSearch::work`].
const NODES_PER_SLICE: usize = 16;

/// The beam search from `pos` over `mass` (0 on searched cells), made in
/// slices of a few partial paths each; the best partial path is
/// [`BeamSearch::best`].
struct BeamSearch {
    width: usize,
    depth: usize,
    words: usize,
    front: usize,
    reach: u32,
    /// The heaviest cells with mass, heaviest first, with their
    /// coordinates (the rest bound's distances then need no division).
    heavy: Vec<(u32, u32, u32)>,
    arena: Vec<u64>,
    hist: Vec<(usize, u32)>,
    nodes: Vec<Node>,
    next_arena: Vec<u64>,
    next_nodes: Vec<Node>,
    children: Vec<Child>,
    fresh: Vec<u32>,
    seen: HashSet<u64>,
    per_cell: Vec<u8>,
    /// Depths finished, and the next node of the depth under way.
    level: usize,
    at: usize,
    done: bool,
}

impl BeamSearch {
    fn new(
        torus: &Torus,
        sensor: &Sensor,
        mass: &[f64],
        pos: u32,
        width: usize,
        depth: usize,
    ) -> BeamSearch {
        let cells = torus.cells();
        let (front, reach) = front_and_reach(sensor);
        let mut heavy: Vec<u32> = (0..cells as u32)
            .filter(|&c| mass[c as usize] > 0.0)
            .collect();
        heavy.sort_by(|&a, &b| {
            mass[b as usize]
                .total_cmp(&mass[a as usize])
                .then(a.cmp(&b))
        });
        let total_left = heavy.len() as u32;
        heavy.truncate(4 * front * depth + sensor.offsets().len());
        let heavy = with_xy(torus, &heavy);
        let words = cells.div_ceil(64);
        BeamSearch {
            width,
            depth,
            words,
            front,
            reach,
            heavy,
            arena: vec![0u64; words],
            hist: Vec::new(),
            nodes: vec![Node {
                pos,
                cost: 0.0,
                left_mass: mass.iter().sum(),
                left: total_left,
                key: 0,
                bits: 0,
                hist: usize::MAX,
            }],
            next_arena: Vec::new(),
            next_nodes: Vec::new(),
            children: Vec::new(),
            fresh: Vec::new(),
            seen: HashSet::new(),
            per_cell: vec![0u8; cells],
            level: 0,
            at: 0,
            done: depth == 0,
        }
    }

    /// One slice: expands up to [`NODES_PER_SLICE`] partial paths, ending
    /// each depth by keeping the best children. True when the search is
    /// done (the depth reached, every cell covered, or no child left).
    fn work(&mut self, torus: &Torus, sensor: &Sensor, mass: &[f64]) -> bool {
        let mut budget = NODES_PER_SLICE;
        while !self.done && budget > 0 {
            if self.at == 0 {
                if self.nodes[0].left == 0 {
                    self.done = true;
                    break;
                }
                self.children.clear();
            }
            let end = (self.at + budget).min(self.nodes.len());
            for i in self.at..end {
                self.expand(torus, sensor, mass, i);
            }
            budget -= end - self.at;
            self.at = end;
            if self.at == self.nodes.len() {
                self.select(sensor);
                self.at = 0;
                self.level += 1;
                if self.level == self.depth {
                    self.done = true;
                }
            }
        }
        self.done
    }

    /// The children of node `i`, ranked.
    fn expand(&mut self, torus: &Torus, sensor: &Sensor, mass: &[f64], i: usize) {
        let node = self.nodes[i];
        if node.left == 0 {
            return;
        }
        let (arena, fresh) = (&self.arena, &mut self.fresh);
        let covered = |at: usize, c: u32| arena[at + c as usize / 64] >> (c % 64) & 1 == 1;
        for m in Move::ALL {
            let q = torus.step(node.pos, m);
            fresh.clear();
            let (mut gain, mut count, mut key) = (0.0, 0, node.key);
            for c in sensor.around(q) {
                if !covered(node.bits, c) && mass[c as usize] > 0.0 {
                    fresh.push(c);
                    gain += mass[c as usize];
                    count += 1;
                    key ^= zobrist(c);
                }
            }
            let left = node.left - count;
            let r = if left == 0 {
                0.0
            } else {
                node.left_mass - gain
            };
            let cost = node.cost + r;
            let rank = cost
                + if left == 0 {
                    0.0
                } else {
                    let fresh = &*fresh;
                    rest_bound(
                        torus,
                        mass,
                        &self.heavy,
                        self.front,
                        self.reach,
                        q,
                        r,
                        |c| covered(node.bits, c) || fresh.contains(&c),
                    )
                };
            self.children.push(Child {
                rank,
                key: key ^ zobrist_pos(q),
                parent: i,
                cell: q,
                cost,
                left_mass: r,
                left,
            });
        }
    }

    /// Keeps the best children as the next depth's nodes.
    fn select(&mut self, sensor: &Sensor) {
        let words = self.words;
        self.children
            .sort_by(|a, b| a.rank.total_cmp(&b.rank).then(a.key.cmp(&b.key)));
        self.seen.clear();
        self.next_nodes.clear();
        self.next_arena.clear();
        for ch in &self.children {
            if self.next_nodes.len() == self.width {
                break;
            }
            if self.per_cell[ch.cell as usize] >= PER_CELL || !self.seen.insert(ch.key) {
                continue;
            }
            self.per_cell[ch.cell as usize] += 1;
            let parent = self.nodes[ch.parent];
            let at = self.next_arena.len();
            self.next_arena
                .extend_from_slice(&self.arena[parent.bits..parent.bits + words]);
            for c in sensor.around(ch.cell) {
                self.next_arena[at + c as usize / 64] |= 1 << (c % 64);
            }
            self.hist.push((parent.hist, ch.cell));
            self.next_nodes.push(Node {
                pos: ch.cell,
                cost: ch.cost,
                left_mass: ch.left_mass,
                left: ch.left,
                key: ch.key ^ zobrist_pos(ch.cell),
                bits: at,
                hist: self.hist.len() - 1,
            });
        }
        for n in &self.next_nodes {
            self.per_cell[n.pos as usize] = 0;
        }
        if self.next_nodes.is_empty() {
            self.done = true;
            return;
        }
        std::mem::swap(&mut self.nodes, &mut self.next_nodes);
        std::mem::swap(&mut self.arena, &mut self.next_arena);
    }

    /// The best partial path of the last depth finished, as the cells it
    /// enters, written into `out` after its first cell (the searcher's).
    fn best(&self, out: &mut Vec<u32>) {
        out.truncate(1);
        let mut h = self.nodes[0].hist;
        while h != usize::MAX {
            out.push(self.hist[h].1);
            h = self.hist[h].0;
        }
        out[1..].reverse();
    }
}

/// The most new cells one move can cover, and the sensor's ℓ1 reach.
fn front_and_reach(sensor: &Sensor) -> (usize, u32) {
    (sensor.front_len().max(1), sensor.reach_l1())
}

/// A lower bound on `Σ R` over the moves after reaching `q` with mass `r`
/// left: the larger of the front bound and the distance bound, over the
/// `heavy` cells not `covered` (see the module doc).
#[allow(clippy::too_many_arguments)]
fn rest_bound(
    torus: &Torus,
    mass: &[f64],
    heavy: &[(u32, u32, u32)],
    front: usize,
    reach: u32,
    q: u32,
    r: f64,
    covered: impl Fn(u32) -> bool,
) -> f64 {
    let (mut by_front, mut by_distance) = (0.0, 0.0);
    let mut rest = r;
    let mut k = 0;
    let (qx, qy) = torus.xy(q);
    for &(c, x, y) in heavy {
        if covered(c) {
            continue;
        }
        let m = mass[c as usize];
        rest -= m;
        k += 1;
        if k == front {
            k = 0;
            by_front += rest.max(0.0);
        }
        // Seen no sooner than l1 − reach moves from now, so uncovered for
        // at least l1 − reach − 1 of the later moves.
        let l1 = torus.axis_dist(qx, x) + torus.axis_dist(qy, y);
        by_distance += m * l1.saturating_sub(reach + 1) as f64;
    }
    f64::max(by_front, by_distance)
}

/// Each cell with its coordinates.
fn with_xy(torus: &Torus, cells: &[u32]) -> Vec<(u32, u32, u32)> {
    cells
        .iter()
        .map(|&c| {
            let (x, y) = torus.xy(c);
            (c, x, y)
        })
        .collect()
}

impl Searcher for Beam {
    fn think(&mut self, w: &mut World<'_>, max_loops: u32) -> Option<Move> {
        let done = self.plan.walked();
        if !self.plan.on_plan(w.torus, w.pos) && !done {
            if self.job.is_none() {
                self.begin(w.belief, w.pos);
            }
            // A slice of planning per loop asked for: the decision is
            // under way until the plan is made.
            if !self.work(w.torus, w.sensor, w.belief, max_loops) {
                return None;
            }
        }
        if let Some(c) = self.plan.next_cell() {
            return Some(w.torus.move_to(w.pos, c).unwrap_or(Move::Right));
        }
        // The plan covered every cell with mass (only a step cap or a
        // target the prior ruled out leaves the searcher here).
        self.cov.clear();
        let (m, _, _) = decide(
            &mut self.look,
            w.torus,
            w.sensor,
            w.belief,
            &mut self.cov,
            w.pos,
            self.last,
            FarGoal::Compared,
            Scored::Winner,
            None,
        );
        Some(m)
    }

    fn observe(&mut self, _torus: &Torus, m: Move, pos: u32) {
        self.last = Some(m);
        self.plan.observe(pos);
    }

    fn intent(&self) -> &[u32] {
        match self.job.as_deref() {
            Some(job) => match job.stage {
                Stage::Rule(_) | Stage::RefineRule => &job.rule,
                Stage::Search(_) => &job.sketch,
                Stage::Tail(..) | Stage::RefineBeam => &job.beam,
            },
            None => self.plan.ahead(),
        }
    }

    fn planning(&self) -> Option<Planning> {
        self.progress()
    }
}

#[cfg(test)]
#[path = "beam_tests.rs"]
mod tests;
