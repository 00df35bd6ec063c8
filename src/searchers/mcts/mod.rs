//! UCT Monte Carlo Tree Search: shared selection maths and the two variants.
//!
//! * [`cells`] keeps statistics per lattice cell, as the paper and its code do.
//! * [`tree`] keeps a real search tree of move sequences.
//! * [`code`] keeps the per-cell statistics of the authors' MATLAB code.
//! * [`pomcp`] plans on the belief (POMCP-style): posterior practice
//!   targets, a reused tree, returns that suit UCT, [`coverage_walk`] rollouts.

pub mod cells;
pub mod code;
pub mod coverage_walk;
pub mod plan_walk;
pub mod pomcp;
pub mod tree;

use crate::config::Config;
use crate::display::view::Layer;
use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::Sensor;
use crate::game::lattice::{Move, Torus};
use crate::game::named::named_enum;
use crate::game::rng::{self, Rng};
use crate::searchers::plan::{fallback_target, toward, FarScan};
use crate::searchers::{Outcome, Planning, Policy, Searcher, SearcherInfo, Setup, Visit, World};
use cells::CellTable;
use code::CodeTable;
use pomcp::BeliefTree;
use tree::Tree;

/// MCTS as a searcher: the variant (`cells` or `tree`) keeps the statistics.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "mcts",
    label: "MCTS",
    help: "before each move it runs L loops: a practice target from the belief, UCT selection, a rollout, backpropagation",
    deterministic: false,
    deliberates: true,
    uses: |c, key| {
        // The belief MCTS always plans on the posterior with its own rollout.
        let pomcp = c.variant == Variant::Pomcp;
        match key {
            "variant" | "ms" | "c" | "rollout_cap" | "keep_traces" => true,
            "final" => !pomcp,
            "rollout" | "belief" => !pomcp,
            "loops" => c.ms.is_none(),
            "reset_each_move" => c.variant != Variant::Tree && !pomcp,
            "tree_nodes" => c.variant == Variant::Tree || pomcp,
            "pomcp_scale" | "pomcp_exact" | "pomcp_depth" | "pomcp_plan" => pomcp,
            "decay" => c.variant == Variant::Cells,
            "escape" => true,
            "mu" => !pomcp && c.rollout == crate::searchers::PolicyKind::Levy,
            "epsilon" => !pomcp && c.rollout == crate::searchers::PolicyKind::Greedy,
            _ => false,
        }
    },
    build: |s| match s.cfg.variant {
        Variant::Cells => Box::new(Mcts::new(
            CellTable::with_decay(s.torus.cells(), s.cfg.decay),
            s,
        )),
        Variant::Tree => Box::new(Mcts::new(Tree::new(s.cfg.tree_nodes), s)),
        Variant::Code => Box::new(Mcts::new(CodeTable::new(s.torus.cells()), s)),
        Variant::Pomcp => Box::new(Mcts::new(
            BeliefTree::new(
                s.torus.cells(),
                s.cfg.tree_nodes,
                s.cfg.pomcp_scale,
                s.cfg.pomcp_exact,
                s.cfg.pomcp_depth,
                s.cfg.pomcp_plan,
            ),
            s,
        )),
    },
};

named_enum! {
    /// Which MCTS variant.
    pub enum Variant {
        /// Per-cell statistics, depth-1 selection (the paper).
        Cells = "cells",
        /// A search tree of move sequences with subtree reuse.
        Tree = "tree",
        /// The statistics of the authors' `MCTSgaussian.m` (the `paper-code` preset).
        Code = "code",
        /// A belief MCTS (POMCP-style): posterior practice targets, a reused
        /// tree, range-scaled expected-time returns, coverage-walk rollouts.
        Pomcp = "pomcp",
    }
}

