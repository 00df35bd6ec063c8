//! The decision's search tree as data, for drawing: nodes in preorder with
//! their parent, move, cell, visits and value, cut to a size a display can
//! lay out (most visited first, a visit threshold, or one line in focus).
//!
//! `tree` and `pomcp` report their real trees; `cells` and `code` report
//! the depth-1 star they select in: the root and its four neighbours.
//! Every node but the root carries its UCT split as its parent's selection
//! would weigh it now, from the variant's own selection rule.

use crate::game::lattice::Move;
use crate::game::named::named_enum;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The most nodes one export may ask for.
pub const MAX_EXPORT_NODES: u32 = 1 << 24;

/// Nodes exported when a query does not say.
pub const DEFAULT_EXPORT_NODES: u32 = 2000;

/// Which part of the tree to export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TreeFocus {
    /// The most visited nodes.
    All,
    /// The best line (the most visited child at every level from the
    /// root) with every child of its nodes.
    Best,
    /// A node's line from the root and its subtree.
    Node(u32),
}

impl<'de> serde::Deserialize<'de> for TreeFocus {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<TreeFocus, D::Error> {
        #[derive(serde::Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Name(String),
            Id(u32),
        }
        match Raw::deserialize(d)? {
            Raw::Name(s) if s == "all" => Ok(TreeFocus::All),
            Raw::Name(s) if s == "best" => Ok(TreeFocus::Best),
            Raw::Name(s) => Err(serde::de::Error::custom(format!(
                "focus must be \"all\", \"best\" or a node id (an integer), got {s:?}"
            ))),
            Raw::Id(id) => Ok(TreeFocus::Node(id)),
        }
    }
}

/// What part of the tree to export, and how much of it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TreeQuery {
    /// At most this many nodes (1..=[`MAX_EXPORT_NODES`]), the most
    /// visited first; a node's line to the root always comes with it.
    pub max_nodes: u32,
    /// Leave out nodes with fewer visits (the root always stays).
    pub min_visits: u32,
    /// Which part of the tree.
    pub focus: TreeFocus,
}

impl Default for TreeQuery {
    fn default() -> TreeQuery {
        TreeQuery {
            max_nodes: DEFAULT_EXPORT_NODES,
            min_visits: 0,
            focus: TreeFocus::All,
        }
    }
}

/// A query the tree cannot answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TreeError {
    /// `max_nodes` outside 1..=[`MAX_EXPORT_NODES`].
    MaxNodes(u32),
    /// A focus on a node the tree does not hold.
    NoNode {
        /// The id asked for.
        id: u32,
        /// How many nodes the tree holds.
        nodes: u32,
    },
}

impl std::fmt::Display for TreeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TreeError::MaxNodes(n) => write!(
                f,
                "tree max_nodes must be an integer in 1..={MAX_EXPORT_NODES}, got {n}"
            ),
            TreeError::NoNode { id, nodes } => write!(
                f,
                "tree focus: node {id} is not in the tree (ids 0..={}); it may have gone with a real move",
                nodes.saturating_sub(1)
            ),
        }
    }
}

impl std::error::Error for TreeError {}

named_enum! {
    /// What an export draws.
    pub enum TreeShape {
        /// A search tree of move sequences.
        Tree = "tree",
        /// The root and its four neighbours (the table variants select at depth 1).
        Star = "star",
    }
}

/// One exported node.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TreeNode {
    /// Its id: the arena index (0 is the root); under a star, 1 + move index.
    pub id: u32,
    /// Its parent's id (`None` at the root).
    pub parent: Option<u32>,
    /// The move from its parent (`None` at the root).
    #[serde(rename = "move")]
    pub mv: Option<Move>,
    /// Its cell.
    pub cell: u32,
    /// Moves from the root.
    pub depth: u32,
    /// N: the loops through it (a table's count, pass-through included).
    pub visits: u32,
    /// Its mean value, as the decision panel shows it (`None` when unvisited).
    pub value: Option<f64>,
    /// Its UCT split as its parent's selection would weigh it now
    /// (`None` at the root): the exploitation term Q/N (0 when unvisited),
    pub mean: Option<f64>,
    /// the exploration term c·sqrt(ln N_parent / N) (∞ when unvisited),
    pub explore: Option<f64>,
    /// and their sum, the UCT value selection ranks the siblings by.
    pub uct: Option<f64>,
    /// The root's children: times selected in this decision.
    pub picks: Option<u32>,
    /// A star's nodes: visits gained in this decision.
    pub gained: Option<u32>,
    /// A star's neighbours: visits gained in this decision from rollouts
    /// passing through, not from being picked (`gained − picks`).
    pub passes: Option<u32>,
    /// Its children in the tree.
    pub children: u8,
    /// Its children the export left out.
    pub hidden: u8,
    /// Exported leaves at or below it (a tidy layout's width).
    pub leaves: u32,
    /// True on the best line (the most visited child at each level).
    pub best: bool,
}

