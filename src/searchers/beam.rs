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
//! ([`PLANS`]), and trials of one configuration make the plan once.

use super::horizon::{completion, decide, Lookahead};
use super::refine::Refiner;
use super::{Searcher, SearcherInfo, World};
use crate::belief::BeliefState;
use crate::config::Config;
use crate::coverage::Coverage;
use crate::lattice::{Move, Sensor, Torus};
use crate::mcts::DecisionView;
use crate::rng::splitmix64;
use crate::view::Layer;
use std::collections::HashSet;
use std::sync::Mutex;

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
/// Plans kept for the process.
const KEPT: usize = 8;

/// The beam planner as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "beam",
    label: "Beam planner",
    help: "plans its whole path at the first move: beam search over the first beam_depth moves (exact cost so far plus a lower bound on the rest), finished by the horizon rule and refined by exact local search; never worse than the horizon rule's path",
    deterministic: true,
    deliberates: false,
    uses: |_, key| matches!(key, "beam_width" | "beam_depth" | "horizon"),
    build: |s| Box::new(Beam::new(s.cfg, s.torus)),
};

/// What a plan is a function of.
#[derive(Clone, Debug, PartialEq)]
struct PlanKey {
    n: u32,
    rv: u64,
    width: u32,
    depth: u32,
    horizon: u32,
    step_cap: u32,
    pos: u32,
    last: Option<Move>,
    /// The planning mass of each cell, 0 where searched.
    mass: Vec<f64>,
}

/// The last plans made in this process, newest last.
static PLANS: Mutex<Vec<(PlanKey, Vec<u32>)>> = Mutex::new(Vec::new());

/// The beam planner.
pub struct Beam {
    rv: f64,
    width: u32,
    depth: u32,
    horizon: u32,
    step_cap: u32,
    look: Lookahead,
    cov: Coverage,
    /// The cells still to enter, from `next`.
    plan: Vec<u32>,
    next: usize,
    planned: bool,
    last: Option<Move>,
}

impl Beam {
    /// A beam planner for `cfg` on `torus`.
    pub fn new(cfg: &Config, torus: &Torus) -> Beam {
        Beam {
            rv: cfg.rv,
            width: cfg.beam_width,
            depth: cfg.beam_depth,
            horizon: cfg.horizon,
            step_cap: cfg.step_cap,
            look: Lookahead::new(cfg.horizon),
            cov: Coverage::new(torus.cells()),
            plan: Vec::new(),
            next: 0,
            planned: false,
            last: None,
        }
    }

