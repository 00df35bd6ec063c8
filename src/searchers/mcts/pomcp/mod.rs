//! The belief MCTS (POMCP-style, beyond the paper): practice targets from
//! the posterior, a tree reused across moves, returns that count the
//! expected steps left exactly, and rollouts along a plan (the horizon
//! rule's completion) that a move leaves only for a line checked exactly
//! to be cheaper. `docs/belief-mcts.md` explains the returns, the scales,
//! the plan and why each choice was made.
//!
//! * [`params`]: its parameters and return scales.
//! * [`plan`]: the plan's completion and the walk along it.
//! * [`count`]: a loop's running count of the expected steps left.
//! * `descent`: a loop's selection, expansion and back-up, and the tree as data.
//! * the tree, its values and a loop's phases are here.

pub mod count;
mod descent;
pub mod node;
pub mod params;
pub mod plan;

use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::searchers::decision::{ChildStat, DecisionView, Planning};
use crate::searchers::mcts::plan_walk::PlanWalk;
use crate::searchers::mcts::uct::argmax_random;
use crate::searchers::mcts::variant::{note_rollout, trace_len, LoopEnv, LoopReport, Stats};
use crate::searchers::phase::PhaseRecord;
use crate::searchers::planning::completion::{Completion, SLICE_WORK};
use crate::searchers::planning::coverage_walk::CoverageWalk;
use crate::searchers::planning::lookahead::Lookahead;
use crate::searchers::planning::plan_cache::{self, PlanKey};
use crate::searchers::tree_export::{TreeError, TreeExport, TreeQuery};
use count::Count;
use node::{Node, NONE};
use params::ReturnScale;
use plan::{first_plan, follow_plan};

/// A rollout is cut only once it has covered this share of the posterior
/// mass the tree path left.
const CUT_SHARE: f64 = 0.05;

/// How deep the intended line is followed, for drawing.
const MAX_INTENT: usize = 64;

/// Below this unsearched planning mass the posterior is the uniform
/// fallback of [`crate::game::belief::BeliefState`], which the planning mass
/// cannot measure: a loop then returns the sampled τ.
const NO_MASS: f64 = 1e-300;

/// The belief MCTS's search tree. The root (node 0) is the searcher's cell.
#[derive(Clone, Debug)]
pub struct BeliefTree {
    nodes: Vec<Node>,
    scratch: Vec<Node>,
    stack: Vec<(u32, u32)>,
    path: Vec<u32>,
    max_nodes: usize,
    selected: [u32; 4],
    scale: ReturnScale,
    exact: f64,
    /// Rollout steps counted exactly before the reference tail stands in.
    depth: u32,
    /// The reference completion from the root: its `R_t` and `Σ_{u>t} R_u`.
    ref_r: Vec<f64>,
    ref_tail: Vec<f64>,
    cov: Coverage,
    walk: CoverageWalk,
    /// Unsearched planning mass when the current returns were measured.
    mass: f64,
    /// The kept subtree's returns still need rescaling to the new belief.
    rescale: bool,
    /// True until the decision's first loop has run.
    fresh: bool,
    intent: Vec<u32>,
    /// The first plan's horizon depth (0: no plan, the coverage walk).
    plan_depth: u32,
    look: Lookahead,
    /// The plan from `plan_at` on: the cells after the root, completing the search.
    plan: Vec<u32>,
    plan_at: usize,
    /// The plan's exact return from the root.
    plan_cost: f64,
    /// Scratch: a completion being checked, and the tree line it starts with.
    cand: Vec<u32>,
    line: Vec<u32>,
    /// The decision's next loop replays the plan.
    replay: bool,
    /// The move [`Stats::conclude`] chose, which keeps the plan valid.
    planned: Option<Move>,
    /// A new plan being made in slices, before the decision's first loop,
    /// and the key it is kept under once made.
    making: Option<(Completion, PlanKey)>,
    /// The loop in flight: its running count, the node reached, the
    /// simulated moves of its tree path, and whether its rollout was cut.
    count: Count,
    node: u32,
    path_t: u32,
    cut: bool,
}

