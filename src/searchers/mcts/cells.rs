//! The `cells` variant: the paper's per-cell statistics and depth-1 selection.
//!
//! Every cell a loop passes through (the searcher's cell, the selected
//! neighbour and each rollout cell, once per loop) gets one visit: the paper
//! adds the result "to the data for each searcher location that the
//! simulation visited". Each such cell is credited with the reward of its
//! own stopping time, as the authors' `BackPropagate` credits each cell with
//! the steps that remained after it: a cell first entered at index k of a
//! loop that detects at index τ (root 0, selected neighbour 1) gets
//! 1/(τ − k + 1), so the selected neighbour gets exactly 1/τ. The
//! searcher's own cell gets the visit (it is N(v), the parent count) but no
//! reward, as in the authors' scripts that raise only its count: were it
//! credited with its best child's returns, its mean would rise above its
//! neighbours' and the searcher would shuttle back to it forever. The table
//! persists across the searcher's moves unless reset each move, as some of
//! the paper's scripts do.
//!
//! **Decay** (beyond the paper): when a move searches cells that hold
//! planning mass, the practice targets come from a new posterior, and part
//! of the table's evidence was earned on targets that are no longer
//! possible: it values searched cells, and with ~10⁵ pass-through visits it
//! outweighs the new evidence for the rest of the trial, trapping the
//! searcher in 2- and 4-cycles (`docs/model.md`, "Departures that keep MCTS
//! out of traps"). Each count is then multiplied by decay^(lost / 1%),
//! where `lost` is the share of the unsearched mass the move searched
//! (rounded down, the reward sum scaled with it so that each mean is
//! kept): old evidence fades with what the belief lost. Searching cells
//! without mass changes no practice target, so at a delta prior nothing
//! fades and the table's means converge as Theorem 1 needs. A decay of 1 is
//! the paper's table exactly; 0 clears it whenever mass is searched.

use super::uct::argmax_random;
use super::variant::{note_rollout, rollout_traced, star, trace_len, LoopEnv, LoopReport, Stats};
use crate::game::lattice::{Move, Torus};
use crate::param::{Param, ParamKind, Value};
use crate::searchers::decision::DecisionView;
use crate::searchers::phase::{
    BackupEntry, Candidate, Expansion, PhaseRecord, SelectLevel, SelectRule,
};
use crate::searchers::tree_export::{export_star, StarNode, TreeError, TreeExport, TreeQuery};
use crate::searchers::walks::visit::Visit;

/// Per-cell MCTS statistics.
#[derive(Clone, Debug)]
pub struct CellTable {
    visits: Vec<u32>,
    reward: Vec<f64>,
    stamp: Vec<u32>,
    epoch: u32,
    /// (cell, index of its first visit) for a loop's distinct cells, in
    /// its first `Mark::len` slots; sized once for the longest possible loop.
    touched: Vec<(u32, u32)>,
    selected: [u32; 4],
    /// Counts are multiplied by this for each 1% of the unsearched mass a
    /// move searches (1 = never).
    decay: f64,
    /// The loop in flight: the selected move and neighbour, the distinct
    /// cells marked, the rollout's steps and outcome.
    pick: usize,
    child: u32,
    marked: usize,
    steps: u32,
    detected: bool,
    /// The decision's root and the counts of its star when it began.
    start: Option<(u32, [u32; 5])>,
}

/// What the table's counts mean, for people.
const NOTE: &str = "cells (the paper's table): N counts every loop that passes through a cell, picked or not, over the whole trial (decayed as searched cells lose the belief's mass); picks are this decision's selections; passes are this decision's pass-through visits; a neighbour's UCT split is the next selection's, from the table's counts with pass-through visits included, as the paper selects";

/// The default decay factor: the share of the table's counts kept for
/// each 1% of the unsearched mass a move searches (`EXPERIMENTS.md`, "The
/// default searcher", has the measurements it was chosen by).
pub const DEFAULT_DECAY: f64 = 0.8;

/// The share of the belief's unsearched mass whose search multiplies the
/// table's counts by `decay` once: 1%.
pub const LOST_UNIT: f64 = 0.01;

