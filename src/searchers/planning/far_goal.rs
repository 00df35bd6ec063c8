//! The far-goal scans: where to head when nothing near adds planning mass.
//! [`fallback_target`] ranks cells by the uncovered mass in their disc per
//! step of distance, [`cell_goal`] by a cell's own mass per step; both skip
//! the rows that cannot win, so their result is that of a full scan.
//!
//! Every quantity here is a planning quantity: mass is the belief's
//! planning mass, "covered" means searched for real or by the simulation.
//! For a path `p_0, p_1, …` from the current cell the expected number of
//! further moves until detection, given no detection so far, is
//! proportional to `Σ_{t≥1} R_t` (`R_t`: planning mass left after `t`
//! simulated moves): see `crate::analysis::bound`. Planners compare paths by that sum.

use crate::game::belief::BeliefState;
use crate::game::coverage::Coverage;
use crate::game::lattice::{wrap_once, Move, Sensor, Torus};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// The planning mass of each cell, 0 where searched: what a plan made
/// from here has left to find.
pub fn mass_left(belief: &BeliefState) -> Vec<f64> {
    belief
        .plan_mass()
        .iter()
        .zip(belief.searched())
        .map(|(&m, &s)| if s == 0 { m } else { 0.0 })
        .collect()
}

/// The planning mass in the disc around `cell` that is not covered yet.
#[inline]
pub fn disc_gain(sensor: &Sensor, belief: &BeliefState, cov: &Coverage, cell: u32) -> f64 {
    cov.gain(sensor, belief, cell)
}

/// Scratch for [`fallback_target`] and [`cell_goal`], and the work its
/// scans have done in
/// [`crate::searchers::planning::completion::SLICE_WORK`]'s units (a unit is about what a
/// simulated lookahead move costs): one per [`ROW_CELLS_PER_UNIT`] cells of
/// the rows scanned, and one per [`BOUND_CELLS_PER_UNIT`] cells of the
/// rows whose maxima it reads and terms of the rows' bounds.
///
/// A caller that scans again and again while the uncovered mass only
/// shrinks (a horizon-rule completion, move after move) may say so by
/// passing the scan the run it continues (from [`FarScan::new_run`]): the
/// scan then keeps each row's largest uncovered mass, and its largest
/// disc gain, from the scans before as bounds (both can only have fallen),
/// and reads a row's masses afresh only when the mass bound would not let
/// a row it reaches, and has not summed yet in the run, be skipped. The
/// result is that of a scan from scratch (a row skipped by either bound
/// holds no cell that could win).
#[derive(Clone, Debug, Default)]
pub struct FarScan {
    buf: Vec<f64>,
    /// Each row's largest uncovered mass, read at the scan of `fresh`'s
    /// stamp or before, under the run `kept_for`.
    rows: Vec<f64>,
    fresh: Vec<u32>,
    /// Each row's largest disc gain when [`fallback_target`] last summed
    /// the row's gains under the run `kept_for` (+∞ before): gains only
    /// fall within a run, so it bounds the row's gains from above.
    gains: Vec<f64>,
    stamp: u32,
    kept_for: Option<u64>,
    /// Work units done since last taken.
    pub work: u64,
}

impl FarScan {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.buf[..])
            + size_of_val(&self.rows[..])
            + size_of_val(&self.fresh[..])
            + size_of_val(&self.gains[..])
    }

    /// A run number no other run in the process has. A scan given a run
    /// says that since the last scan of that run with this scratch (if
    /// any), cells have only been covered or searched, on the same
    /// lattice, belief and sensor.
    pub fn new_run() -> u64 {
        RUNS.fetch_add(1, Relaxed)
    }

    /// Begins a scan of an `n`-wide lattice and returns its stamp: keeps
    /// the rows' maxima when the scan continues their `run`, else reads
    /// them all (and counts the work).
    fn begin(&mut self, belief: &BeliefState, cov: &Coverage, n: usize, run: Option<u64>) -> u32 {
        self.stamp = self.stamp.wrapping_add(1);
        let stamp = self.stamp;
        // (A stamp that has wrapped round reads every row afresh.)
        let reuse = run.is_some() && run == self.kept_for && self.rows.len() == n && stamp != 0;
        self.kept_for = run;
        if !reuse {
            self.rows.resize(n, 0.0);
            self.fresh.clear();
            self.fresh.resize(n, stamp);
            self.gains.clear();
            self.gains.resize(n, f64::INFINITY);
            cov.live_max_rows(belief, &mut self.rows);
            self.work += ((n * n) as u64).div_ceil(BOUND_CELLS_PER_UNIT);
        }
        stamp
    }
}