named_enum! {
    /// How the real move is chosen once a decision's loops are done.
    pub enum FinalRule {
        /// The child selected most often in this decision (robust child).
        Visits = "visits",
        /// The child with the best mean reward.
        Mean = "mean",
        /// The child with the best UCT value (the paper's Gaussian code).
        Uct = "uct",
    }
}

/// The statistics of one of the four moves at the decision under way.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ChildStat {
    /// The cell the move leads to.
    pub cell: u32,
    /// N(v_i): visits of the child.
    pub visits: u32,
    /// Q(v_i): summed reward 1/τ.
    pub reward: f64,
    /// Q/N, the exploitation term (0 when unvisited).
    pub mean: f64,
    /// c·sqrt(ln N_parent / N_child), the exploration term (∞ when unvisited).
    pub explore: f64,
    /// mean + explore.
    pub uct: f64,
    /// Times this move was selected in the current decision.
    pub selected: u32,
}

impl ChildStat {
    /// The statistics of a child with `visits` and summed `reward` under a
    /// parent with `parent_visits`, selected `selected` times this decision.
    pub fn new(
        cell: u32,
        visits: u32,
        reward: f64,
        parent_visits: u32,
        c: f64,
        selected: u32,
    ) -> ChildStat {
        let (mean, explore, uct) = uct_terms(reward, visits, parent_visits, c);
        ChildStat {
            cell,
            visits,
            reward,
            mean,
            explore,
            uct,
            selected,
        }
    }
}

/// A snapshot of the decision under way.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct DecisionView {
    /// N(v): visits of the parent (the searcher's cell or the root node).
    pub parent_visits: u32,
    /// The exploration constant.
    pub c: f64,
    /// Per move, in `Move::ALL` order (up, right, down, left).
    pub children: [ChildStat; 4],
}

/// The UCT terms `(mean, explore, uct)` of a child.
#[inline]
pub fn uct_terms(reward: f64, visits: u32, parent_visits: u32, c: f64) -> (f64, f64, f64) {
    if visits == 0 {
        return (0.0, f64::INFINITY, f64::INFINITY);
    }
    let mean = reward / visits as f64;
    let lnp = libm::log(parent_visits.max(1) as f64);
    let explore = c * libm::sqrt(lnp / visits as f64);
    (mean, explore, mean + explore)
}

/// The index of the largest valid value, ties broken uniformly at random.
/// Returns `None` when nothing is valid.
pub fn argmax_random(values: [f64; 4], valid: [bool; 4], rng: &mut Rng) -> Option<usize> {
    let mut best = f64::NEG_INFINITY;
    let mut ties = [0usize; 4];
    let mut k = 0;
    for i in 0..4 {
        if !valid[i] {
            continue;
        }
        let v = values[i];
        if k == 0 || v > best {
            best = v;
            k = 0;
        }
        if v == best {
            ties[k] = i;
            k += 1;
        }
    }
    if k == 0 {
        None
    } else {
        Some(ties[rng::below(rng, k as u32) as usize])
    }
}

/// What `rule` ranks the children by. An unvisited child has no evidence
/// of its mean: it ranks below every visited one.
fn final_values(view: &DecisionView, rule: FinalRule) -> [f64; 4] {
    let ch = &view.children;
    std::array::from_fn(|i| match rule {
        FinalRule::Visits => ch[i].selected as f64,
        FinalRule::Mean => {
            if ch[i].visits == 0 {
                -1.0
            } else {
                ch[i].mean
            }
        }
        FinalRule::Uct => ch[i].uct,
    })
}

/// The final move under `rule` from the children's statistics (ties at random).
pub fn final_move(view: &DecisionView, rule: FinalRule, rng: &mut Rng) -> Move {
    let values = final_values(view, rule);
    Move::from_index(argmax_random(values, [true; 4], rng).unwrap_or(0) as u32)
}

/// The moves [`final_move`] would choose among if the decision ended now:
/// one, or several tied (it then picks one of them at random).
pub fn leading(view: &DecisionView, rule: FinalRule) -> [bool; 4] {
    let values = final_values(view, rule);
    let best = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    values.map(|v| v == best)
}

