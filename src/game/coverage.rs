//! Simulated coverage: the planning mass a hypothetical path would search on
//! top of what the belief has already searched, with undo, so planners and
//! belief rollouts can try paths without copying the searched set.

use crate::game::belief::BeliefState;
use crate::game::lattice::{Move, Sensor};
use std::ops::Range;

/// The cells a simulated path has covered beyond the belief's searched set.
///
/// Marks live in a byte per cell plus a stack of the cells marked, so a
/// simulation is undone in time proportional to what it covered, never to
/// the lattice (an N = 1024 planner tries thousands of paths per move).
#[derive(Clone, Debug, Default)]
pub struct Coverage {
    marked: Vec<u8>,
    stack: Vec<u32>,
}

/// A cell's planning mass when it is neither simulated (`marked`) nor
/// searched for real, else 0: what is still to be found there.
#[inline(always)]
fn live(marked: u8, searched: u8, mass: f64) -> f64 {
    if marked | searched == 0 {
        mass
    } else {
        0.0
    }
}

impl Coverage {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.marked[..]) + std::mem::size_of_val(&self.stack[..])
    }

    /// Room for a lattice of `cells` cells, nothing simulated.
    pub fn new(cells: usize) -> Coverage {
        Coverage {
            marked: vec![0; cells],
            stack: Vec::new(),
        }
    }

    /// True when `cell` is searched for real or covered by the simulation.
    #[inline]
    pub fn covered(&self, belief: &BeliefState, cell: u32) -> bool {
        let c = cell as usize;
        self.marked[c] != 0 || belief.searched()[c] != 0
    }

    /// Moves the simulated searcher to `cell`: marks the sensor's disc there
    /// and returns the planning mass it newly covers.
    ///
    /// # Panics
    /// When `cell` is off the lattice this was built for.
    #[inline]
    pub fn cover(&mut self, sensor: &Sensor, belief: &BeliefState, cell: u32) -> f64 {
        self.mark(belief, sensor.around(cell))
    }

    /// Marks the uncovered ones of `cells` and returns their planning mass,
    /// summed in their order.
    // Always inlined: it is the lookahead's inner loop, and a plain
    // #[inline] left a call (callgrind, 800 horizon moves at N = 40: 389M
    // instructions against 355M).
    #[inline(always)]
    fn mark(&mut self, belief: &BeliefState, cells: impl Iterator<Item = u32>) -> f64 {
        let searched = belief.searched();
        let mass = belief.plan_mass();
        let mut gain = 0.0;
        for c in cells {
            let i = c as usize;
            if self.marked[i] == 0 && searched[i] == 0 {
                self.marked[i] = 1;
                self.stack.push(c);
                gain += mass[i];
            }
        }
        gain
    }

    /// As [`cover`](Coverage::cover) for a step `m` into `cell`, looking
    /// only at the cells the disc of the cell it came from does not hold
    /// ([`Sensor::front`]). When that disc is covered (searched or
    /// simulated), which holds along any simulated path after its first
    /// cell, it covers the same cells in the same order and returns the
    /// same gain, bit for bit; otherwise it may miss some.
    #[inline]
    pub fn cover_step(&mut self, sensor: &Sensor, belief: &BeliefState, m: Move, cell: u32) -> f64 {
        self.mark(belief, sensor.front(m, cell))
    }

    /// What [`cover_step`](Coverage::cover_step) would return, without
    /// marking anything: the same cells in the same order, summed alike (a
    /// front holds no cell twice), so the same gain bit for bit. The
    /// lookahead's last move needs no undo.
    #[inline(always)]
    pub fn step_gain(&self, sensor: &Sensor, belief: &BeliefState, m: Move, cell: u32) -> f64 {
        let searched = belief.searched();
        let mass = belief.plan_mass();
        let mut gain = 0.0;
        for c in sensor.front(m, cell) {
            let i = c as usize;
            if self.marked[i] == 0 && searched[i] == 0 {
                gain += mass[i];
            }
        }
        gain
    }

    /// True when every cell of the disc around `cell` is covered.
    pub fn disc_covered(&self, sensor: &Sensor, belief: &BeliefState, cell: u32) -> bool {
        sensor.around(cell).all(|c| self.covered(belief, c))
    }

    /// As [`cover`](Coverage::cover), also returning how many of the newly
    /// covered cells carry positive planning mass: a planner knows the search
    /// is over when that count reaches the number left, which a running
    /// difference of masses cannot tell exactly.
    ///
    /// # Panics
    /// When `cell` is off the lattice this was built for.
    #[inline]
    pub fn cover_counted(
        &mut self,
        sensor: &Sensor,
        belief: &BeliefState,
        cell: u32,
    ) -> (f64, u32) {
        let searched = belief.searched();
        let mass = belief.plan_mass();
        let mut gain = 0.0;
        let mut count = 0;
        for c in sensor.around(cell) {
            let i = c as usize;
            if self.marked[i] == 0 && searched[i] == 0 {
                self.marked[i] = 1;
                self.stack.push(c);
                gain += mass[i];
                count += (mass[i] > 0.0) as u32;
            }
        }
        (gain, count)
    }

    /// The planning mass that moving to `cell` would newly cover, without
    /// moving there.
    #[inline]
    pub fn gain(&self, sensor: &Sensor, belief: &BeliefState, cell: u32) -> f64 {
        let searched = belief.searched();
        let mass = belief.plan_mass();
        sensor
            .around(cell)
            .filter(|&c| self.marked[c as usize] == 0 && searched[c as usize] == 0)
            .map(|c| mass[c as usize])
            .sum()
    }

    /// [`gain`](Coverage::gain) for every cell of row `y` at once, into
    /// `row` (one entry per column), bit for bit the same positive values
    /// (a zero may differ in sign): each is summed over the disc in the
    /// sensor's order, a covered cell adding +0.0, which leaves a sum of
    /// non-negative masses unchanged. Offset by
    /// offset over whole rows, so no cell is tested for wrapping and the
    /// adds vectorise (a fallback scan of the lattice costs one pass per
    /// offset, not a disc walk per cell).
    ///
    /// # Panics
    /// When `y` is off the lattice or `row` is not one row long.
    pub fn gains_row(&self, sensor: &Sensor, belief: &BeliefState, y: u32, row: &mut [f64]) {
        let n = row.len();
        assert!(
            n * n == self.marked.len() && (y as usize) < n,
            "row {y} of a {n}-wide lattice"
        );
        let searched = belief.searched();
        let mass = belief.plan_mass();
        row.fill(0.0);
        let wrap = |v: i64| v.rem_euclid(n as i64) as usize;
        for &(dx, dy) in sensor.offsets() {
            let base = wrap(y as i64 + dy as i64) * n;
            // Column x reads column (x + dx) mod n: two unwrapped stretches.
            let shift = wrap(dx as i64);
            let (left, right) = row.split_at_mut(n - shift);
            for (part, from) in [(left, base + shift), (right, base)] {
                let cells = from..from + part.len();
                for ((g, &m), (&k, &s)) in part
                    .iter_mut()
                    .zip(&mass[cells.clone()])
                    .zip(self.marked[cells.clone()].iter().zip(&searched[cells]))
                {
                    *g += if k == 0 && s == 0 { m } else { 0.0 };
                }
            }
        }
    }

    /// The largest planning mass of a cell that is neither searched nor
    /// simulated, row by row, into `out` (one entry per row; 0 for a row
    /// with none). A row of [`gains_row`](Coverage::gains_row) sums one such
    /// cell or +0.0 per disc offset, so summing these row maxima over the
    /// offsets in the sensor's order bounds every gain from above, bit for
    /// bit (rounding is monotone).
    ///
    /// # Panics
    /// When `out` is not one entry per row.
    pub fn live_max_rows(&self, belief: &BeliefState, out: &mut [f64]) {
        let n = out.len();
        assert!(
            n * n == self.marked.len(),
            "{n} rows for {} cells",
            self.marked.len()
        );
        for (y, best) in out.iter_mut().enumerate() {
            *best = self.live_max_row(belief, n, y);
        }
    }

    /// [`live_max_rows`](Coverage::live_max_rows) for row `y` of an
    /// `n`-wide lattice alone.
    ///
    /// # Panics
    /// When row `y` is off the lattice.
    #[inline]
    pub fn live_max_row(&self, belief: &BeliefState, n: usize, y: usize) -> f64 {
        self.live_max_in(belief, y * n..(y + 1) * n)
    }

    /// The largest planning mass of a live cell (neither searched nor
    /// simulated) at each ℓ1 distance `d` from `cell`, into `out[d]`, over
    /// the box of `half` columns and rows around it (`out` is `2·half + 1`
    /// long; 0 where there is none). When that box would wrap onto itself,
    /// every entry is the largest over the whole lattice instead, which
    /// bounds them all.
    ///
    /// # Panics
    /// When `out` is not `2·half + 1` long.
    pub fn live_max_rings(
        &self,
        belief: &BeliefState,
        n: u32,
        cell: u32,
        half: u32,
        out: &mut [f64],
    ) {
        assert_eq!(out.len(), 2 * half as usize + 1, "one entry per distance");
        if 2 * half + 1 >= n {
            out.fill(self.live_max_in(belief, 0..self.marked.len()));
            return;
        }
        out.fill(0.0);
        let (mass, searched) = (belief.plan_mass(), belief.searched());
        let (n, half) = (n as usize, half as usize);
        let (x, y) = (cell as usize % n, cell as usize / n);
        // Each row's columns x − half ..= x + half as at most two unwrapped
        // stretches: no division a cell.
        let (width, lo) = (2 * half + 1, (x + n - half) % n);
        let first = width.min(n - lo);
        for k in 0..width {
            let row = (y + n - half + k) % n * n;
            let ady = k.abs_diff(half);
            let stretches = [(row + lo, 0, first), (row, first, width)];
            for (start, from, to) in stretches {
                for dx in from..to {
                    let i = start + dx - from;
                    let v = live(self.marked[i], searched[i], mass[i]);
                    let d = &mut out[ady + dx.abs_diff(half)];
                    *d = if v > *d { v } else { *d };
                }
            }
        }
    }

    /// The largest live planning mass among the cells `span`; 0 when none.
    /// It keeps eight running maxima, so a compare need not wait for the
    /// one before it (a max is exact in any order): a third faster than one
    /// over a row at N = 256.
    #[inline]
    fn live_max_in(&self, belief: &BeliefState, span: Range<usize>) -> f64 {
        let (mass, marked, searched) = (
            &belief.plan_mass()[span.clone()],
            &self.marked[span.clone()],
            &belief.searched()[span],
        );
        let mut lanes = [0.0f64; 8];
        let whole = mass.len() / 8 * 8;
        for i in (0..whole).step_by(8) {
            for (j, l) in lanes.iter_mut().enumerate() {
                let v = live(marked[i + j], searched[i + j], mass[i + j]);
                *l = if v > *l { v } else { *l };
            }
        }
        for i in whole..mass.len() {
            let v = live(marked[i], searched[i], mass[i]);
            lanes[0] = if v > lanes[0] { v } else { lanes[0] };
        }
        lanes
            .iter()
            .fold(0.0, |b: f64, &l| if l > b { l } else { b })
    }

    /// A point to [`undo`](Coverage::undo) back to.
    #[inline]
    pub fn checkpoint(&self) -> usize {
        self.stack.len()
    }

    /// Forgets every cell covered since `checkpoint`.
    #[inline]
    pub fn undo(&mut self, checkpoint: usize) {
        while self.stack.len() > checkpoint {
            let c = self.stack.pop().expect("longer than the checkpoint");
            self.marked[c as usize] = 0;
        }
    }

    /// Forgets the whole simulation.
    pub fn clear(&mut self) {
        self.undo(0);
    }

    /// Cells covered by the simulation so far (beyond the searched set).
    pub fn len(&self) -> usize {
        self.stack.len()
    }

    /// True when the simulation has covered nothing.
    pub fn is_empty(&self) -> bool {
        self.stack.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::lattice::Torus;
    use crate::game::prior::{PriorSpec, TargetPrior};

    #[test]
    fn cover_counts_only_new_mass_and_undo_restores() {
        let torus = Torus::new(10).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let prior = TargetPrior::new(&torus, &PriorSpec::Uniform).unwrap();
        let mut belief = BeliefState::new(Belief::Posterior, prior, None);
        belief.search_around(&sensor, 0);
        let mut cov = Coverage::new(torus.cells());
        let cell = 1; // right of the start: 3 of its 5 disc cells are new
        assert!((cov.gain(&sensor, &belief, cell) - 0.03).abs() < 1e-12);
        let cp = cov.checkpoint();
        assert!((cov.cover(&sensor, &belief, cell) - 0.03).abs() < 1e-12);
        assert_eq!(cov.cover(&sensor, &belief, cell), 0.0, "covered twice");
        assert!(cov.covered(&belief, 2) && cov.covered(&belief, 0));
        cov.undo(cp);
        assert!(cov.is_empty() && !cov.covered(&belief, 2));
        assert!((cov.gain(&sensor, &belief, cell) - 0.03).abs() < 1e-12);
    }

    /// A belief on the posterior of a prior with these weights.
    fn weighted(torus: &Torus, weights: &[f64]) -> BeliefState {
        let weights = weights.to_vec();
        let prior = TargetPrior::new(torus, &PriorSpec::Weights { weights }).unwrap();
        BeliefState::new(Belief::Posterior, prior, None)
    }

    /// An `n`-wide lattice, r_v = 1, every cell given a random positive
    /// weight, nothing searched or simulated.
    fn positive(n: u32, rng: &mut crate::game::rng::Rng) -> (Torus, Sensor, BeliefState, Coverage) {
        let torus = Torus::new(n).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let weights: Vec<f64> = (0..n * n)
            .map(|_| crate::game::rng::unit_f64(rng) + 0.01)
            .collect();
        let belief = weighted(&torus, &weights);
        let cov = Coverage::new(torus.cells());
        (torus, sensor, belief, cov)
    }

    #[test]
    fn a_row_of_gains_is_gain_cell_by_cell_bit_for_bit() {
        // Small lattices, where discs wrap onto themselves, radii from a
        // single cell to discs wider than the lattice, uneven masses (some
        // zero), and searched and simulated cover scattered at random.
        let mut rng = crate::game::rng::stream(7, 0);
        for n in [3u32, 4, 5, 8, 13] {
            let torus = Torus::new(n).unwrap();
            let weights: Vec<f64> = (0..n * n)
                .map(|_| match crate::game::rng::below(&mut rng, 4) {
                    0 => 0.0,
                    _ => crate::game::rng::unit_f64(&mut rng),
                })
                .collect();
            for rv in [0.0, 1.0, 1.5, 2.0, 3.0] {
                let sensor = Sensor::new(&torus, rv).unwrap();
                let mut belief = weighted(&torus, &weights);
                let mut cov = Coverage::new(torus.cells());
                let mut row = vec![f64::NAN; n as usize];
                for round in 0..6 {
                    let mut checked = 0;
                    for y in 0..n {
                        cov.gains_row(&sensor, &belief, y, &mut row);
                        for x in 0..n {
                            let want = cov.gain(&sensor, &belief, y * n + x);
                            let got = row[x as usize];
                            if want > 0.0 || got > 0.0 {
                                assert_eq!(
                                    got.to_bits(),
                                    want.to_bits(),
                                    "n {n} rv {rv} round {round} ({x},{y})"
                                );
                                checked += 1;
                            } else {
                                assert_eq!(got, 0.0);
                            }
                        }
                    }
                    assert!(
                        checked > 0 || round > 0,
                        "n {n} rv {rv}: something to compare"
                    );
                    belief.search_around(&sensor, crate::game::rng::below(&mut rng, n * n));
                    cov.cover(&sensor, &belief, crate::game::rng::below(&mut rng, n * n));
                }
            }
        }
    }

    #[test]
    fn the_largest_live_masses_around_a_cell_are_the_box_scanned_cell_by_cell() {
        // Every cell, boxes from the cell alone to wider than the lattice,
        // the box wrapping at every edge; against the cells whose column and
        // row lie within `half` of the cell's on the torus, the largest live
        // mass at each ℓ1 distance (each the whole lattice's when the box
        // wraps onto itself). A box one column short on the left, and rings
        // counted one farther out (tried), fail it.
        let mut rng = crate::game::rng::stream(9, 0);
        let mut rings = Vec::new();
        for n in [3u32, 4, 7, 12] {
            let (torus, sensor, mut belief, mut cov) = positive(n, &mut rng);
            for round in 0..4 {
                for cell in 0..n * n {
                    let (x, y) = torus.xy(cell);
                    for half in 0..=n / 2 + 1 {
                        let box_wraps = 2 * half + 1 >= n;
                        let live = (0..n * n).filter(|&c| !cov.covered(&belief, c));
                        let in_box = live.filter(|&c| {
                            let (cx, cy) = torus.xy(c);
                            box_wraps
                                || (torus.axis_dist(x, cx) <= half
                                    && torus.axis_dist(y, cy) <= half)
                        });
                        let mass = |c: u32| belief.plan_mass()[c as usize];
                        rings.resize(2 * half as usize + 1, f64::NAN);
                        cov.live_max_rings(&belief, n, cell, half, &mut rings);
                        for (d, &got) in rings.iter().enumerate() {
                            let at_d = in_box.clone().filter(|&c| {
                                let (cx, cy) = torus.xy(c);
                                box_wraps
                                    || (torus.axis_dist(x, cx) + torus.axis_dist(y, cy)) as usize
                                        == d
                            });
                            let want = at_d.map(mass).fold(0.0, f64::max);
                            assert_eq!(
                                got, want,
                                "n {n} round {round} cell {cell} half {half} d {d}"
                            );
                        }
                    }
                }
                belief.search_around(&sensor, crate::game::rng::below(&mut rng, n * n));
                cov.cover(&sensor, &belief, crate::game::rng::below(&mut rng, n * n));
            }
        }
    }

    #[test]
    fn a_step_covers_what_cover_does_once_the_disc_it_left_is_covered() {
        // Random walks of simulated steps over random searched cells, on
        // lattices small enough for discs to wrap onto themselves: each
        // step by cover_step marks the same cells in the same order, with
        // the same gain bit for bit, as cover, and step_gain foresees that
        // gain bit for bit.
        let mut rng = crate::game::rng::stream(11, 0);
        for n in [3u32, 4, 5, 9] {
            let torus = Torus::new(n).unwrap();
            let weights: Vec<f64> = (0..n * n)
                .map(|_| crate::game::rng::unit_f64(&mut rng))
                .collect();
            for rv in [0.0, 1.0, 1.5, 2.0, 2.5] {
                let sensor = Sensor::new(&torus, rv).unwrap();
                if rv == 1.0 && n > 3 {
                    for m in Move::ALL {
                        assert_eq!(sensor.front(m, 0).count(), 3, "r_v = 1: a front of three");
                    }
                }
                let mut belief = weighted(&torus, &weights);
                for _ in 0..3 {
                    belief.search_around(&sensor, crate::game::rng::below(&mut rng, n * n));
                }
                let (mut a, mut b) = (Coverage::new(torus.cells()), Coverage::new(torus.cells()));
                let mut pos = crate::game::rng::below(&mut rng, n * n);
                a.cover(&sensor, &belief, pos);
                b.cover(&sensor, &belief, pos);
                for step in 0..40 {
                    let m = Move::from_index(crate::game::rng::below(&mut rng, 4));
                    pos = torus.step(pos, m);
                    let probe = b.step_gain(&sensor, &belief, m, pos);
                    let (ga, gb) = (
                        a.cover(&sensor, &belief, pos),
                        b.cover_step(&sensor, &belief, m, pos),
                    );
                    assert_eq!(ga.to_bits(), gb.to_bits(), "n {n} rv {rv} step {step}");
                    assert_eq!(probe.to_bits(), gb.to_bits(), "step_gain, step {step}");
                    assert_eq!(a.stack, b.stack, "n {n} rv {rv} step {step}");
                }
            }
        }
    }

    #[test]
    fn a_counted_cover_counts_new_cells_with_mass_and_a_disc_is_covered_when_all_its_cells_are() {
        // Against a set of covered cells the test keeps itself, over
        // simulated covers interleaved with real searches, on lattices small
        // enough for discs to wrap. A third of the masses are zero, so the
        // count differs from the number of cells marked.
        let mut rng = crate::game::rng::stream(13, 0);
        for n in [3u32, 4, 6, 9] {
            let torus = Torus::new(n).unwrap();
            let cells = torus.cells();
            let weights: Vec<f64> = (0..n * n)
                .map(|_| match crate::game::rng::below(&mut rng, 3) {
                    0 => 0.0,
                    _ => crate::game::rng::unit_f64(&mut rng),
                })
                .collect();
            for rv in [0.0, 1.0, 2.0] {
                let sensor = Sensor::new(&torus, rv).unwrap();
                let mut belief = weighted(&torus, &weights);
                let (mut a, mut b) = (Coverage::new(cells), Coverage::new(cells));
                let (mut seen, mut simulated) = (vec![false; cells], 0);
                let (mut counted, mut whole) = (0, 0);
                for round in 0..40 {
                    let cell = crate::game::rng::below(&mut rng, n * n);
                    let all_seen = sensor.around(cell).all(|c| seen[c as usize]);
                    assert_eq!(
                        b.disc_covered(&sensor, &belief, cell),
                        all_seen,
                        "n {n} rv {rv} round {round}"
                    );
                    whole += all_seen as u32;
                    if round % 4 == 3 {
                        belief.search_around(&sensor, cell);
                        sensor.around(cell).for_each(|c| seen[c as usize] = true);
                        continue;
                    }
                    let fresh: Vec<u32> =
                        sensor.around(cell).filter(|&c| !seen[c as usize]).collect();
                    let with_mass = fresh
                        .iter()
                        .filter(|&&c| belief.plan_mass()[c as usize] > 0.0)
                        .count() as u32;
                    let ga = a.cover(&sensor, &belief, cell);
                    let (gb, count) = b.cover_counted(&sensor, &belief, cell);
                    assert_eq!(gb.to_bits(), ga.to_bits(), "n {n} rv {rv} round {round}");
                    assert_eq!(count, with_mass, "n {n} rv {rv} round {round}");
                    assert_eq!(b.stack, a.stack, "n {n} rv {rv} round {round}");
                    counted += count;
                    simulated += fresh.len();
                    fresh.iter().for_each(|&c| seen[c as usize] = true);
                    assert!(b.disc_covered(&sensor, &belief, cell));
                    assert_eq!(b.len(), simulated);
                }
                assert!(
                    counted > 0 && whole > 0 && whole < 40,
                    "n {n} rv {rv}: both cases"
                );
                b.clear();
                assert!(b.is_empty());
                for c in 0..n * n {
                    assert_eq!(b.covered(&belief, c), belief.searched()[c as usize] != 0);
                }
            }
        }
    }

    #[test]
    fn the_largest_live_mass_of_each_row_is_the_row_scanned_cell_by_cell() {
        // Row lengths below, at and between multiples of the eight lanes, so
        // a row's largest live mass falls in the lanes and in the tail.
        let mut rng = crate::game::rng::stream(17, 0);
        let mut emptied = 0;
        for n in [3u32, 5, 8, 9, 13, 16, 19] {
            let (_, sensor, mut belief, mut cov) = positive(n, &mut rng);
            let mut rows = vec![f64::NAN; n as usize];
            for round in 0..2 * n {
                cov.live_max_rows(&belief, &mut rows);
                for y in 0..n {
                    let want = (0..n)
                        .map(|x| y * n + x)
                        .filter(|&c| !cov.covered(&belief, c))
                        .map(|c| belief.plan_mass()[c as usize])
                        .fold(0.0, f64::max);
                    let got = cov.live_max_row(&belief, n as usize, y as usize);
                    assert_eq!(got, want, "n {n} round {round} row {y}");
                    assert_eq!(rows[y as usize], want, "n {n} round {round} row {y}");
                    emptied += (want == 0.0) as u32;
                }
                belief.search_around(&sensor, crate::game::rng::below(&mut rng, n * n));
                cov.cover(&sensor, &belief, crate::game::rng::below(&mut rng, n * n));
            }
        }
        assert!(emptied > 0, "some row covered whole");
    }

    #[test]
    fn undo_goes_back_to_its_checkpoint_and_no_further() {
        let torus = Torus::new(9).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let belief = weighted(&torus, &[1.0; 81]);
        let mut cov = Coverage::new(torus.cells());
        assert!(cov.is_empty());
        cov.cover(&sensor, &belief, 0);
        let (outer, first) = (cov.checkpoint(), cov.stack.clone());
        assert_eq!(outer, 5);
        assert!(!cov.is_empty());
        cov.cover(&sensor, &belief, 40);
        let inner = cov.checkpoint();
        cov.cover(&sensor, &belief, 41);
        assert_eq!((inner, cov.len()), (10, 13));
        cov.undo(inner);
        assert_eq!(cov.len(), 10);
        assert!(cov.covered(&belief, 40) && !cov.covered(&belief, 42));
        cov.undo(outer);
        assert_eq!(cov.stack, first);
        assert!(cov.covered(&belief, 1) && !cov.covered(&belief, 40));
        assert_eq!((0..81).filter(|&c| cov.covered(&belief, c)).count(), 5);
    }
}
