//! The path a planner made and follows.

use crate::game::lattice::Torus;

/// The path a planner made and follows (the beam and spiral planners):
/// the cells still to enter, and whether the searcher is on it.
#[derive(Clone, Debug, Default)]
pub struct PlannedPath {
    cells: Vec<u32>,
    next: usize,
    /// False until a plan is made, and again once the searcher leaves it.
    held: bool,
}

impl PlannedPath {
    /// Starts a new plan, followed from its first cell: returns its cells,
    /// cleared, for the caller to fill.
    pub fn start(&mut self) -> &mut Vec<u32> {
        self.cells.clear();
        self.next = 0;
        self.held = true;
        &mut self.cells
    }

    /// True when the plan's next cell is a move away from `pos`.
    pub fn on_plan(&self, torus: &Torus, pos: u32) -> bool {
        self.held && self.next_cell().is_some_and(|c| torus.l1(pos, c) == 1)
    }

    /// True when the whole plan has been walked.
    pub fn walked(&self) -> bool {
        self.held && self.next >= self.cells.len()
    }

    /// The next cell to enter, if the plan has one left.
    pub fn next_cell(&self) -> Option<u32> {
        self.cells.get(self.next).copied()
    }

    /// The searcher entered `pos`: the plan moves on, or is left.
    pub fn observe(&mut self, pos: u32) {
        if self.next_cell() == Some(pos) {
            self.next += 1;
        } else {
            self.held = false;
        }
    }

    /// The cells still to enter.
    pub fn ahead(&self) -> &[u32] {
        &self.cells[self.next.min(self.cells.len())..]
    }
}