/// A variant's statistics: what [`Mcts`] needs from `cells` and `tree`.
pub trait Stats {
    /// True when practice targets come from the posterior whatever the
    /// `belief` parameter says.
    const POSTERIOR_TARGETS: bool = false;
    /// Starts a decision at `root`; `reset` clears persistent statistics.
    fn begin_decision(&mut self, root: u32, reset: bool);
    /// One loop from `root`: select, roll out, backpropagate.
    fn iterate(&mut self, env: &mut LoopEnv<'_>, root: u32) -> LoopReport;
    /// The decision statistics at `root`.
    fn view(&self, torus: &Torus, root: u32, c: f64) -> DecisionView;
    /// The real move `m` was made (a tree keeps that subtree).
    fn advance(&mut self, m: Move);
    /// Visit counts per cell of a lattice of `cells` cells (`scratch` is
    /// room to project a tree into).
    fn visits<'a>(&'a self, cells: usize, scratch: &'a mut Vec<u32>) -> &'a [u32];
    /// The belief changed since the last decision (a move searched new
    /// cells): statistics gathered for the old belief are now stale.
    fn belief_changed(&mut self) {}
    /// The cells the statistics mean to enter next (see [`Searcher::intent`]).
    fn intent(&self) -> &[u32] {
        &[]
    }
    /// Work a decision does before its first loop, a slice at a time
    /// (the belief MCTS makes its plan): does a slice and returns false
    /// while some is left, true once the loops can run. It draws no random
    /// numbers, so where the slices fall changes nothing.
    fn prepare(
        &mut self,
        _torus: &Torus,
        _sensor: &Sensor,
        _belief: &BeliefState,
        _root: u32,
        _cap: u32,
    ) -> bool {
        true
    }
    /// How far the work of [`Stats::prepare`] has got, while some is left.
    fn planning(&self) -> Option<Planning> {
        None
    }
    /// True while the statistics follow a plan that completes the search
    /// (the belief MCTS's): such a searcher cannot be trapped, so the
    /// escape must not walk it off the plan.
    fn holds_plan(&self) -> bool {
        false
    }
    /// Ends a decision with the statistics' own choice of move, or `None`
    /// to leave it to the final rule (`cap`: the rollout step cap).
    fn conclude(
        &mut self,
        _torus: &Torus,
        _sensor: &Sensor,
        _belief: &BeliefState,
        _cap: u32,
    ) -> Option<Move> {
        None
    }
}

/// The rule that picks the real move under `cfg`: the `final` parameter,
/// except for the belief MCTS, whose returns are exact expectations of a
/// path it can follow, so it plays the child through which the best one
/// was found (its scaled value, the `mean` rule).
pub fn final_rule(cfg: &Config) -> FinalRule {
    if cfg.variant == Variant::Pomcp {
        FinalRule::Mean
    } else {
        cfg.final_rule
    }
}

/// UCT search with a variant's statistics and a rollout policy.
pub struct Mcts<S: Stats> {
    stats: S,
    policy: Policy,
    c: f64,
    final_rule: FinalRule,
    rollout_cap: u32,
    reset_each_move: bool,
    cells: usize,
    /// The belief's generation at the last decision.
    generation: Option<u64>,
    /// Moves in a row that searched no new cell.
    stalled: u32,
    /// Escape after this many stalled moves (0 = never).
    escape: u32,
    /// The cell an escape is heading for.
    escape_to: Option<u32>,
    /// An empty simulation, for the fallback target's gains.
    coverage: Coverage,
    /// Scratch for the escape's fallback scan.
    scan: FarScan,
}

/// The default `escape`: stalled moves before an MCTS heads for unsearched
/// mass. Ten lets the search work its way out of a searched patch on its own
/// most of the time (a shuttle of 2 or 4 cells is well within it) and bounds
/// how long a trap can last.
pub const DEFAULT_ESCAPE: u32 = 10;

impl<S: Stats> Mcts<S> {
    /// A searcher with these statistics, configured by `setup`.
    pub fn new(stats: S, setup: &Setup<'_>) -> Mcts<S> {
        let cfg = setup.cfg;
        Mcts {
            stats,
            policy: Policy::new(cfg.rollout, setup.torus, cfg.mu, cfg.epsilon),
            c: cfg.c,
            final_rule: final_rule(cfg),
            rollout_cap: cfg.rollout_cap,
            reset_each_move: cfg.reset_each_move,
            cells: setup.torus.cells(),
            generation: None,
            stalled: 0,
            escape: cfg.escape,
            escape_to: None,
            coverage: Coverage::new(setup.torus.cells()),
            scan: FarScan::default(),
        }
    }
}

impl<S: Stats> Searcher for Mcts<S> {
    fn think(&mut self, w: &mut World<'_>, max_loops: u32) -> Option<Move> {
        if !w.budget.is_open() {
            let generation = w.belief.generation();
            if self.generation == Some(generation) {
                self.stalled += 1;
            } else {
                self.stalled = 0;
                self.escape_to = None;
            }
            if self.escape > 0 && self.stalled >= self.escape && !self.stats.holds_plan() {
                // Stuck in searched ground: walk to unsearched mass without
                // deliberating (the target keeps mass until the belief
                // changes, which ends the escape).
                if self.escape_to.is_none() {
                    self.escape_to = fallback_target(
                        w.torus,
                        w.sensor,
                        w.belief,
                        &self.coverage,
                        w.pos,
                        None,
                        &mut self.scan,
                        None,
                    )
                    .map(|(c, _)| c);
                }
                if let Some(target) = self.escape_to {
                    let m = toward(w.torus, w.pos, target, Move::Up);
                    self.generation = Some(generation);
                    self.stats.advance(m);
                    return Some(m);
                }
            }
            w.budget.open();
            if self.generation.is_some_and(|g| g != generation) {
                self.stats.belief_changed();
            }
            self.generation = Some(generation);
            self.stats.begin_decision(w.pos, self.reset_each_move);
        }
        if !self
            .stats
            .prepare(w.torus, w.sensor, w.belief, w.pos, self.rollout_cap)
        {
            return None;
        }
        let mut done = 0;
        while done < max_loops && !w.budget.spent() {
            let practice = if S::POSTERIOR_TARGETS {
                w.belief.posterior_target(w.rng)
            } else {
                w.belief.practice_target(w.rng)
            };
            w.sensor.arm(practice);
            let mut env = LoopEnv {
                torus: w.torus,
                belief: w.belief,
                sensor: w.sensor,
                mask: w.sensor.mask(),
                practice,
                policy: &mut self.policy,
                rng: w.rng,
                rollout_cap: self.rollout_cap,
                c: self.c,
                trace: w.traces.slot(),
            };
            let report = self.stats.iterate(&mut env, w.pos);
            w.traces.commit(practice);
            w.counters.add(report.rollout_steps, report.detected);
            if report.counts {
                w.budget.record(report.rollout_steps, report.detected);
                done += 1;
            }
        }
        if !w.budget.spent() {
            return None;
        }
        let m = match self
            .stats
            .conclude(w.torus, w.sensor, w.belief, self.rollout_cap)
        {
            Some(m) => m,
            None => final_move(
                &self.stats.view(w.torus, w.pos, self.c),
                self.final_rule,
                w.rng,
            ),
        };
        self.stats.advance(m);
        w.budget.close();
        Some(m)
    }

