//! The nearly self-avoiding random walk (NSARW): each step chooses uniformly
//! among the neighbours visited the fewest times so far.

use super::{Outcome, Policy, SearcherInfo, Visit, Walker};
use crate::lattice::{Move, Torus};
use crate::rng::{self, Rng};

/// NSARW as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "nsarw",
    label: "NSARW",
    help: "each step goes to a least-visited neighbour, ties broken at random",
    deterministic: false,
    deliberates: false,
    uses: |_, _| false,
    build: |s| {
        Box::new(Walker::new(
            Policy::Nsarw(Nsarw::new(s.torus.cells())),
            s.start,
        ))
    },
};

/// `TIE[k]`: the k-th of the 24 orders of the four moves, each move's rank
/// shifted left by 2 (bits 2–3 of a key). A step takes the least key
/// `visits << 4 | rank << 2 | move`: fewest visits first, ties by a uniform
/// random order, so each of k tied moves is taken with probability exactly
/// 1/k.
const TIE: [[u64; 4]; 24] = {
    let mut t = [[0u64; 4]; 24];
    let mut k = 0;
    let mut a = 0;
    while a < 4 {
        let mut b = 0;
        while b < 4 {
            let mut c = 0;
            while c < 4 {
                // d is the rank left over when a, b, c are distinct.
                if a != b && a != c && b != c {
                    let d = 6 - a - b - c;
                    t[k] = [a << 2, b << 2, c << 2, d << 2];
                    k += 1;
                }
                c += 1;
            }
            b += 1;
        }
        a += 1;
    }
    t
};

/// A uniform index into [`TIE`] from 16 of the random bits in `bits`
/// (`left` draws of 16 bits remain in it; refilled from `rng`): multiply
/// by 24 and keep the top 16 bits, redrawing the 16 of 65 536 values that
/// would make some orders likelier (once in 4096 draws).
#[inline(always)]
fn order(rng: &mut Rng, bits: &mut u64, left: &mut u32) -> usize {
    loop {
        if *left == 0 {
            *bits = rng::bits(rng);
            *left = 4;
        }
        let x = (*bits & 0xffff) * 24;
        *bits >>= 16;
        *left -= 1;
        if x & 0xffff >= 16 {
            return (x >> 16) as usize;
        }
    }
}

/// NSARW with its own visit counts.
///
/// One word per cell holds `base + visits` for the cells visited in the
/// current walk; anything at most `base` was written by an earlier walk and
/// counts 0. Starting a new walk (every rollout) moves `base` past every
/// value written, which is O(1) instead of clearing N² counters, and the
/// count of a neighbour is one load and a `max` with `base`.
#[derive(Clone, Debug)]
pub struct Nsarw {
    val: Vec<u32>,
    base: u32,
    /// The largest value written so far.
    top: u32,
}

impl Nsarw {
    /// A walker for a lattice of `cells` cells.
    pub fn new(cells: usize) -> Nsarw {
        Nsarw {
            val: vec![0; cells],
            base: 0,
            top: 0,
        }
    }

    /// Starts a new walk at `start`, which counts as visited once.
    pub fn begin(&mut self, start: u32) {
        if self.top >= 1 << 31 {
            // Far from overflow still (a walk adds at most its own steps).
            self.val.fill(0);
            self.top = 0;
        }
        self.base = self.top;
        self.enter(start);
    }

    /// Records a visit to `cell`.
    #[inline]
    pub fn enter(&mut self, cell: u32) {
        let v = &mut self.val[cell as usize];
        *v = (*v).max(self.base) + 1;
        self.top = self.top.max(*v);
    }

    /// The move to a least-visited neighbour of the cell at table offset
    /// `p` (4 × the cell), ties broken by the order `TIE[k]`, and the
    /// neighbour's table offset. The neighbours are loaded once: the next
    /// offset is selected from them, not loaded again, which keeps the
    /// walk's chain of dependent loads short.
    ///
    /// # Safety
    /// `p + 3 < nbr.len()`, every entry of `nbr` is 4 × an index of `val`,
    /// and `k < 24`.
    #[inline(always)]
    unsafe fn choose(&self, nbr: &[u32], p: usize, k: usize) -> (usize, usize) {
        let r = TIE.get_unchecked(k);
        let q = [
            *nbr.get_unchecked(p),
            *nbr.get_unchecked(p + 1),
            *nbr.get_unchecked(p + 2),
            *nbr.get_unchecked(p + 3),
        ];
        // Older walks' values (at most `base`) count 0.
        let key = |i: usize| {
            let v = (*self.val.get_unchecked(q[i] as usize >> 2)).max(self.base) as u64;
            v << 4 | r[i] | i as u64
        };
        let m = (key(0).min(key(1)).min(key(2).min(key(3))) & 3) as usize;
        // q[m] by two selects on m's bits, not an indexed load.
        let (low, high) = if m & 1 == 0 {
            (q[0], q[2])
        } else {
            (q[1], q[3])
        };
        (m, (if m & 2 == 0 { low } else { high }) as usize)
    }

