//! Path refinement: local search over the start of a search path, each
//! change counted exactly.
//!
//! For a path `p_0, p_1, …` and first-sight times `τ(c)` (the first `t`
//! whose disc holds cell `c`; the cap when none does), the path's mean is
//! `E[min(T, cap)] = Σ_c m(c) · min(τ(c), cap)` (mass `m` normalised or
//! not: refinement only compares paths). A change to the path's cells over
//! a window of times moves only the terms of cells seen in that window, so
//! it is counted in time proportional to the window, not to the path.
//!
//! The changes keep every move a unit move and every cell outside the
//! window where it was, between moves `i < j`:
//! - *pair*: the two moves become `a, b` with `a + b` unchanged, which
//!   shifts the cells between them (swapping them is one such change);
//! - *shift*: move `i` is taken out and put back after move `j`, or move
//!   `j` before move `i`, which shifts the stretch between by one cell;
//! - *reverse*: moves `i..=j` are made in the opposite order.
//!
//! A pass tries every change with `j − i` below the window among the first
//! `span` moves and keeps each that lowers the mean; passes repeat until
//! one keeps nothing. So the mean never goes up. Deterministic: no random
//! numbers.

use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::sum::Sum;

/// First sight of a cell the path never sees.
const NEVER: u32 = u32::MAX;

/// Change kinds per pair of moves: four pairs, two shifts, one reversal.
const KINDS: u32 = 7;

/// Most passes over the span; a pass that keeps nothing ends refinement
/// sooner (measured: 3–12 passes at N = 40).
const MAX_PASSES: u32 = 100;

/// What a refinement did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refined {
    /// `Σ_c m(c) · min(τ(c), cap)` before.
    pub before: f64,
    /// The same after.
    pub after: f64,
    /// Changes kept.
    pub changes: u32,
}

/// The refiner's working memory, reused between refinements.
#[derive(Clone, Debug, Default)]
pub struct Refiner {
    /// The span being refined (cells `0..=span` of the path) and their
    /// coordinates.
    head: Vec<u32>,
    xs: Vec<i32>,
    ys: Vec<i32>,
    /// First sight of each cell after the span (`NEVER`: none).
    tail_first: Vec<u32>,
    /// First sight of each cell anywhere on the path.
    tau: Vec<u32>,
    /// Every sight within the span as (cell, time), sorted, and where each
    /// cell's sights begin in it (for cells with any).
    sights: Vec<(u32, u32)>,
    sights_at: Vec<u32>,
    /// Which cells the change under test touches (by stamp), and when the
    /// changed window first sees them.
    stamp: Vec<u32>,
    now: u32,
    seen_new: Vec<u32>,
    touched: Vec<u32>,
    /// The window's new cells.
    q: Vec<(u32, i32, i32)>,
    /// Where the refinement under way stands.
    cursor: Cursor,
}

/// Where a refinement stands between slices of [`Refiner::work`].
#[derive(Clone, Copy, Debug, Default)]
struct Cursor {
    /// The total before refining.
    before: f64,
    /// Changes kept in finished passes, and in the pass under way.
    changes: u32,
    kept: u32,
    /// Passes finished, and the next first move of the one under way.
    passes: u32,
    i: usize,
    done: bool,
}

impl Refiner {
    /// Refines the first `span` moves of `path` at once: [`Refiner::start`],
    /// [`Refiner::work`] until done, [`Refiner::finish`].
    ///
    /// # Panics
    /// As [`Refiner::start`].
    #[cfg(test)]
    #[allow(clippy::too_many_arguments)]
    pub fn refine(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        mass: &[f64],
        cap: u32,
        window: u32,
        span: usize,
        path: &mut [u32],
    ) -> Refined {
        self.start(torus, sensor, mass, cap, span, path);
        while !self.work(torus, sensor, mass, cap, window, usize::MAX) {}
        self.finish(mass, cap, path)
    }

