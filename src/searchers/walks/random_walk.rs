//! The simple random walk: each step is one of the four moves, uniformly.

use super::visit::{Outcome, Visit};
use crate::game::lattice::{Move, Torus};
use crate::game::rng::{self, Rng};

/// Uniform random walk (no state).
#[derive(Clone, Copy, Debug, Default)]
pub struct RandomWalk;

impl RandomWalk {
    /// One uniformly random move.
    #[inline]
    pub fn next_move(&mut self, rng: &mut Rng) -> Move {
        Move::from_index((rng::bits(rng) >> 62) as u32)
    }

    /// Walks from `start` until `mask` marks the cell or `cap` moves.
    ///
    /// The hot loop: 2 random bits per step from one 64-bit draw, the
    /// neighbour table instead of modular arithmetic, one byte load for
    /// detection, no allocation.
    ///
    /// # Panics
    /// If `mask` is shorter than the lattice.
    #[inline]
    pub fn rollout<V: Visit>(
        &mut self,
        torus: &Torus,
        mask: &[u8],
        rng: &mut Rng,
        start: u32,
        cap: u32,
        visit: &mut V,
    ) -> Outcome {
        let nbr = torus.neighbours();
        assert!(mask.len() >= torus.cells() && (start as usize) < torus.cells());
        if mask[start as usize] != 0 {
            return Outcome {
                steps: 0,
                detected: true,
            };
        }
        // `p` is 4 × the current cell: the next cell's table row is one
        // load away, with no multiply on the dependency chain.
        let mut p = 4 * start as usize;
        let mut steps = 0u32;
        while steps < cap {
            let end = steps + (cap - steps).min(32);
            let mut b = rng::bits(rng);
            // One counter, the move number, also ends the chunk: a second
            // one (moves left) cost wasm engines a register and a spill.
            while steps != end {
                // SAFETY: `p / 4` starts in range and every table entry is
                // 4 × a cell index < cells() ≤ mask.len() (asserted above), so
                // `p + (b & 3) < 4 * cells() = nbr.len()` and `p >> 2 < mask.len()`.
                unsafe {
                    p = *nbr.get_unchecked(p + (b & 3) as usize) as usize;
                    // Every entry is 4 × a cell: saying so lets a visitor
                    // that indexes by cell use `p` as the byte offset.
                    core::hint::assert_unchecked(p % 4 == 0);
                    b >>= 2;
                    steps += 1;
                    visit.visit((p >> 2) as u32, steps);
                    if *mask.get_unchecked(p >> 2) != 0 {
                        return Outcome {
                            steps,
                            detected: true,
                        };
                    }
                }
            }
        }
        Outcome {
            steps: cap,
            detected: false,
        }
    }
}
