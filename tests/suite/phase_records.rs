//! What each phase reports agrees with the statistics: selection takes the
//! highest UCT with the decision panel's terms, expansion adds the node
//! the tree then holds, the rollout's trace is its steps, and back-up
//! adds one visit along the path (under `cells`, to every cell the loop
//! passed through; under `code`, to every rollout step).

use std::collections::BTreeSet;
use torus_search::config::Config;
use torus_search::run::episode::{Episode, Status};
use torus_search::searchers::phase::{PhaseKind, PhaseRecord, PhaseStep, SelectRule};
use torus_search::searchers::tree_export::{TreeFocus, TreeQuery};
use wasm_bindgen_test::wasm_bindgen_test;

fn cfg(variant: &str) -> Config {
    Config {
        n: 14,
        sigma: 3.0,
        seed: 11,
        ..Config::default()
    }
    .with(&[("variant", variant), ("loops", "30")])
}

fn all_nodes() -> TreeQuery {
    TreeQuery {
        max_nodes: 1 << 20,
        ..TreeQuery::default()
    }
}

/// Steps one loop phase by phase (work before it done first), calling
/// `check` after each phase with the record and the episode.
fn one_loop(ep: &mut Episode, mut check: impl FnMut(PhaseKind, &PhaseRecord, &Episode)) -> bool {
    loop {
        match ep.step_phase() {
            None => return false,
            Some(PhaseStep::Work(_)) => continue,
            Some(PhaseStep::Phase(k, _)) => {
                let rec = ep.phase().expect("a recorded phase").clone();
                check(k, &rec, ep);
                if k == PhaseKind::Backup {
                    return true;
                }
            }
        }
    }
}