    /// Starts refining the first `span` moves of `path` (cells; `path[0]`
    /// is the searcher's cell and stays) for the mass `mass` (0 on cells
    /// already searched) and step cap `cap`. Cells after the span stay as
    /// they are. [`Refiner::work`] then tries the changes in slices, and
    /// [`Refiner::finish`] writes the refined span back.
    ///
    /// # Panics
    /// If a cell of `path` is off `torus`, or consecutive cells are not
    /// neighbours.
    pub fn start(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        mass: &[f64],
        cap: u32,
        span: usize,
        path: &[u32],
    ) {
        let cells = torus.cells();
        self.head.clear();
        self.cursor = Cursor::default();
        if path.is_empty() {
            self.cursor.done = true;
            return;
        }
        let end = span.min(path.len() - 1);
        self.head.extend_from_slice(&path[..=end]);
        self.xs.clear();
        self.ys.clear();
        for &c in &self.head {
            let (x, y) = torus.xy(c);
            self.xs.push(x as i32);
            self.ys.push(y as i32);
        }
        self.tail_first.clear();
        self.tail_first.resize(cells, NEVER);
        for (t, &p) in path.iter().enumerate().skip(self.head.len()) {
            for c in sensor.around(p) {
                let f = &mut self.tail_first[c as usize];
                *f = (*f).min(t as u32);
            }
        }
        self.tau.clone_from(&self.tail_first);
        self.stamp.clear();
        self.stamp.resize(cells, 0);
        self.seen_new.clear();
        self.seen_new.resize(cells, NEVER);
        self.now = 0;
        self.sights.clear();
        self.sights_at.resize(cells, 0);
        self.index(sensor);
        self.cursor.before = self.total(mass, cap);
    }

    /// Tries the changes from up to `rows` first moves `i` of the passes
    /// under way (the arguments as given to [`Refiner::start`]), changes
    /// spanning fewer than `window` moves. True once a pass keeps nothing
    /// (or the passes run out): refinement is done.
    pub fn work(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        mass: &[f64],
        cap: u32,
        window: u32,
        rows: usize,
    ) -> bool {
        let mut rows = rows;
        // Moves i and j both lie in the span: j + 1 ≤ len − 1.
        let last = self.head.len().saturating_sub(2);
        while !self.cursor.done {
            let c = self.cursor;
            if c.i >= last {
                self.cursor.passes += 1;
                self.cursor.changes += c.kept;
                self.cursor.done = c.kept == 0 || self.cursor.passes == MAX_PASSES;
                (self.cursor.i, self.cursor.kept) = (0, 0);
                continue;
            }
            if rows == 0 {
                break;
            }
            self.cursor.kept += self.row(torus, sensor, mass, cap, window, c.i);
            self.cursor.i += 1;
            rows -= 1;
        }
        self.cursor.done
    }

    /// Where the passes stand, as (pass, first move i, moves in the span).
    pub fn progress(&self) -> (u32, usize, usize) {
        (self.cursor.passes, self.cursor.i, self.head.len())
    }

    /// Writes the refined span back into `path` (the one given to
    /// [`Refiner::start`]) and says what refinement did.
    pub fn finish(&mut self, mass: &[f64], cap: u32, path: &mut [u32]) -> Refined {
        if self.head.is_empty() {
            return Refined {
                before: 0.0,
                after: 0.0,
                changes: 0,
            };
        }
        path[..self.head.len()].copy_from_slice(&self.head);
        Refined {
            before: self.cursor.before,
            after: self.total(mass, cap),
            changes: self.cursor.changes,
        }
    }

    /// The changes whose first move is `i`, in one pass over the span; the
    /// number kept.
    fn row(
        &mut self,
        torus: &Torus,
        sensor: &Sensor,
        mass: &[f64],
        cap: u32,
        window: u32,
        i: usize,
    ) -> u32 {
        let len = self.head.len();
        let mut kept = 0;
        let top = (i + window as usize).min(len - 1);
        let mut j = i + 1;
        while j < top {
            let mut better = false;
            for kind in 0..KINDS {
                if self.candidate(torus, i, j, kind)
                    && self.keep_if_better(sensor, mass, cap, i + 1)
                {
                    better = true;
                    break;
                }
            }
            if better {
                kept += 1;
            } else {
                j += 1;
            }
        }
        kept
    }