/// The decision's tree, cut to the query.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TreeExport {
    /// A search tree or the table variants' star.
    pub shape: TreeShape,
    /// The nodes in preorder (a parent before its children, children in
    /// `Move::ALL` order).
    pub nodes: Vec<TreeNode>,
    /// Nodes in the whole tree.
    pub total_nodes: u32,
    /// What the counts mean, for people.
    pub note: &'static str,
}

/// A tree kept in an arena, read by [`export_arena`].
pub trait Arena {
    /// Nodes in the arena (all reachable from node 0, the root).
    fn nodes(&self) -> usize;
    /// A node's children by move (`u32::MAX` for none).
    fn children(&self, id: u32) -> [u32; 4];
    /// A node's visits.
    fn visits(&self, id: u32) -> u32;
    /// A node's cell.
    fn cell(&self, id: u32) -> u32;
    /// A node's mean value (`None` when unvisited).
    fn value(&self, id: u32) -> Option<f64>;
    /// The UCT terms `(mean, explore, uct)` of `child` under `parent`, by
    /// the function the variant's selection ranks children with.
    fn uct(&self, parent: u32, child: u32) -> (f64, f64, f64);
}

const NONE: u32 = u32::MAX;

/// The best line: the root, then the most visited child (the first in
/// move order among equals) while it has visits.
fn best_line<A: Arena>(a: &A) -> Vec<u32> {
    let mut line = vec![0u32];
    let mut node = 0u32;
    loop {
        let mut best = None;
        for k in a.children(node) {
            if k != NONE && a.visits(k) > 0 && best.is_none_or(|b| a.visits(k) > a.visits(b)) {
                best = Some(k);
            }
        }
        match best {
            Some(k) => {
                line.push(k);
                node = k;
            }
            None => return line,
        }
    }
}

/// A bit per arena node.
struct Bits(Vec<u64>);

impl Bits {
    fn new(n: usize) -> Bits {
        Bits(vec![0; n.div_ceil(64)])
    }
    fn set(&mut self, i: u32) {
        self.0[i as usize / 64] |= 1 << (i % 64);
    }
    fn get(&self, i: u32) -> bool {
        self.0[i as usize / 64] >> (i % 64) & 1 == 1
    }
    fn count(&self) -> usize {
        self.0.iter().map(|w| w.count_ones() as usize).sum()
    }
}