/// The factor the table's counts are multiplied by for each 1% of the
/// unsearched mass a move searches.
pub static DECAY: Param = Param {
    key: "decay",
    label: "Table decay",
    kind: ParamKind::Float {
        min: 0.0,
        max: 1.0,
        min_open: false,
    },
    default: Value::Float(DEFAULT_DECAY),
    help: "cells: for each 1% of the unsearched prior mass a move searches, each table count is multiplied by this (rounded down, the mean kept), so statistics fade as their practice targets become impossible, and not at all at a delta prior; 1 keeps them for ever (the paper), 0 clears them whenever mass is searched",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// Records each distinct cell of a loop with the index of its first visit
/// (root 0, selected neighbour 1, rollout move j at j + 1).
///
/// The list is a presized slice with its length in a local, not a `Vec`:
/// in the rollout's inner loop that keeps the length in a register (wasm
/// loops about 1.35× faster). Marking is branch-free (about 1.8× faster
/// loops natively and in wasm): a random walk revisits cells often and at
/// random, so a branch on "first visit?" mispredicts.
struct Mark<'a> {
    stamp: &'a mut [u32],
    epoch: u32,
    /// The list's first slot, and the next free one.
    base: *mut (u32, u32),
    cur: *mut (u32, u32),
    /// One past the list's last slot (checked in debug builds).
    end: *mut (u32, u32),
    _list: core::marker::PhantomData<&'a mut [(u32, u32)]>,
}

impl<'a> Mark<'a> {
    fn new(stamp: &'a mut [u32], epoch: u32, touched: &'a mut [(u32, u32)]) -> Mark<'a> {
        let range = touched.as_mut_ptr_range();
        Mark {
            stamp,
            epoch,
            base: range.start,
            cur: range.start,
            end: range.end,
            _list: core::marker::PhantomData,
        }
    }

    /// Distinct cells marked so far.
    fn len(&self) -> usize {
        // SAFETY: `cur` only moves forward from `base` within one slice.
        unsafe { self.cur.offset_from(self.base) as usize }
    }

    #[inline]
    fn mark(&mut self, cell: u32, index: u32) {
        debug_assert!((cell as usize) < self.stamp.len());
        // SAFETY: every cell comes from the torus, and `iterate` asserts
        // that the table has one stamp per torus cell.
        let s = unsafe { self.stamp.get_unchecked_mut(cell as usize) };
        let new = *s != self.epoch;
        *s = self.epoch;
        debug_assert!(self.cur < self.end);
        // Always write the slot; keep it only for a first visit. A moving
        // pointer, not base + length, saves wasm engines a register.
        // SAFETY: `cur` is `base` + the distinct cells before this one, and
        // there are at most min(cells, cap + 2) < the slice's length:
        // `iterate` sizes it with one spare slot for this unconditional write.
        unsafe {
            self.cur.write((cell, index));
            self.cur = self.cur.add(new as usize);
        }
    }
}

impl Visit for Mark<'_> {
    #[inline]
    fn visit(&mut self, cell: u32, step: u32) {
        self.mark(cell, step + 1);
    }
}

impl CellTable {
    /// An empty table for `cells` cells with the paper's statistics: kept
    /// for the whole trial.
    pub fn new(cells: usize) -> CellTable {
        CellTable::with_decay(cells, 1.0)
    }

    /// An empty table for `cells` cells whose counts are multiplied by
    /// `decay` (clamped to [0, 1]; NaN means 1) whenever the belief changes.
    pub fn with_decay(cells: usize, decay: f64) -> CellTable {
        CellTable {
            visits: vec![0; cells],
            reward: vec![0.0; cells],
            stamp: vec![0; cells],
            epoch: 0,
            touched: Vec::new(),
            selected: [0; 4],
            decay: if decay.is_nan() {
                1.0
            } else {
                decay.clamp(0.0, 1.0)
            },
            pick: 0,
            child: 0,
            marked: 0,
            steps: 0,
            detected: false,
            start: None,
        }
    }

    fn mean(&self, cell: u32) -> f64 {
        let v = self.visits[cell as usize];
        if v == 0 {
            0.0
        } else {
            self.reward[cell as usize] / v as f64
        }
    }
}

