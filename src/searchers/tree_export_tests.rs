//! The export's cuts on a tree built by hand.

use super::*;

/// Nodes as (children by move, visits); cell = id, value = visits / 100.
struct Hand(Vec<([u32; 4], u32)>);

impl Arena for Hand {
    fn nodes(&self) -> usize {
        self.0.len()
    }
    fn children(&self, id: u32) -> [u32; 4] {
        self.0[id as usize].0
    }
    fn visits(&self, id: u32) -> u32 {
        self.0[id as usize].1
    }
    fn cell(&self, id: u32) -> u32 {
        id
    }
    fn value(&self, id: u32) -> Option<f64> {
        let v = self.visits(id);
        (v > 0).then(|| v as f64 / 100.0)
    }
    /// Names the pair, so a test sees which parent the export asked about.
    fn uct(&self, parent: u32, child: u32) -> (f64, f64, f64) {
        let (p, c) = (parent as f64, child as f64);
        (p, c, p + c)
    }
}

const X: u32 = u32::MAX;

/// root 0 (10 visits): up → 1 (6), right → 2 (3), left → 3 (0);
/// 1: down → 4 (4), left → 5 (1); 4: up → 6 (2).
fn hand() -> Hand {
    Hand(vec![
        ([1, 2, X, 3], 10),
        ([X, X, 4, 5], 6),
        ([X; 4], 3),
        ([X; 4], 0),
        ([6, X, X, X], 4),
        ([X; 4], 1),
        ([X; 4], 2),
    ])
}

fn ids(e: &TreeExport) -> Vec<u32> {
    e.nodes.iter().map(|n| n.id).collect()
}

fn query(max_nodes: u32, min_visits: u32, focus: TreeFocus) -> TreeQuery {
    TreeQuery {
        max_nodes,
        min_visits,
        focus,
    }
}

#[test]
fn the_whole_tree_comes_in_preorder_with_layout_widths() {
    let e = export_arena(&hand(), [5, 3, 0, 2], &TreeQuery::default(), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4, 6, 5, 2, 3]);
    assert_eq!(e.total_nodes, 7);
    let by = |id: u32| e.nodes.iter().find(|n| n.id == id).unwrap();
    assert_eq!((by(0).parent, by(0).mv, by(0).depth), (None, None, 0));
    assert_eq!(
        (by(4).parent, by(4).mv, by(4).depth),
        (Some(1), Some(Move::Down), 2)
    );
    // Leaves: 6, 5, 2 and 3; node 1 spans two of them.
    assert_eq!((by(0).leaves, by(1).leaves, by(4).leaves), (4, 2, 1));
    // Picks only at the root's children; no value without visits.
    assert_eq!(
        (by(1).picks, by(3).picks, by(4).picks),
        (Some(5), Some(2), None)
    );
    assert_eq!((by(3).value, by(2).value), (None, Some(0.03)));
    // The best line: 0, 1 (6 of 10), 4, 6.
    let best: Vec<u32> = e.nodes.iter().filter(|n| n.best).map(|n| n.id).collect();
    assert_eq!(best, [0, 1, 4, 6]);
    assert!(e.nodes.iter().all(|n| n.hidden == 0));
}

#[test]
fn cuts_keep_the_most_visited_nodes_with_their_lines() {
    // Four nodes: 0 (10), 1 (6), 4 (4), 2 (3); their parents come along.
    let e = export_arena(&hand(), [0; 4], &query(4, 0, TreeFocus::All), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4, 2]);
    let by = |id: u32| e.nodes.iter().find(|n| n.id == id).unwrap();
    assert_eq!((by(0).hidden, by(1).hidden, by(4).hidden), (1, 1, 1));
    // A threshold of 3 visits drops 3, 5 and 6.
    let e = export_arena(&hand(), [0; 4], &query(100, 3, TreeFocus::All), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4, 2]);
    // The root stays whatever the threshold.
    let e = export_arena(&hand(), [0; 4], &query(100, 1000, TreeFocus::All), "n").unwrap();
    assert_eq!(ids(&e), [0]);
}

