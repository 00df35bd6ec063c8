//! A node of the belief MCTS's tree.

/// No child.
pub const NONE: u32 = u32::MAX;

/// A node of the tree: a cell reached by a line of moves from the root,
/// and the returns of the loops through it.
#[derive(Clone, Copy, Debug)]
pub struct Node {
    /// Sum of the returns of the loops through this node.
    pub sum: f64,
    /// Smallest and largest return through this node.
    pub lo: f64,
    pub hi: f64,
    pub cell: u32,
    pub visits: u32,
    pub children: [u32; 4],
}

impl Node {
    pub fn leaf(cell: u32) -> Node {
        Node {
            sum: 0.0,
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            cell,
            visits: 0,
            children: [NONE; 4],
        }
    }
}