    /// The move from span cell `t` to `t + 1`, as a unit `(dx, dy)`.
    #[inline]
    fn mv(&self, t: usize, n: i32) -> (i32, i32) {
        let wrap = |d: i32| {
            if d > 1 {
                d - n
            } else if d < -1 {
                d + n
            } else {
                d
            }
        };
        (
            wrap(self.xs[t + 1] - self.xs[t]),
            wrap(self.ys[t + 1] - self.ys[t]),
        )
    }

    /// Fills `q` with the cells `i + 1..=j` become under change `kind`
    /// between moves `i` and `j`; false when that change does not apply.
    fn candidate(&mut self, torus: &Torus, i: usize, j: usize, kind: u32) -> bool {
        let n = torus.n() as i32;
        let (mi, mj) = (self.mv(i, n), self.mv(j, n));
        self.q.clear();
        match kind {
            0..=3 => {
                let a = Move::ALL[kind as usize].delta();
                let b = (mi.0 + mj.0 - a.0, mi.1 + mj.1 - a.1);
                if a == mi || b.0.abs() + b.1.abs() != 1 {
                    return false;
                }
                let d = (a.0 - mi.0, a.1 - mi.1);
                for t in i + 1..=j {
                    self.q.push(torus.near(self.xs[t] + d.0, self.ys[t] + d.1));
                }
            }
            4 | 5 => {
                if mi == mj {
                    return false;
                }
                for t in i + 1..=j {
                    let (x, y) = if kind == 4 {
                        (self.xs[t + 1] - mi.0, self.ys[t + 1] - mi.1)
                    } else {
                        (self.xs[t - 1] + mj.0, self.ys[t - 1] + mj.1)
                    };
                    self.q.push(torus.near(x, y));
                }
            }
            _ => {
                if j == i + 1 {
                    return false;
                }
                let (mut x, mut y) = (self.xs[i], self.ys[i]);
                for t in (i + 1..=j).rev() {
                    let m = self.mv(t, n);
                    x += m.0;
                    y += m.1;
                    let c = torus.near(x, y);
                    (x, y) = (c.1, c.2);
                    self.q.push(c);
                }
            }
        }
        true
    }

    /// Counts the change of span cells `s..s + q.len()` to `q`; keeps it
    /// when it lowers the mean.
    fn keep_if_better(&mut self, sensor: &Sensor, mass: &[f64], cap: u32, s: usize) -> bool {
        if self.q.iter().zip(&self.head[s..]).all(|(a, &b)| a.0 == b) {
            return false;
        }
        // Below this a gain is rounding, and keeping it could cycle.
        if self.delta(sensor, mass, cap, s) >= -1e-12 {
            return false;
        }
        self.apply(sensor, s);
        true
    }

    /// Makes span cells `s..s + q.len()` the cells of `q` and rebuilds the
    /// index of sights.
    fn apply(&mut self, sensor: &Sensor, s: usize) {
        for (k, &(c, x, y)) in self.q.iter().enumerate() {
            self.head[s + k] = c;
            self.xs[s + k] = x;
            self.ys[s + k] = y;
        }
        self.index(sensor);
    }

