//! The `code` variant: the statistics of the authors' `MCTSgaussian.m`.
//!
//! The paper's text and its code differ (`../shared/paper-code-differences.md`,
//! items 6–12); this variant reproduces the code's selection and statistics
//! on the true N-torus, so that the `paper-code` preset can be compared with
//! the authors' published numbers:
//! * `Nx` counts visits per cell: +1 for the root and for the selected
//!   neighbour each loop, and +1 for **every rollout step** into a cell
//!   (repeats included), so pass-through visits dominate it.
//! * `K(s)` sums the rollout steps of every loop that selected neighbour `s`
//!   (a rollout cut at the cap adds the cap), and `Qx(s)` is refreshed to
//!   `Nx(s)/K(s)` each time `s` is selected. The exploitation term
//!   `Qx/Nx` is then about `1/K(s)`: normalised twice, it shrinks as a child
//!   gets more rollouts, whatever they found.
//! * Before a decision's loops, each neighbour with `Nx = 0` gets one
//!   expansion rollout (up, right, down, left). These are rollouts but not
//!   loops: they do not count against the loop budget, as in the code.
//! * UCT is `Qx/Nx + c·sqrt(|ln Nx(root)| / Nx)`.
//!
//! A rollout that detects its target on the selected cell adds no steps, so
//! `K(s) = 0` and `Qx(s) = ∞`: the code's `1/0`, which makes that neighbour
//! win every later selection. Statistics persist for the whole trial unless
//! reset each move.

use super::uct::argmax_random;
use super::variant::{note_rollout, rollout_traced, star, trace_len, LoopEnv, LoopReport, Stats};
use crate::game::lattice::{Move, Torus};
use crate::searchers::decision::DecisionView;
use crate::searchers::phase::{
    BackupEntry, Candidate, Expansion, PhaseRecord, SelectLevel, SelectRule,
};
use crate::searchers::tree_export::{export_star, StarNode, TreeError, TreeExport, TreeQuery};
use crate::searchers::walks::visit::Visit;

/// Per-cell statistics of the authors' code.
#[derive(Clone, Debug)]
pub struct CodeTable {
    /// `Nx`: visits, pass-through rollout steps included.
    visits: Vec<u32>,
    /// `K`: rollout steps of the loops that selected the cell.
    steps: Vec<u64>,
    /// `Qx`: `Nx/K` as of the cell's last selection (∞ when `K = 0`).
    q: Vec<f64>,
    selected: [u32; 4],
    /// The loop in flight: the neighbour chosen (by move index), whether
    /// the loop counts (not an expansion rollout), the rollout's outcome.
    pick: usize,
    child: u32,
    counts: bool,
    loop_steps: u32,
    detected: bool,
    /// The star's `Nx` and exploitation terms before the rollout (kept
    /// only while a loop is recorded).
    before: [(u32, f64); 5],
    /// The decision's root and the counts of its star when it began.
    start: Option<(u32, [u32; 5])>,
}

/// What the code's counts mean, for people.
const NOTE: &str = "code (the authors' MATLAB statistics): Nx counts the root and the picked neighbour once a loop and every rollout step into a cell, repeats included, over the whole trial; picks are this decision's selections; passes are this decision's visits from rollouts passing through; a neighbour's UCT split is the next selection's, with that loop's root visit counted first as the code does (a neighbour never visited is rolled out from first)";

/// Counts a visit for every rollout step (the code's `Nx(sx1,sy1) += 1`).
struct PassThrough<'a> {
    visits: &'a mut [u32],
}

impl Visit for PassThrough<'_> {
    #[inline]
    fn visit(&mut self, cell: u32, _step: u32) {
        debug_assert!((cell as usize) < self.visits.len());
        // SAFETY: every cell comes from the torus, and `playout` asserts
        // that the table has a count per torus cell.
        unsafe { *self.visits.get_unchecked_mut(cell as usize) += 1 };
    }
}

impl CodeTable {
    /// An empty table for `cells` cells.
    pub fn new(cells: usize) -> CodeTable {
        CodeTable {
            visits: vec![0; cells],
            steps: vec![0; cells],
            q: vec![0.0; cells],
            selected: [0; 4],
            pick: 0,
            child: 0,
            counts: false,
            loop_steps: 0,
            detected: false,
            before: [(0, 0.0); 5],
            start: None,
        }
    }