    /// Makes (or recalls) the plan from `pos`.
    fn make(&mut self, torus: &Torus, sensor: &Sensor, belief: &BeliefState, pos: u32) {
        let mass: Vec<f64> = belief
            .plan_mass()
            .iter()
            .zip(belief.searched())
            .map(|(&m, &s)| if s == 0 { m } else { 0.0 })
            .collect();
        let key = PlanKey {
            n: torus.n(),
            rv: self.rv.to_bits(),
            width: self.width,
            depth: self.depth,
            horizon: self.horizon,
            step_cap: self.step_cap,
            pos,
            last: self.last,
            mass,
        };
        let mut plans = PLANS.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, plan)) = plans.iter().find(|(k, _)| *k == key) {
            self.plan.clone_from(plan);
        } else {
            drop(plans);
            self.plan = self.compute(torus, sensor, belief, &key);
            plans = PLANS.lock().unwrap_or_else(|e| e.into_inner());
            if plans.len() == KEPT {
                plans.remove(0);
            }
            plans.push((key, self.plan.clone()));
        }
        self.next = 0;
        self.planned = true;
    }

    /// The plan (cells after `key.pos`).
    fn compute(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        key: &PlanKey,
    ) -> Vec<u32> {
        let cap = self.step_cap as usize;
        let pos = key.pos;
        // The horizon rule's own path.
        let mut rule = Vec::new();
        completion(
            &mut self.look,
            torus,
            sensor,
            belief,
            &mut self.cov,
            pos,
            self.last,
            cap,
            &mut rule,
        );
        rule.insert(0, pos);
        // The beam's path, finished by the rule.
        let head = search(
            torus,
            sensor,
            &key.mass,
            pos,
            self.width as usize,
            self.depth as usize,
        );
        let mut after = belief.clone();
        for &c in &head {
            after.search_around(sensor, c);
        }
        let end = head.last().copied().unwrap_or(pos);
        let last = match head.len() {
            0 => self.last,
            1 => torus.move_to(pos, end),
            k => torus.move_to(head[k - 2], end),
        };
        let mut tail = Vec::new();
        completion(
            &mut self.look,
            torus,
            sensor,
            &after,
            &mut self.cov,
            end,
            last,
            cap.saturating_sub(head.len()),
            &mut tail,
        );
        let mut beam = Vec::with_capacity(1 + head.len() + tail.len());
        beam.push(pos);
        beam.extend_from_slice(&head);
        beam.extend_from_slice(&tail);
        let mut refiner = Refiner::default();
        let span = 2 * self.depth as usize;
        let (m, c) = (&key.mass, self.step_cap);
        let by_rule = refiner.refine(torus, sensor, m, c, WINDOW, span, &mut rule);
        let by_beam = refiner.refine(torus, sensor, m, c, WINDOW, span, &mut beam);
        let plan = if by_beam.after < by_rule.after {
            beam
        } else {
            rule
        };
        plan[1..].to_vec()
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

/// The beam search: the best partial path from `pos` over `mass` (0 on
/// searched cells), as the cells it enters.
fn search(
    torus: &Torus,
    sensor: &Sensor,
    mass: &[f64],
    pos: u32,
    width: usize,
    depth: usize,
) -> Vec<u32> {
    let cells = torus.cells();
    let words = cells.div_ceil(64);
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
    let left_mass: f64 = mass.iter().sum();

    let mut arena = vec![0u64; words];
    let mut hist: Vec<(usize, u32)> = Vec::new();
    let mut nodes = vec![Node {
        pos,
        cost: 0.0,
        left_mass,
        left: total_left,
        key: 0,
        bits: 0,
        hist: usize::MAX,
    }];
    let covered =
        |arena: &[u64], at: usize, c: u32| arena[at + c as usize / 64] >> (c % 64) & 1 == 1;
    let mut next_arena: Vec<u64> = Vec::new();
    let mut next_nodes: Vec<Node> = Vec::new();
    let mut children: Vec<Child> = Vec::new();
    let mut fresh: Vec<u32> = Vec::new();
    let mut seen: HashSet<u64> = HashSet::new();
    let mut per_cell = vec![0u8; cells];
    for _ in 0..depth {
        if nodes[0].left == 0 {
            break;
        }
        children.clear();
        for (i, node) in nodes.iter().enumerate() {
            if node.left == 0 {
                continue;
            }
            for m in Move::ALL {
                let q = torus.step(node.pos, m);
                fresh.clear();
                let (mut gain, mut count, mut key) = (0.0, 0, node.key);
                for c in sensor.around(q) {
                    if !covered(&arena, node.bits, c) && mass[c as usize] > 0.0 {
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
                        rest_bound(torus, mass, &heavy, front, reach, q, r, |c| {
                            covered(&arena, node.bits, c) || fresh.contains(&c)
                        })
                    };
                children.push(Child {
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
        children.sort_by(|a, b| a.rank.total_cmp(&b.rank).then(a.key.cmp(&b.key)));
        seen.clear();
        next_nodes.clear();
        next_arena.clear();
        for ch in &children {
            if next_nodes.len() == width {
                break;
            }
            if per_cell[ch.cell as usize] >= PER_CELL || !seen.insert(ch.key) {
                continue;
            }
            per_cell[ch.cell as usize] += 1;
            let parent = nodes[ch.parent];
            let at = next_arena.len();
            next_arena.extend_from_slice(&arena[parent.bits..parent.bits + words]);
            for c in sensor.around(ch.cell) {
                next_arena[at + c as usize / 64] |= 1 << (c % 64);
            }
            hist.push((parent.hist, ch.cell));
            next_nodes.push(Node {
                pos: ch.cell,
                cost: ch.cost,
                left_mass: ch.left_mass,
                left: ch.left,
                key: ch.key ^ zobrist_pos(ch.cell),
                bits: at,
                hist: hist.len() - 1,
            });
        }
        for n in &next_nodes {
            per_cell[n.pos as usize] = 0;
        }
        if next_nodes.is_empty() {
            break;
        }
        std::mem::swap(&mut nodes, &mut next_nodes);
        std::mem::swap(&mut arena, &mut next_arena);
    }
    let mut path = Vec::new();
    let mut h = nodes[0].hist;
    while h != usize::MAX {
        path.push(hist[h].1);
        h = hist[h].0;
    }
    path.reverse();
    path
}

/// The most new cells one move can cover, and the sensor's ℓ1 reach.
fn front_and_reach(sensor: &Sensor) -> (usize, u32) {
    let offsets = sensor.offsets();
    let front = Move::ALL
        .iter()
        .map(|m| {
            let (mx, my) = m.delta();
            offsets
                .iter()
                .filter(|&&(dx, dy)| !offsets.contains(&(dx - mx, dy - my)))
                .count()
        })
        .max()
        .unwrap_or(1)
        .max(1);
    let reach = offsets
        .iter()
        .map(|&(dx, dy)| dx.unsigned_abs() + dy.unsigned_abs())
        .max()
        .unwrap_or(0);
    (front, reach)
}

/// A lower bound on `Σ R` over the moves after reaching `q` with mass `r`
/// left: the larger of the front bound and the distance bound, over the
/// `heavy` cells not `covered` (see the module doc).
#[allow(clippy::too_many_arguments)]
fn rest_bound(
    torus: &Torus,
    mass: &[f64],
    heavy: &[u32],
    front: usize,
    reach: u32,
    q: u32,
    r: f64,
    covered: impl Fn(u32) -> bool,
) -> f64 {
    let (mut by_front, mut by_distance) = (0.0, 0.0);
    let mut rest = r;
    let mut k = 0;
    for &c in heavy {
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
        by_distance += m * torus.l1(q, c).saturating_sub(reach + 1) as f64;
    }
    f64::max(by_front, by_distance)
}

impl Searcher for Beam {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        let done = self.planned && self.next >= self.plan.len();
        let on_plan = self.planned
            && self
                .plan
                .get(self.next)
                .is_some_and(|&c| w.torus.l1(w.pos, c) == 1);
        if !on_plan && !done {
            self.make(w.torus, w.sensor, w.belief, w.pos);
        }
        if let Some(&c) = self.plan.get(self.next) {
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
            true,
        );
        Some(m)
    }

    fn observe(&mut self, _torus: &Torus, m: Move, pos: u32) {
        self.last = Some(m);
        if self.plan.get(self.next) == Some(&pos) {
            self.next += 1;
        } else {
            self.planned = false;
        }
    }

    fn counts<'a>(&'a self, _layer: Layer, _scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        None
    }

    fn decision(&self, _torus: &Torus, _pos: u32) -> Option<DecisionView> {
        None
    }

    fn intent(&self) -> &[u32] {
        &self.plan[self.next.min(self.plan.len())..]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    #[test]
    fn front_and_reach_follow_the_radius() {
        let t = Torus::new(12).unwrap();
        for (rv, front, reach) in [(0.0, 1, 0), (1.0, 3, 1), (1.5, 3, 2), (2.0, 5, 2)] {
            let s = Sensor::new(&t, rv).unwrap();
            assert_eq!(front_and_reach(&s), (front, reach), "rv {rv}");
        }
    }

    #[test]
    fn the_rest_bound_never_exceeds_what_a_path_has_left() {
        // Along a planned path, at every step, the bound on the rest is at
        // most the rest's exact Σ R (with all cells and with only a few
        // heavy ones). Fails if the front were too large or the reach too
        // small.
        for (rv, sigma) in [(1.0, 2.0), (0.0, 1.5), (2.0, 3.0)] {
            let mut cfg = Config::default();
            for (k, v) in [
                ("n", "12"),
                ("searcher", "beam"),
                ("beam_width", "6"),
                ("beam_depth", "20"),
            ] {
                cfg.set(k, v).unwrap();
            }
            cfg.rv = rv;
            cfg.sigma = sigma;
            let g = cfg.game().unwrap();
            let mut ep = crate::episode::Episode::blind(&cfg).unwrap();
            while ep.steps() < 400 {
                ep.step_move();
            }
            let path = ep.path();
            let mass = g.prior.mass();
            let (front, reach) = front_and_reach(&g.sensor);
            let mut heavy: Vec<u32> = (0..g.torus.cells() as u32).collect();
            heavy.sort_by(|&a, &b| mass[b as usize].total_cmp(&mass[a as usize]));
            // R_t along the path.
            let mut covered = vec![false; g.torus.cells()];
            let mut rs = Vec::new();
            let mut left = 1.0;
            for &p in path {
                for c in g.sensor.around(p) {
                    if !std::mem::replace(&mut covered[c as usize], true) {
                        left -= mass[c as usize];
                    }
                }
                rs.push(left.max(0.0));
            }
            covered.iter_mut().for_each(|c| *c = false);
            for (t, &p) in path.iter().enumerate().take(150) {
                for c in g.sensor.around(p) {
                    covered[c as usize] = true;
                }
                let rest: f64 = rs[t + 1..].iter().sum();
                for top in [heavy.len(), 7] {
                    let b =
                        rest_bound(&g.torus, mass, &heavy[..top], front, reach, p, rs[t], |c| {
                            covered[c as usize]
                        });
                    assert!(
                        b <= rest + 1e-9,
                        "rv {rv} t {t} top {top}: bound {b} > rest {rest}"
                    );
                }
            }
        }
    }
}
