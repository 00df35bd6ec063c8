//! The belief MCTS's loop phases but the rollout: selection by UCT,
//! expansion (or the plan's move), backpropagation; and its tree read for
//! export.

use super::count::Count;
use super::node::{Node, NONE};
use super::BeliefTree;
use crate::game::lattice::{Move, Torus};
use crate::game::rng;
use crate::searchers::decision::ChildStat;
use crate::searchers::mcts::variant::LoopEnv;
use crate::searchers::phase::{
    BackupEntry, Candidate, Expansion, PhaseRecord, SelectLevel, SelectRule,
};
use crate::searchers::tree_export::{export_arena, Arena, TreeError, TreeExport, TreeQuery};

/// What the belief MCTS's counts mean, for people.
const NOTE: &str = "pomcp (the belief MCTS): N counts the loops through a node, kept across real moves with its subtree; a node's value is its mean return scaled to [0, 1] (higher is better), as the decision panel shows; picks are this decision's selections at the root; a node's UCT split is its parent's selection's terms now, on the scaled values (a parent with an untried move expands it first, and the root follows the plan on the decision's first loop)";

/// The tree as [`Arena`] reads it, with its values and the exploration
/// constant.
struct View<'a>(&'a BeliefTree, f64);

impl Arena for View<'_> {
    fn nodes(&self) -> usize {
        self.0.nodes.len()
    }
    fn children(&self, id: u32) -> [u32; 4] {
        self.0.nodes[id as usize].children
    }
    fn visits(&self, id: u32) -> u32 {
        self.0.nodes[id as usize].visits
    }
    fn cell(&self, id: u32) -> u32 {
        self.0.nodes[id as usize].cell
    }
    fn value(&self, id: u32) -> Option<f64> {
        let n = &self.0.nodes[id as usize];
        (n.visits > 0).then(|| self.0.value(n))
    }
    fn uct(&self, parent: u32, child: u32) -> (f64, f64, f64) {
        let n = &self.0.nodes;
        self.0
            .weigh(&n[parent as usize], &n[child as usize], self.1)
    }
}

impl BeliefTree {
    /// The tree cut by `q`, with its scaled values and UCT splits at `c`.
    pub(super) fn export(&self, c: f64, q: &TreeQuery) -> Result<TreeExport, TreeError> {
        export_arena(&View(self, c), self.selected, q, NOTE)
    }

    /// The index of the move the plan forces at `node` (the root, while
    /// the decision's loop replays the plan).
    fn forced(&self, torus: &Torus, node: u32) -> Option<usize> {
        if self.replay && node == 0 {
            self.plan_move(torus, self.nodes[node as usize].cell)
        } else {
            None
        }
    }

    /// True when the descent at `node` would add a node (or follow the
    /// plan) rather than select among children by UCT.
    fn expands_at(&self, torus: &Torus, node: u32) -> bool {
        self.forced(torus, node).is_some()
            || (self.nodes.len() < self.max_nodes
                && self.nodes[node as usize].children.contains(&NONE))
    }

    /// The four moves at `node` as [`BeliefTree::select_child`] saw them.
    fn candidates(&self, torus: &Torus, node: u32, c: f64) -> [Candidate; 4] {
        let n = &self.nodes[node as usize];
        std::array::from_fn(|i| {
            let m = Move::ALL[i];
            match n.children[i] {
                NONE => Candidate::missing(m, torus.step(n.cell, m)),
                k => {
                    let ch = &self.nodes[k as usize];
                    let q = self.value(ch) * ch.visits as f64;
                    let stat = ChildStat::new(ch.cell, ch.visits, q, n.visits, c, 0);
                    Candidate::of(m, &stat, Some(k))
                }
            }
        })
    }

    /// Selection: down the tree by UCT from the root while the node
    /// reached is full (or the arena is), until nothing is left to count.
    pub(super) fn descend(
        &mut self,
        env: &mut LoopEnv<'_>,
        count: &mut Count,
        mut rec: Option<&mut PhaseRecord>,
    ) {
        let mut node = 0u32;
        while !count.done() && !self.expands_at(env.torus, node) {
            let Some(i) = self.select_child(node, env) else {
                break;
            };
            if node == 0 {
                self.selected[i] += 1;
            }
            if let Some(r) = rec.as_deref_mut() {
                // Selection changed no statistic the terms read.
                let cands = self.candidates(env.torus, node, env.c);
                let n = &self.nodes[node as usize];
                let level = SelectLevel::new(node, n.cell, n.visits, cands, i, SelectRule::Uct);
                r.select.push(level);
            }
            node = self.nodes[node as usize].children[i];
            self.path.push(node);
            count.advance_to(env, &mut self.cov, self.nodes[node as usize].cell);
        }
        self.node = node;
    }