    /// A uniformly random move among the least-visited neighbours.
    ///
    /// # Panics
    /// If `cell` or a neighbour is outside the walk's lattice.
    pub fn next_move(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> Move {
        let nbr = torus.neighbours();
        let p = 4 * cell as usize;
        assert!(p + 3 < nbr.len() && self.val.len() >= torus.cells());
        let (mut bits, mut left) = (0, 0);
        let k = order(rng, &mut bits, &mut left);
        // SAFETY: asserted just above; entries are 4 × a cell < cells(); k < 24.
        let (m, _) = unsafe { self.choose(nbr, p, k) };
        Move::from_index(m as u32)
    }

    /// Walks from `start` until `mask` marks the cell or `cap` moves,
    /// continuing the walk begun by [`Nsarw::begin`].
    ///
    /// The hot loop: the neighbour table, one word per neighbour, the tie
    /// broken by a random order of the moves from 16 bits of a 64-bit draw
    /// (off the walk's chain of loads), no allocation.
    ///
    /// # Panics
    /// If `mask` or the counts are shorter than the lattice.
    #[inline]
    pub fn rollout<V: Visit>(
        &mut self,
        torus: &Torus,
        mask: &[u8],
        rng: &mut Rng,
        start: u32,
        cap: u32,
        visit: &mut V,
    ) -> Outcome {
        let nbr = torus.neighbours();
        let cells = torus.cells();
        assert!(mask.len() >= cells && self.val.len() >= cells && (start as usize) < cells);
        if mask[start as usize] != 0 {
            return Outcome {
                steps: 0,
                detected: true,
            };
        }
        let mut p = 4 * start as usize;
        let mut bits = 0u64;
        let mut left = 0u32;
        for steps in 1..=cap {
            // SAFETY: `p / 4` starts in range and every table entry is
            // 4 × a cell index < cells() ≤ mask.len(), val.len() (asserted
            // above), so `p + 3 < nbr.len()` and `p >> 2` indexes both.
            unsafe {
                let k = order(rng, &mut bits, &mut left);
                p = self.choose(nbr, p, k).1;
                core::hint::assert_unchecked(p % 4 == 0);
                let cell = p >> 2;
                let v = self.val.get_unchecked_mut(cell);
                *v = (*v).max(self.base) + 1;
                self.top = self.top.max(*v);
                visit.visit(cell as u32, steps);
                if *mask.get_unchecked(cell) != 0 {
                    return Outcome {
                        steps,
                        detected: true,
                    };
                }
            }
        }
        Outcome {
            steps: cap,
            detected: false,
        }
    }

    /// Per-cell values of the walk, `y * n + x`: the visit counts of the
    /// first walk exactly (a standalone walker walks once); after later
    /// walks, offset by where the current walk's counts start.
    pub fn counts(&self) -> &[u32] {
        &self.val
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_tied_move_leads_equally_many_of_the_orders() {
        // The 24 orders are the permutations, so within any set of tied
        // moves each move ranks first in 24/k of them.
        let mut seen = std::collections::HashSet::new();
        for r in TIE {
            let mut ranks: Vec<u64> = r.iter().map(|x| x >> 2).collect();
            ranks.sort();
            assert_eq!(ranks, [0, 1, 2, 3]);
            assert!(seen.insert(r), "{r:?} twice");
        }
        for tied in 1..16usize {
            let moves: Vec<usize> = (0..4).filter(|m| tied & (1 << m) != 0).collect();
            let mut first = [0; 4];
            for r in TIE {
                first[*moves.iter().min_by_key(|&&m| r[m]).unwrap()] += 1;
            }
            for &m in &moves {
                assert_eq!(first[m], 24 / moves.len(), "{tied:04b}: {first:?}");
            }
        }
    }

    #[test]
    fn orders_are_drawn_uniformly() {
        // Every 16-bit value: each order from exactly 2730, 16 redrawn.
        let mut n = [0u32; 24];
        let mut redrawn = 0;
        for x in 0..=0xffffu64 {
            let y = x * 24;
            if y & 0xffff >= 16 {
                n[(y >> 16) as usize] += 1;
            } else {
                redrawn += 1;
            }
        }
        assert_eq!(n, [2730; 24]);
        assert_eq!(redrawn, 16);
    }

    #[test]
    fn a_new_walk_forgets_the_old_one() {
        let t = Torus::new(5).unwrap();
        let mut w = Nsarw::new(t.cells());
        let mask = vec![0u8; t.cells()];
        let mut r = rng::stream(1, 0);
        w.begin(0);
        w.rollout(&t, &mask, &mut r, 0, 200, &mut crate::searchers::NoVisit);
        w.begin(12);
        // Only the start has been visited in the new walk: all four
        // neighbours of the start are tied, whatever the old walk left, so
        // each is chosen under some order.
        let p = 4 * 12;
        let chosen: std::collections::HashSet<usize> = (0..24)
            .map(|k| unsafe { w.choose(t.neighbours(), p, k) }.0)
            .collect();
        assert_eq!(chosen.len(), 4);
        let c = |cell: u32| w.val[cell as usize].saturating_sub(w.base);
        assert_eq!(c(12), 1);
        assert_eq!((0..25).map(c).sum::<u32>(), 1);
    }
}