impl BeliefTree {
    /// An empty tree for a lattice of `cells` cells, with at most
    /// `max_nodes` nodes, returns scaled by `scale`, counted exactly until
    /// `exact` of the posterior is left or `depth` rollout steps, and a
    /// first plan by the horizon rule of depth `plan_depth` (0: no plan).
    pub fn new(
        cells: usize,
        max_nodes: u32,
        scale: ReturnScale,
        exact: f64,
        depth: u32,
        plan_depth: u32,
    ) -> BeliefTree {
        BeliefTree {
            nodes: Vec::new(),
            scratch: Vec::new(),
            stack: Vec::new(),
            path: Vec::new(),
            max_nodes: max_nodes.max(super::tree::MIN_MAX_NODES) as usize,
            selected: [0; 4],
            scale,
            exact,
            depth: depth.max(1),
            ref_r: Vec::new(),
            ref_tail: Vec::new(),
            cov: Coverage::new(cells),
            walk: CoverageWalk::randomised(),
            mass: 0.0,
            rescale: false,
            fresh: true,
            intent: Vec::new(),
            plan_depth,
            look: Lookahead::new(plan_depth.max(1)),
            plan: Vec::new(),
            plan_at: 0,
            plan_cost: f64::INFINITY,
            cand: Vec::new(),
            line: Vec::new(),
            replay: false,
            planned: None,
            making: None,
            count: Count::default(),
            node: 0,
            path_t: 0,
            cut: false,
        }
    }

    /// The key a first plan from `root` is kept under for the process
    /// ([`kept`]): the plan is a function of it, so the trials of one
    /// configuration make it once.
    fn plan_key(&self, sensor: &Sensor, belief: &BeliefState, root: u32, cap: u32) -> PlanKey {
        let params = [sensor.radius2(), self.plan_depth.into(), cap.into()];
        PlanKey::new("pomcp", &params, belief, root, None)
    }

    /// True when the plan's next cell is a neighbour of `root` (a real move
    /// that left the plan invalidates it).
    fn plan_holds(&self, torus: &Torus, root: u32) -> bool {
        self.plan_at < self.plan.len() && torus.l1(root, self.plan[self.plan_at]) == 1
    }

    /// True while the searcher holds a plan (rollouts follow it).
    fn follows_plan(&self) -> bool {
        self.plan_depth > 0 && self.plan_at < self.plan.len()
    }

    /// The index in `Move::ALL` of the plan's next move from `cell`, if the
    /// plan's next cell is a neighbour of it.
    fn plan_move(&self, torus: &Torus, cell: u32) -> Option<usize> {
        let next = *self.plan.get(self.plan_at)?;
        torus.move_to(cell, next).map(|m| m as usize)
    }

    /// The value of a node's mean return under the scale, higher is better.
    fn value(&self, n: &Node) -> f64 {
        if n.visits == 0 {
            return 0.0;
        }
        let mean = n.sum / n.visits as f64;
        let root = &self.nodes[0];
        match self.scale {
            ReturnScale::Range => {
                let span = root.hi - root.lo;
                if span > 0.0 {
                    (root.hi - mean) / span
                } else {
                    1.0
                }
            }
            ReturnScale::Best => {
                let span = root.hi - root.lo;
                if span > 0.0 {
                    (root.hi - n.lo) / span
                } else {
                    1.0
                }
            }
            ReturnScale::Left => {
                let left = root.sum / root.visits.max(1) as f64;
                if left > 0.0 {
                    1.0 - mean / left
                } else {
                    0.0
                }
            }
        }
    }

    /// The UCT terms of `child` under `parent`, on the scaled values:
    /// what selection ranks the children by (and the export shows).
    #[inline(always)]
    fn weigh(&self, parent: &Node, child: &Node, c: f64) -> (f64, f64, f64) {
        let v = self.value(child);
        crate::searchers::decision::uct_terms(
            v * child.visits as f64,
            child.visits,
            parent.visits,
            c,
        )
    }

    fn select_child(&self, node: u32, env: &mut LoopEnv<'_>) -> Option<usize> {
        let n = &self.nodes[node as usize];
        let mut values = [0.0; 4];
        let mut valid = [false; 4];
        for i in 0..4 {
            if n.children[i] != NONE {
                let ch = &self.nodes[n.children[i] as usize];
                values[i] = self.weigh(n, ch, env.c).2;
                valid[i] = true;
            }
        }
        argmax_random(values, valid, env.rng)
    }

    /// Maps every kept return onto the belief after the real move:
    /// G ↦ (G − 1)·M/M′.
    fn rescale_to(&mut self, mass: f64) {
        let k = self.mass / mass;
        for n in &mut self.nodes {
            n.sum = (n.sum - n.visits as f64) * k;
            if n.visits > 0 {
                n.lo = (n.lo - 1.0) * k;
                n.hi = (n.hi - 1.0) * k;
            }
        }
    }