    /// Expansion: the node reached gets a child by a random untried move
    /// (or the plan's move, while the loop replays the plan).
    pub(super) fn grow(
        &mut self,
        env: &mut LoopEnv<'_>,
        count: &mut Count,
        rec: Option<&mut PhaseRecord>,
    ) {
        let node = self.node;
        let cur = self.nodes[node as usize];
        let k = cur.children.iter().filter(|&&c| c == NONE).count();
        let nothing = |what: &'static str| Expansion {
            node: None,
            parent: node,
            mv: None,
            cell: cur.cell,
            untried: k as u8,
            what,
        };
        if count.done() || !self.expands_at(env.torus, node) {
            if let Some(r) = rec {
                r.expansion = Some(nothing(if count.done() {
                    "nothing is added: the loop has nothing left to count (the practice target is detected and the exact count has ended)"
                } else {
                    "nothing is added: the tree has reached its node cap"
                }));
            }
            return;
        }
        let mut miss = [0usize; 4];
        let mut k = 0;
        for i in 0..4 {
            if cur.children[i] == NONE {
                miss[k] = i;
                k += 1;
            }
        }
        let (i, id, added, what) = if let Some(i) = self.forced(env.torus, node) {
            // The plan's loop: its first cell, then the plan walk uncut.
            if cur.children[i] == NONE {
                if self.nodes.len() >= self.max_nodes {
                    self.replay = false;
                    if let Some(r) = rec {
                        r.expansion = Some(nothing("nothing is added: the tree is full, so the loop no longer replays the plan"));
                    }
                    return;
                }
                let id = self.nodes.len() as u32;
                self.nodes
                    .push(Node::leaf(env.torus.step(cur.cell, Move::ALL[i])));
                self.nodes[node as usize].children[i] = id;
            }
            let added = cur.children[i] == NONE;
            let what = "the plan's next move: this loop replays the plan";
            (i, self.nodes[node as usize].children[i], added, what)
        } else {
            let i = miss[rng::below(env.rng, k as u32) as usize];
            let id = self.nodes.len() as u32;
            self.nodes
                .push(Node::leaf(env.torus.step(cur.cell, Move::ALL[i])));
            self.nodes[node as usize].children[i] = id;
            (i, id, true, "a new node, drawn among the untried moves")
        };
        if node == 0 {
            self.selected[i] += 1;
        }
        self.node = id;
        self.path.push(id);
        let cell = self.nodes[id as usize].cell;
        count.advance_to(env, &mut self.cov, cell);
        if let Some(r) = rec {
            r.expansion = Some(Expansion {
                node: added.then_some(id),
                parent: node,
                mv: Some(Move::ALL[i]),
                cell,
                untried: k as u8,
                what,
            });
        }
    }

    /// Backpropagation: the return `g` to every node of the loop's path.
    pub(super) fn credit(&mut self, g: f64, rec: Option<&mut PhaseRecord>) {
        let before: Option<Vec<(u32, f64)>> = rec.as_ref().map(|_| {
            self.path
                .iter()
                .map(|&id| {
                    let n = &self.nodes[id as usize];
                    (n.visits, self.value(n))
                })
                .collect()
        });
        for &id in &self.path {
            let n = &mut self.nodes[id as usize];
            n.visits += 1;
            n.sum += g;
            n.lo = n.lo.min(g);
            n.hi = n.hi.max(g);
        }
        if let (Some(r), Some(before)) = (rec, before) {
            r.reward = g;
            for (at, (&id, (v0, m0))) in self.path.iter().zip(before).enumerate() {
                let n = &self.nodes[id as usize];
                r.backup.push(BackupEntry {
                    node: id,
                    cell: n.cell,
                    visits: [v0, n.visits],
                    value: [m0, self.value(n)],
                    picked: at == 1,
                });
            }
        }
        self.cov.clear();
        self.update_intent();
    }
}
