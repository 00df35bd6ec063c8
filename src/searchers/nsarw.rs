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

/// The move to a least-visited of the neighbour cells `q` (in
/// `Move::ALL` order) under visit values `val` and base `base`, ties broken
/// by the order `TIE[k]`. Free of the struct so the hot loop can pass its
/// locals: a store through the walk's own slice then cannot alias the
/// struct's fields, so they stay in registers.
///
/// # Safety
/// Every cell of `q` indexes `val`, and `k < 24`.
#[inline(always)]
unsafe fn choose(val: &[u32], base: u32, q: [u32; 4], k: usize) -> usize {
    let r = TIE.get_unchecked(k);
    // Older walks' values (at most `base`) count 0.
    let key = |i: usize| {
        let v = (*val.get_unchecked(q[i] as usize)).max(base) as u64;
        v << 4 | r[i] | i as u64
    };
    (key(0).min(key(1)).min(key(2).min(key(3))) & 3) as usize
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
    /// At least every value written so far (an upper bound, not the maximum).
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

    /// A uniformly random move among the least-visited neighbours.
    ///
    /// # Panics
    /// If `cell` is outside the walk's lattice, or the walk was made for a
    /// smaller one.
    pub fn next_move(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> Move {
        assert!((cell as usize) < torus.cells() && self.val.len() >= torus.cells());
        let (mut bits, mut left) = (0, 0);
        let k = order(rng, &mut bits, &mut left);
        let at = At::new(torus, cell);
        // SAFETY: asserted just above (neighbours of a cell are cells); k < 24.
        let m = unsafe { choose(&self.val, self.base, at.around(torus.n()).cells(), k) };
        Move::from_index(m as u32)
    }

    /// Walks from `start` until `mask` marks the cell or `cap` moves,
    /// continuing the walk begun by [`Nsarw::begin`].
    ///
    /// The hot loop: the neighbours computed from the column and row by
    /// compare-and-select (no table load on the walk's chain of dependent
    /// loads), the tie broken by a random order of the moves from 16 bits
    /// of a 64-bit draw (off that chain too), no allocation.
    ///
    /// # Panics
    /// If `mask` or the counts are shorter than the lattice.
    // Not inlined, so the loop's registers are allocated for it alone:
    // inlined into the policies' large rollout dispatch, more of its live
    // values were spilled to the stack.
    #[inline(never)]
    pub fn rollout<V: Visit>(
        &mut self,
        torus: &Torus,
        mask: &[u8],
        rng: &mut Rng,
        start: u32,
        cap: u32,
        visit: &mut V,
    ) -> Outcome {
        let cells = torus.cells();
        assert!(mask.len() >= cells && self.val.len() >= cells && (start as usize) < cells);
        if mask[start as usize] != 0 {
            return Outcome {
                steps: 0,
                detected: true,
            };
        }
        let n = torus.n();
        let mut at = At::new(torus, start);
        let mut bits = 0u64;
        let mut left = 0u32;
        let base = self.base;
        let val = &mut self.val[..];
        // A local copy of the generator, written back after the walk, so
        // its state stays in registers rather than going back to memory at
        // every refill.
        let mut r = rng.clone();
        let mut out = Outcome {
            steps: cap,
            detected: false,
        };
        // A plain counter: `1..=cap` keeps an extra exhaustion flag live.
        let mut steps = 0;
        while steps < cap {
            steps += 1;
            // SAFETY: `at` starts on the lattice and `At::around` keeps it
            // there, so every cell is < cells() ≤ mask.len(), val.len()
            // (asserted above); k < 24.
            unsafe {
                let k = order(&mut r, &mut bits, &mut left);
                let around = at.around(n);
                let m = choose(val, base, around.cells(), k);
                at = around.go(m);
                let cell = (at.row + at.x) as usize;
                let v = val.get_unchecked_mut(cell);
                *v = (*v).max(base) + 1;
                visit.visit(cell as u32, steps);
                if *mask.get_unchecked(cell) != 0 {
                    out = Outcome {
                        steps,
                        detected: true,
                    };
                    break;
                }
            }
        }
        *rng = r;
        // Each step adds 1 to one value, so none exceeds this: an upper
        // bound is all `begin` needs, and tracking the maximum would hold a
        // register in the loop.
        self.top = self.top.max(base) + out.steps;
        out
    }

    /// Per-cell values of the walk, `y * n + x`: the visit counts of the
    /// first walk exactly (a standalone walker walks once); after later
    /// walks, offset by where the current walk's counts start.
    pub fn counts(&self) -> &[u32] {
        &self.val
    }
}

/// Where a walk stands: column `x` and the row's first cell `row` (y · N),
/// from which the four neighbours follow by compare-and-select.
#[derive(Clone, Copy, Debug, PartialEq)]
struct At {
    x: u32,
    row: u32,
}

/// The rows above and below and the columns right and left of an [`At`].
#[derive(Clone, Copy)]
struct Around {
    at: At,
    up: u32,
    down: u32,
    right: u32,
    left: u32,
}

impl At {
    fn new(torus: &Torus, cell: u32) -> At {
        let (x, y) = torus.xy(cell);
        At {
            x,
            row: y * torus.n(),
        }
    }

    /// The neighbouring rows and columns on an `n` × `n` torus.
    #[inline(always)]
    fn around(self, n: u32) -> Around {
        let last_row = n * n - n;
        Around {
            at: self,
            up: if self.row == 0 {
                last_row
            } else {
                self.row - n
            },
            down: if self.row == last_row {
                0
            } else {
                self.row + n
            },
            right: if self.x + 1 == n { 0 } else { self.x + 1 },
            left: if self.x == 0 { n - 1 } else { self.x - 1 },
        }
    }
}

impl Around {
    /// The four neighbour cells, in `Move::ALL` order.
    #[inline(always)]
    fn cells(&self) -> [u32; 4] {
        let At { x, row } = self.at;
        [
            self.up + x,
            row + self.right,
            self.down + x,
            row + self.left,
        ]
    }

    /// Where move `m` (index in `Move::ALL`) leads: selects on m's bits, not
    /// an indexed load, which would put a store and a load on the walk's
    /// chain.
    #[inline(always)]
    fn go(&self, m: usize) -> At {
        let (odd, high) = (m & 1 != 0, m & 2 != 0);
        let side = if high { self.left } else { self.right };
        let vertical = if high { self.down } else { self.up };
        At {
            x: if odd { side } else { self.at.x },
            row: if odd { self.at.row } else { vertical },
        }
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
    fn neighbours_by_compare_and_select_match_the_lattice() {
        // Every cell of small and odd lattices, including each wrap.
        for n in [3, 4, 5, 8] {
            let t = Torus::new(n).unwrap();
            for c in 0..t.cells() as u32 {
                let around = At::new(&t, c).around(n);
                for m in Move::ALL {
                    let want = t.step(c, m);
                    assert_eq!(around.cells()[m as usize], want, "n {n} cell {c} {m:?}");
                    assert_eq!(
                        around.go(m as usize),
                        At::new(&t, want),
                        "n {n} cell {c} {m:?}"
                    );
                }
            }
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
        // neighbours of the start are tied, whatever the old walk left, so
        // each is chosen under some order.
        let q = At::new(&t, 12).around(t.n()).cells();
        let chosen: std::collections::HashSet<usize> = (0..24)
            .map(|k| unsafe { choose(&w.val, w.base, q, k) })
            .collect();
        assert_eq!(chosen.len(), 4);
        let c = |cell: u32| w.val[cell as usize].saturating_sub(w.base);
        assert_eq!(c(12), 1);
        assert_eq!((0..25).map(c).sum::<u32>(), 1);
    }
}