    /// The change in `Σ_c m(c) · min(τ(c), cap)` if span cells `s..` became
    /// `q`.
    fn delta(&mut self, sensor: &Sensor, mass: &[f64], cap: u32, s: usize) -> f64 {
        let e = s + self.q.len() - 1;
        self.now = self.now.wrapping_add(1);
        if self.now == 0 {
            self.stamp.iter_mut().for_each(|v| *v = 0);
            self.now = 1;
        }
        self.touched.clear();
        // Cells seen before the window keep their first sight; the rest of
        // the new window's cells, at their first new sight.
        for (k, &(_, x, y)) in self.q.iter().enumerate() {
            for c in sensor.around_xy(x, y) {
                let ci = c as usize;
                if (self.tau[ci] as usize) < s || mass[ci] == 0.0 || self.stamp[ci] == self.now {
                    continue;
                }
                self.stamp[ci] = self.now;
                self.seen_new[ci] = (s + k) as u32;
                self.touched.push(c);
            }
        }
        // Cells the old window saw first may lose that sight.
        for t in s..=e {
            for c in sensor.around_xy(self.xs[t], self.ys[t]) {
                let ci = c as usize;
                if (self.tau[ci] as usize) < s || mass[ci] == 0.0 || self.stamp[ci] == self.now {
                    continue;
                }
                self.stamp[ci] = self.now;
                self.seen_new[ci] = NEVER;
                self.touched.push(c);
            }
        }
        let mut d = 0.0;
        for &c in &self.touched {
            let ci = c as usize;
            let old = self.tau[ci];
            // The first sight after the window: τ itself when it is later,
            // else the next one in the span, else the tail's.
            let outside = if (old as usize) > e {
                old
            } else {
                // A cell is seen a few times at most (once per pass of
                // the path within reach), so walking its own sights from
                // the first is cheaper than a binary search of all of them.
                let mut k = self.sights_at[ci] as usize;
                while self
                    .sights
                    .get(k)
                    .is_some_and(|&(sc, st)| sc == c && st <= e as u32)
                {
                    k += 1;
                }
                match self.sights.get(k) {
                    Some(&(sc, st)) if sc == c => st,
                    _ => self.tail_first[ci],
                }
            };
            let new = outside.min(self.seen_new[ci]);
            if new != old {
                d += mass[ci] * (new.min(cap) as f64 - old.min(cap) as f64);
            }
        }
        d
    }

    /// Rebuilds the span's sights and first sights. The sights of the
    /// span as it was name every cell whose first sight may have changed.
    fn index(&mut self, sensor: &Sensor) {
        for &(c, _) in &self.sights {
            self.tau[c as usize] = self.tail_first[c as usize];
        }
        self.sights.clear();
        for (t, &p) in self.head.iter().enumerate() {
            for c in sensor.around(p) {
                self.sights.push((c, t as u32));
                let f = &mut self.tau[c as usize];
                *f = (*f).min(t as u32);
            }
        }
        self.sights.sort_unstable();
        for (k, &(c, _)) in self.sights.iter().enumerate().rev() {
            self.sights_at[c as usize] = k as u32;
        }
    }

