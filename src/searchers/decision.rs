//! What a searcher reports about the decision under way, for the page's
//! decision panel: MCTS's statistics of the four moves with their UCT
//! terms, a planner's move scores, and how far a plan being made has got.

use crate::game::lattice::{Move, Torus};

/// The statistics of one of the four moves at the decision under way.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ChildStat {
    /// The cell the move leads to.
    pub cell: u32,
    /// N(v_i): visits of the child.
    pub visits: u32,
    /// Q(v_i): summed reward 1/τ.
    pub reward: f64,
    /// Q/N, the exploitation term (0 when unvisited).
    pub mean: f64,
    /// c·sqrt(ln N_parent / N_child), the exploration term (∞ when unvisited).
    pub explore: f64,
    /// mean + explore.
    pub uct: f64,
    /// Times this move was selected in the current decision.
    pub selected: u32,
}

impl ChildStat {
    /// The statistics of a child with `visits` and summed `reward` under a
    /// parent with `parent_visits`, selected `selected` times this decision.
    pub fn new(
        cell: u32,
        visits: u32,
        reward: f64,
        parent_visits: u32,
        c: f64,
        selected: u32,
    ) -> ChildStat {
        let (mean, explore, uct) = uct_terms(reward, visits, parent_visits, c);
        ChildStat {
            cell,
            visits,
            reward,
            mean,
            explore,
            uct,
            selected,
        }
    }
}

/// A snapshot of the decision under way.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct DecisionView {
    /// N(v): visits of the parent (the searcher's cell or the root node).
    pub parent_visits: u32,
    /// The exploration constant.
    pub c: f64,
    /// Per move, in `Move::ALL` order (up, right, down, left).
    pub children: [ChildStat; 4],
}

impl DecisionView {
    /// The view at `root` of a table kept per cell (`visits` and summed
    /// `reward`, indexed by cell): each move's child is its neighbour's
    /// entry, under a parent count of `parent`.
    #[inline(always)]
    pub fn of_table(
        torus: &Torus,
        root: u32,
        c: f64,
        parent: u32,
        (visits, reward): (&[u32], &[f64]),
        selected: [u32; 4],
    ) -> DecisionView {
        let children = std::array::from_fn(|i| {
            let cell = torus.step(root, Move::ALL[i]);
            let (v, q) = (visits[cell as usize], reward[cell as usize]);
            ChildStat::new(cell, v, q, parent, c, selected[i])
        });
        DecisionView {
            parent_visits: parent,
            c,
            children,
        }
    }
}

/// The UCT terms `(mean, explore, uct)` of a child.
#[inline]
pub fn uct_terms(reward: f64, visits: u32, parent_visits: u32, c: f64) -> (f64, f64, f64) {
    if visits == 0 {
        return (0.0, f64::INFINITY, f64::INFINITY);
    }
    let mean = reward / visits as f64;
    let lnp = libm::log(parent_visits.max(1) as f64);
    let explore = c * libm::sqrt(lnp / visits as f64);
    (mean, explore, mean + explore)
}

/// How far a plan being made has got, for people: the stage and, where it
/// has a known length, the steps done of it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Planning {
    /// What is being done (e.g. "beam search, depth").
    pub stage: &'static str,
    /// Steps of the stage done.
    pub done: u32,
    /// Steps in the stage (0 when not known ahead).
    pub total: u32,
    /// True for work every move's decision does (rollout improvement's
    /// completions), false for a plan made once before the moves (the beam).
    pub per_move: bool,
    /// How far the step under way has got, in `inner_unit` (0 and "" when
    /// the stage does not say): a completion of rollout improvement takes
    /// seconds on a large lattice, so its moves show the work going on.
    pub inner: u32,
    /// What `inner` counts, for people.
    pub inner_unit: &'static str,
}

impl Planning {
    /// The progress of a plan made once before the moves: `done` of `total`
    /// steps of `stage`, nothing finer.
    pub fn plan(stage: &'static str, done: u32, total: u32) -> Planning {
        Planning {
            stage,
            done,
            total,
            per_move: false,
            inner: 0,
            inner_unit: "",
        }
    }
}

/// A planner's score of each of the four moves (in `Move::ALL` order) and
/// what the score means, so the page can explain the choice without
/// computing anything.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MoveScores {
    /// What a score is, for people (e.g. "mass covered in 4 moves").
    pub meaning: &'static str,
    /// True when a larger score is better.
    pub higher_is_better: bool,
    /// The score per move (NaN for a move that was not scored).
    pub score: [f64; 4],
    /// The move taken, by index in `Move::ALL`.
    pub chosen: u8,
}
