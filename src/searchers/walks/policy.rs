//! Walk policies: each works standalone (one real move per call, through
//! [`super::walker::Walker`]) and as an MCTS rollout (default) policy.

use super::greedy::Greedy;
use super::levy::Levy;
use super::nsarw::Nsarw;
use super::random_walk::RandomWalk;
use super::visit::{Outcome, Visit};
use crate::game::lattice::{Move, Torus};
use crate::game::named::named_enum;
use crate::game::rng::Rng;

named_enum! {
    /// The name of a walk policy.
    pub enum PolicyKind {
        /// Uniform random walk.
        Rw = "rw",
        /// Lévy flight walked as unit moves.
        Levy = "levy",
        /// Nearly self-avoiding random walk.
        Nsarw = "nsarw",
        /// Shortest path toward the (practice) target, random with probability ε.
        Greedy = "greedy",
    }
}

/// A walk policy with its state.
#[derive(Clone, Debug)]
pub enum Policy {
    /// Uniform random walk.
    Rw(RandomWalk),
    /// Lévy flight.
    Levy(Levy),
    /// Nearly self-avoiding random walk.
    Nsarw(Nsarw),
    /// Greedy walk toward a target.
    Greedy(Greedy),
}

impl Policy {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        match self {
            Policy::Rw(_) | Policy::Greedy(_) => 0,
            Policy::Levy(l) => l.heap_bytes(),
            Policy::Nsarw(w) => w.heap_bytes(),
        }
    }

    /// Builds the policy `kind` for lattice `torus`.
    ///
    /// `mu` is the Lévy exponent and `epsilon` the greedy noise; both are
    /// validated by the caller's config.
    pub fn new(kind: PolicyKind, torus: &Torus, mu: f64, epsilon: f64) -> Policy {
        match kind {
            PolicyKind::Rw => Policy::Rw(RandomWalk),
            PolicyKind::Levy => Policy::Levy(Levy::new(mu, torus.n())),
            PolicyKind::Nsarw => Policy::Nsarw(Nsarw::new(torus.cells())),
            PolicyKind::Greedy => Policy::Greedy(Greedy::new(epsilon)),
        }
    }

    /// Forgets the walk's memory and starts afresh at `start`; `target` is
    /// what a greedy walk heads for.
    pub fn begin(&mut self, start: u32, target: u32) {
        match self {
            Policy::Rw(_) => {}
            Policy::Levy(l) => l.begin(),
            Policy::Nsarw(w) => w.begin(start),
            Policy::Greedy(g) => g.begin(target),
        }
    }

    /// One unit move from `cell`.
    pub fn next_move(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> Move {
        match self {
            Policy::Rw(w) => w.next_move(rng),
            Policy::Levy(l) => l.next_move(rng),
            Policy::Nsarw(w) => w.next_move(torus, rng, cell),
            Policy::Greedy(g) => g.next_move(torus, rng, cell),
        }
    }

    /// Tells the walk it entered `cell` (NSARW counts its visits).
    #[inline]
    pub fn observe(&mut self, cell: u32) {
        if let Policy::Nsarw(w) = self {
            w.enter(cell);
        }
    }

    /// Applies [`Policy::next_move`] and returns the new cell, updating memory.
    pub fn advance(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> u32 {
        let m = self.next_move(torus, rng, cell);
        let next = torus.step(cell, m);
        self.observe(next);
        next
    }

    /// Walks from `start` until `mask[cell] != 0` or `cap` moves, after
    /// [`Policy::begin`]. Every entered cell goes to `visit`.
    pub fn rollout<V: Visit>(
        &mut self,
        torus: &Torus,
        mask: &[u8],
        rng: &mut Rng,
        start: u32,
        cap: u32,
        visit: &mut V,
    ) -> Outcome {
        match self {
            Policy::Rw(w) => w.rollout(torus, mask, rng, start, cap, visit),
            Policy::Levy(l) => l.rollout(torus, mask, rng, start, cap, visit),
            Policy::Nsarw(w) => w.rollout(torus, mask, rng, start, cap, visit),
            Policy::Greedy(_) => {
                if mask[start as usize] != 0 {
                    return Outcome {
                        steps: 0,
                        detected: true,
                    };
                }
                let mut cell = start;
                for steps in 1..=cap {
                    cell = self.advance(torus, rng, cell);
                    visit.visit(cell, steps);
                    if mask[cell as usize] != 0 {
                        return Outcome {
                            steps,
                            detected: true,
                        };
                    }
                }
                Outcome {
                    steps: cap,
                    detected: false,
                }
            }
        }
    }

    /// The walk's own per-cell visit counts (NSARW only).
    pub fn counts(&self) -> Option<&[u32]> {
        match self {
            Policy::Nsarw(w) => Some(w.counts()),
            _ => None,
        }
    }
}