    /// `Σ_c m(c) · min(τ(c), cap)`.
    fn total(&self, mass: &[f64], cap: u32) -> f64 {
        let mut s = Sum::default();
        for (&m, &t) in mass.iter().zip(&self.tau) {
            if m > 0.0 {
                s.add(m * t.min(cap) as f64);
            }
        }
        s.value()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::bound;
    use crate::config::Config;

    /// The game of the default configuration with `settings`.
    fn game(settings: &[(&str, &str)]) -> (Config, crate::config::Game) {
        let cfg = Config::default().with(settings);
        let g = cfg.game().unwrap();
        (cfg, g)
    }

    /// The moves of a lawnmower over four rows of a 12-torus, with a wasted
    /// up-and-down after the `k`-th move of a row where `wiggle(k)`.
    fn meander(wiggle: impl Fn(usize) -> bool) -> Vec<Move> {
        let mut moves = Vec::new();
        for row in 0..4 {
            let along = if row % 2 == 0 {
                Move::Right
            } else {
                Move::Left
            };
            for k in 0..11 {
                moves.push(along);
                if wiggle(k) {
                    moves.extend([Move::Up, Move::Down]);
                }
            }
            moves.extend([Move::Down; 3]);
        }
        moves
    }

    /// A path from `start` along `moves`.
    fn walk(t: &Torus, start: u32, moves: &[Move]) -> Vec<u32> {
        let mut p = vec![start];
        for &m in moves {
            p.push(t.step(*p.last().unwrap(), m));
        }
        p
    }

    /// `Σ_c m(c) · min(τ(c), cap)` of `path`, counted from scratch.
    fn brute_total(g: &crate::config::Game, mass: &[f64], cap: u32, path: &[u32]) -> f64 {
        let mut tau = vec![NEVER; g.torus.cells()];
        for (t, &p) in path.iter().enumerate() {
            for c in g.sensor.around(p) {
                tau[c as usize] = tau[c as usize].min(t as u32);
            }
        }
        let mut s = Sum::default();
        for (&m, &t) in mass.iter().zip(&tau) {
            s.add(m * t.min(cap) as f64);
        }
        s.value()
    }

    #[test]
    fn every_change_is_counted_as_a_recount_of_the_whole_path_would() {
        // Each change's `delta` against the totals of the path before and
        // after, counted from scratch: random walks that revisit cells (so
        // cells are seen several times in and after the window), a tail
        // after the span, a cap shorter than the path, and changes kept
        // as they come so the index is rebuilt between checks. A slip in
        // which sight counts after the window shows here at once, where
        // the other tests would only run their passes longer.
        let mut rng = crate::game::rng::stream(11, 0);
        let mut checked = 0;
        for (n, rv, cap) in [(7u32, "1", 45u32), (9, "1.5", 200), (11, "0", 30)] {
            let (_, g) = game(&[("n", &n.to_string()), ("rv", rv), ("sigma", "2")]);
            let mass = g.prior.mass();
            let moves: Vec<Move> = (0..70)
                .map(|_| Move::from_index(crate::game::rng::below(&mut rng, 4)))
                .collect();
            let mut path = walk(&g.torus, g.start, &moves);
            let span = 50;
            let mut r = Refiner::default();
            r.start(&g.torus, &g.sensor, mass, cap, span, &path);
            for _ in 0..400 {
                let i = crate::game::rng::below(&mut rng, (span - 2) as u32) as usize;
                let j = i + 1 + crate::game::rng::below(&mut rng, (span - 1 - i) as u32) as usize;
                let kind = crate::game::rng::below(&mut rng, KINDS);
                if j + 1 >= r.head.len() || !r.candidate(&g.torus, i, j, kind) {
                    continue;
                }
                let before = brute_total(&g, mass, cap, &path);
                let mut changed = path.clone();
                for (k, &(c, _, _)) in r.q.iter().enumerate() {
                    changed[i + 1 + k] = c;
                }
                let want = brute_total(&g, mass, cap, &changed) - before;
                let got = r.delta(&g.sensor, mass, cap, i + 1);
                assert!(
                    (got - want).abs() < 1e-12,
                    "n {n} rv {rv} cap {cap} i {i} j {j} kind {kind}: {got} != {want}"
                );
                checked += 1;
                if crate::game::rng::below(&mut rng, 4) == 0 {
                    // Keep it whatever its sign, as the next checks need a
                    // rebuilt index, not a better path.
                    r.apply(&g.sensor, i + 1);
                    path = changed;
                }
            }
        }
        assert!(checked > 600, "{checked} changes checked");
    }

    #[test]
    fn its_counts_are_the_exact_mean_and_never_go_up() {
        // A lawnmower with wasted wiggles over a 12-torus, Gaussian prior:
        // the refiner's totals must equal `path_mean` of the paths before
        // and after (they cover everything, so nothing is capped).
        let (cfg, g) = game(&[("n", "12"), ("sigma", "2")]);
        let mut path = walk(&g.torus, g.start, &meander(|k| k == 5));
        let mass = g.prior.mass();
        let before = bound::path_mean(&g.torus, &g.sensor, mass, &path);
        assert_eq!(before.uncovered, 0.0);
        let mut r = Refiner::default();
        let out = r.refine(
            &g.torus,
            &g.sensor,
            mass,
            cfg.step_cap,
            30,
            path.len(),
            &mut path,
        );
        let after = bound::path_mean(&g.torus, &g.sensor, mass, &path);
        assert!(
            (out.before - before.mean).abs() < 1e-9,
            "{out:?} {before:?}"
        );
        assert!((out.after - after.mean).abs() < 1e-9, "{out:?} {after:?}");
        assert!(out.changes > 0 && out.after < out.before - 0.1, "{out:?}");
        for w in path.windows(2) {
            assert_eq!(g.torus.l1(w[0], w[1]), 1, "unit moves");
        }
        assert_eq!(path[0], g.start);
        // A refined path is a fixed point.
        let again = r.refine(
            &g.torus,
            &g.sensor,
            mass,
            cfg.step_cap,
            30,
            path.len(),
            &mut path,
        );
        assert_eq!(again.changes, 0);
    }

    #[test]
    fn refining_in_slices_of_one_row_is_refining_at_once() {
        // A meander with wasted wiggles: many changes are kept, in several
        // passes, so the slices cross pass boundaries.
        let (cfg, g) = game(&[("n", "12"), ("sigma", "3")]);
        let path = walk(&g.torus, g.start, &meander(|k| k % 4 == 1));
        let mass = g.prior.mass();
        let (cap, span) = (cfg.step_cap, path.len());
        let mut whole = path.clone();
        let at_once =
            Refiner::default().refine(&g.torus, &g.sensor, mass, cap, 30, span, &mut whole);
        let mut sliced = path.clone();
        let mut r = Refiner::default();
        r.start(&g.torus, &g.sensor, mass, cap, span, &sliced);
        let mut slices = 0;
        let mut passes = Vec::new();
        while !r.work(&g.torus, &g.sensor, mass, cap, 30, 1) {
            slices += 1;
            let (pass, i, len) = r.progress();
            assert!(i < len);
            passes.push(pass);
        }
        let out = r.finish(mass, cap, &mut sliced);
        assert_eq!(out, at_once);
        assert_eq!(sliced, whole);
        assert!(at_once.changes > 0);
        assert!(passes.last() > passes.first(), "more than one pass");
        assert!(slices > path.len(), "{slices} slices");
    }

    /// The path a plain local search makes from `path`: the documented
    /// changes, tried in the documented order (first move `i`, then second
    /// move `j` below the window, then kind), each counted by
    /// [`brute_total`] and kept when it lowers the total by more than
    /// 10⁻¹²; passes until one keeps nothing. Returns the path, the changes
    /// kept and the passes made.
    fn plain_refine(
        g: &crate::config::Game,
        mass: &[f64],
        cap: u32,
        window: usize,
        span: usize,
        path: &[u32],
    ) -> (Vec<u32>, u32, u32) {
        let t = &g.torus;
        let len = span.min(path.len() - 1) + 1;
        let tail = &path[len..];
        let mut moves: Vec<Move> = path[..len]
            .windows(2)
            .map(|w| t.move_to(w[0], w[1]).unwrap())
            .collect();
        let cells = |moves: &[Move]| {
            let mut p = walk(t, path[0], moves);
            p.extend_from_slice(tail);
            p
        };
        let unit = |d: (i32, i32)| Move::ALL.into_iter().find(|m| m.delta() == d);
        let mut old = cells(&moves);
        let mut old_total = brute_total(g, mass, cap, &old);
        let (mut changes, mut passes) = (0, 0);
        loop {
            let mut kept = 0;
            for i in 0..len.saturating_sub(2) {
                let mut j = i + 1;
                while j < (i + window).min(len - 1) {
                    let (mi, mj) = (moves[i], moves[j]);
                    let mut better = false;
                    for kind in 0..KINDS {
                        let mut c = moves.clone();
                        match kind {
                            0..=3 => {
                                let a = Move::ALL[kind as usize];
                                let (da, di, dj) = (a.delta(), mi.delta(), mj.delta());
                                let Some(b) = unit((di.0 + dj.0 - da.0, di.1 + dj.1 - da.1)) else {
                                    continue;
                                };
                                if a == mi {
                                    continue;
                                }
                                (c[i], c[j]) = (a, b);
                            }
                            4 | 5 if mi == mj => continue,
                            4 => c[i..=j].rotate_left(1),
                            5 => c[i..=j].rotate_right(1),
                            _ if j == i + 1 => continue,
                            _ => c[i..=j].reverse(),
                        }
                        let new = cells(&c);
                        if new == old {
                            continue;
                        }
                        let new_total = brute_total(g, mass, cap, &new);
                        if new_total - old_total < -1e-12 {
                            (moves, old, old_total) = (c, new, new_total);
                            better = true;
                            break;
                        }
                    }
                    if better {
                        kept += 1;
                    } else {
                        j += 1;
                    }
                }
            }
            passes += 1;
            changes += kept;
            if kept == 0 || passes == MAX_PASSES {
                return (old, changes, passes);
            }
        }
    }

    #[test]
    fn refinement_is_the_plain_search_over_the_documented_changes() {
        // The same path, changes and passes as a plain search that counts
        // every change from scratch. This pins each kind of change (the
        // delta test above only checks a change's count, whatever the
        // change), the order they are tried in, the window, the span and
        // the end of the passes. Paths: a meander with wasted wiggles, and
        // random walks (revisits, reversals) with a tail after the span
        // and a cap inside the path.
        let mut rng = crate::game::rng::stream(5, 0);
        let mut cases = Vec::new();
        cases.push((12u32, "1", "2", 40, 8, usize::MAX, meander(|k| k % 4 == 1)));
        for (n, rv, sigma, cap, window, span) in [
            (9u32, "1", "1.5", 1000, 6, 30),
            (11, "1.5", "2", 35, 12, 45),
            (8, "0", "inf", 60, 5, 50),
        ] {
            let moves: Vec<Move> = (0..60)
                .map(|_| Move::from_index(crate::game::rng::below(&mut rng, 4)))
                .collect();
            cases.push((n, rv, sigma, cap, window, span, moves));
        }
        for (n, rv, sigma, cap, window, span, moves) in cases {
            let (_, g) = game(&[("n", &n.to_string()), ("rv", rv), ("sigma", sigma)]);
            let mass = g.prior.mass();
            let path = walk(&g.torus, g.start, &moves);
            let (want, changes, passes) = plain_refine(&g, mass, cap, window, span, &path);
            let mut got = path.clone();
            let mut r = Refiner::default();
            let out = r.refine(
                &g.torus,
                &g.sensor,
                mass,
                cap,
                window as u32,
                span,
                &mut got,
            );
            let case = format!("n {n} rv {rv} cap {cap} window {window} span {span}");
            assert_eq!(got, want, "{case}");
            assert_eq!((out.changes, r.progress().0), (changes, passes), "{case}");
            assert!(changes > 2 && passes > 1, "{case}: {changes} changes");
            assert!(
                (out.after - brute_total(&g, mass, cap, &got)).abs() < 1e-9,
                "{case}"
            );
        }
    }

    #[test]
    fn cells_after_the_span_stay_and_count() {
        // Only the first 10 moves change; a cell the tail sees first still
        // counts at the tail's time (a wrong tail time would change `after`
        // against `path_mean`).
        let (cfg, g) = game(&[("n", "9"), ("prior", "uniform")]);
        // Wiggles, then a lawnmower that covers the whole 9-torus.
        let mut moves: Vec<Move> = [Move::Right, Move::Up, Move::Down]
            .into_iter()
            .cycle()
            .take(30)
            .collect();
        for stripe in 0..3 {
            let along = if stripe % 2 == 0 {
                Move::Right
            } else {
                Move::Left
            };
            moves.extend([along; 8]);
            moves.extend([Move::Down; 3]);
        }
        let mut path = walk(&g.torus, g.start, &moves);
        let tail = path[11..].to_vec();
        let mass = g.prior.mass();
        let mut r = Refiner::default();
        let out = r.refine(&g.torus, &g.sensor, mass, cfg.step_cap, 8, 10, &mut path);
        assert_eq!(&path[11..], &tail[..]);
        let pm = bound::path_mean(&g.torus, &g.sensor, mass, &path);
        assert_eq!(pm.uncovered, 0.0);
        assert!((out.after - pm.mean).abs() < 1e-9, "{out:?} {pm:?}");
        assert!(out.changes > 0 && out.after < out.before, "{out:?}");
    }
}
