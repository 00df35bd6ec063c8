//! One MCTS loop shown a phase at a time: what selection, expansion, the
//! rollout and backpropagation each did, with the numbers, for teaching.
//!
//! An MCTS searcher fills a [`PhaseRecord`] only when its loop is stepped
//! phase by phase (`Searcher::think_phase` with recording on); running
//! loops whole records nothing, so the page's full speed pays nothing.

use crate::game::lattice::Move;
use crate::game::named::named_enum;
use crate::searchers::decision::ChildStat;

named_enum! {
    /// The four phases of an MCTS loop, in order.
    pub enum PhaseKind {
        /// Down the tree by UCT (the practice target is drawn first).
        Select = "select",
        /// One node added below the selected leaf.
        Expand = "expand",
        /// The rollout policy walks from the leaf until it detects the
        /// practice target or reaches its cap.
        Rollout = "rollout",
        /// The reward goes back up the path: visits and values updated.
        Backup = "backup",
    }
}

impl PhaseKind {
    /// The phase after this one in a loop (`None` after back-up).
    pub fn next(self) -> Option<PhaseKind> {
        match self {
            PhaseKind::Select => Some(PhaseKind::Expand),
            PhaseKind::Expand => Some(PhaseKind::Rollout),
            PhaseKind::Rollout => Some(PhaseKind::Backup),
            PhaseKind::Backup => None,
        }
    }
}

/// What one call of `Searcher::think_phase` did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhaseStep {
    /// A phase of an MCTS loop; the back-up of a decision's last loop
    /// also makes the real move.
    Phase(PhaseKind, Option<Move>),
    /// Work that is not a loop's phase: a move of a searcher without loops
    /// (a walk, a planner, an MCTS escaping searched ground) or a slice of
    /// a plan being made (`None`).
    Work(Option<Move>),
}

impl PhaseStep {
    /// The real move made, if any.
    pub fn moved(self) -> Option<Move> {
        match self {
            PhaseStep::Phase(_, m) | PhaseStep::Work(m) => m,
        }
    }

    /// The phase done, if this was one.
    pub fn phase(self) -> Option<PhaseKind> {
        match self {
            PhaseStep::Phase(k, _) => Some(k),
            PhaseStep::Work(_) => None,
        }
    }
}

named_enum! {
    /// How a level of the selection chose its move.
    pub enum SelectRule {
        /// The highest UCT value, ties at random.
        Uct = "uct",
        /// The first neighbour never visited (the `code` variant's
        /// expansion rollouts, which do not count as loops).
        Unvisited = "unvisited",
        /// The plan's next move (the belief MCTS replays its plan once a decision).
        Plan = "plan",
    }
}

/// One of the four moves at a node, as selection saw it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Candidate {
    /// The move.
    #[serde(rename = "move")]
    pub mv: Move,
    /// The cell it leads to.
    pub cell: u32,
    /// The child's node id (`None`: no such child yet, or a table variant).
    pub node: Option<u32>,
    /// N of the child.
    pub visits: u32,
    /// Q/N, the exploitation term.
    pub mean: f64,
    /// c·sqrt(ln N_parent / N), the exploration term (∞ when unvisited).
    pub explore: f64,
    /// mean + explore.
    pub uct: f64,
    /// False for a move selection could not take (no child in the tree).
    pub valid: bool,
}

impl Candidate {
    /// A candidate with the terms of `stat` (a decision panel's row).
    pub fn of(mv: Move, stat: &ChildStat, node: Option<u32>) -> Candidate {
        Candidate {
            mv,
            cell: stat.cell,
            node,
            visits: stat.visits,
            mean: stat.mean,
            explore: stat.explore,
            uct: stat.uct,
            valid: true,
        }
    }

    /// A move with no child to select.
    pub fn missing(mv: Move, cell: u32) -> Candidate {
        Candidate {
            mv,
            cell,
            node: None,
            visits: 0,
            mean: 0.0,
            explore: 0.0,
            uct: f64::NEG_INFINITY,
            valid: false,
        }
    }
}

/// One level of the selection: a node, its four moves, the one taken.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SelectLevel {
    /// The node chosen from (0 is the root).
    pub node: u32,
    /// Its cell.
    pub cell: u32,
    /// Its visits N, the parent count of the exploration terms.
    pub parent_visits: u32,
    /// The moves, in `Move::ALL` order.
    pub candidates: [Candidate; 4],
    /// The move taken.
    pub chosen: Move,
    /// How it was chosen.
    pub rule: SelectRule,
    /// How many valid moves shared the highest UCT (one was drawn at random).
    pub ties: u8,
}

impl SelectLevel {
    /// A level where `chosen` was taken by `rule` among `candidates`.
    pub fn new(
        node: u32,
        cell: u32,
        parent_visits: u32,
        candidates: [Candidate; 4],
        chosen: usize,
        rule: SelectRule,
    ) -> SelectLevel {
        let best = candidates
            .iter()
            .filter(|c| c.valid)
            .map(|c| c.uct)
            .fold(f64::NEG_INFINITY, f64::max);
        let ties = candidates
            .iter()
            .filter(|c| c.valid && c.uct == best)
            .count() as u8;
        SelectLevel {
            node,
            cell,
            parent_visits,
            candidates,
            chosen: Move::ALL[chosen],
            rule,
            ties,
        }
    }
}

