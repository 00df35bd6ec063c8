//! The `tree` variant: a real search tree of move sequences from the
//! searcher's position, one node expanded per loop, subtree reuse after
//! each real move, in a bounded arena.

use super::uct::argmax_random;
use super::variant::{note_rollout, rollout_traced, trace_len, LoopEnv, LoopReport, Stats};
use crate::game::lattice::{Move, Torus};
use crate::game::rng;
use crate::param::{Param, ParamKind, Value};
use crate::searchers::decision::{uct_terms, ChildStat, DecisionView};
use crate::searchers::phase::{
    BackupEntry, Candidate, Expansion, PhaseRecord, SelectLevel, SelectRule,
};
use crate::searchers::tree_export::{export_arena, Arena, TreeError, TreeExport, TreeQuery};
use crate::searchers::walks::visit::NoVisit;

const NONE: u32 = u32::MAX;

/// Default arena cap: 131 072 nodes of 32 bytes, twice (live arena plus the
/// scratch arena used when re-rooting) = 8 MiB.
pub const DEFAULT_MAX_NODES: u32 = 1 << 17;
/// The smallest arena: the root and its four children must fit.
pub const MIN_MAX_NODES: u32 = 16;
/// The largest arena cap accepted (2 × 512 MiB).
pub const MAX_MAX_NODES: u32 = 1 << 24;

/// The tree's arena cap.
pub static TREE_NODES: Param = Param {
    key: "tree_nodes",
    label: "Tree node cap",
    kind: ParamKind::Int {
        min: MIN_MAX_NODES as u64,
        max: MAX_MAX_NODES as u64,
    },
    default: Value::Int(DEFAULT_MAX_NODES as u64),
    help: "tree: arena cap in nodes (32 bytes each, twice)",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

#[derive(Clone, Copy, Debug)]
struct Node {
    reward: f64,
    cell: u32,
    visits: u32,
    children: [u32; 4],
}

impl Node {
    fn leaf(cell: u32) -> Node {
        Node {
            reward: 0.0,
            cell,
            visits: 0,
            children: [NONE; 4],
        }
    }
}

/// A search tree rooted at the searcher's cell. The root is always node 0.
#[derive(Debug)]
pub struct Tree {
    nodes: Vec<Node>,
    scratch: Vec<Node>,
    stack: Vec<(u32, u32)>,
    path: Vec<u32>,
    max_nodes: usize,
    selected: [u32; 4],
    /// The loop in flight: the node reached, its depth, whether its cell
    /// detects the practice target, the rollout's outcome.
    node: u32,
    depth: u32,
    terminal: bool,
    steps: u32,
    detected: bool,
}

/// A copy holds the tree, not the scratch room for re-rooting it.
impl Clone for Tree {
    fn clone(&self) -> Tree {
        Tree {
            nodes: self.nodes.clone(),
            scratch: Vec::new(),
            stack: Vec::new(),
            path: self.path.clone(),
            ..*self
        }
    }
}

/// What a tree's counts mean, for people.
const NOTE: &str = "tree: N counts the loops through a node (the root's since it was created, kept across real moves with its subtree); a node's N is 1 more than its children's sum when it was the leaf a loop expanded, or its cell detected the practice target; picks are this decision's selections at the root; a node's UCT split is its parent's selection's terms now (a parent with an untried move expands it first)";

/// The tree as [`Arena`] reads it, with the exploration constant.
struct View<'a>(&'a [Node], f64);

impl Arena for View<'_> {
    fn nodes(&self) -> usize {
        self.0.len()
    }
    fn children(&self, id: u32) -> [u32; 4] {
        self.0[id as usize].children
    }
    fn visits(&self, id: u32) -> u32 {
        self.0[id as usize].visits
    }
    fn cell(&self, id: u32) -> u32 {
        self.0[id as usize].cell
    }
    fn value(&self, id: u32) -> Option<f64> {
        let n = &self.0[id as usize];
        (n.visits > 0).then(|| n.reward / n.visits as f64)
    }
    fn uct(&self, parent: u32, child: u32) -> (f64, f64, f64) {
        weigh(&self.0[parent as usize], &self.0[child as usize], self.1)
    }
}