    /// Completes the search from the root with the coverage walk and keeps
    /// its `R_t` profile: a rollout cut after `depth` steps with `R` of the
    /// posterior left is charged what the reference still spent from the
    /// point where it had `R` left, scaled to `R`.
    fn reference(&mut self, env: &mut LoopEnv<'_>, mass: f64) {
        self.ref_r.clear();
        self.ref_tail.clear();
        if mass <= NO_MASS {
            return;
        }
        let (belief, sensor) = (env.belief, env.sensor);
        if self.plan_depth > 0 {
            self.plan_reference(env, mass);
            if self.follows_plan() {
                self.tails();
                return;
            }
        }
        self.cov.clear();
        self.walk.begin_rollout();
        let mut cell = self.nodes[0].cell;
        let mut covered = 0.0;
        let mut r = 1.0;
        while r > 1e-12 && (self.ref_r.len() as u32) < env.rollout_cap {
            let m = self
                .walk
                .next_random(env.torus, sensor, belief, &self.cov, env.rng, cell);
            cell = env.torus.step(cell, m);
            covered += self.cov.cover(sensor, belief, cell);
            r = 1.0 - covered / mass;
            self.ref_r.push(r.max(0.0));
        }
        self.cov.clear();
        self.tails();
    }

    /// `ref_tail` from `ref_r`.
    fn tails(&mut self) {
        self.ref_tail.clear();
        self.ref_tail.resize(self.ref_r.len(), 0.0);
        let mut acc = 0.0;
        for i in (0..self.ref_r.len()).rev() {
            self.ref_tail[i] = acc;
            acc += self.ref_r[i];
        }
    }

    /// Makes the plan the reference: rebuilds it by the horizon rule when
    /// the last real move left it (or there is none yet), then follows it
    /// from the root with the plan walk, which becomes the plan, and keeps
    /// its `R_t` and exact return.
    fn plan_reference(&mut self, env: &mut LoopEnv<'_>, mass: f64) {
        let root = self.nodes[0].cell;
        let (torus, sensor, belief) = (env.torus, env.sensor, env.belief);
        if !self.plan_holds(torus, root) {
            self.cov.clear();
            self.plan.clear();
            let key = self.plan_key(sensor, belief, root, env.rollout_cap);
            if let Some(plan) = plan_cache::recall(&key) {
                self.plan = plan;
            } else {
                let mut run = first_plan(belief, root, env.rollout_cap);
                let (look, cov, plan) = (&mut self.look, &mut self.cov, &mut self.plan);
                while !run.moves(look, torus, sensor, belief, cov, plan, u64::MAX) {}
                plan_cache::keep(key, &self.plan);
            }
            self.plan_at = 0;
        }
        self.plan_cost = follow_plan(
            torus,
            sensor,
            belief,
            mass,
            env.rollout_cap,
            &mut self.cov,
            &self.plan[self.plan_at..],
            root,
            &[],
            &mut self.cand,
            Some(&mut self.ref_r),
        );
        std::mem::swap(&mut self.plan, &mut self.cand);
        self.plan_at = 0;
        self.replay = self.follows_plan();
    }

    /// The best line below root child `i`: its cell, then the child with
    /// the lowest return found, while there is one.
    fn best_line(&self, i: usize, out: &mut Vec<u32>) {
        out.clear();
        let mut k = self.nodes[0].children[i];
        while k != NONE && self.nodes[k as usize].visits > 0 {
            let n = &self.nodes[k as usize];
            out.push(n.cell);
            k = n
                .children
                .iter()
                .copied()
                .filter(|&c| c != NONE && self.nodes[c as usize].visits > 0)
                .min_by(|&a, &b| {
                    self.nodes[a as usize]
                        .lo
                        .total_cmp(&self.nodes[b as usize].lo)
                })
                .unwrap_or(NONE);
        }
    }

    /// The reference's estimate of `Σ_{u>t} R_u` after a cut with `r` left.
    fn tail(&self, r: f64) -> f64 {
        // R_t only decreases along the reference: the first t with R_t ≤ r.
        let i = self.ref_r.partition_point(|&x| x > r);
        match self.ref_r.get(i) {
            Some(&ri) if ri > 0.0 => self.ref_tail[i] * r / ri,
            _ => 0.0,
        }
    }

