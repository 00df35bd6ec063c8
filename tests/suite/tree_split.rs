//! The tree export's UCT split is what selection weighs: after each loop's
//! select phase, every move a level weighed carries, on its exported node,
//! the same terms bit for bit, and the move it took has the highest
//! exported UCT among its siblings. Between phases every exported node
//! but the root has a split, and `mean + explore = uct`.

use torus_search::config::Config;
use torus_search::run::episode::Episode;
use torus_search::searchers::phase::{PhaseKind, PhaseStep, SelectRule};
use torus_search::searchers::tree_export::{TreeExport, TreeNode, TreeQuery};
use wasm_bindgen_test::wasm_bindgen_test;

fn cfg(variant: &str, c: &str) -> Config {
    Config {
        n: 14,
        sigma: 3.0,
        seed: 11,
        ..Config::default()
    }
    .with(&[("variant", variant), ("loops", "30"), ("c", c)])
}

fn whole(ep: &Episode) -> TreeExport {
    let q = TreeQuery {
        max_nodes: 1 << 20,
        ..TreeQuery::default()
    };
    ep.tree(&q).expect("an MCTS searcher has a tree").unwrap()
}

fn split(n: &TreeNode) -> (f64, f64, f64) {
    (n.mean.unwrap(), n.explore.unwrap(), n.uct.unwrap())
}

/// Every node but the root has a split whose terms add up; an unvisited
/// one is tried first (∞).
fn check_every_node(t: &TreeExport) {
    for n in &t.nodes {
        if n.parent.is_none() {
            assert_eq!((n.mean, n.explore, n.uct), (None, None, None));
            continue;
        }
        let (mean, explore, uct) = split(n);
        assert_eq!(uct, mean + explore, "{n:?}");
        assert_eq!(n.visits == 0, explore == f64::INFINITY, "{n:?}");
    }
}

/// Steps `loops` loops phase by phase; after each select phase, checks
/// every level of the selection against the export. Returns the levels
/// checked below the root.
fn check_variant(variant: &str, c: &str, loops: u32) -> u32 {
    let mut ep = Episode::new(&cfg(variant, c)).unwrap();
    let (mut done, mut deep) = (0, 0);
    while done < loops {
        match ep.step_phase() {
            None => break,
            Some(PhaseStep::Work(_)) => continue,
            Some(PhaseStep::Phase(k, _)) => {
                let t = whole(&ep);
                check_every_node(&t);
                if k == PhaseKind::Backup {
                    done += 1;
                }
                if k != PhaseKind::Select {
                    continue;
                }
                let rec = ep.phase().expect("a recorded phase");
                for level in &rec.select {
                    let star = t.shape.name() == "star";
                    let node = |mv| {
                        *t.nodes
                            .iter()
                            .find(|n| n.parent == Some(level.node) && n.mv == Some(mv))
                            .unwrap_or_else(|| {
                                panic!("{variant}: no child {mv:?} of {}", level.node)
                            })
                    };
                    let mut best = f64::NEG_INFINITY;
                    for cand in level.candidates.iter().filter(|c| c.valid) {
                        let n = node(cand.mv);
                        if !star {
                            assert_eq!(Some(n.id), cand.node);
                        }
                        let want = (cand.mean, cand.explore, cand.uct);
                        assert_eq!(split(&n), want, "{variant}: {cand:?}");
                        best = best.max(cand.uct);
                    }
                    let chosen = node(level.candidates[level.chosen as usize].mv);
                    if level.rule == SelectRule::Uct {
                        assert_eq!(chosen.uct, Some(best), "{variant}: {level:?}");
                    }
                    deep += u32::from(level.node != 0);
                }
            }
        }
    }
    assert_eq!(done, loops, "{variant}: the episode ended early");
    deep
}

#[wasm_bindgen_test(unsupported = test)]
fn the_exported_split_is_what_selection_weighs_at_every_level() {
    // A small c lets the trees grow deep; the default c keeps them wide.
    for c in ["0.3", "1.4"] {
        for variant in ["tree", "pomcp"] {
            let deep = check_variant(variant, c, 150);
            assert!(
                deep > 50,
                "{variant} c={c}: only {deep} levels below the root"
            );
        }
        for variant in ["cells", "code"] {
            assert_eq!(check_variant(variant, c, 150), 0, "{variant}");
        }
    }
}