/// The UCT terms of `child` under `parent`: what selection ranks the
/// children by (and the export shows).
#[inline(always)]
fn weigh(parent: &Node, child: &Node, c: f64) -> (f64, f64, f64) {
    uct_terms(child.reward, child.visits, parent.visits, c)
}

impl Tree {
    /// An empty tree whose arena holds at most `max_nodes` nodes.
    pub fn new(max_nodes: u32) -> Tree {
        Tree {
            nodes: Vec::new(),
            scratch: Vec::new(),
            stack: Vec::new(),
            path: Vec::new(),
            max_nodes: max_nodes.max(MIN_MAX_NODES) as usize,
            selected: [0; 4],
            node: 0,
            depth: 0,
            terminal: false,
            steps: 0,
            detected: false,
        }
    }

    /// Adds each node's visits to its cell in `out` (after zeroing it).
    pub fn project(&self, out: &mut [u32]) {
        out.fill(0);
        for n in &self.nodes {
            out[n.cell as usize] = out[n.cell as usize].saturating_add(n.visits);
        }
    }

    fn select_child(&self, node: u32, env: &mut LoopEnv<'_>) -> Option<usize> {
        let n = &self.nodes[node as usize];
        let mut values = [0.0; 4];
        let mut valid = [false; 4];
        for i in 0..4 {
            if n.children[i] != NONE {
                let ch = &self.nodes[n.children[i] as usize];
                values[i] = weigh(n, ch, env.c).2;
                valid[i] = true;
            }
        }
        argmax_random(values, valid, env.rng)
    }

    /// The four moves at `node` as [`Tree::select_child`] saw them.
    fn candidates(&self, torus: &Torus, node: u32, c: f64) -> [Candidate; 4] {
        let n = &self.nodes[node as usize];
        std::array::from_fn(|i| {
            let m = Move::ALL[i];
            match n.children[i] {
                NONE => Candidate::missing(m, torus.step(n.cell, m)),
                k => {
                    let ch = &self.nodes[k as usize];
                    let stat = ChildStat::new(ch.cell, ch.visits, ch.reward, n.visits, c, 0);
                    Candidate::of(m, &stat, Some(k))
                }
            }
        })
    }

    /// True when `node` has an untried move and the arena has room.
    fn expandable(&self, node: u32) -> bool {
        self.nodes.len() < self.max_nodes && self.nodes[node as usize].children.contains(&NONE)
    }

    /// Steps into `id` (a child of the node reached): the path and trace
    /// grow, and the loop ends there if its cell detects the practice target.
    fn enter(&mut self, env: &mut LoopEnv<'_>, id: u32) {
        self.node = id;
        self.depth += 1;
        self.path.push(id);
        let cell = self.nodes[id as usize].cell;
        if let Some(t) = env.trace.as_deref_mut() {
            t.push(cell);
        }
        self.terminal = env.mask[cell as usize] != 0;
    }
}

impl Stats for Tree {
    /// Starts a decision at `root`, keeping the reused subtree when it is rooted there.
    fn begin_decision(&mut self, _torus: &Torus, root: u32, _reset: bool) {
        if self.nodes.first().map(|n| n.cell) != Some(root) {
            self.nodes.clear();
            self.nodes.push(Node::leaf(root));
        }
        self.selected = [0; 4];
    }

    fn visits<'a>(&'a self, cells: usize, scratch: &'a mut Vec<u32>) -> &'a [u32] {
        scratch.resize(cells, 0);
        self.project(scratch);
        scratch
    }

    /// The decision statistics of the root's children.
    fn view(&self, torus: &Torus, root_cell: u32, c: f64) -> DecisionView {
        let root = self.nodes.first().copied().unwrap_or(Node::leaf(root_cell));
        let children = std::array::from_fn(|i| {
            let cell = torus.step(root.cell, Move::ALL[i]);
            let (v, q) = match root.children[i] {
                NONE => (0, 0.0),
                k => (self.nodes[k as usize].visits, self.nodes[k as usize].reward),
            };
            ChildStat::new(cell, v, q, root.visits, c, self.selected[i])
        });
        DecisionView {
            parent_visits: root.visits,
            c,
            children,
        }
    }

