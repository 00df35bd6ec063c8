//! The nearly self-avoiding random walk (NSARW): each step chooses uniformly
//! among the neighbours visited the fewest times so far.

use super::visit::{Outcome, Visit};
use crate::game::lattice::{Move, Torus, MAX_N};
use crate::game::rng::{self, Rng};

/// Where a move's rank sits in the low word of a key (above any
/// neighbour entry `4 · cell`, which is below 2³⁰ since N ≤ 1024).
const RANK_SHIFT: u32 = 30;
const _: () = assert!(4 * (MAX_N as u64) * (MAX_N as u64) <= 1 << RANK_SHIFT);

/// `TIE[k]`: the k-th of the 24 orders of the four moves, each move's rank
/// shifted to bits 30–31. A step takes the least key
/// `visits << 32 | rank << 30 | 4 · neighbour`: fewest visits first, ties by
/// a uniform random order (the ranks are distinct, so the entry never
/// decides), so each of k tied moves is taken with probability exactly 1/k.
/// The winner's low bits are then the next cell, with no second lookup.
const TIE: [[u32; 4]; 24] = {
    let mut t = [[0u32; 4]; 24];
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
                    t[k] = [
                        a << RANK_SHIFT,
                        b << RANK_SHIFT,
                        c << RANK_SHIFT,
                        d << RANK_SHIFT,
                    ];
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

/// A uniform index into [`TIE`] from one 16-bit chunk `x`: multiply by 24
/// and keep the top 16 bits, or `None` for the 16 of 65 536 values that
/// would make some orders likelier (once in 4096 draws; the next chunk is
/// then used).
#[inline(always)]
fn order_of(x: u16) -> Option<usize> {
    let y = x as u64 * 24;
    (y & 0xffff >= 16).then_some((y >> 16) as usize)
}

/// A uniform index into [`TIE`] from 16 of the random bits in `bits`
/// (`left` draws of 16 bits remain in it; refilled from `rng`).
#[inline(always)]
fn order(rng: &mut Rng, bits: &mut u64, left: &mut u32) -> usize {
    loop {
        if *left == 0 {
            *bits = rng::bits(rng);
            *left = 4;
        }
        let x = *bits as u16;
        *bits >>= 16;
        *left -= 1;
        if let Some(k) = order_of(x) {
            return k;
        }
    }
}

/// Draws held by a [`Chunks`] buffer.
const DRAWS: usize = 16;

/// The 16-bit chunks of a block of draws, low chunk of each draw first: the
/// same chunks, in the same order, as [`order`] takes them one draw at a
/// time. Drawing a block at once keeps the generator's four words out of
/// the walk's registers; [`Chunks::finish`] puts the generator where taking
/// only the draws used would have left it. The position in the block is
/// the caller's local, so it can live in a register.
struct Chunks {
    buf: [u16; 4 * DRAWS],
    /// The generator before the current block (None: no block drawn yet).
    from: Option<Rng>,
}

impl Chunks {
    /// Chunks and the position `4 · DRAWS` (nothing drawn yet).
    fn new() -> (Chunks, usize) {
        let c = Chunks {
            buf: [0; 4 * DRAWS],
            from: None,
        };
        (c, 4 * DRAWS)
    }

    /// The next order index, from position `at`.
    #[inline(always)]
    fn order(&mut self, at: &mut usize, rng: &mut Rng) -> usize {
        loop {
            if *at == 4 * DRAWS {
                self.refill(rng);
                *at = 0;
            }
            // SAFETY: at < 4 · DRAWS after the refill check.
            let x = unsafe { *self.buf.get_unchecked(*at) };
            *at += 1;
            if let Some(k) = order_of(x) {
                return k;
            }
        }
    }

    /// Draws a block, keeping the generator from before it.
    #[cold]
    #[inline(never)]
    fn refill(&mut self, rng: &mut Rng) {
        self.from = Some(rng.clone());
        for d in self.buf.chunks_exact_mut(4) {
            let x = rng::bits(rng);
            for (j, c) in d.iter_mut().enumerate() {
                *c = (x >> (16 * j)) as u16;
            }
        }
    }

    /// Leaves `rng` as if only the draws whose chunks were used (up to
    /// position `at`) had been taken; a draw partly used counts, as with
    /// [`order`].
    fn finish(&self, at: usize, rng: &mut Rng) {
        if let Some(from) = &self.from {
            *rng = from.clone();
            for _ in 0..at.div_ceil(4) {
                rng::bits(rng);
            }
        }
    }
}

/// The low word `rank << 30 | 4 · cell` of the least key among the
/// neighbour entries `q` (`4 · cell`, in `Move::ALL` order) under visit
/// counts `val`, ties broken by the order `TIE[k]`. Free of
/// the struct so the hot loop can pass its locals: a store through the
/// walk's own slice then cannot alias the struct's fields, so they stay in
/// registers.
///
/// # Safety
/// Every `q[i] / 4` indexes `val`, and `k < 24`.
#[inline(always)]
unsafe fn choose(val: &[u32], q: &[u32], k: usize) -> u32 {
    let r = TIE.get_unchecked(k);
    let bytes = val.as_ptr().cast::<u8>();
    // The entry is the count's byte offset, so no shift sits between the
    // two loads.
    let key = |i: usize| {
        let e = *q.get_unchecked(i);
        let v = bytes.add(e as usize).cast::<u32>().read() as u64;
        v << 32 | (*r.get_unchecked(i) | e) as u64
    };
    key(0).min(key(1)).min(key(2).min(key(3))) as u32
}

/// Counts a visit to `cell` in `val` and lists the cell in `seen` on its
/// first visit of the walk (`len` cells listed so far).
///
/// # Safety
/// `cell < val.len()` and `*len < seen.len()`.
#[inline(always)]
unsafe fn record(val: &mut [u32], seen: &mut [u32], len: &mut usize, cell: usize) {
    let v = val.get_unchecked_mut(cell);
    let first = *v == 0;
    *v += 1;
    // Written every time, kept only on a first visit: no branch in the walk.
    *seen.get_unchecked_mut(*len) = cell as u32;
    *len += first as usize;
}

/// NSARW with its own visit counts.
///
/// One word per cell holds its visits in the current walk, and a list holds
/// each cell the walk has visited, once. Starting a new walk (every
/// rollout) zeroes only the listed cells, so it costs what the last walk
/// touched, not N², and the count of a neighbour is one plain load.
#[derive(Clone, Debug)]
pub struct Nsarw {
    val: Vec<u32>,
    /// The cells visited in this walk, each once, in `seen[..len]`; one
    /// spare slot, since the walk writes `seen[len]` at every step and
    /// moves `len` on only for a first visit.
    seen: Vec<u32>,
    len: usize,
}

impl Nsarw {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.val[..]) + std::mem::size_of_val(&self.seen[..])
    }

    /// A walker for a lattice of `cells` cells.
    pub fn new(cells: usize) -> Nsarw {
        Nsarw {
            val: vec![0; cells],
            seen: vec![0; cells + 1],
            len: 0,
        }
    }

    /// Starts a new walk at `start`, which counts as visited once.
    pub fn begin(&mut self, start: u32) {
        for &c in &self.seen[..self.len] {
            self.val[c as usize] = 0;
        }
        self.len = 0;
        self.enter(start);
    }

    /// Records a visit to `cell`.
    ///
    /// # Panics
    /// If `cell` is outside the walk's lattice.
    #[inline]
    pub fn enter(&mut self, cell: u32) {
        assert!((cell as usize) < self.val.len());
        // SAFETY: asserted just above; `len` counts distinct cells, so
        // len ≤ val.len() < seen.len().
        unsafe { record(&mut self.val, &mut self.seen, &mut self.len, cell as usize) };
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
        let q = &torus.neighbours()[4 * cell as usize..][..4];
        // SAFETY: asserted just above (neighbours of a cell are cells); k < 24.
        let low = unsafe { choose(&self.val, q, k) };
        // The rank names the move even when two moves reach one cell.
        let rank = low >> RANK_SHIFT << RANK_SHIFT;
        let m = TIE[k]
            .iter()
            .position(|&r| r == rank)
            .expect("a rank of the order");
        Move::from_index(m as u32)
    }

    /// Walks from `start` until `mask` marks the cell or `cap` moves,
    /// continuing the walk begun by [`Nsarw::begin`].
    ///
    /// The hot loop: the walk's chain of dependent work is a load of the
    /// cell's four neighbour entries, a load of each count, and the least
    /// of four keys, whose low bits are the next cell. The tie is broken by
    /// a random order of the moves from 16 bits of a block of draws made
    /// ahead (off that chain), and nothing is allocated.
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
        // The list has a slot for every cell and the spare one.
        assert!(self.seen.len() > self.val.len());
        if mask[start as usize] != 0 {
            return Outcome {
                steps: 0,
                detected: true,
            };
        }
        let nbr = torus.neighbours();
        let (mut chunks, mut at) = Chunks::new();
        let val = &mut self.val[..];
        let seen = &mut self.seen[..];
        let mut len = self.len;
        let mut e = 4 * start;
        let mut out = Outcome {
            steps: cap,
            detected: false,
        };
        // A plain counter: `1..=cap` keeps an extra exhaustion flag live.
        let mut steps = 0;
        while steps < cap {
            steps += 1;
            // SAFETY: `e` is 4 · a cell, so its row of the table is in
            // bounds and every entry in it is 4 · a cell < 4 · cells()
            // ≤ 4 · mask.len(), 4 · val.len() (asserted above); k < 24;
            // `len` counts distinct cells, so len ≤ val.len() < seen.len().
            unsafe {
                let k = chunks.order(&mut at, rng);
                let q = nbr.get_unchecked(e as usize..e as usize + 4);
                e = choose(val, q, k) & ((1 << RANK_SHIFT) - 1);
                let cell = (e >> 2) as usize;
                record(val, seen, &mut len, cell);
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
        chunks.finish(at, rng);
        self.len = len;
        out
    }

    /// Per-cell visits of the current walk, `y * n + x`.
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
            let mut ranks: Vec<u32> = r.iter().map(|x| x >> RANK_SHIFT).collect();
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
        for x in 0..=0xffffu16 {
            match order_of(x) {
                Some(k) => n[k] += 1,
                None => redrawn += 1,
            }
        }
        assert_eq!(n, [2730; 24]);
        assert_eq!(redrawn, 16);
    }

    #[test]
    fn the_walk_follows_the_law_step_by_step() {
        // A plain walk of the law (counts from `Torus::step`, least count
        // first, ties by the drawn order, 16 bits a step taken one draw at a
        // time) against the hot loop, on small and odd lattices where every
        // wrap is taken, with walks long enough to use many blocks of
        // draws: the same cells, the same counts, and the generator left in
        // the same state.
        for n in [3, 4, 5, 8] {
            let t = Torus::new(n).unwrap();
            let mut mask = vec![0u8; t.cells()];
            // One walker for all the walks: each begins where the last left
            // its counts.
            let mut w = Nsarw::new(t.cells());
            for seed in 0..6u64 {
                let start = (seed as u32 * 7) % t.cells() as u32;
                // Every third walk ends on a target; the others at the cap.
                let target = (seed % 3 == 0).then(|| (start + 1 + seed as u32) % t.cells() as u32);
                mask.fill(0);
                if let Some(c) = target {
                    mask[c as usize] = 1;
                }
                let cap = 50 + 97 * seed as u32;
                let mut r = rng::stream(seed, 9);
                w.begin(start);
                let mut path = Vec::new();
                let got = w.rollout(&t, &mask, &mut r, start, cap, &mut path);

                let mut want_r = rng::stream(seed, 9);
                let mut count = vec![0u32; t.cells()];
                count[start as usize] = 1;
                let (mut bits, mut left, mut cell) = (0, 0, start);
                let mut want = Vec::new();
                while (want.len() as u32) < cap && target != Some(cell) {
                    let k = order(&mut want_r, &mut bits, &mut left);
                    let m = (0..4)
                        .min_by_key(|&i| {
                            let to = t.step(cell, Move::from_index(i as u32));
                            (count[to as usize], TIE[k][i])
                        })
                        .unwrap();
                    cell = t.step(cell, Move::from_index(m as u32));
                    count[cell as usize] += 1;
                    want.push(cell);
                }
                assert_eq!(path, want, "n {n} seed {seed}");
                assert_eq!(w.counts(), &count[..], "n {n} seed {seed}");
                assert_eq!(got.steps as usize, want.len());
                assert_eq!(got.detected, target == Some(cell));
                assert_eq!(
                    rng::bits(&mut r),
                    rng::bits(&mut want_r),
                    "n {n} seed {seed}"
                );
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
        w.rollout(
            &t,
            &mask,
            &mut r,
            0,
            200,
            &mut crate::searchers::walks::visit::NoVisit,
        );
        w.begin(12);
        // Only the start has been visited in the new walk: all four
        // neighbours of the start are tied, whatever the old walk left, so
        // each is chosen under some order.
        let q = &t.neighbours()[4 * 12..][..4];
        let chosen: std::collections::HashSet<u32> = (0..24)
            .map(|k| unsafe { choose(&w.val, q, k) } & ((1 << RANK_SHIFT) - 1))
            .collect();
        assert_eq!(chosen.len(), 4);
        let c = |cell: u32| w.counts()[cell as usize];
        assert_eq!(c(12), 1);
        assert_eq!((0..25).map(c).sum::<u32>(), 1);
    }
}
