//! Counters of the rollouts a run makes.

/// Rollout counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Counters {
    /// Rollouts (MCTS loops) run.
    pub rollouts: u64,
    /// Unit moves made by rollouts.
    pub rollout_steps: u64,
    /// Rollouts cut short by the rollout cap.
    pub truncated: u64,
}

impl Counters {
    /// Counts one rollout of `steps` moves; `detected` is false when it was cut short.
    pub fn add(&mut self, steps: u32, detected: bool) {
        self.rollouts += 1;
        self.rollout_steps += steps as u64;
        self.truncated += (!detected) as u64;
    }
}

impl std::ops::AddAssign for Counters {
    fn add_assign(&mut self, o: Counters) {
        self.rollouts += o.rollouts;
        self.rollout_steps += o.rollout_steps;
        self.truncated += o.truncated;
    }
}
