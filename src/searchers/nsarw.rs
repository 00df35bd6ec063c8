//! The nearly self-avoiding random walk (NSARW): each step chooses uniformly
//! among the neighbours visited the fewest times so far.

use super::{Policy, SearcherInfo, Walker};
use crate::lattice::{Move, Torus};
use crate::rng::{self, Rng};

/// NSARW as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "nsarw",
    label: "NSARW",
    help: "each step goes to a least-visited neighbour, ties broken at random",
    deliberates: false,
    uses: |_, _| false,
    build: |s| {
        Box::new(Walker::new(
            Policy::Nsarw(Nsarw::new(s.torus.cells())),
            s.start,
        ))
    },
};

/// NSARW with its own visit counts.
///
/// Counts are epoch-stamped so that starting a new walk (every rollout) is
/// O(1) instead of clearing N² counters.
#[derive(Clone, Debug)]
pub struct Nsarw {
    count: Vec<u32>,
    stamp: Vec<u32>,
    epoch: u32,
}

impl Nsarw {
    /// A walker for a lattice of `cells` cells.
    pub fn new(cells: usize) -> Nsarw {
        Nsarw {
            count: vec![0; cells],
            stamp: vec![0; cells],
            epoch: 0,
        }
    }

    /// Starts a new walk at `start`, which counts as visited once.
    pub fn begin(&mut self, start: u32) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.fill(0);
            self.epoch = 1;
        }
        self.enter(start);
    }

    #[inline]
    fn get(&self, c: u32) -> u32 {
        if self.stamp[c as usize] == self.epoch {
            self.count[c as usize]
        } else {
            0
        }
    }

    /// Records a visit to `cell`.
    #[inline]
    pub fn enter(&mut self, cell: u32) {
        let c = cell as usize;
        if self.stamp[c] != self.epoch {
            self.stamp[c] = self.epoch;
            self.count[c] = 0;
        }
        self.count[c] += 1;
    }

    /// A uniformly random move among the least-visited neighbours.
    pub fn next_move(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> Move {
        let mut best = u32::MAX;
        let mut ties = [0u32; 4];
        let mut k = 0;
        for m in Move::ALL {
            let c = self.get(torus.step(cell, m));
            if c < best {
                best = c;
                k = 0;
            }
            if c == best {
                ties[k] = m as u32;
                k += 1;
            }
        }
        Move::from_index(ties[rng::below(rng, k as u32) as usize])
    }

    /// Visit counts of the current walk, `y * n + x` (cells not visited in
    /// this walk may hold counts of earlier walks unless only one walk ran).
    pub fn counts(&self) -> &[u32] {
        &self.count
    }
}