/// Runs of far-goal scans begun so far in the process.
static RUNS: AtomicU64 = AtomicU64::new(0);

/// The rows of an `n`-wide lattice nearest `py` first: py, py + 1, py − 1,
/// py + 2, …, each once (the order both goal scans visit rows in, so a
/// nearer row's value is found before farther rows are bounded by it).
fn rows_nearest(n: u32, py: u32) -> impl Iterator<Item = u32> {
    let (n, py) = (n as i32, py as i32);
    (0..n).map(move |k| {
        let step = (k + 1) / 2;
        wrap_once(n, py + if k % 2 == 1 { step } else { -step }) as u32
    })
}

/// Cells of the bounds' pass per work unit: a compare a cell, eight at a
/// time (timed with `torus-search bench --moves`' plan slices).
pub const BOUND_CELLS_PER_UNIT: u64 = 32;

/// Cells of a scanned row per work unit: a row sums the disc offset by
/// offset over whole rows, which vectorises.
pub const ROW_CELLS_PER_UNIT: u64 = 8;

/// The fallback target: the cell maximising (uncovered planning mass in its
/// disc) ÷ (torus ℓ1 distance from `pos` + 1), with that value; `None` when
/// no mass is left, or when `beat` is given and no cell's value exceeds
/// it. Ties go to the lower cell index.
///
/// Rows are visited nearest first, and a row is skipped when a bound on its
/// values (the largest uncovered mass of each row the disc reaches, summed
/// over the disc, ÷ the row's distance + 1) is below the best value found
/// or not above `beat`. The bound holds bit for bit, so the result is that
/// of a full scan. One pass over the lattice for the bounds, then a row of
/// gains at a time ([`Coverage::gains_row`]) for the rows not skipped:
/// O(N² · disc) at worst. `scan` is scratch the caller keeps, so the scan
/// allocates nothing, and counts the work done in it; `run`, if given, is
/// the run the scan continues ([`FarScan`]).
#[allow(clippy::too_many_arguments)]
pub fn fallback_target(
    torus: &Torus,
    sensor: &Sensor,
    belief: &BeliefState,
    cov: &Coverage,
    pos: u32,
    beat: Option<f64>,
    scan: &mut FarScan,
    run: Option<u64>,
) -> Option<(u32, f64)> {
    let n = torus.n();
    let nu = n as usize;
    let (px, py) = torus.xy(pos);
    let stamp = scan.begin(belief, cov, nu, run);
    // The row's gains, and each column's distance from `pos` (small
    // integers, so sums of them as f64 are exact).
    scan.buf.resize(2 * nu, 0.0);
    let (gains, cols) = scan.buf.split_at_mut(nu);
    let (live, fresh, kept) = (&mut scan.rows, &mut scan.fresh, &mut scan.gains);
    for (x, d) in (0..n).zip(cols.iter_mut()) {
        *d = torus.axis_dist(px, x) as f64;
    }
    // Rows a disc reaches lie within n of the lattice: one correction
    // wraps them, without a division (a scan wraps every row's disc rows,
    // and divisions were most of its cost once it kept its rows' maxima).
    let wrap = |v: i32| wrap_once(n as i32, v) as usize;
    // Summed in the sensor's order from +0.0, as `gains_row` sums: with
    // every row read at this scan, bit for bit the bound of a scan from
    // scratch; with older reads, no smaller (rounding is monotone).
    let bound = |live: &[f64], y: u32| {
        let mut s = 0.0;
        for &(_, dy) in sensor.offsets() {
            s += live[wrap(y as i32 + dy)];
        }
        s
    };
    // Every row's bound is summed (a compare's worth a term, as the pass
    // over the lattice counts).
    let terms = n as u64 * sensor.offsets().len() as u64;
    scan.work += terms.div_ceil(BOUND_CELLS_PER_UNIT);
    let mut best: Option<(u32, f64)> = None;
    let skip = |top: f64, best: Option<(u32, f64)>| {
        best.is_some_and(|(_, b)| top < b) || beat.is_some_and(|f| top <= f)
    };
    for y in rows_nearest(n, py) {
        let dy = torus.axis_dist(py, y) as f64 + 1.0;
        // No value in the row exceeds its largest gain ÷ dy: the gain kept
        // from the row's last sum in this run bounds it, and so does the
        // sum of its disc rows' largest masses.
        let top = kept[y as usize];
        if skip(top / dy, best) || skip(bound(live, y) / dy, best) {
            continue;
        }
        // Only a row not summed yet in this run reads its disc rows'
        // masses afresh, for a tighter bound before it is summed: a row
        // summed before is bounded by its kept gain, which fresher masses
        // seldom beat (reading them cost more than the sums they saved).
        let mut read = false;
        if top == f64::INFINITY {
            for &(_, oy) in sensor.offsets() {
                let r = wrap(y as i32 + oy);
                if fresh[r] != stamp {
                    fresh[r] = stamp;
                    live[r] = cov.live_max_row(belief, nu, r);
                    scan.work += (n as u64).div_ceil(BOUND_CELLS_PER_UNIT);
                    read = true;
                }
            }
        }
        if read && skip(bound(live, y) / dy, best) {
            continue;
        }
        cov.gains_row(sensor, belief, y, gains);
        scan.work += (n as u64).div_ceil(ROW_CELLS_PER_UNIT);
        let mut most = 0.0;
        for ((x, &g), &dx) in (0..n).zip(gains.iter()).zip(cols.iter()) {
            most = if g > most { g } else { most };
            if g <= 0.0 {
                continue;
            }
            let v = g / (dx + dy);
            if beat.is_some_and(|f| v <= f) {
                continue;
            }
            let c = y * n + x;
            if best.is_none_or(|(bc, b)| v > b || (v == b && c < bc)) {
                best = Some((c, v));
            }
        }
        kept[y as usize] = most;
    }
    best
}

