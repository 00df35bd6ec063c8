//! A walk used as a searcher: one real move per decision, no deliberation.
//! The random walk, the Lévy flight and NSARW are registered here.

use super::levy::{Levy, MU};
use super::nsarw::Nsarw;
use super::policy::Policy;
use super::random_walk::RandomWalk;
use crate::game::lattice::{Move, Torus};
use crate::game::layer::Layer;
use crate::searchers::info::{Reads, SearcherInfo};
use crate::searchers::searcher::{Searcher, World};

/// The random walk as a searcher.
pub static RW: SearcherInfo = SearcherInfo {
    name: "rw",
    label: "Random walk",
    help: "each step is one of the four moves, uniformly at random",
    deterministic: false,
    deliberates: false,
    params: &[],
    build: |s| Box::new(Walker::new(Policy::Rw(RandomWalk), s.start)),
};

/// The Lévy flight as a searcher.
pub static LEVY: SearcherInfo = SearcherInfo {
    name: "levy",
    label: "Lévy flight",
    help: "it flies a power-law distributed length (exponent mu) in a uniformly random direction, walked as unit moves",
    deterministic: false,
    deliberates: false,
    params: &[Reads::always(&MU)],
    build: |s| {
        Box::new(Walker::new(
            Policy::Levy(Levy::new(s.settings.float(&MU), s.torus.n())),
            s.start,
        ))
    },
};

/// NSARW as a searcher.
pub static NSARW: SearcherInfo = SearcherInfo {
    name: "nsarw",
    label: "NSARW",
    help: "each step goes to a least-visited neighbour, ties broken at random",
    deterministic: false,
    deliberates: false,
    params: &[],
    build: |s| {
        Box::new(Walker::new(
            Policy::Nsarw(Nsarw::new(s.torus.cells())),
            s.start,
        ))
    },
};

/// A walk used as a searcher: one real move per decision, no deliberation.
#[derive(Clone)]
pub struct Walker {
    policy: Policy,
}

impl Walker {
    /// A walker that starts at `start`.
    pub fn new(mut policy: Policy, start: u32) -> Walker {
        // A walk never sees the target: the second argument only steers a
        // greedy walk, which is not a standalone searcher.
        policy.begin(start, start);
        Walker { policy }
    }
}

impl Searcher for Walker {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        Some(self.policy.next_move(w.torus, w.rng, w.pos))
    }

    fn observe(&mut self, _torus: &Torus, _m: Move, pos: u32) {
        self.policy.observe(pos);
    }

    fn counts<'a>(&'a self, layer: Layer, _scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        match layer {
            Layer::Visits | Layer::Walker => self.policy.counts(),
            _ => None,
        }
    }

    fn snapshot(&self) -> Option<Box<dyn Searcher>> {
        Some(Box::new(self.clone()))
    }

    fn heap_bytes(&self) -> usize {
        self.policy.heap_bytes()
    }
}