    /// Visits `root` and `child` and rolls out from `child`, a visit for
    /// every step.
    fn playout(&mut self, env: &mut LoopEnv<'_>, root: u32, child: u32) -> (u32, bool) {
        self.visits[root as usize] += 1;
        self.visits[child as usize] += 1;
        if env.mask[child as usize] != 0 {
            return (0, true);
        }
        // The counts are written unchecked in the rollout's inner loop.
        assert_eq!(
            self.visits.len(),
            env.torus.cells(),
            "table and torus sizes differ"
        );
        let visit = PassThrough {
            visits: &mut self.visits,
        };
        let (out, _) = rollout_traced(env, child, visit);
        (out.steps, out.detected)
    }

    /// The decision statistics at `root` with its count taken as `parent`.
    #[inline(always)]
    fn view_with(&self, torus: &Torus, root: u32, c: f64, parent: u32) -> DecisionView {
        let table = (&self.visits[..], &self.q[..]);
        DecisionView::of_table(torus, root, c, parent, table, self.selected)
    }

    /// What the next loop's selection at `root` reads: the first
    /// neighbour never visited, if any (an expansion rollout, not a loop),
    /// and the view it ranks by, whose parent count includes that loop's
    /// root visit when it is a loop (the code counts it before the UCT
    /// values).
    #[inline(always)]
    fn selection(&self, torus: &Torus, root: u32, c: f64) -> (Option<usize>, DecisionView) {
        // The code tests the neighbours in this order once per move, and a
        // count never returns to 0, so testing here on every call finds
        // them exactly then.
        let unvisited = Move::ALL
            .iter()
            .map(|&m| torus.step(root, m))
            .position(|cell| self.visits[cell as usize] == 0);
        let parent = self.visits[root as usize] + u32::from(unvisited.is_none());
        (unvisited, self.view_with(torus, root, c, parent))
    }

    /// The exploitation term `Qx/Nx` the decision panel shows for `cell`.
    fn mean(&self, cell: u32) -> f64 {
        let v = self.visits[cell as usize];
        if v == 0 {
            0.0
        } else {
            self.q[cell as usize] / v as f64
        }
    }
}

impl Stats for CodeTable {
    fn begin_decision(&mut self, torus: &Torus, root: u32, reset: bool) {
        if reset {
            self.visits.fill(0);
            self.steps.fill(0);
            self.q.fill(0.0);
        }
        self.selected = [0; 4];
        self.start = Some((root, star(torus, root).map(|c| self.visits[c as usize])));
    }

    fn advance(&mut self, _m: Move) {}

    fn visits<'a>(&'a self, _cells: usize, _scratch: &'a mut Vec<u32>) -> &'a [u32] {
        &self.visits
    }

    fn view(&self, torus: &Torus, root: u32, c: f64) -> DecisionView {
        self.view_with(torus, root, c, self.visits[root as usize])
    }

    /// Selection: the first neighbour never visited (an expansion
    /// rollout, not a loop), else the highest UCT with the root's visit
    /// of this loop counted first, as in the code.
    #[inline(always)]
    fn select(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>) {
        let (unvisited, view) = self.selection(env.torus, root, env.c);
        let (a, counts, rule) = match unvisited {
            Some(i) => (i, false, SelectRule::Unvisited),
            None => {
                let a =
                    argmax_random(view.children.map(|ch| ch.uct), [true; 4], env.rng).unwrap_or(0);
                self.selected[a] += 1;
                (a, true, SelectRule::Uct)
            }
        };
        (self.pick, self.child, self.counts) = (a, view.children[a].cell, counts);
        if let Some(t) = env.trace.as_deref_mut() {
            t.clear();
            t.push(root);
            t.push(self.child);
        }
        if let Some(r) = rec {
            r.counts = counts;
            let candidates =
                std::array::from_fn(|i| Candidate::of(Move::ALL[i], &view.children[i], None));
            let level = SelectLevel::new(0, root, view.parent_visits, candidates, a, rule);
            r.select.push(level);
        }
    }

    /// No node is added; a neighbour's first rollout is the code's expansion.
    #[inline(always)]
    fn expand(&mut self, _env: &mut LoopEnv<'_>, _root: u32, rec: Option<&mut PhaseRecord>) {
        if let Some(r) = rec {
            let mv = Move::ALL[self.pick];
            r.expansion = Some(Expansion {
                node: (!self.counts).then_some(1 + self.pick as u32),
                parent: 0,
                mv: (!self.counts).then_some(mv),
                cell: self.child,
                untried: u8::from(!self.counts),
                what: if self.counts {
                    "nothing is added: every neighbour has been rolled out from, and the code searches at depth 1"
                } else {
                    "the code's expansion: a neighbour never visited gets one rollout, which is not one of the decision's loops"
                },
            });
        }
    }