/// The nodes `q` keeps: the eligible ones (all, or the focus's), with at
/// least `min_visits` (the forced ones whatever their visits), the most
/// visited first up to `max_nodes`. A child never has more visits than its
/// parent, so the kept set holds each kept node's line to the root.
fn keep<A: Arena>(a: &A, q: &TreeQuery, line: &[u32]) -> Result<Bits, TreeError> {
    let n = a.nodes();
    let mut eligible: Option<Bits> = None;
    let mut forced = Bits::new(n);
    forced.set(0);
    match q.focus {
        TreeFocus::All => {}
        TreeFocus::Best => {
            let mut e = Bits::new(n);
            for &id in line {
                forced.set(id);
                e.set(id);
                for k in a.children(id) {
                    if k != NONE {
                        e.set(k);
                    }
                }
            }
            eligible = Some(e);
        }
        TreeFocus::Node(id) => {
            if id as usize >= n {
                return Err(TreeError::NoNode {
                    id,
                    nodes: n as u32,
                });
            }
            let mut parent = vec![NONE; n];
            for p in 0..n as u32 {
                for k in a.children(p) {
                    if k != NONE {
                        parent[k as usize] = p;
                    }
                }
            }
            let mut e = Bits::new(n);
            let mut up = id;
            while up != NONE {
                forced.set(up);
                e.set(up);
                up = parent[up as usize];
            }
            let mut stack = vec![id];
            while let Some(v) = stack.pop() {
                e.set(v);
                stack.extend(a.children(v).into_iter().filter(|&k| k != NONE));
            }
            eligible = Some(e);
        }
    }
    let ok = |id: u32| {
        eligible.as_ref().is_none_or(|e| e.get(id))
            && (forced.get(id) || a.visits(id) >= q.min_visits)
    };
    let mut kept = Bits::new(n);
    let max = q.max_nodes as usize;
    if max >= n {
        // Nothing to rank: every eligible node reached through kept ones.
        let mut stack = vec![0u32];
        while let Some(v) = stack.pop() {
            kept.set(v);
            stack.extend(a.children(v).into_iter().filter(|&k| k != NONE && ok(k)));
        }
        return Ok(kept);
    }
    // Forced nodes first, then by visits, then by id.
    let mut heap = BinaryHeap::new();
    heap.push((true, a.visits(0), Reverse(0u32)));
    let mut count = 0;
    while let Some((_, _, Reverse(v))) = heap.pop() {
        if count == max {
            break;
        }
        kept.set(v);
        count += 1;
        for k in a.children(v) {
            if k != NONE && ok(k) {
                heap.push((forced.get(k), a.visits(k), Reverse(k)));
            }
        }
    }
    Ok(kept)
}

/// Exports an arena tree whose root's children were selected `picks`
/// times this decision, cut by `q`.
///
/// # Errors
/// [`TreeError`] for a `max_nodes` out of range or a focus on a node the
/// tree does not hold.
pub fn export_arena<A: Arena>(
    a: &A,
    picks: [u32; 4],
    q: &TreeQuery,
    note: &'static str,
) -> Result<TreeExport, TreeError> {
    if q.max_nodes == 0 || q.max_nodes > MAX_EXPORT_NODES {
        return Err(TreeError::MaxNodes(q.max_nodes));
    }
    let n = a.nodes();
    if n == 0 {
        return Ok(TreeExport {
            shape: TreeShape::Tree,
            nodes: Vec::new(),
            total_nodes: 0,
            note,
        });
    }
    let line = best_line(a);
    // The whole tree needs no ranking and no set of kept nodes.
    let whole = q.focus == TreeFocus::All && q.min_visits == 0 && q.max_nodes as usize >= n;
    let kept = if whole {
        None
    } else {
        Some(keep(a, q, &line)?)
    };
    let shown = kept.as_ref().map_or(n, |k| k.count());
    let mut on_line = Bits::new(n);
    for &id in &line {
        on_line.set(id);
    }
    let mut nodes: Vec<TreeNode> = Vec::with_capacity(shown);
    let mut parent_at: Vec<u32> = Vec::with_capacity(shown);
    // (id, parent id, index of the parent in `nodes`, move, depth)
    let mut stack = vec![(0u32, NONE, NONE, None::<Move>, 0u32)];
    while let Some((id, parent, at, mv, depth)) = stack.pop() {
        let kids = a.children(id);
        let (mut children, mut shown) = (0u8, 0u8);
        let here = nodes.len() as u32;
        for i in (0..4).rev() {
            let k = kids[i];
            if k == NONE {
                continue;
            }
            children += 1;
            if kept.as_ref().is_none_or(|kept| kept.get(k)) {
                shown += 1;
                stack.push((k, id, here, Some(Move::ALL[i]), depth + 1));
            }
        }
        let visits = a.visits(id);
        let split = (parent != NONE).then(|| a.uct(parent, id));
        nodes.push(TreeNode {
            id,
            parent: (parent != NONE).then_some(parent),
            mv,
            cell: a.cell(id),
            depth,
            visits,
            value: a.value(id),
            mean: split.map(|t| t.0),
            explore: split.map(|t| t.1),
            uct: split.map(|t| t.2),
            picks: (depth == 1).then(|| mv.map_or(0, |m| picks[m as usize])),
            gained: None,
            passes: None,
            children,
            hidden: children - shown,
            leaves: 0,
            best: on_line.get(id),
        });
        parent_at.push(at);
    }
    // A node's leaves: 1 for an exported leaf, else the sum of its
    // children's (children come after their parent in preorder).
    for i in (0..nodes.len()).rev() {
        let leaves = nodes[i].leaves.max(1);
        nodes[i].leaves = leaves;
        if parent_at[i] != NONE {
            nodes[parent_at[i] as usize].leaves += leaves;
        }
    }
    Ok(TreeExport {
        shape: TreeShape::Tree,
        nodes,
        total_nodes: n as u32,
        note,
    })
}