    /// Selection: down by UCT from the root while the node reached has
    /// no untried move (or the arena is full), until a cell detects the
    /// practice target.
    ///
    /// # Panics
    /// If called before [`Stats::begin_decision`].
    fn select(&mut self, env: &mut LoopEnv<'_>, _root: u32, mut rec: Option<&mut PhaseRecord>) {
        self.path.clear();
        self.path.push(0);
        if let Some(t) = env.trace.as_deref_mut() {
            t.clear();
            t.push(self.nodes[0].cell);
        }
        (self.node, self.depth, self.terminal) = (0, 0, false);
        while !self.terminal && !self.expandable(self.node) {
            let node = self.node;
            let Some(i) = self.select_child(node, env) else {
                break;
            };
            if self.depth == 0 {
                self.selected[i] += 1;
            }
            if let Some(r) = rec.as_deref_mut() {
                // Selection changed no statistic the terms read.
                let cands = self.candidates(env.torus, node, env.c);
                let n = &self.nodes[node as usize];
                let level = SelectLevel::new(node, n.cell, n.visits, cands, i, SelectRule::Uct);
                r.select.push(level);
            }
            self.enter(env, self.nodes[node as usize].children[i]);
        }
    }

    /// Expansion: a random untried move of the node reached becomes a
    /// new node (one per loop), unless the loop already ended.
    fn expand(&mut self, env: &mut LoopEnv<'_>, _root: u32, rec: Option<&mut PhaseRecord>) {
        let node = self.node;
        let cur = self.nodes[node as usize];
        let mut miss = [0usize; 4];
        let mut k = 0;
        for i in 0..4 {
            if cur.children[i] == NONE {
                miss[k] = i;
                k += 1;
            }
        }
        if self.terminal || !self.expandable(node) {
            if let Some(r) = rec {
                r.expansion = Some(Expansion {
                    node: None,
                    parent: node,
                    mv: None,
                    cell: cur.cell,
                    untried: k as u8,
                    what: if self.terminal {
                        "nothing is added: the selected node's cell detects the practice target"
                    } else {
                        "nothing is added: the tree has reached its node cap"
                    },
                });
            }
            return;
        }
        let i = miss[rng::below(env.rng, k as u32) as usize];
        let id = self.nodes.len() as u32;
        let cell = env.torus.step(cur.cell, Move::ALL[i]);
        self.nodes.push(Node::leaf(cell));
        self.nodes[node as usize].children[i] = id;
        if self.depth == 0 {
            self.selected[i] += 1;
        }
        self.enter(env, id);
        if let Some(r) = rec {
            r.expansion = Some(Expansion {
                node: Some(id),
                parent: node,
                mv: Some(Move::ALL[i]),
                cell,
                untried: k as u8,
                what: if self.terminal {
                    "a new node, drawn among the untried moves; its cell detects the practice target"
                } else {
                    "a new node, drawn among the untried moves"
                },
            });
        }
    }

    /// The rollout from the node reached (none when its cell detects the
    /// practice target).
    fn roll_out(&mut self, env: &mut LoopEnv<'_>, _root: u32, rec: Option<&mut PhaseRecord>) {
        let from = trace_len(env);
        let (steps, detected) = if self.terminal {
            (0, true)
        } else {
            let from = self.nodes[self.node as usize].cell;
            let (out, _) = rollout_traced(env, from, NoVisit);
            (out.steps, out.detected)
        };
        (self.steps, self.detected) = (steps, detected);
        note_rollout(rec, from, steps, detected);
    }

