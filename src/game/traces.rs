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
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        self.ring
            .iter()
            .map(|t| std::mem::size_of_val(&t[..]))
            .sum::<usize>()
            + std::mem::size_of_val(&self.targets[..])
    }

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

#[cfg(test)]
mod tests {
    use super::*;

    /// Records `cells` as one loop's trace chasing `practice`.
    fn record(t: &mut Traces, cells: &[u32], practice: u32) {
        if let Some(slot) = t.slot() {
            slot.clear();
            slot.extend_from_slice(cells);
        }
        t.commit(practice);
    }

    fn kept(t: &Traces) -> Vec<(Vec<u32>, u32)> {
        t.iter().map(|(cells, p)| (cells.to_vec(), p)).collect()
    }

    #[test]
    fn the_ring_keeps_the_newest_traces_newest_first() {
        let mut t = Traces::new(3);
        assert!(kept(&t).is_empty());
        record(&mut t, &[1, 2], 10);
        record(&mut t, &[3], 11);
        assert_eq!(kept(&t), [(vec![3], 11), (vec![1, 2], 10)]);
        // Past its room it overwrites the oldest, round and round.
        for i in 0..7u32 {
            record(&mut t, &[100 + i, 200 + i], 20 + i);
        }
        assert_eq!(
            kept(&t),
            [
                (vec![106, 206], 26),
                (vec![105, 205], 25),
                (vec![104, 204], 24)
            ]
        );
        // A slot holds last round's trace until the loop clears it.
        assert_eq!(t.slot().map(|s| s.clone()), Some(vec![104, 204]));
    }

    #[test]
    fn keeping_none_records_nothing() {
        let mut t = Traces::new(0);
        assert!(t.slot().is_none());
        record(&mut t, &[1, 2], 3);
        assert!(kept(&t).is_empty());
    }
}
