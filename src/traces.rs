//! The most recent rollout traces, kept for drawing: each is the cells one
//! MCTS loop passed through, with the practice target it chased.

/// A ring of the last `k` traces.
#[derive(Clone, Debug, Default)]
pub struct Traces {
    ring: Vec<Vec<u32>>,
    targets: Vec<u32>,
    next: usize,
    filled: usize,
}

impl Traces {
    /// Room for `keep` traces (0 keeps none and costs nothing).
    pub fn new(keep: usize) -> Traces {
        Traces {
            ring: vec![Vec::new(); keep],
            targets: vec![0; keep],
            next: 0,
            filled: 0,
        }
    }

    /// The buffer the next loop records into, if traces are kept. The loop
    /// clears it first; [`Traces::commit`] then keeps it.
    pub fn slot(&mut self) -> Option<&mut Vec<u32>> {
        self.ring.get_mut(self.next)
    }

    /// Keeps the trace just recorded, chasing `practice`.
    pub fn commit(&mut self, practice: u32) {
        let k = self.ring.len();
        if k > 0 {
            self.targets[self.next] = practice;
            self.next = (self.next + 1) % k;
            self.filled = (self.filled + 1).min(k);
        }
    }

    /// Kept traces, newest first, each with its practice target.
    pub fn iter(&self) -> impl Iterator<Item = (&[u32], u32)> + '_ {
        let k = self.ring.len();
        (0..self.filled).map(move |i| {
            let slot = (self.next + k - 1 - i) % k;
            (self.ring[slot].as_slice(), self.targets[slot])
        })
    }
}
