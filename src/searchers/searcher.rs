//! The [`Searcher`] trait: who decides each real move, and what it works with.

use super::decision::{DecisionView, MoveScores, Planning};
use super::phase::{PhaseRecord, PhaseStep};
use super::tree_export::{TreeError, TreeExport, TreeQuery};
use crate::game::belief::BeliefState;
use crate::game::budget::Budget;
use crate::game::counters::Counters;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::layer::Layer;
use crate::game::rng::Rng;
use crate::game::traces::Traces;
use crate::param::Settings;

/// What a searcher works with while it decides: the trial's lattice,
/// sensor, belief and random stream, the decision's budget, and where its
/// loops are recorded.
pub struct World<'a> {
    /// The lattice.
    pub torus: &'a Torus,
    /// The detection sensor (MCTS arms it with practice targets).
    pub sensor: &'a mut Sensor,
    /// What is known about the target.
    pub belief: &'a mut BeliefState,
    /// The searcher's random stream.
    pub rng: &'a mut Rng,
    /// The searcher's cell.
    pub pos: u32,
    /// The decision's budget.
    pub budget: &'a mut Budget,
    /// Recent rollout traces, for drawing.
    pub traces: &'a mut Traces,
    /// The episode's rollout counters.
    pub counters: &'a mut Counters,
}

/// Who decides each real move.
pub trait Searcher {
    /// Works on the decision under way for at most `max_loops` loops
    /// (`max_loops` ≥ 1) and returns the move once it is decided. A searcher
    /// that does not deliberate decides at once.
    fn think(&mut self, w: &mut World<'_>, max_loops: u32) -> Option<Move>;

    /// Learns that the real move `m` took the searcher to `pos`.
    fn observe(&mut self, torus: &Torus, m: Move, pos: u32);

    /// The per-cell counts drawn as heat layer `layer`, if this searcher
    /// has them (`scratch` is room for counts it must assemble; none by
    /// default).
    fn counts<'a>(&'a self, layer: Layer, scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        let _ = (layer, scratch);
        None
    }

    /// The decision under way at `pos`, for a searcher that deliberates
    /// (none by default).
    fn decision(&self, torus: &Torus, pos: u32) -> Option<DecisionView> {
        let _ = (torus, pos);
        None
    }

    /// The cells a planner means to enter next, in order (empty for a
    /// searcher that does not plan a path); the page draws it as a layer.
    fn intent(&self) -> &[u32] {
        &[]
    }

    /// How a planner scored the four moves at its last decision, for the
    /// decision panel (`None` for a searcher that does not score moves).
    fn scores(&self) -> Option<MoveScores> {
        None
    }

    /// How far a plan being made has got, while a planner that makes its
    /// plan in slices is making one (`None` otherwise).
    fn planning(&self) -> Option<Planning> {
        None
    }

    /// Works on the decision under way by one phase of a loop (recording
    /// what it did when `record`, see [`Searcher::phase`]). Stepped a phase
    /// at a time or by [`Searcher::think`], loops give the same moves: a
    /// call of `think` first finishes the loop in flight. A searcher
    /// without loops does one call of its work (`think` for one loop).
    fn think_phase(&mut self, w: &mut World<'_>, record: bool) -> PhaseStep {
        let _ = record;
        PhaseStep::Work(self.think(w, 1))
    }

    /// The loop stepped phase by phase with recording on, as far as it has
    /// gone (`None` for a searcher without loops).
    fn phase(&self) -> Option<&PhaseRecord> {
        None
    }

    /// The decision's search tree at `pos`, cut by `q` (`None` for a
    /// searcher without one).
    ///
    /// # Errors
    /// A [`TreeError`] for a query the tree cannot answer.
    fn tree(
        &self,
        torus: &Torus,
        pos: u32,
        q: &TreeQuery,
    ) -> Option<Result<TreeExport, TreeError>> {
        let _ = (torus, pos, q);
        None
    }

    /// A copy of this searcher in its present state, for a snapshot of the
    /// run (`None` when it cannot copy itself: the run is then replayed
    /// from its start).
    fn snapshot(&self) -> Option<Box<dyn Searcher>> {
        None
    }

    /// Heap bytes the searcher holds (what [`Searcher::snapshot`] copies).
    fn heap_bytes(&self) -> usize {
        0
    }
}

/// What a searcher is built from.
pub struct Setup<'a> {
    /// The values of the searchers' parameters.
    pub settings: &'a Settings,
    /// The lattice.
    pub torus: &'a Torus,
    /// The detection sensor.
    pub sensor: &'a Sensor,
    /// The start cell.
    pub start: u32,
    /// The detection radius r_v the sensor was built with.
    pub rv: f64,
    /// The episode's step cap (a planner plans no further).
    pub step_cap: u32,
}