/// What the expansion did.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Expansion {
    /// The node added (`None` when nothing was added).
    pub node: Option<u32>,
    /// The node it was added below (the selected leaf).
    pub parent: u32,
    /// The move from the parent (`None` when nothing was added).
    #[serde(rename = "move")]
    pub mv: Option<Move>,
    /// The new node's cell, or the leaf's when nothing was added.
    pub cell: u32,
    /// The parent's untried moves before the expansion (one was drawn).
    pub untried: u8,
    /// What happened, for people.
    pub what: &'static str,
}

/// One node or table entry updated by the back-up.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BackupEntry {
    /// Its node id (for the table variants: 0 the root, 1 + move index a neighbour).
    pub node: u32,
    /// Its cell.
    pub cell: u32,
    /// Visits before and after.
    pub visits: [u32; 2],
    /// Mean value before and after (what the decision panel shows as Q/N).
    pub value: [f64; 2],
    /// True for the root's child this loop selected (a table's other
    /// neighbours gain a visit only when the rollout passes through them).
    pub picked: bool,
}

/// The loop in flight (or just finished), as far as its phases have gone.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct PhaseRecord {
    /// The last phase done.
    pub phase: Option<PhaseKind>,
    /// The practice target this loop chases.
    pub practice: u32,
    /// Selection, root first.
    pub select: Vec<SelectLevel>,
    /// The expansion, once done.
    pub expansion: Option<Expansion>,
    /// The loop's cells: its tree path (root first), then its rollout.
    pub trace: Vec<u32>,
    /// Where the rollout starts in `trace` (the cells before it are the path).
    pub rollout_from: u32,
    /// Steps of the rollout proper.
    pub rollout_steps: u32,
    /// True when the practice target was detected.
    pub detected: bool,
    /// True when the rollout stopped at its step cap (it earns nothing).
    pub truncated: bool,
    /// True when the belief MCTS cut the rollout and charged the rest from
    /// its reference walk.
    pub cut: bool,
    /// The reward (or return) backed up.
    pub reward: f64,
    /// The entries the back-up updated.
    pub backup: Vec<BackupEntry>,
    /// Cells outside the root and its four neighbours that the back-up
    /// (or, under `code`, the rollout) gave a visit: the table variants'
    /// pass-through visits.
    pub others: u32,
    /// False for a rollout that is not one of the decision's loops (the
    /// `code` variant's expansion rollouts).
    pub counts: bool,
}

/// The most chunks a rollout is revealed in.
pub const ROLLOUT_CHUNKS: usize = 24;

impl PhaseRecord {
    /// Starts a new loop's record chasing `practice`.
    pub fn begin(&mut self, practice: u32) {
        self.phase = None;
        self.practice = practice;
        self.select.clear();
        self.expansion = None;
        self.trace.clear();
        self.rollout_from = 0;
        self.rollout_steps = 0;
        self.detected = false;
        self.truncated = false;
        self.cut = false;
        self.reward = 0.0;
        self.backup.clear();
        self.others = 0;
        self.counts = true;
    }

    /// The rollout's cells (after the leaf).
    pub fn rollout(&self) -> &[u32] {
        let from = (self.rollout_from as usize).min(self.trace.len());
        &self.trace[from..]
    }

    /// Where each chunk of the rollout ends (exclusive indices into
    /// [`PhaseRecord::rollout`]): at most [`ROLLOUT_CHUNKS`] chunks of
    /// nearly equal length, so a display can animate any rollout in the
    /// same number of frames.
    pub fn chunks(&self) -> Vec<u32> {
        let len = self.rollout().len();
        let k = len.min(ROLLOUT_CHUNKS);
        (1..=k).map(|i| (len * i).div_ceil(k) as u32).collect()
    }

    /// Heap bytes held (a snapshot copies them).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.select[..])
            + std::mem::size_of_val(&self.trace[..])
            + std::mem::size_of_val(&self.backup[..])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_come_in_order_and_chunks_cover_the_rollout() {
        let order: Vec<PhaseKind> =
            std::iter::successors(Some(PhaseKind::Select), |k| k.next()).collect();
        assert_eq!(order, PhaseKind::ALL);
        let mut r = PhaseRecord::default();
        r.begin(7);
        r.trace = (0..103).collect();
        r.rollout_from = 3;
        let chunks = r.chunks();
        assert_eq!(chunks.len(), ROLLOUT_CHUNKS);
        assert_eq!(*chunks.last().unwrap(), 100);
        assert!(chunks.windows(2).all(|w| w[1] > w[0] && w[1] - w[0] <= 5));
        r.trace.truncate(5);
        assert_eq!(r.chunks(), [1, 2]);
        r.trace.truncate(3);
        assert!(r.chunks().is_empty());
        // Ties count the valid moves at the highest UCT.
        let c = |uct: f64, valid: bool| Candidate {
            uct,
            valid,
            ..Candidate::missing(Move::Up, 0)
        };
        let level = SelectLevel::new(
            0,
            0,
            5,
            [c(1.0, true), c(2.0, true), c(2.0, false), c(2.0, true)],
            1,
            SelectRule::Uct,
        );
        assert_eq!((level.ties, level.chosen), (2, Move::Right));
    }
}