    fn observe(&mut self, _torus: &Torus, _m: Move, _pos: u32) {}

    fn counts<'a>(&'a self, layer: Layer, scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        (layer == Layer::Visits).then(|| self.stats.visits(self.cells, scratch))
    }

    fn decision(&self, torus: &Torus, pos: u32) -> Option<DecisionView> {
        Some(self.stats.view(torus, pos, self.c))
    }

    fn intent(&self) -> &[u32] {
        self.stats.intent()
    }

    fn planning(&self) -> Option<Planning> {
        self.stats.planning()
    }
}

/// What one MCTS loop needs besides the variant's own statistics.
pub struct LoopEnv<'a> {
    /// The lattice.
    pub torus: &'a Torus,
    /// What is known about the target (the belief MCTS plans on it).
    pub belief: &'a BeliefState,
    /// The detection sensor, armed with the practice target.
    pub sensor: &'a Sensor,
    /// Detection mask of the practice target.
    pub mask: &'a [u8],
    /// The practice target.
    pub practice: u32,
    /// The rollout (default) policy.
    pub policy: &'a mut Policy,
    /// The searcher's random stream.
    pub rng: &'a mut Rng,
    /// Rollout step cap.
    pub rollout_cap: u32,
    /// Exploration constant.
    pub c: f64,
    /// Where to record this loop's trace (tree path then rollout), if wanted.
    pub trace: Option<&'a mut Vec<u32>>,
}