    /// The rollout from the chosen neighbour: the root and the neighbour
    /// get a visit, and so does every cell a rollout step enters.
    #[inline(always)]
    fn roll_out(&mut self, env: &mut LoopEnv<'_>, root: u32, rec: Option<&mut PhaseRecord>) {
        let child = self.child;
        if rec.is_some() {
            self.before = star(env.torus, root).map(|c| (self.visits[c as usize], self.mean(c)));
        }
        let from = trace_len(env);
        let (steps, detected) = self.playout(env, root, child);
        (self.loop_steps, self.detected) = (steps, detected);
        note_rollout(rec, from, steps, detected);
    }

    /// The chosen neighbour's `K` and `Qx`.
    #[inline(always)]
    fn back_up(
        &mut self,
        env: &mut LoopEnv<'_>,
        root: u32,
        rec: Option<&mut PhaseRecord>,
    ) -> LoopReport {
        let (steps, detected) = (self.loop_steps, self.detected);
        let c = self.child as usize;
        self.steps[c] += steps as u64;
        // The code's Qx = 1/Kx with Kx = K/Nx; K = 0 gives 1/0 = ∞.
        self.q[c] = if self.steps[c] == 0 {
            f64::INFINITY
        } else {
            self.visits[c] as f64 / self.steps[c] as f64
        };
        let tau = 1 + steps;
        let reward = if detected { 1.0 / tau as f64 } else { 0.0 };
        if let Some(r) = rec {
            r.reward = reward;
            let cells = star(env.torus, root);
            let mut in_star = 0;
            for i in 0..5 {
                let (cell, (v0, m0)) = (cells[i], self.before[i]);
                let v1 = self.visits[cell as usize];
                if v1 != v0 && !cells[..i].contains(&cell) {
                    in_star += v1 - v0;
                }
                if v1 != v0 || (i == 1 + self.pick) {
                    r.backup.push(BackupEntry {
                        node: i as u32,
                        cell,
                        visits: [v0, v1],
                        value: [m0, self.mean(cell)],
                        picked: i == 1 + self.pick,
                    });
                }
            }
            // Every rollout adds 2 visits (root and neighbour) and one a step.
            r.others = (2 + steps).saturating_sub(in_star);
        }
        LoopReport {
            rollout_steps: steps,
            detected,
            reward,
            counts: self.counts,
        }
    }

    fn tree(
        &self,
        torus: &Torus,
        root: u32,
        c: f64,
        q: &TreeQuery,
    ) -> Result<TreeExport, TreeError> {
        // The terms the next loop's selection reads (its picks are the view's).
        let (_, view) = self.selection(torus, root, c);
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
            + std::mem::size_of_val(&self.steps[..])
            + std::mem::size_of_val(&self.q[..])
    }
}

#[cfg(test)]
mod tests {
    use crate::config::Config;
    use crate::game::layer::Layer;
    use crate::run::episode::{Episode, Status};

    #[test]
    fn a_decision_counts_its_own_selections_and_a_reset_clears_the_table() {
        // Every rollout adds 2 visits (root and neighbour) and one per
        // rollout step, expansions included, so the table's total is
        // 2 × rollouts + rollout steps: over the whole trial when the
        // table persists, over the decision under way when it is reset.
        for reset in [false, true] {
            let c = Config::default().with(&[
                ("variant", "code"),
                ("loops", "10"),
                ("reset_each_move", if reset { "1" } else { "0" }),
                ("seed", "5"),
            ]);
            let mut ep = Episode::new(&c).unwrap();
            let mut scratch = Vec::new();
            let mut total = |ep: &Episode| -> u64 {
                let v = ep.counts(Layer::Visits, &mut scratch).unwrap();
                v.iter().map(|&x| u64::from(x)).sum()
            };
            for _ in 0..3 {
                assert_eq!(ep.step_move(), Status::Running);
            }
            let before = ep.counters();
            ep.step_loops(4);
            let now = ep.counters();
            let (rollouts, steps) = if reset {
                (
                    now.rollouts - before.rollouts,
                    now.rollout_steps - before.rollout_steps,
                )
            } else {
                (now.rollouts, now.rollout_steps)
            };
            assert!(now.rollouts > before.rollouts + 3, "reset {reset}");
            assert_eq!(total(&ep), 2 * rollouts + steps, "reset {reset}");
            // The panel's selections are this decision's loops alone.
            let view = ep.decision().unwrap();
            let selected: u32 = view.children.iter().map(|ch| ch.selected).sum();
            assert_eq!(selected, 4, "reset {reset}");
        }
    }
}
