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

/// Marks a byte that must be redrawn (a 3-way tie drew 255).
const REDRAW: u8 = 4;

/// `PICK[tied][b]`: the move chosen among the moves whose bits are set in
/// `tied`, by a uniform random byte `b`: the `(b mod k)`-th of the k tied
/// moves, except that a 3-way tie redraws `b = 255` ([`REDRAW`], once in
/// 256), so that each tied move has probability exactly 1/k.
const PICK: [[u8; 256]; 16] = {
    let mut t = [[REDRAW; 256]; 16];
    let mut tied = 1;
    while tied < 16 {
        let k = (tied as u32).count_ones() as usize;
        let mut b = 0;
        while b < 256 {
            if !(k == 3 && b == 255) {
                let nth = b % k;
                // The nth set bit of `tied`.
                let mut seen = 0;
                let mut m = 0;
                while m < 4 {
                    if tied & (1 << m) != 0 {
                        if seen == nth {
                            t[tied][b] = m as u8;
                        }
                        seen += 1;
                    }
                    m += 1;
                }
            }
            b += 1;
        }
        tied += 1;
    }
    t
};

/// NSARW with its own visit counts.
///
/// One word per cell holds `base + visits` for the cells visited in the
/// current walk; anything at most `base` was written by an earlier walk and
/// counts 0. Starting a new walk (every rollout) moves `base` past every
/// value written, which is O(1) instead of clearing N² counters, and the
/// count of a neighbour is one load and a saturating subtraction.
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

    /// The tied least-visited moves from the cell at table offset `p`
    /// (4 × the cell), as a 4-bit mask in move order.
    ///
    /// # Safety
    /// `p + 3 < nbr.len()`, and every entry of `nbr` is 4 × an index of `val`.
    #[inline(always)]
    unsafe fn least(&self, nbr: &[u32], p: usize) -> usize {
        let c = |m: usize| {
            let q = *nbr.get_unchecked(p + m) as usize >> 2;
            (*self.val.get_unchecked(q)).saturating_sub(self.base)
        };
        let (c0, c1, c2, c3) = (c(0), c(1), c(2), c(3));
        let lo = c0.min(c1).min(c2.min(c3));
        (c0 == lo) as usize
            | ((c1 == lo) as usize) << 1
            | ((c2 == lo) as usize) << 2
            | ((c3 == lo) as usize) << 3
    }

    /// A uniformly random move among the least-visited neighbours.
    ///
    /// # Panics
    /// If `cell` or a neighbour is outside the walk's lattice.
    pub fn next_move(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> Move {
        let nbr = torus.neighbours();
        let p = 4 * cell as usize;
        assert!(p + 3 < nbr.len() && self.val.len() >= torus.cells());
        // SAFETY: asserted just above; entries are 4 × a cell < cells().
        let tied = unsafe { self.least(nbr, p) };
        loop {
            let m = PICK[tied][(rng::bits(rng) >> 56) as usize];
            if m != REDRAW {
                return Move::from_index(m as u32);
            }
        }
    }

    /// Walks from `start` until `mask` marks the cell or `cap` moves,
    /// continuing the walk begun by [`Nsarw::begin`].
    ///
    /// The hot loop: the neighbour table, one word per neighbour, the tie
    /// broken by a table and a random byte from a 64-bit draw (redrawn only
    /// on a 3-way tie that drew 255), no allocation.
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
                let tied = self.least(nbr, p);
                let m = loop {
                    if left == 0 {
                        bits = rng::bits(rng);
                        left = 8;
                    }
                    let m = *PICK
                        .get_unchecked(tied)
                        .get_unchecked((bits & 255) as usize);
                    bits >>= 8;
                    left -= 1;
                    if m != REDRAW {
                        break m as usize;
                    }
                };
                p = *nbr.get_unchecked(p + m) as usize;
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
    fn pick_chooses_each_tied_move_equally_often() {
        // Over the 256 bytes (redraws dropped), each tied move comes up
        // equally often and no untied one ever does.
        for (tied, row) in PICK.iter().enumerate().skip(1) {
            let mut n = [0u32; 4];
            for &m in row.iter().filter(|&&m| m != REDRAW) {
                assert!(tied & (1 << m) != 0, "tied {tied:04b} picked {m}");
                n[m as usize] += 1;
            }
            let hits: Vec<u32> = n.iter().copied().filter(|&x| x > 0).collect();
            assert_eq!(
                hits.len(),
                (tied as u32).count_ones() as usize,
                "{tied:04b}"
            );
            assert!(hits.iter().all(|&x| x == hits[0]), "{tied:04b}: {n:?}");
        }
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
        // neighbours of the start are tied, whatever the old walk left.
        let p = 4 * 12;
        assert_eq!(unsafe { w.least(t.neighbours(), p) }, 0b1111);
        let c = |cell: u32| w.val[cell as usize].saturating_sub(w.base);
        assert_eq!(c(12), 1);
        assert_eq!((0..25).map(c).sum::<u32>(), 1);
    }
}