    /// Backpropagation: each node of the path gets a visit and 1/τ.
    fn back_up(
        &mut self,
        _env: &mut LoopEnv<'_>,
        _root: u32,
        mut rec: Option<&mut PhaseRecord>,
    ) -> LoopReport {
        let (steps, detected) = (self.steps, self.detected);
        // τ counts the tree path plus the rollout; depth ≥ 1 because the
        // root always has a child (the arena holds at least 16 nodes).
        let tau = self.depth + steps;
        let reward = if detected && tau > 0 {
            1.0 / tau as f64
        } else {
            0.0
        };
        for (at, &id) in self.path.iter().enumerate() {
            let n = &mut self.nodes[id as usize];
            let old = (n.visits, n.reward);
            n.visits += 1;
            n.reward += reward;
            if let Some(r) = rec.as_deref_mut() {
                let mean = |v: u32, q: f64| if v == 0 { 0.0 } else { q / v as f64 };
                r.backup.push(BackupEntry {
                    node: id,
                    cell: n.cell,
                    visits: [old.0, n.visits],
                    value: [mean(old.0, old.1), mean(n.visits, n.reward)],
                    picked: at == 1,
                });
            }
        }
        if let Some(r) = rec {
            r.reward = reward;
        }
        LoopReport {
            rollout_steps: steps,
            detected,
            reward,
            counts: true,
        }
    }

    fn tree(
        &self,
        _torus: &Torus,
        _root: u32,
        c: f64,
        q: &TreeQuery,
    ) -> Result<TreeExport, TreeError> {
        export_arena(&View(&self.nodes, c), self.selected, q, NOTE)
    }

    fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.nodes[..]) + std::mem::size_of_val(&self.path[..])
    }

    /// Re-roots the tree at the child reached by `m`, keeping its subtree.
    fn advance(&mut self, m: Move) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let keep = root.children[m as usize];
        if keep == NONE {
            self.nodes.clear();
            return;
        }
        reroot(
            &mut self.nodes,
            &mut self.scratch,
            &mut self.stack,
            keep,
            |n| &mut n.children,
        );
    }
}