#[test]
fn a_focus_shows_a_line_or_a_subtree() {
    // The best line with its nodes' children.
    let e = export_arena(&hand(), [0; 4], &query(100, 0, TreeFocus::Best), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4, 6, 5, 2, 3]);
    let e = export_arena(&hand(), [0; 4], &query(100, 2, TreeFocus::Best), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4, 6, 2]);
    // Node 4: its line (0, 1) and its subtree (6), whatever the threshold.
    let e = export_arena(&hand(), [0; 4], &query(100, 5, TreeFocus::Node(4)), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4]);
    let e = export_arena(&hand(), [0; 4], &query(100, 0, TreeFocus::Node(4)), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 4, 6]);
    // A node that is not there, and sizes out of range.
    assert_eq!(
        export_arena(&hand(), [0; 4], &query(100, 0, TreeFocus::Node(7)), "n"),
        Err(TreeError::NoNode { id: 7, nodes: 7 })
    );
    let msg = TreeError::NoNode { id: 7, nodes: 7 }.to_string();
    assert!(msg.contains("node 7") && msg.contains("0..=6"), "{msg}");
    assert_eq!(
        export_arena(&hand(), [0; 4], &query(0, 0, TreeFocus::All), "n"),
        Err(TreeError::MaxNodes(0))
    );
}

#[test]
fn a_query_reads_from_json_strictly() {
    let q: TreeQuery = serde_json::from_str(r#"{"max_nodes": 9, "focus": "best"}"#).unwrap();
    assert_eq!(q, query(9, 0, TreeFocus::Best));
    let q: TreeQuery = serde_json::from_str(r#"{"focus": 12}"#).unwrap();
    assert_eq!(q.focus, TreeFocus::Node(12));
    assert_eq!(
        serde_json::from_str::<TreeQuery>("{}").unwrap(),
        TreeQuery::default()
    );
    for bad in [
        r#"{"focus": "root"}"#,
        r#"{"focus": -1}"#,
        r#"{"maxNodes": 3}"#,
    ] {
        assert!(serde_json::from_str::<TreeQuery>(bad).is_err(), "{bad}");
    }
}

#[test]
fn a_star_shows_picks_and_passes() {
    let s = |mv: Option<Move>, visits, gained, picks| StarNode {
        mv,
        cell: 0,
        visits,
        value: Some(0.5),
        gained,
        picks,
        split: mv.map(|m| (m as u32 as f64, 1.0, m as u32 as f64 + 1.0)),
    };
    let star = [
        s(None, 40, 10, 0),
        s(Some(Move::Up), 30, 9, 6),
        s(Some(Move::Right), 12, 5, 4),
        s(Some(Move::Down), 2, 2, 0),
        s(Some(Move::Left), 0, 0, 0),
    ];
    let e = export_star(&star, &TreeQuery::default(), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 2, 3, 4]);
    assert_eq!(e.shape, TreeShape::Star);
    // Up gained 9 this decision: 6 picks and 3 rollouts passing through.
    assert_eq!((e.nodes[1].picks, e.nodes[1].passes), (Some(6), Some(3)));
    assert_eq!((e.nodes[3].picks, e.nodes[3].passes), (Some(0), Some(2)));
    assert_eq!(e.nodes[0].passes, None);
    // Each neighbour carries its own split; the root none.
    assert_eq!((e.nodes[0].mean, e.nodes[0].uct), (None, None));
    for n in &e.nodes[1..] {
        let m = n.mv.unwrap() as u32 as f64;
        assert_eq!(
            (n.mean, n.explore, n.uct),
            (Some(m), Some(1.0), Some(m + 1.0))
        );
    }
    let best: Vec<u32> = e.nodes.iter().filter(|n| n.best).map(|n| n.id).collect();
    assert_eq!(best, [0, 1]);
    let e = export_star(&star, &query(3, 0, TreeFocus::All), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 2]);
    assert_eq!(e.nodes[0].hidden, 2);
    let e = export_star(&star, &query(10, 10, TreeFocus::All), "n").unwrap();
    assert_eq!(ids(&e), [0, 1, 2]);
    let e = export_star(&star, &query(10, 0, TreeFocus::Node(3)), "n").unwrap();
    assert_eq!(ids(&e), [0, 3]);
    assert!(export_star(&star, &query(10, 0, TreeFocus::Node(5)), "n").is_err());
}

#[test]
fn every_node_but_the_root_carries_the_split_its_parent_weighs() {
    for q in [
        TreeQuery::default(),
        query(4, 0, TreeFocus::All),
        query(100, 0, TreeFocus::Node(4)),
    ] {
        let e = export_arena(&hand(), [0; 4], &q, "n").unwrap();
        assert!(e.nodes.len() > 1);
        for n in &e.nodes {
            match n.parent {
                None => assert_eq!((n.mean, n.explore, n.uct), (None, None, None)),
                Some(p) => assert_eq!(
                    (n.mean, n.explore, n.uct),
                    (Some(p as f64), Some(n.id as f64), Some((p + n.id) as f64)),
                    "{q:?}"
                ),
            }
        }
    }
}