impl Stats for CellTable {
    /// Starts a decision; clears the table when `reset`.
    fn begin_decision(&mut self, torus: &Torus, root: u32, reset: bool) {
        if reset {
            self.visits.fill(0);
            self.reward.fill(0.0);
        }
        self.selected = [0; 4];
        self.start = Some((root, star(torus, root).map(|c| self.visits[c as usize])));
    }

    fn advance(&mut self, _m: Move) {}

    /// Fades the table by what the belief lost: each count n becomes
    /// ⌊f·n⌋ with f = decay^(lost / 1%), and its reward sum keeps its mean
    /// (a count that reaches 0 drops its reward). A decay of 1, or nothing
    /// lost, leaves the table as it is.
    fn belief_changed(&mut self, lost: f64) {
        let f = libm::pow(self.decay, lost / LOST_UNIT);
        if f >= 1.0 {
            return;
        }
        for (v, r) in self.visits.iter_mut().zip(&mut self.reward) {
            if *v == 0 {
                continue;
            }
            let kept = libm::floor(*v as f64 * f) as u32;
            *r = if kept == 0 {
                0.0
            } else {
                *r * (kept as f64 / *v as f64)
            };
            *v = kept;
        }
    }

    fn visits<'a>(&'a self, _cells: usize, _scratch: &'a mut Vec<u32>) -> &'a [u32] {
        &self.visits
    }

    /// The decision statistics at `root`.
    fn view(&self, env_torus: &Torus, root: u32, c: f64) -> DecisionView {
        let parent = self.visits[root as usize];
        let table = (&self.visits[..], &self.reward[..]);
        DecisionView::of_table(env_torus, root, c, parent, table, self.selected)
    }

    /// Selection: the neighbour with the highest UCT (unvisited ones
    /// first, their UCT is +∞), ties at random.
    #[inline(always)]
    fn select(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>) {
        let view = self.view(env.torus, root, env.c);
        let values = view.children.map(|ch| ch.uct);
        let a = argmax_random(values, [true; 4], env.rng).unwrap_or(0);
        let child = view.children[a].cell;
        self.selected[a] += 1;
        (self.pick, self.child) = (a, child);
        if let Some(t) = env.trace.as_deref_mut() {
            t.clear();
            t.push(root);
            t.push(child);
        }
        if let Some(r) = rec {
            let candidates =
                std::array::from_fn(|i| Candidate::of(Move::ALL[i], &view.children[i], None));
            let level =
                SelectLevel::new(0, root, view.parent_visits, candidates, a, SelectRule::Uct);
            r.select.push(level);
        }
    }

    /// A depth-1 table grows no tree: a neighbour without an entry gets one.
    #[inline(always)]
    fn expand(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>) {
        if let Some(r) = rec {
            let fresh = self.visits[self.child as usize] == 0;
            let untried = star(env.torus, root)[1..]
                .iter()
                .filter(|&&c| self.visits[c as usize] == 0)
                .count() as u8;
            let mv = Move::ALL[self.pick];
            r.expansion = Some(Expansion {
                node: fresh.then_some(1 + self.pick as u32),
                parent: 0,
                mv: fresh.then_some(mv),
                cell: self.child,
                untried,
                what: if fresh {
                    "the table had no count for this neighbour: this loop gives it its first"
                } else {
                    "nothing is added: the table already counts this neighbour, and a depth-1 search grows no deeper"
                },
            });
        }
    }

