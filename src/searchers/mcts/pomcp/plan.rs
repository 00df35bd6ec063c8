//! The belief MCTS's plan: the horizon rule's completion that a new plan
//! is made by, and the walk along a plan that rollouts and checked lines
//! follow (`docs/belief-mcts.md`, "The plan").

use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Sensor, Torus};
use crate::searchers::mcts::plan_walk::PlanWalk;
use crate::searchers::planning::completion::{Completion, FarGoal};

/// The share of the posterior left at which a followed plan ends
/// ([`follow_plan`]): each later move would add at most this to the
/// expected time.
pub const PLAN_END: f64 = 1e-12;

/// The share of the posterior below which a plan takes the greedy step
/// ([`Completion::greedy_below`]). Past it the horizon rule spends much
/// of a plan's time on moves that weigh at most this much each in E\[T\]
/// (`EXPERIMENTS.md` has the measurements, `docs/belief-mcts.md` the
/// reasoning).
const GREEDY_TAIL: f64 = 1e-3;

/// The completion a new plan is made by: the horizon rule's from `root`,
/// its far goal compared every move, as the horizon searcher plays, until
/// [`GREEDY_TAIL`] of the posterior is left, then the greedy step.
pub fn plan_maker(belief: &BeliefState, root: u32, cap: u32) -> Completion {
    Completion::new(belief, root, None, cap as usize, FarGoal::Compared)
        .greedy_below(belief.remaining() * GREEDY_TAIL)
}

/// The completion from `root` that a new plan is made by
/// ([`plan_maker`]), up to `cap` moves. It ends once a tenth of
/// [`PLAN_END`] of the posterior is left. A [`follow_plan`] walk never
/// asks for a plan cell past that: by each plan cell it passes it has
/// covered at least what the plan had, and it stops at `PLAN_END` (the
/// factor of ten is far more than the two running sums' rounding). So the
/// plan walked is the one the whole completion would give, and the
/// thinnest of its tail (at N = 40, σ = 2.5, 59 of its 840 moves) is never
/// made.
pub fn first_plan(belief: &BeliefState, root: u32, cap: u32) -> Completion {
    plan_maker(belief, root, cap).ending_at(belief.remaining() * PLAN_END / 10.0)
}

/// Follows `prefix` from `root` (each cell next to the one before), then
/// the plan walk over `plan` until every unsearched cell with planning
/// mass is covered or `cap` moves; writes the cells into `out` and their
/// `R_t` into `rs` (if given) and returns the exact return
/// `1 + Σ_{t≥1} R_t` of that path from the root.
#[allow(clippy::too_many_arguments)]
pub fn follow_plan(
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    mass: f64,
    cap: u32,
    cov: &mut Coverage,
    plan: &[u32],
    root: u32,
    prefix: &[u32],
    out: &mut Vec<u32>,
    mut rs: Option<&mut Vec<f64>>,
) -> f64 {
    cov.clear();
    out.clear();
    if let Some(rs) = rs.as_deref_mut() {
        rs.clear();
    }
    let mut walk = PlanWalk::new();
    let (mut g, mut covered, mut r, mut cell) = (1.0, 0.0, 1.0, root);
    let mut i = 0;
    while r > PLAN_END && (out.len() as u32) < cap {
        let next = match prefix.get(i) {
            Some(&c) => c,
            None => match walk.next_move(torus, sensor, belief, cov, plan, cell) {
                Some(m) => torus.step(cell, m),
                None => break,
            },
        };
        i += 1;
        cell = next;
        covered += cov.cover(sensor, belief, cell);
        r = (1.0 - covered / mass).max(0.0);
        g += r;
        out.push(cell);
        if let Some(rs) = rs.as_deref_mut() {
            rs.push(r);
        }
    }
    cov.clear();
    g
}
