//! The plan walk: the belief MCTS's rollout policy while it holds a plan.
//!
//! A plan is a path that completes the search (the horizon planner's at
//! first, then the best completion the tree has verified). The walk heads,
//! by a shortest torus path, for the plan's first cell whose disc still adds
//! planning mass, so a rollout that left the plan in the tree rejoins it
//! where it is still useful, and a rollout on the plan follows it, skipping
//! the stretches that cover nothing new. A loop's return then measures
//! "this deviation, then the plan", which is what the tree is for: finding
//! where to leave the plan. It is deterministic and allocates nothing.

use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::searchers::planning::far_goal::toward;

/// Where a plan walk is along its plan.
#[derive(Clone, Copy, Debug, Default)]
pub struct PlanWalk {
    /// Every plan cell before this one adds no mass any more.
    next: usize,
}

impl PlanWalk {
    /// A walk at the start of its plan.
    pub fn new() -> PlanWalk {
        PlanWalk::default()
    }

    /// The next move from `pos` toward the first cell of `plan` that still
    /// adds mass over `cov`, or `None` when none does (the plan covered all
    /// it could).
    pub fn next_move(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &Coverage,
        plan: &[u32],
        pos: u32,
    ) -> Option<Move> {
        // A covered plan cell stays covered within a rollout: `next` only moves on.
        while self.next < plan.len() && cov.gain(sensor, belief, plan[self.next]) <= 0.0 {
            self.next += 1;
        }
        let goal = *plan.get(self.next)?;
        Some(toward(torus, pos, goal, Move::Up))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    #[test]
    fn follows_the_plan_skips_what_is_covered_and_stops_at_its_end() {
        let mut c = Config::default();
        c.set("n", "12").unwrap();
        c.set("sigma", "inf").unwrap();
        let g = c.game().unwrap();
        let t = &g.torus;
        let belief = crate::game::belief::BeliefState::new(
            c.settings
                .choice::<crate::game::belief::Belief>(&crate::searchers::mcts::search::BELIEF),
            g.prior.clone(),
            None,
        );
        let mut cov = Coverage::new(t.cells());
        // A plan along row 5 from x = 1 to 6.
        let plan: Vec<u32> = (1..=6).map(|x| t.cell(x, 5)).collect();
        let mut w = PlanWalk::new();
        // From (0, 5) the plan is followed step by step.
        let mut p = t.cell(0, 5);
        cov.cover(&g.sensor, &belief, p);
        for want in &plan[..3] {
            let m = w.next_move(t, &g.sensor, &belief, &cov, &plan, p).unwrap();
            p = t.step(p, m);
            assert_eq!(p, *want);
            cov.cover(&g.sensor, &belief, p);
        }
        // Covering around (4, 5) and (5, 5) from elsewhere leaves only
        // (6, 5)'s far side: the walk skips both and heads for (6, 5).
        for x in 4..=5 {
            for y in 4..=6 {
                cov.cover(&g.sensor, &belief, t.cell(x, y));
            }
        }
        let m = w.next_move(t, &g.sensor, &belief, &cov, &plan, p).unwrap();
        assert_eq!(m, Move::Right);
        assert_eq!(w.next, 5, "(4, 5) and (5, 5) add nothing");
        cov.cover(&g.sensor, &belief, t.cell(7, 5));
        assert_eq!(w.next_move(t, &g.sensor, &belief, &cov, &plan, p), None);
    }
}