/// A move from `pos` that shortens the torus ℓ1 distance to `target`: along
/// the axis with the longer way to go (x on a tie); `fallback` when already
/// there.
#[inline]
pub fn toward(torus: &Torus, pos: u32, target: u32, fallback: Move) -> Move {
    let (dx, dy) = torus.delta(pos, target);
    if dx == 0 && dy == 0 {
        fallback
    } else if dx.abs() >= dy.abs() {
        if dx > 0 {
            Move::Right
        } else {
            Move::Left
        }
    } else if dy > 0 {
        Move::Down
    } else {
        Move::Up
    }
}

/// The move that undoes `m`.
#[inline]
pub fn reverse(m: Move) -> Move {
    Move::from_index(m as u32 + 2)
}

/// The uncovered cell with positive mass maximising mass ÷ (distance + 1)
/// (cheaper than [`fallback_target`]: one cell, not a disc, per candidate);
/// ties go to the lower cell index. `scan` is scratch, whose rows' maxima
/// it keeps when `run` says the scan continues their run, as
/// [`fallback_target`] does ([`FarScan`]).
///
/// Rows are visited nearest first, and a row is skipped when its largest
/// uncovered mass ÷ (its distance + 1), which no value in it exceeds (bit
/// for bit: division is monotone), is below the best value found: the
/// rows' maxima come from one branch-free pass (or from the scan before,
/// a row read afresh only when its old maximum would not skip it), then a
/// division only for the cells of the rows that can win.
pub fn cell_goal(
    torus: &Torus,
    belief: &BeliefState,
    cov: &Coverage,
    pos: u32,
    scan: &mut FarScan,
    run: Option<u64>,
) -> Option<u32> {
    let mass = belief.plan_mass();
    let n = torus.n();
    let nu = n as usize;
    let (px, py) = torus.xy(pos);
    let stamp = scan.begin(belief, cov, nu, run);
    let mut best: Option<(u32, f64)> = None;
    for y in rows_nearest(n, py) {
        let (yu, dy) = (y as usize, torus.axis_dist(py, y));
        let beaten = |m: f64| best.is_some_and(|(_, b)| m / (dy as f64 + 1.0) < b);
        if beaten(scan.rows[yu]) {
            continue;
        }
        if scan.fresh[yu] != stamp {
            scan.fresh[yu] = stamp;
            scan.rows[yu] = cov.live_max_row(belief, nu, yu);
            scan.work += (n as u64).div_ceil(BOUND_CELLS_PER_UNIT);
            if beaten(scan.rows[yu]) {
                continue;
            }
        }
        scan.work += (n as u64).div_ceil(ROW_CELLS_PER_UNIT);
        let row = yu * nu;
        for x in 0..n {
            let c = row + x as usize;
            let m = mass[c];
            if m <= 0.0 || cov.covered(belief, c as u32) {
                continue;
            }
            // The torus ℓ1 distance, summed from each axis's.
            let v = m / ((torus.axis_dist(px, x) + dy) as f64 + 1.0);
            let c = c as u32;
            if best.is_none_or(|(bc, b)| v > b || (v == b && c < bc)) {
                best = Some((c, v));
            }
        }
    }
    best.map(|(c, _)| c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::belief::Belief;
    use crate::game::prior::{PriorSpec, TargetPrior};
    use crate::game::rng;

    /// The scan without bounds: every row in order, every cell compared.
    fn full_scan(
        torus: &Torus,
        sensor: &Sensor,
        belief: &BeliefState,
        cov: &Coverage,
        pos: u32,
    ) -> Option<(u32, f64)> {
        let n = torus.n();
        let mut gains = vec![0.0; n as usize];
        let mut best: Option<(u32, f64)> = None;
        for y in 0..n {
            cov.gains_row(sensor, belief, y, &mut gains);
            for (x, &g) in gains.iter().enumerate() {
                let c = y * n + x as u32;
                let v = g / (torus.l1(pos, c) + 1) as f64;
                if g > 0.0 && best.is_none_or(|(_, b)| v > b) {
                    best = Some((c, v));
                }
            }
        }
        best
    }

    #[test]
    fn the_pruned_cell_goal_is_the_full_scan_of_cells() {
        // Every cell in index order, as the goal was found before rows were
        // skipped: the same cell on priors full of ties (uniform, painted
        // in four levels) and smooth ones, as ever more is searched and
        // simulated, from random cells; and with the rows' maxima kept
        // from scan to scan, for less work.
        let full = |torus: &Torus, belief: &BeliefState, cov: &Coverage, pos: u32| {
            let mut best: Option<(u32, f64)> = None;
            for (c, &m) in belief.plan_mass().iter().enumerate() {
                if m <= 0.0 || cov.covered(belief, c as u32) {
                    continue;
                }
                let v = m / (torus.l1(pos, c as u32) as f64 + 1.0);
                if best.is_none_or(|(_, b)| v > b) {
                    best = Some((c as u32, v));
                }
            }
            best.map(|(c, _)| c)
        };
        let mut r = rng::stream(13, 0);
        let (mut checked, mut some, mut runs) = (0, 0, 0);
        let (mut work, mut kept_work) = (0, 0);
        for n in [3u32, 4, 7, 12, 40] {
            let torus = Torus::new(n).unwrap();
            let cells = torus.cells();
            let sensor = Sensor::new(&torus, 1.0).unwrap();
            let paint: Vec<f64> = (0..cells).map(|_| rng::below(&mut r, 4) as f64).collect();
            for spec in [
                PriorSpec::Uniform,
                PriorSpec::Weights { weights: paint },
                PriorSpec::Gaussian { sigma: 2.0 },
            ] {
                let prior = TargetPrior::new(&torus, &spec).unwrap();
                let mut belief = BeliefState::new(Belief::Posterior, prior, None);
                let mut cov = Coverage::new(cells);
                // A second scratch keeps its rows' maxima through a run,
                // which a cleared simulation ends.
                let (mut scan, mut kept) = (FarScan::default(), FarScan::default());
                runs += 1;
                for i in 0..2 * cells {
                    if i == cells / 2 {
                        cov.clear();
                        runs += 1;
                    }
                    let pos = rng::below(&mut r, cells as u32);
                    let want = full(&torus, &belief, &cov, pos);
                    let got = cell_goal(&torus, &belief, &cov, pos, &mut scan, None);
                    assert_eq!(got, want, "n {n}, {spec:?}, pos {pos}");
                    let got = cell_goal(&torus, &belief, &cov, pos, &mut kept, Some(runs));
                    assert_eq!(got, want, "kept: n {n}, {spec:?}, pos {pos}");
                    work += std::mem::take(&mut scan.work);
                    kept_work += std::mem::take(&mut kept.work);
                    checked += 1;
                    some += want.is_some() as u32;
                    let c = rng::below(&mut r, cells as u32);
                    if rng::below(&mut r, 2) == 0 {
                        belief.search_around(&sensor, c);
                    } else {
                        cov.cover(&sensor, &belief, c);
                    }
                }
            }
        }
        assert!(
            checked > 10_000 && some > checked / 2,
            "{some} of {checked}"
        );
        assert!(kept_work * 10 < work * 9, "{kept_work} against {work}");
    }

    /// The pruned scan returns the full scan's cell and value, bit for bit,
    /// and with `beat` the same cell exactly when its value exceeds `beat`:
    /// on priors full of ties (uniform, painted levels 0–3), where skipping a
    /// row whose bound only equals the best would lose a lower-index tie,
    /// and on Gaussians, over random searched sets, simulations and
    /// positions, at two sensor radii and on odd and even lattices.
    #[test]
    fn the_pruned_far_goal_scan_is_the_full_scan() {
        // A second scratch is given the run each scan continues (the mass
        // has only shrunk since its last scan) and keeps its
        // rows' maxima from scan to scan: the same results, for less work.
        // Where the simulation is cleared (mass comes back), a new run
        // begins, which reads every row afresh.
        let mut r = rng::stream(11, 0);
        let mut checked = 0;
        let (mut work, mut kept_work) = (0, 0);
        let mut runs = 0;
        for n in [3u32, 4, 7, 12, 40] {
            let torus = Torus::new(n).unwrap();
            let cells = torus.cells();
            let paint: Vec<f64> = (0..cells).map(|_| rng::below(&mut r, 4) as f64).collect();
            let specs = [
                PriorSpec::Uniform,
                PriorSpec::Weights { weights: paint },
                PriorSpec::Gaussian { sigma: 2.0 },
                PriorSpec::Gaussian {
                    sigma: n as f64 / 4.0,
                },
            ];
            for spec in &specs {
                for rv in [1.0, 2.5] {
                    let sensor = Sensor::new(&torus, rv).unwrap();
                    let prior = TargetPrior::new(&torus, spec).unwrap();
                    let mut belief = BeliefState::new(Belief::Posterior, prior, None);
                    let mut cov = Coverage::new(cells);
                    let (mut scan, mut kept) = (FarScan::default(), FarScan::default());
                    runs += 1;
                    // Ever more searched and simulated, to the end of the mass,
                    // but for the simulation cleared once on the way.
                    for i in 0..4 * cells {
                        if i == cells {
                            cov.clear();
                            runs += 1;
                        }
                        let pos = rng::below(&mut r, cells as u32);
                        let want = full_scan(&torus, &sensor, &belief, &cov, pos);
                        let beats = match want {
                            Some((_, v)) => [0.0, v * 0.5, v, v * 1.5],
                            None => [0.0; 4],
                        };
                        for beat in std::iter::once(None).chain(beats.map(Some)) {
                            for (s, keep) in [(&mut scan, false), (&mut kept, true)] {
                                let got = fallback_target(
                                    &torus,
                                    &sensor,
                                    &belief,
                                    &cov,
                                    pos,
                                    beat,
                                    s,
                                    keep.then_some(runs),
                                );
                                let want = want.filter(|&(_, v)| beat.is_none_or(|f| v > f));
                                assert_eq!(
                                    got, want,
                                    "n {n}, {spec:?}, r_v {rv}, pos {pos}, beat {beat:?}, kept {keep}"
                                );
                            }
                        }
                        work += std::mem::take(&mut scan.work);
                        kept_work += std::mem::take(&mut kept.work);
                        checked += 1;
                        let c = rng::below(&mut r, cells as u32);
                        if rng::below(&mut r, 2) == 0 {
                            belief.search_around(&sensor, c);
                        } else {
                            cov.cover(&sensor, &belief, c);
                        }
                    }
                }
            }
        }
        assert!(checked > 10_000);
        assert!(kept_work * 10 < work * 9, "{kept_work} against {work}");
    }
}
