//! Plans kept for the process.
//!
//! A deterministic planner's plan is a function of the planning mass left,
//! the searcher's cell and last move, and the planner's parameters. Every
//! trial of one configuration starts from the same of these, so a plan kept
//! under them is made once for all the trials a process runs (a batch, a
//! page's next episode), and recalled bit for bit.
//!
//! The last [`KEPT`] plans are kept, and fewer when their keys' masses
//! would hold more than [`KEPT_CELLS`] cells in all (the newest is always
//! kept): at N = 1024 a key's mass is 8 MB.

use super::far_goal::mass_left;
use crate::game::belief::BeliefState;
use crate::game::lattice::Move;
use std::sync::Mutex;

/// Most plans kept. Unit tests run side by side in one process, and a
/// test that recalls a plan must not lose it to the others' plans.
pub const KEPT: usize = if cfg!(test) { 64 } else { 8 };

/// Most cells the kept plans' keys may cover in all (16 MB of masses).
pub const KEPT_CELLS: usize = 1 << 21;

/// What a plan is a function of.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanKey {
    /// The planner, and every parameter its plan depends on.
    maker: &'static str,
    params: Vec<u64>,
    pos: u32,
    last: Option<Move>,
    /// The planning mass of each cell, 0 where searched.
    mass: Vec<f64>,
}

impl PlanKey {
    /// The key of the plan `maker` with `params` would make from `pos`
    /// after `last` over `belief`.
    pub fn new(
        maker: &'static str,
        params: &[u64],
        belief: &BeliefState,
        pos: u32,
        last: Option<Move>,
    ) -> PlanKey {
        PlanKey {
            maker,
            params: params.to_vec(),
            pos,
            last,
            mass: mass_left(belief),
        }
    }

    /// The cell the plan starts from.
    pub fn pos(&self) -> u32 {
        self.pos
    }

    /// The planning mass of each cell the plan is made over, 0 where
    /// searched.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }
}

/// Plans under their keys, newest last.
#[derive(Debug, Default)]
struct Kept {
    plans: Vec<(PlanKey, Vec<u32>)>,
}

impl Kept {
    const fn new() -> Kept {
        Kept { plans: Vec::new() }
    }

    fn recall(&self, key: &PlanKey) -> Option<Vec<u32>> {
        let (_, plan) = self.plans.iter().find(|(k, _)| k == key)?;
        Some(plan.clone())
    }

    fn keep(&mut self, key: PlanKey, plan: &[u32]) {
        let plans = &mut self.plans;
        plans.retain(|(k, _)| *k != key);
        plans.push((key, plan.to_vec()));
        let mut cells: usize = plans.iter().map(|(k, _)| k.mass.len()).sum();
        while plans.len() > KEPT || (plans.len() > 1 && cells > KEPT_CELLS) {
            let (old, _) = plans.remove(0);
            cells -= old.mass.len();
        }
    }
}

/// The process's kept plans.
static PLANS: Mutex<Kept> = Mutex::new(Kept::new());

/// A copy of the plan kept under `key`, if one is.
pub fn recall(key: &PlanKey) -> Option<Vec<u32>> {
    PLANS.lock().unwrap_or_else(|e| e.into_inner()).recall(key)
}

/// Keeps `plan` under `key` as the newest, forgetting the oldest plans
/// beyond [`KEPT`] or [`KEPT_CELLS`].
pub fn keep(key: PlanKey, plan: &[u32]) {
    PLANS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .keep(key, plan);
}

/// Forgets every kept plan of `maker`, so a test makes its plans afresh.
#[cfg(test)]
pub fn forget(maker: &str) {
    PLANS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .plans
        .retain(|(k, _)| k.maker != maker);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::lattice::{Sensor, Torus};
    use crate::game::prior::{PriorSpec, TargetPrior};

    fn belief(n: u32) -> BeliefState {
        let torus = Torus::new(n).unwrap();
        let prior = TargetPrior::new(&torus, &PriorSpec::Uniform).unwrap();
        BeliefState::new(Belief::Posterior, prior, None)
    }

    #[test]
    fn a_plan_is_recalled_only_under_its_own_key_and_the_oldest_go_first() {
        let maker = "kept-test";
        let mut kept = Kept::new();
        let b = belief(6);
        let key = |p: u64, pos: u32| PlanKey::new(maker, &[p], &b, pos, None);
        assert_eq!(kept.recall(&key(1, 0)), None);
        kept.keep(key(1, 0), &[1, 2, 3]);
        assert_eq!(kept.recall(&key(1, 0)), Some(vec![1, 2, 3]));
        // Another parameter, cell, last move or mass is another plan.
        assert_eq!(kept.recall(&key(2, 0)), None);
        assert_eq!(kept.recall(&key(1, 1)), None);
        assert_eq!(
            kept.recall(&PlanKey::new(maker, &[1], &b, 0, Some(Move::Up))),
            None
        );
        let mut searched = belief(6);
        let torus = Torus::new(6).unwrap();
        searched.search_around(&Sensor::new(&torus, 1.0).unwrap(), 7);
        assert_eq!(
            kept.recall(&PlanKey::new(maker, &[1], &searched, 0, None)),
            None
        );
        assert_eq!(kept.recall(&PlanKey::new("other", &[1], &b, 0, None)), None);
        // Kept again, a plan replaces the one under its key.
        kept.keep(key(1, 0), &[4]);
        assert_eq!(kept.recall(&key(1, 0)), Some(vec![4]));
        // Past KEPT plans, the oldest is forgotten first.
        for p in 2..=KEPT as u64 + 1 {
            kept.keep(key(p, 0), &[p as u32]);
        }
        assert_eq!(kept.recall(&key(1, 0)), None);
        assert_eq!(kept.recall(&key(2, 0)), Some(vec![2]));
    }

    #[test]
    fn plans_whose_masses_hold_too_many_cells_are_forgotten_but_the_newest_is_kept() {
        let maker = "kept-test-cells";
        let mut kept = Kept::new();
        // N = 1024: each key's mass is half of KEPT_CELLS.
        let b = belief(1024);
        assert_eq!(2 * b.plan_mass().len(), KEPT_CELLS);
        let key = |p: u64| PlanKey::new(maker, &[p], &b, 0, None);
        for p in 0..3 {
            kept.keep(key(p), &[p as u32]);
            assert!(kept.recall(&key(p)).is_some(), "the newest is kept");
        }
        assert_eq!(kept.recall(&key(0)), None, "three such keys are too many");
        assert!(kept.recall(&key(1)).is_some());
    }
}
