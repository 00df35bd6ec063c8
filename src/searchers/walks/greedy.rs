//! The greedy rollout (beyond the paper): a shortest torus path toward the
//! practice target, with a random move with probability ε.

use crate::game::lattice::{Move, Torus};
use crate::game::rng::{self, Rng};
use crate::param::{Param, ParamKind, Value};

/// The greedy rollout's noise ε.
pub static EPSILON: Param = Param {
    key: "epsilon",
    label: "Greedy noise ε",
    kind: ParamKind::Float {
        min: 0.0,
        max: 1.0,
        min_open: false,
    },
    default: Value::Float(0.2),
    help: "greedy rollout noise ε: the chance of a random move",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// Greedy walk toward a known target.
#[derive(Clone, Debug)]
pub struct Greedy {
    epsilon: f64,
    target: u32,
}

impl Greedy {
    /// A greedy walk with noise `epsilon` in `[0, 1]`.
    pub fn new(epsilon: f64) -> Greedy {
        Greedy { epsilon, target: 0 }
    }

    /// Sets the cell to head for.
    pub fn begin(&mut self, target: u32) {
        self.target = target;
    }

    /// One move: random with probability ε, else uniformly among the moves
    /// that shorten the torus ℓ1 distance.
    pub fn next_move(&mut self, torus: &Torus, rng: &mut Rng, cell: u32) -> Move {
        let (dx, dy) = torus.delta(cell, self.target);
        if (dx == 0 && dy == 0) || rng::chance(rng, self.epsilon) {
            return Move::from_index(rng::below(rng, 4));
        }
        let mx = if dx > 0 { Move::Right } else { Move::Left };
        let my = if dy > 0 { Move::Down } else { Move::Up };
        match (dx != 0, dy != 0) {
            (true, false) => mx,
            (false, true) => my,
            _ => {
                if rng::below(rng, 2) == 0 {
                    mx
                } else {
                    my
                }
            }
        }
    }
}