    /// Follows the most visited child from the root (the line the tree
    /// would play if nothing changed), for drawing.
    fn update_intent(&mut self) {
        self.intent.clear();
        let mut node = 0usize;
        while self.intent.len() < MAX_INTENT {
            let kids = self.nodes[node].children;
            let best = kids
                .iter()
                .filter(|&&k| k != NONE)
                .max_by_key(|&&k| self.nodes[k as usize].visits);
            match best {
                Some(&k) if self.nodes[k as usize].visits > 0 => {
                    node = k as usize;
                    self.intent.push(self.nodes[node].cell);
                }
                _ => break,
            }
        }
    }
}

impl BeliefTree {
    /// Starts a loop from the root: the decision's first loop rescales the
    /// kept returns and makes the reference tail.
    fn begin_loop(&mut self, env: &mut LoopEnv<'_>) -> Count {
        let belief = env.belief;
        let mass = belief.remaining();
        if self.fresh {
            self.fresh = false;
            if self.rescale && mass > NO_MASS && self.mass > NO_MASS {
                self.rescale_to(mass);
            }
            self.rescale = false;
            self.mass = mass;
            self.walk.begin_decision(belief);
            self.reference(env, mass);
        }
        // A belief without planning mass left counts nothing exactly.
        let rho = if mass > NO_MASS {
            self.exact.max(1e-12)
        } else {
            f64::INFINITY
        };
        let exact = 1.0 > rho; // R_0 = 1
        self.cov.clear();
        self.path.clear();
        self.path.push(0);
        let cell = self.nodes[0].cell;
        if let Some(tr) = env.trace.as_deref_mut() {
            tr.clear();
            tr.push(cell);
        }
        Count {
            mass,
            rho,
            g: if exact { 1.0 } else { 0.0 },
            exact,
            h: 0,
            covered: 0.0,
            tau: None,
            t: 0,
            cell,
        }
    }

    /// The rollout, along the plan or by the coverage walk; returns true
    /// when it was cut and its tail charged from the reference. It may be
    /// cut once it has covered [`CUT_SHARE`] of what the tree left: before
    /// that, every rollout would be charged the same reference tail, and
    /// the returns would not tell moves apart (all of them, with a delta
    /// prior far away).
    fn roll_out_count(&mut self, env: &mut LoopEnv<'_>, count: &mut Count) -> bool {
        let (belief, sensor) = (env.belief, env.sensor);
        let depth = count.t;
        self.walk.begin_rollout();
        let mut pwalk = PlanWalk::new();
        let planning = self.follows_plan();
        let replay = std::mem::take(&mut self.replay);
        let cut_below = 1.0 - (1.0 - CUT_SHARE) * (1.0 - count.covered / count.mass);
        while !count.done() && count.t - depth < env.rollout_cap {
            if count.exact
                && !replay
                && count.t - depth >= self.depth
                && count.covered / count.mass >= cut_below
            {
                count.g += self.tail(1.0 - count.covered / count.mass);
                count.exact = false;
                return true;
            }
            let cell = count.cell;
            let planned = if planning {
                let plan = &self.plan[self.plan_at..];
                pwalk.next_move(env.torus, sensor, belief, &self.cov, plan, cell)
            } else {
                None
            };
            let m = match planned {
                Some(m) => m,
                None => self
                    .walk
                    .next_random(env.torus, sensor, belief, &self.cov, env.rng, cell),
            };
            count.advance_to(env, &mut self.cov, env.torus.step(cell, m));
        }
        false
    }
}

impl Stats for BeliefTree {
    const POSTERIOR_TARGETS: bool = true;

    /// Starts a decision at `root`, keeping the reused subtree when it is rooted there.
    fn begin_decision(&mut self, _torus: &Torus, root: u32, _reset: bool) {
        if self.nodes.first().map(|n| n.cell) != Some(root) {
            self.nodes.clear();
            self.nodes.push(Node::leaf(root));
            self.rescale = false;
        }
        self.selected = [0; 4];
        self.fresh = true;
    }

