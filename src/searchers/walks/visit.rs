//! What a walk reports: how a rollout ended, and every cell it enters.

/// How a rollout ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// Unit moves made.
    pub steps: u32,
    /// False when the step cap cut the rollout short.
    pub detected: bool,
}

/// Receives every cell a rollout enters, in order.
pub trait Visit {
    /// Called once per unit move with the cell entered and the move's
    /// number `step` (1 for the first move of the rollout).
    fn visit(&mut self, cell: u32, step: u32);
}

/// A visitor that records nothing (the fastest rollout).
pub struct NoVisit;

impl Visit for NoVisit {
    #[inline(always)]
    fn visit(&mut self, _: u32, _: u32) {}
}

impl Visit for Vec<u32> {
    #[inline]
    fn visit(&mut self, cell: u32, _: u32) {
        self.push(cell);
    }
}