fn check_select_levels(rec: &PhaseRecord) {
    for level in &rec.select {
        let chosen = level.candidates[level.chosen as usize];
        assert!(chosen.valid);
        let best = level
            .candidates
            .iter()
            .filter(|c| c.valid)
            .map(|c| c.uct)
            .fold(f64::NEG_INFINITY, f64::max);
        if level.rule == SelectRule::Uct {
            assert_eq!(chosen.uct, best, "{level:?}");
        }
        for c in level.candidates.iter().filter(|c| c.valid) {
            assert_eq!(c.uct, c.mean + c.explore);
        }
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_tree_loop_reports_its_path_node_rollout_and_back_up() {
    for variant in ["tree", "pomcp"] {
        let mut ep = Episode::new(&cfg(variant)).unwrap();
        for _ in 0..90 {
            let mut nodes_before = 0;
            one_loop(&mut ep, |k, rec, ep| {
                let tree = ep.tree(&all_nodes()).unwrap().unwrap();
                match k {
                    PhaseKind::Select => {
                        check_select_levels(rec);
                        nodes_before = tree.total_nodes;
                        // Each level goes down to the node chosen.
                        for w in rec.select.windows(2) {
                            let c = w[0].candidates[w[0].chosen as usize];
                            assert_eq!(c.node, Some(w[1].node));
                        }
                        if let Some(first) = rec.select.first() {
                            // The root's terms are the decision panel's.
                            let view = ep.decision().unwrap();
                            assert_eq!(first.node, 0);
                            for (c, ch) in first.candidates.iter().zip(view.children) {
                                if c.valid {
                                    assert_eq!((c.visits, c.uct), (ch.visits, ch.uct));
                                }
                            }
                        }
                    }
                    PhaseKind::Expand => {
                        let e = rec.expansion.unwrap();
                        if let Some(id) = e.node {
                            assert_eq!(id, nodes_before);
                            let n = tree.nodes.iter().find(|n| n.id == id).unwrap();
                            assert_eq!((n.parent, n.mv, n.visits), (Some(e.parent), e.mv, 0));
                        }
                    }
                    PhaseKind::Rollout => {
                        assert_eq!(rec.rollout().len() as u32, rec.rollout_steps);
                        assert_eq!(rec.chunks().last().copied().unwrap_or(0), rec.rollout_steps);
                    }
                    PhaseKind::Backup => {
                        // The path: root first, one more visit each.
                        assert_eq!(rec.backup[0].node, 0);
                        let path: Vec<u32> = rec.trace[..rec.rollout_from as usize].to_vec();
                        let cells: Vec<u32> = rec.backup.iter().map(|b| b.cell).collect();
                        assert_eq!(cells, path);
                        for b in &rec.backup {
                            assert_eq!(b.visits[1], b.visits[0] + 1);
                            // (Unless the loop ended the decision: the
                            // tree is then the kept subtree.)
                            if ep.loops_of_decision() > 0 {
                                let n = tree.nodes.iter().find(|n| n.id == b.node).unwrap();
                                assert_eq!(n.visits, b.visits[1]);
                            }
                        }
                    }
                }
            });
            if ep.status() != Status::Running {
                break;
            }
        }
        assert!(ep.steps() >= 2, "{variant}: {} moves", ep.steps());
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_table_loop_reports_picks_and_pass_through_visits() {
    for variant in ["cells", "code"] {
        let mut ep = Episode::new(&cfg(variant)).unwrap();
        let mut passes = 0;
        for _ in 0..120 {
            let mut before = None;
            one_loop(&mut ep, |k, rec, ep| match k {
                PhaseKind::Select => {
                    check_select_levels(rec);
                    assert_eq!(rec.select.len(), 1);
                    before = Some(ep.tree(&TreeQuery::default()).unwrap().unwrap());
                }
                PhaseKind::Backup => {
                    let star = ep.tree(&TreeQuery::default()).unwrap().unwrap();
                    let star0 = before.as_ref().unwrap();
                    // Each entry's old and new visits are the star's
                    // (unless the loop ended the decision and moved it).
                    let moved = ep.loops_of_decision() == 0;
                    for b in rec.backup.iter().filter(|_| !moved) {
                        let id = b.node as usize;
                        assert_eq!(
                            (star0.nodes[id].visits, star.nodes[id].visits),
                            (b.visits[0], b.visits[1])
                        );
                    }
                    let picked: Vec<u32> = rec
                        .backup
                        .iter()
                        .filter(|b| b.picked)
                        .map(|b| b.node)
                        .collect();
                    assert_eq!(picked, [1 + rec.select[0].chosen as u32]);
                    let gained: u32 = rec.backup.iter().map(|b| b.visits[1] - b.visits[0]).sum();
                    let star_cells: BTreeSet<u32> = star0.nodes.iter().map(|n| n.cell).collect();
                    if variant == "cells" {
                        // A visit per distinct cell the loop passed through.
                        let distinct: BTreeSet<u32> = rec.trace.iter().copied().collect();
                        assert_eq!(gained + rec.others, distinct.len() as u32);
                        let outside = distinct.difference(&star_cells).count() as u32;
                        assert_eq!(rec.others, outside);
                    } else {
                        // The root, the neighbour, and a visit per step.
                        assert_eq!(gained + rec.others, 2 + rec.rollout_steps);
                    }
                    passes += rec
                        .backup
                        .iter()
                        .filter(|b| b.node >= 1 && !b.picked)
                        .count();
                }
                _ => {}
            });
            if ep.status() != Status::Running {
                break;
            }
        }
        assert!(passes > 0, "{variant}: no pass-through visit seen");
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn the_tree_counts_are_the_loops_and_the_decision_panels() {
    // Under `tree`, a fresh root's visits are the loops run, and every
    // loop passes exactly one of its children. Once a real move keeps a
    // subtree, the root already had visits (the loops through it, one of
    // which expanded it and so reached no child): from there each loop
    // adds one to the root and one to a child.
    let mut ep = Episode::new(&cfg("tree").with(&[("loops", "50")])).unwrap();
    let q = all_nodes();
    let counts = |ep: &Episode| {
        let t = ep.tree(&q).unwrap().unwrap();
        let root = t.nodes[0];
        let kids: u32 = t
            .nodes
            .iter()
            .filter(|n| n.parent == Some(0))
            .map(|n| n.visits)
            .sum();
        (root.visits, kids, t)
    };
    for k in [1, 7, 20] {
        ep.step_loops(k - ep.loops_of_decision());
        let (root, kids, t) = counts(&ep);
        assert_eq!((root, kids), (k, k));
        let view = ep.decision().unwrap();
        assert_eq!(view.parent_visits, root);
        for n in t.nodes.iter().filter(|n| n.parent == Some(0)) {
            let ch = view.children[n.mv.unwrap() as usize];
            assert_eq!(
                (n.visits, n.picks, n.cell),
                (ch.visits, Some(ch.selected), ch.cell)
            );
            assert_eq!(n.value, Some(ch.mean));
        }
        // At most one node a loop (none when the selected cell detects).
        assert!(t.total_nodes <= 1 + k && t.total_nodes > k.min(4));
    }
    ep.step_move();
    let (root0, kids0, _) = counts(&ep);
    assert!(root0 > kids0, "a kept root was expanded by a loop");
    ep.step_loops(13);
    let (root, kids, _) = counts(&ep);
    assert_eq!((root - root0, kids - kids0), (13, 13));
}

#[wasm_bindgen_test(unsupported = test)]
fn the_star_counts_are_the_decision_panels_with_picks_and_passes() {
    for variant in ["cells", "code"] {
        let mut ep = Episode::new(&cfg(variant)).unwrap();
        ep.step_move();
        ep.step_move();
        ep.step_loops(17);
        let t = ep.tree(&TreeQuery::default()).unwrap().unwrap();
        let view = ep.decision().unwrap();
        assert_eq!(t.nodes[0].visits, view.parent_visits);
        let mut picks = 0;
        for n in &t.nodes[1..] {
            let ch = view.children[n.mv.unwrap() as usize];
            assert_eq!((n.visits, n.picks), (ch.visits, Some(ch.selected)));
            assert_eq!(n.gained.unwrap(), n.picks.unwrap() + n.passes.unwrap());
            picks += n.picks.unwrap();
        }
        assert_eq!(picks, 17, "{variant}");
        if variant == "cells" {
            // The root gains one visit a loop.
            assert_eq!(t.nodes[0].gained, Some(17));
        }
        let best = TreeQuery {
            focus: TreeFocus::Best,
            ..TreeQuery::default()
        };
        assert_eq!(ep.tree(&best).unwrap().unwrap().nodes.len(), 5);
    }
    // A walker has no tree.
    let walk = Episode::new(&cfg("cells").with(&[("searcher", "rw")])).unwrap();
    assert!(walk.tree(&TreeQuery::default()).is_none());
}
