//! A loop's running count of the expected steps left, move by move.

use crate::game::coverage::Coverage;
use crate::searchers::mcts::variant::LoopEnv;

/// A loop's running count: the simulated moves so far and what they have
/// covered, the practice target's detection, and the return.
#[derive(Clone, Copy, Debug, Default)]
pub struct Count {
    /// The unsearched planning mass at the decision.
    pub mass: f64,
    /// `R_t ≤ rho` ends the exact count.
    pub rho: f64,
    /// `Σ_{t<H} R_t` so far, plus the tail once counted.
    pub g: f64,
    /// True while `R_t` is counted exactly.
    pub exact: bool,
    /// H, once the exact count ends.
    pub h: u32,
    pub covered: f64,
    /// The practice target's detection time, once detected.
    pub tau: Option<u32>,
    /// Simulated moves made.
    pub t: u32,
    /// The cell reached.
    pub cell: u32,
}

impl Count {
    /// One simulated move to `to`: cover its disc, note the practice
    /// target's detection, count `R_t` while the exact count lasts.
    pub fn advance_to(&mut self, env: &mut LoopEnv<'_>, cov: &mut Coverage, to: u32) {
        self.cell = to;
        self.t += 1;
        self.covered += cov.cover(env.sensor, env.belief, to);
        if self.tau.is_none() && env.mask[to as usize] != 0 {
            self.tau = Some(self.t);
        }
        if self.exact {
            let r = 1.0 - self.covered / self.mass;
            if r <= self.rho {
                self.exact = false;
                self.h = self.t;
            } else {
                self.g += r;
            }
        }
        if let Some(tr) = env.trace.as_deref_mut() {
            tr.push(to);
        }
    }

    /// True once nothing is left to count: the exact count has ended and
    /// the practice target has been detected.
    pub fn done(&self) -> bool {
        !self.exact && self.tau.is_some()
    }
}