/// One node of a star: the root (`mv` `None`) or a neighbour.
#[derive(Clone, Copy, Debug)]
pub struct StarNode {
    /// The move from the root (`None` for the root).
    pub mv: Option<Move>,
    /// Its cell.
    pub cell: u32,
    /// Its table count.
    pub visits: u32,
    /// Its table mean (`None` when unvisited).
    pub value: Option<f64>,
    /// Visits gained this decision.
    pub gained: u32,
    /// Times selected this decision (neighbours).
    pub picks: u32,
    /// A neighbour's UCT terms `(mean, explore, uct)` as the variant's
    /// selection weighs them now (`None` for the root).
    pub split: Option<(f64, f64, f64)>,
}

/// Exports the table variants' star (`star[0]` the root, `star[1 + i]`
/// the neighbour by move `i`), cut by `q` as a tree of five nodes.
///
/// # Errors
/// [`TreeError`] for a `max_nodes` out of range or a focus beyond node 4.
pub fn export_star(
    star: &[StarNode; 5],
    q: &TreeQuery,
    note: &'static str,
) -> Result<TreeExport, TreeError> {
    if q.max_nodes == 0 || q.max_nodes > MAX_EXPORT_NODES {
        return Err(TreeError::MaxNodes(q.max_nodes));
    }
    // The best neighbour: the most picks this decision, as the final rule
    // `visits` counts them (the first in move order among equals).
    let best = (1..5)
        .filter(|&i| star[i].picks > 0)
        .fold(None, |b: Option<usize>, i| match b {
            Some(j) if star[j].picks >= star[i].picks => Some(j),
            _ => Some(i),
        });
    if let TreeFocus::Node(id) = q.focus {
        if id > 4 {
            return Err(TreeError::NoNode { id, nodes: 5 });
        }
    }
    let mut order: Vec<usize> = (1..5)
        .filter(|&i| match q.focus {
            TreeFocus::Node(id) => id == 0 || id as usize == i,
            _ => q.focus == TreeFocus::Best || star[i].visits >= q.min_visits,
        })
        .collect();
    // Cut to max_nodes, the most visited neighbours kept, in move order.
    if order.len() + 1 > q.max_nodes as usize {
        let mut ranked = order.clone();
        ranked.sort_by_key(|&i| (Reverse(star[i].visits), i));
        ranked.truncate(q.max_nodes as usize - 1);
        order.retain(|i| ranked.contains(i));
    }
    let node = |i: usize| {
        let s = &star[i];
        TreeNode {
            id: i as u32,
            parent: (i > 0).then_some(0),
            mv: s.mv,
            cell: s.cell,
            depth: (i > 0) as u32,
            visits: s.visits,
            value: s.value,
            mean: s.split.map(|t| t.0),
            explore: s.split.map(|t| t.1),
            uct: s.split.map(|t| t.2),
            picks: (i > 0).then_some(s.picks),
            gained: Some(s.gained),
            passes: (i > 0).then(|| s.gained.saturating_sub(s.picks)),
            children: if i == 0 { 4 } else { 0 },
            hidden: if i == 0 { 4 - order.len() as u8 } else { 0 },
            leaves: 1,
            best: i == 0 || Some(i) == best,
        }
    };
    let mut nodes = vec![node(0)];
    nodes.extend(order.iter().map(|&i| node(i)));
    nodes[0].leaves = order.len().max(1) as u32;
    Ok(TreeExport {
        shape: TreeShape::Star,
        nodes,
        total_nodes: 5,
        note,
    })
}

#[cfg(test)]
#[path = "tree_export_tests.rs"]
mod tests;