    /// Makes the plan the decision's first loop would make (when the last
    /// real move left it), in slices: [`Stats::iterate`] then finds it
    /// valid and keeps it, so the plan is the one made at once.
    fn prepare(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        root: u32,
        cap: u32,
    ) -> bool {
        if self.making.is_none() {
            // The conditions under which `reference` makes a new plan.
            let holds = self.plan_holds(torus, root);
            if !self.fresh || self.plan_depth == 0 || belief.remaining() <= NO_MASS || holds {
                return true;
            }
            self.cov.clear();
            self.plan.clear();
            self.plan_at = 0;
            let key = self.plan_key(sensor, belief, root, cap);
            if let Some(plan) = plan_cache::recall(&key) {
                self.plan = plan;
                return true;
            }
            self.making = Some((first_plan(belief, root, cap), key));
        }
        let (run, _) = self.making.as_mut().expect("a plan is being made");
        let (look, cov, plan) = (&mut self.look, &mut self.cov, &mut self.plan);
        if run.moves(look, torus, sensor, belief, cov, plan, SLICE_WORK) {
            let (_, key) = self.making.take().expect("the plan just made");
            plan_cache::keep(key, &self.plan);
            return true;
        }
        false
    }

    fn holds_plan(&self) -> bool {
        self.follows_plan()
    }

    fn planning(&self) -> Option<Planning> {
        let (run, _) = self.making.as_ref()?;
        Some(Planning::plan(
            "the horizon rule's plan, moves",
            run.made() as u32,
            0,
        ))
    }

    fn visits<'a>(&'a self, cells: usize, scratch: &'a mut Vec<u32>) -> &'a [u32] {
        scratch.resize(cells, 0);
        scratch.fill(0);
        for n in &self.nodes {
            scratch[n.cell as usize] = scratch[n.cell as usize].saturating_add(n.visits);
        }
        scratch
    }

    /// The root's children, with the scaled value as each one's mean.
    fn view(&self, torus: &Torus, root_cell: u32, c: f64) -> DecisionView {
        let root = self.nodes.first().copied().unwrap_or(Node::leaf(root_cell));
        let children = std::array::from_fn(|i| {
            let cell = torus.step(root.cell, Move::ALL[i]);
            let (v, q) = match root.children[i] {
                NONE => (0, 0.0),
                k => {
                    let n = &self.nodes[k as usize];
                    (n.visits, self.value(n) * n.visits as f64)
                }
            };
            ChildStat::new(cell, v, q, root.visits, c, self.selected[i])
        });
        DecisionView {
            parent_visits: root.visits,
            c,
            children,
        }
    }

    /// Selection: the loop starts (the decision's first also rescales
    /// the kept returns and makes the reference), then descends by UCT.
    ///
    /// # Panics
    /// If called before [`Stats::begin_decision`].
    fn select(&mut self, env: &mut LoopEnv<'_>, _root: u32, rec: Option<&mut PhaseRecord>) {
        let mut count = self.begin_loop(env);
        self.descend(env, &mut count, rec);
        self.count = count;
    }

    fn expand(&mut self, env: &mut LoopEnv<'_>, _root: u32, rec: Option<&mut PhaseRecord>) {
        let mut count = self.count;
        self.grow(env, &mut count, rec);
        self.path_t = count.t;
        self.count = count;
    }

    /// The rollout, along the plan or by the coverage walk.
    fn roll_out(&mut self, env: &mut LoopEnv<'_>, _root: u32, rec: Option<&mut PhaseRecord>) {
        let mut count = self.count;
        let from = trace_len(env);
        self.cut = self.roll_out_count(env, &mut count);
        self.count = count;
        if let Some(r) = rec {
            note_rollout(
                Some(&mut *r),
                from,
                count.t - self.path_t,
                count.tau.is_some(),
            );
            r.cut = self.cut;
            r.truncated = !self.cut && count.tau.is_none();
        }
    }

    /// Backpropagation of the return: its sampled tail added unless the
    /// rollout was cut (the reference charged it) or counted exactly.
    fn back_up(
        &mut self,
        _env: &mut LoopEnv<'_>,
        _root: u32,
        rec: Option<&mut PhaseRecord>,
    ) -> LoopReport {
        let mut count = self.count;
        let steps = count.t - self.path_t;
        if !count.exact && !self.cut {
            // The sampled tail: 1{τ > H}·(τ − H), or what a truncated
            // rollout saw of it.
            count.g += (count.tau.unwrap_or(count.t).max(count.h) - count.h) as f64;
        }
        self.credit(count.g, rec);
        LoopReport {
            rollout_steps: steps,
            detected: count.tau.is_some(),
            reward: count.g,
            counts: true,
        }
    }

    fn tree(
        &self,
        _torus: &Torus,
        _root: u32,
        c: f64,
        q: &TreeQuery,
    ) -> Result<TreeExport, TreeError> {
        self.export(c, q)
    }

    fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.nodes[..])
            + size_of_val(&self.path[..])
            + size_of_val(&self.ref_r[..])
            + size_of_val(&self.ref_tail[..])
            + self.cov.heap_bytes()
            + size_of_val(&self.intent[..])
            + size_of_val(&self.plan[..])
            + size_of_val(&self.cand[..])
            + size_of_val(&self.line[..])
    }

    /// Re-roots the tree at the child reached by `m`, keeping its subtree;
    /// its returns are rescaled to the new belief at the next loop.
    fn advance(&mut self, m: Move) {
        if self.planned.take() == Some(m) {
            self.plan_at += 1;
        } else {
            self.plan.clear();
            self.plan_at = 0;
        }
        let Some(root) = self.nodes.first() else {
            return;
        };
        let keep = root.children[m as usize];
        if keep == NONE {
            self.nodes.clear();
            self.intent.clear();
            return;
        }
        super::tree::reroot(
            &mut self.nodes,
            &mut self.scratch,
            &mut self.stack,
            keep,
            |n| &mut n.children,
        );
        self.rescale = true;
        // A kept root's best return may be a checked one, above what its
        // children's loops saw: the root's range must hold theirs.
        let root = self.nodes[0];
        for k in root.children.into_iter().filter(|&k| k != NONE) {
            let n = self.nodes[k as usize];
            if n.visits > 0 {
                self.nodes[0].lo = self.nodes[0].lo.min(n.lo);
                self.nodes[0].hi = self.nodes[0].hi.max(n.hi);
            }
        }
        self.update_intent();
    }

    fn intent(&self) -> &[u32] {
        if self.follows_plan() {
            let plan = &self.plan[self.plan_at..];
            &plan[..plan.len().min(MAX_INTENT)]
        } else {
            &self.intent
        }
    }

    /// With a plan: checks the best line below each root child whose best
    /// return beats the plan's by completing it with the plan walk and
    /// counting its return exactly, adopts the cheapest path as the plan,
    /// and plays its first move. A checked child's best return becomes its
    /// exact one, so under `best` the decision panel leads with the move played.
    fn conclude(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cap: u32,
    ) -> Option<Move> {
        let mass = belief.remaining();
        if !self.follows_plan() || self.nodes.is_empty() || mass <= NO_MASS {
            return None;
        }
        let root = self.nodes[0].cell;
        let on_plan = self.plan_move(torus, root)?;
        let lo = |t: &BeliefTree, i: usize| match t.nodes[0].children[i] {
            NONE => f64::INFINITY,
            k if t.nodes[k as usize].visits == 0 => f64::INFINITY,
            k => t.nodes[k as usize].lo,
        };
        let mut order = [0, 1, 2, 3];
        order.sort_by(|&a, &b| lo(self, a).total_cmp(&lo(self, b)));
        let (mut best, mut chosen, mut adopted) = (self.plan_cost, on_plan, false);
        let mut line = std::mem::take(&mut self.line);
        for i in order {
            let l = lo(self, i);
            if !(l < best || (l == best && i != chosen && l.is_finite())) {
                continue;
            }
            self.best_line(i, &mut line);
            let cost = follow_plan(
                torus,
                sensor,
                belief,
                mass,
                cap,
                &mut self.cov,
                &self.plan[self.plan_at..],
                root,
                &line,
                &mut self.cand,
                None,
            );
            let k = self.nodes[0].children[i] as usize;
            self.nodes[k].lo = if i == on_plan {
                cost.min(self.plan_cost)
            } else {
                cost
            };
            // A checked return is one seen through the root: values stay in [0, 1].
            self.nodes[0].hi = self.nodes[0].hi.max(cost);
            if cost < best {
                best = cost;
                chosen = i;
                adopted = true;
                std::mem::swap(&mut self.cand, &mut self.plan);
                self.plan_at = 0;
            }
        }
        self.line = line;
        if adopted {
            self.plan_cost = best;
        }
        let k = self.nodes[0].children[chosen];
        if k != NONE {
            let n = &mut self.nodes[k as usize];
            n.lo = n.lo.min(best);
        }
        let floor = (0..4).map(|i| lo(self, i)).fold(f64::INFINITY, f64::min);
        if floor.is_finite() {
            self.nodes[0].lo = floor;
        }
        self.planned = Some(Move::ALL[chosen]);
        self.planned
    }
}

#[cfg(test)]
mod tests;