/// Re-roots an arena tree at node `keep`: copies its subtree depth-first
/// into `scratch` (root first, child links renumbered), then swaps the two,
/// so the arena holds only what is kept and its old room is reused. Shared
/// by the `tree` and `pomcp` variants, whose nodes differ but link alike
/// (`children`, `u32::MAX` for none).
pub(crate) fn reroot<N: Copy>(
    nodes: &mut Vec<N>,
    scratch: &mut Vec<N>,
    stack: &mut Vec<(u32, u32)>,
    keep: u32,
    children: fn(&mut N) -> &mut [u32; 4],
) {
    scratch.clear();
    stack.clear();
    scratch.push(nodes[keep as usize]);
    stack.push((keep, 0));
    while let Some((old, new)) = stack.pop() {
        let kids = *children(&mut nodes[old as usize]);
        for (i, &k) in kids.iter().enumerate() {
            if k != NONE {
                let id = scratch.len() as u32;
                scratch.push(nodes[k as usize]);
                children(&mut scratch[new as usize])[i] = id;
                stack.push((k, id));
            }
        }
    }
    std::mem::swap(nodes, scratch);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::game::belief::{Belief, BeliefState};
    use crate::searchers::walks::policy::{Policy, PolicyKind};

    /// Runs `loops` loops of `tree` from `root` on the game of a 12-torus
    /// (σ = 2.5, rollouts capped at `cap`), with practice targets from the
    /// prior.
    fn run(tree: &mut Tree, root: u32, loops: u32, cap: u32) -> Config {
        let c = Config::default().with(&[("n", "12"), ("sigma", "2.5")]);
        let mut game = c.game().unwrap();
        let mut belief = BeliefState::new(Belief::Prior, game.prior.clone(), None);
        let mut policy = Policy::new(PolicyKind::Rw, &game.torus, 2.0, 0.2);
        let mut rng = crate::game::rng::stream(9, 0);
        for _ in 0..loops {
            let practice = belief.practice_target(&mut rng);
            game.sensor.arm(practice);
            let mut env = LoopEnv {
                torus: &game.torus,
                belief: &belief,
                sensor: &game.sensor,
                mask: game.sensor.mask(),
                practice,
                policy: &mut policy,
                rng: &mut rng,
                rollout_cap: cap,
                c: c.settings.float(&crate::searchers::mcts::search::C),
                trace: None,
            };
            let report = tree.iterate(&mut env, root);
            assert!(report.counts && report.rollout_steps <= cap);
        }
        c
    }

    #[test]
    fn the_arena_stops_at_its_cap_and_every_loop_passes_a_root_child() {
        let mut tree = Tree::new(MIN_MAX_NODES);
        tree.begin_decision(&Torus::new(12).unwrap(), 5, false);
        run(&mut tree, 5, 300, 50);
        // Full at exactly its cap, then the loops only select.
        assert_eq!(tree.nodes.len(), MIN_MAX_NODES as usize);
        let root = tree.nodes[0];
        let kids = root.children.map(|k| tree.nodes[k as usize]);
        assert_eq!(root.visits, 300);
        assert_eq!(kids.iter().map(|k| k.visits).sum::<u32>(), 300);
        let reward: f64 = kids.iter().map(|k| k.reward).sum();
        assert!((reward - root.reward).abs() < 1e-12 && reward > 0.0);
        assert_eq!(tree.selected, kids.map(|k| k.visits));
        // Caps below the root and its four children are raised to 16.
        assert_eq!(Tree::new(3).max_nodes, MIN_MAX_NODES as usize);
    }

    #[test]
    fn the_visits_layer_adds_each_nodes_visits_to_its_cell() {
        let mut tree = Tree::new(DEFAULT_MAX_NODES);
        tree.begin_decision(&Torus::new(12).unwrap(), 5, false);
        let c = run(&mut tree, 5, 200, 50);
        let cells = (c.n * c.n) as usize;
        let mut want = vec![0u32; cells];
        for n in &tree.nodes {
            want[n.cell as usize] += n.visits;
        }
        // The scratch buffer is resized and cleared first.
        let mut scratch = vec![7u32; 3];
        let got = tree.visits(cells, &mut scratch).to_vec();
        assert_eq!(got, want);
        assert!(got[5] >= 200 && got.iter().filter(|&&v| v > 0).count() > 5);
    }

    #[test]
    fn a_real_move_keeps_the_childs_subtree_as_the_new_tree() {
        let mut tree = Tree::new(DEFAULT_MAX_NODES);
        tree.begin_decision(&Torus::new(12).unwrap(), 5, false);
        run(&mut tree, 5, 200, 50);
        let old = tree.clone();
        let kid = old.nodes[0].children[1];
        tree.advance(Move::ALL[1]);
        // Walk the old subtree and the new tree in step.
        let mut pairs = vec![(kid, 0u32)];
        let mut walked = 0;
        while let Some((o, n)) = pairs.pop() {
            let (was, now) = (old.nodes[o as usize], tree.nodes[n as usize]);
            assert_eq!(
                (now.cell, now.visits, now.reward),
                (was.cell, was.visits, was.reward)
            );
            for i in 0..4 {
                assert_eq!(was.children[i] == NONE, now.children[i] == NONE);
                if was.children[i] != NONE {
                    pairs.push((was.children[i], now.children[i]));
                }
            }
            walked += 1;
        }
        assert_eq!(walked, tree.nodes.len());
        assert!(walked > 1 && walked < old.nodes.len());
        // The next decision keeps it when it starts at its root, and a
        // decision elsewhere starts a new tree.
        let cell = tree.nodes[0].cell;
        tree.begin_decision(&Torus::new(12).unwrap(), cell, false);
        assert_eq!(tree.nodes.len(), walked);
        tree.begin_decision(&Torus::new(12).unwrap(), 5, false);
        assert_eq!(tree.nodes.len(), 1);
        assert_eq!(tree.nodes[0].cell, 5);
        // A move with no child leaves nothing to keep.
        tree.advance(Move::ALL[0]);
        assert!(tree.nodes.is_empty());
    }
}