    /// The rollout from the selected neighbour, marking each distinct cell
    /// with the index of its first visit.
    // The rollout's own function is faster in wasm (its engines keep the
    // walk's state in registers there) and slower natively: measured by
    // instruction counts (benches/instructions.mjs).
    #[cfg_attr(target_arch = "wasm32", inline(never))]
    #[cfg_attr(not(target_arch = "wasm32"), inline(always))]
    fn roll_out(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>) {
        let child = self.child;
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.fill(0);
            self.epoch = 1;
        }
        // A loop visits at most cap + 2 cells (root, child, the rollout).
        let most = self.stamp.len().min(env.rollout_cap as usize + 2) + 1;
        if self.touched.len() < most {
            self.touched.resize(most, (0, 0));
        }
        // The stamp table is read unchecked in the rollout's inner loop.
        assert_eq!(
            self.stamp.len(),
            env.torus.cells(),
            "table and torus sizes differ"
        );
        let from = trace_len(env);
        let mut mark = Mark::new(&mut self.stamp, self.epoch, &mut self.touched);
        mark.mark(root, 0);
        mark.mark(child, 1);
        let (steps, detected) = if env.mask[child as usize] != 0 {
            (0, true)
        } else {
            let (out, m) = rollout_traced(env, child, mark);
            mark = m;
            (out.steps, out.detected)
        };
        self.marked = mark.len();
        (self.steps, self.detected) = (steps, detected);
        note_rollout(rec, from, steps, detected);
    }

    /// Every distinct cell of the loop gets a visit, and each but the root
    /// the reward of its own stopping time.
    #[inline(always)]
    fn back_up(
        &mut self,
        env: &mut LoopEnv<'_>,
        root: u32,
        rec: Option<&mut PhaseRecord>,
    ) -> LoopReport {
        let (steps, detected) = (self.steps, self.detected);
        let cells = rec.as_ref().map(|_| star(env.torus, root));
        let before = cells.map(|s| s.map(|c| (self.visits[c as usize], self.mean(c))));
        // τ counts the move to the neighbour plus the rollout; a truncated
        // rollout found nothing and earns nothing.
        let tau = 1 + steps;
        let reward = if detected { 1.0 / tau as f64 } else { 0.0 };
        for &(c, k) in &self.touched[..self.marked] {
            self.visits[c as usize] += 1;
            if detected && k > 0 {
                self.reward[c as usize] += 1.0 / (tau + 1 - k) as f64;
            }
        }
        if let (Some(r), Some(cells), Some(before)) = (rec, cells, before) {
            r.reward = reward;
            let mut in_star = 0;
            for i in 0..5 {
                let (c, (v0, m0)) = (cells[i], before[i]);
                let v1 = self.visits[c as usize];
                // The root can be its own neighbour's neighbour only on
                // a torus of side 2: count each cell once.
                if v1 != v0 && !cells[..i].contains(&c) {
                    in_star += 1;
                }
                if v1 != v0 {
                    r.backup.push(BackupEntry {
                        node: i as u32,
                        cell: c,
                        visits: [v0, v1],
                        value: [m0, self.mean(c)],
                        picked: i == 1 + self.pick,
                    });
                }
            }
            r.others = (self.marked - in_star) as u32;
        }
        LoopReport {
            rollout_steps: steps,
            detected,
            reward,
            counts: true,
        }
    }

    fn tree(
        &self,
        torus: &Torus,
        root: u32,
        c: f64,
        q: &TreeQuery,
    ) -> Result<TreeExport, TreeError> {
        let view = self.view(torus, root, c);
        let cells = star(torus, root);
        let start = match self.start {
            Some((r, counts)) if r == root => counts,
            _ => cells.map(|c| self.visits[c as usize]),
        };
        let nodes: [StarNode; 5] = std::array::from_fn(|i| {
            let cell = cells[i];
            let visits = self.visits[cell as usize];
            StarNode {
                mv: (i > 0).then(|| Move::ALL[i - 1]),
                cell,
                visits,
                value: (visits > 0).then(|| self.mean(cell)),
                gained: visits.saturating_sub(start[i]),
                picks: if i > 0 {
                    view.children[i - 1].selected
                } else {
                    0
                },
                // Selection ranks the neighbours by this view's terms.
                split: (i > 0).then(|| {
                    let ch = &view.children[i - 1];
                    (ch.mean, ch.explore, ch.uct)
                }),
            }
        });
        export_star(&nodes, q, NOTE)
    }

    fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.visits[..])
            + std::mem::size_of_val(&self.reward[..])
            + std::mem::size_of_val(&self.stamp[..])
            + std::mem::size_of_val(&self.touched[..])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(decay: f64) -> CellTable {
        let mut t = CellTable::with_decay(4, decay);
        t.visits = vec![0, 1, 10, 1000];
        t.reward = vec![0.0, 0.5, 2.0, 30.0];
        t
    }

    #[test]
    fn a_loops_list_of_marked_cells_holds_every_write() {
        // A loop marks at most cap + 2 distinct cells (root, neighbour,
        // rollout), written into a list sized by the cap when the cap is
        // below the cell count (debug builds check every write's slot).
        // Every test's cap used to exceed the cell count.
        let cells = |settings: &[(&str, &str)]| {
            crate::config::Config::default()
                .with(&[("variant", "cells")])
                .with(settings)
        };
        for cap in [1, 3] {
            let cap_text = cap.to_string();
            let c = cells(&[("rollout_cap", &cap_text), ("seed", "7"), ("loops", "50")]);
            let mut ep = crate::run::episode::Episode::trial(&c, 0).unwrap();
            for _ in 0..5 {
                ep.step_move();
            }
            let n = ep.counters();
            assert!(n.rollouts >= 250, "cap {cap}: {} loops", n.rollouts);
            assert!(n.rollout_steps <= cap as u64 * n.rollouts, "cap {cap}");
        }
        // Bounded by the cell count instead, the list needs its spare slot:
        // with a point sensor a practice target at the searcher's own cell
        // is seen only from there, so a rollout can mark every other cell
        // and then revisit one (a write past the distinct cells).
        let c = cells(&[
            ("n", "3"),
            ("rv", "0"),
            ("rollout_cap", "400"),
            ("loops", "200"),
            ("prior", "uniform"),
            ("belief", "prior"),
        ]);
        let mut ep = crate::run::episode::Episode::trial(&c, 0).unwrap();
        ep.step_move();
        assert!(ep.counters().rollouts >= 200);
    }

    #[test]
    fn decay_fades_counts_and_keeps_means() {
        let mut t = table(0.8);
        t.belief_changed(LOST_UNIT);
        // ⌊0.8·n⌋: a single visit is forgotten, larger counts shrink.
        assert_eq!(t.visits, [0, 0, 8, 800]);
        assert_eq!(t.reward[1], 0.0);
        assert!((t.reward[2] / 8.0 - 0.2).abs() < 1e-15);
        assert!((t.reward[3] / 800.0 - 0.03).abs() < 1e-15);
        // Geometric: ten more changes leave ⌊…⌊800·0.8⌋…⌋ of the count.
        for _ in 0..10 {
            t.belief_changed(LOST_UNIT);
        }
        assert_eq!(t.visits[3], 84);
        assert!((t.reward[3] / 84.0 - 0.03).abs() < 1e-12);
    }

    #[test]
    fn decay_follows_the_share_of_mass_searched() {
        // f = decay^(lost / 1%): 2% lost is two 1% steps, 0.5% half of one,
        // nothing lost keeps the table even at decay 0.
        let mut t = table(0.8);
        t.belief_changed(0.02);
        assert_eq!(t.visits, [0, 0, 6, 640]);
        let mut t = table(0.25);
        t.belief_changed(0.005);
        assert_eq!(t.visits, [0, 0, 5, 500]);
        assert!((t.reward[3] / 500.0 - 0.03).abs() < 1e-15);
        for decay in [0.0, 0.8] {
            let mut t = table(decay);
            t.belief_changed(0.0);
            assert_eq!((t.visits, t.reward), (table(1.0).visits, table(1.0).reward));
        }
    }

    #[test]
    fn decay_one_is_the_papers_table_and_zero_clears_it() {
        let mut keep = table(1.0);
        keep.belief_changed(LOST_UNIT);
        assert_eq!(
            (keep.visits, keep.reward),
            (table(1.0).visits, table(1.0).reward)
        );
        let mut clear = table(0.0);
        clear.belief_changed(LOST_UNIT);
        assert_eq!((clear.visits, clear.reward), (vec![0; 4], vec![0.0; 4]));
        // Out-of-range factors are clamped; NaN keeps the table.
        assert_eq!(CellTable::with_decay(1, f64::NAN).decay, 1.0);
        assert_eq!(CellTable::with_decay(1, 2.0).decay, 1.0);
        assert_eq!(CellTable::with_decay(1, -1.0).decay, 0.0);
    }
}