/// What one loop did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopReport {
    /// Steps of the rollout proper (after the selected cell/leaf).
    pub rollout_steps: u32,
    /// False when the rollout hit its cap.
    pub detected: bool,
    /// The backpropagated reward.
    pub reward: f64,
    /// False for a rollout that is not one of the decision's loops (the
    /// `code` variant's expansion rollouts): it is counted as a rollout but
    /// not against the loop budget.
    pub counts: bool,
}

/// A visitor that forwards to an optional trace and an inner visitor.
pub(crate) struct Tee<'a, V: Visit> {
    pub inner: V,
    pub trace: Option<&'a mut Vec<u32>>,
}

impl<V: Visit> Visit for Tee<'_, V> {
    #[inline]
    fn visit(&mut self, cell: u32, step: u32) {
        self.inner.visit(cell, step);
        if let Some(t) = self.trace.as_deref_mut() {
            t.push(cell);
        }
    }
}

/// Runs the rollout policy from `from` and returns the outcome.
pub(crate) fn rollout<V: Visit>(env: &mut LoopEnv<'_>, from: u32, visit: &mut V) -> Outcome {
    env.policy.begin(from, env.practice);
    env.policy
        .rollout(env.torus, env.mask, env.rng, from, env.rollout_cap, visit)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn child(visits: u32, reward: f64, parent: u32, selected: u32) -> ChildStat {
        ChildStat::new(0, visits, reward, parent, 1.5, selected)
    }

    #[test]
    fn the_uct_terms_follow_the_formula() {
        // Q/N, c·sqrt(ln N_parent / N), and their sum: what the decision
        // panel shows and what tree and pomcp select by.
        let (mean, explore, uct) = uct_terms(3.0, 4, 20, 1.5);
        assert_eq!(mean, 0.75);
        let want = 1.5 * (20f64.ln() / 4.0).sqrt();
        assert!((explore - want).abs() < 1e-15, "{explore} against {want}");
        assert_eq!(uct, mean + explore);
        // Exploration shrinks as a child is visited and grows with its
        // parent; an unvisited child is tried first; a parent seen at
        // most once gives ln 1 = 0.
        assert!(uct_terms(3.0, 8, 20, 1.5).1 < explore);
        assert!(uct_terms(3.0, 4, 40, 1.5).1 > explore);
        assert_eq!(
            uct_terms(0.0, 0, 20, 1.5),
            (0.0, f64::INFINITY, f64::INFINITY)
        );
        assert_eq!(uct_terms(2.0, 4, 0, 1.5), (0.5, 0.0, 0.5));
        assert_eq!(uct_terms(2.0, 4, 1, 1.5), (0.5, 0.0, 0.5));
        let s = ChildStat::new(7, 4, 3.0, 20, 1.5, 2);
        assert_eq!(
            (s.cell, s.visits, s.reward, s.mean, s.explore, s.uct, s.selected),
            (7, 4, 3.0, mean, explore, uct, 2)
        );
    }

    #[test]
    fn argmax_breaks_ties_uniformly_among_the_valid_moves() {
        let mut rng = rng::stream(11, 0);
        let values = [0.5, 2.0, 2.0, 2.0];
        let valid = [true, true, false, true];
        let mut seen = [0u32; 4];
        let draws = 6000u32;
        for _ in 0..draws {
            seen[argmax_random(values, valid, &mut rng).unwrap()] += 1;
        }
        // Moves 1 and 3 tie among the valid ones: each half the draws,
        // within 4 standard errors of a binomial count (38.7 here).
        assert_eq!((seen[0], seen[2]), (0, 0));
        let se = (f64::from(draws) / 4.0).sqrt();
        for i in [1, 3] {
            let off = (f64::from(seen[i]) - f64::from(draws) / 2.0).abs();
            assert!(off < 4.0 * se, "{seen:?}");
        }
        // A unique maximum always wins, even at -∞ when it is all that is
        // valid, and nothing valid gives no move.
        let neg = f64::NEG_INFINITY;
        assert_eq!(
            argmax_random([1.0, 3.0, 2.0, 0.0], [true; 4], &mut rng),
            Some(1)
        );
        assert_eq!(
            argmax_random([9.0, neg, 9.0, 9.0], [false, true, false, false], &mut rng),
            Some(1)
        );
        assert_eq!(argmax_random([1.0; 4], [false; 4], &mut rng), None);
    }

    #[test]
    fn the_final_rules_rank_the_children_and_leading_names_the_tied_best() {
        // Move 0: selected most; move 1: best mean; move 2: unvisited
        // (best UCT); move 3: visited once with a mean of 0.
        let view = DecisionView {
            parent_visits: 30,
            c: 1.5,
            children: [
                child(20, 2.0, 30, 20),
                child(9, 4.5, 30, 5),
                child(0, 0.0, 30, 0),
                child(1, 0.0, 30, 1),
            ],
        };
        let mut rng = rng::stream(3, 0);
        for (rule, best) in [
            (FinalRule::Visits, Move::ALL[0]),
            (FinalRule::Mean, Move::ALL[1]),
            (FinalRule::Uct, Move::ALL[2]),
        ] {
            assert_eq!(final_move(&view, rule, &mut rng), best, "{rule}");
            let mut lead = [false; 4];
            lead[best as usize] = true;
            assert_eq!(leading(&view, rule), lead, "{rule}");
        }
        // Under `mean` an unvisited child ranks below a visited one whose
        // mean is 0, and equal selections tie.
        let mut cold = view;
        cold.children[1] = child(0, 0.0, 30, 0);
        cold.children[0].reward = 0.0;
        cold.children[0].mean = 0.0;
        assert_eq!(leading(&cold, FinalRule::Mean), [true, false, false, true]);
        cold.children[3].selected = 20;
        assert_eq!(
            leading(&cold, FinalRule::Visits),
            [true, false, false, true]
        );
    }

    #[test]
    fn only_the_belief_mcts_draws_an_intended_path() {
        use crate::config::Config;
        use crate::run::episode::Episode;
        for variant in ["cells", "tree", "code"] {
            let c = Config::default().with(&[("variant", variant), ("loops", "20")]);
            let mut ep = Episode::new(&c).unwrap();
            for _ in 0..3 {
                ep.step_move();
                assert_eq!(ep.intent(), &[] as &[u32], "{variant}");
            }
        }
        let c = Config::default().with(&[("variant", "pomcp"), ("loops", "20")]);
        let mut ep = Episode::new(&c).unwrap();
        ep.step_move();
        assert!(!ep.intent().is_empty());
    }
}
