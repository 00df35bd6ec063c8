//! Branching a run at move m (`run::branch`, `Race::branch`): with the
//! parent's own configuration the branch is the parent run itself; with
//! another searcher setting it keeps the first m moves and is a pinned
//! function of its inputs; world parameters and moves past the run get an
//! error naming them; seeking within a branched run gives the state
//! reached going forward. Natively and in wasm.

use torus_search::config::Config;
use torus_search::game::prior::PriorKind;
use torus_search::run::batch::{fingerprint, fingerprint_driven};
use torus_search::run::branch::{self, BranchError};
use torus_search::run::episode::{Episode, Status, TimePoint};
use torus_search::run::race::Race;
use torus_search::searchers::registry::SearcherId;
use wasm_bindgen_test::wasm_bindgen_test;

fn small() -> Config {
    Config {
        n: 12,
        sigma: 2.5,
        step_cap: 300,
        seed: 2026,
        ..Config::default()
    }
    .with(&[("loops", "16"), ("rollout_cap", "300")])
}

fn with_searcher(name: &str, cfg: Config) -> Config {
    Config {
        searcher: SearcherId::parse(name).unwrap(),
        ..cfg
    }
}

/// Searchers of every kind: MCTS variants with kept statistics, walkers
/// with memory, planners with plans.
fn cases() -> Vec<(&'static str, Config)> {
    vec![
        ("cells", small()),
        ("tree", small().with(&[("variant", "tree")])),
        ("code", small().with(&[("variant", "code")])),
        ("pomcp", small().with(&[("variant", "pomcp")])),
        ("nsarw", with_searcher("nsarw", small())),
        ("levy", with_searcher("levy", small())),
        ("sweep", with_searcher("sweep", small())),
        (
            "horizon",
            with_searcher("horizon", small()).with(&[("horizon", "3")]),
        ),
    ]
}

/// Runs `ep` until it has made `at` moves or ended.
fn to_move(ep: &mut Episode, at: u32) {
    while ep.steps() < at && ep.step_move() == Status::Running {}
}

/// The fingerprint of trials of `parent` each branched at move `at` (or
/// where it ended) with `child` and run to the end, hashed as
/// `batch::fingerprint` hashes runs.
fn branched(parent: &Config, at: u32, child: &Config, trials: u64) -> u64 {
    fingerprint_driven(parent, trials, |e| {
        to_move(e, at);
        *e = branch::branch(e, e.steps(), child).unwrap();
        e.run();
    })
    .unwrap()
}

#[wasm_bindgen_test(unsupported = test)]
fn a_branch_with_the_parents_config_is_the_parent_run() {
    for (name, cfg) in cases() {
        let whole = fingerprint(&cfg, 3).unwrap();
        for at in [0, 1, 7] {
            assert_eq!(branched(&cfg, at, &cfg, 3), whole, "{name} at move {at}");
        }
        // The state at the branch move, not only the path: what the
        // searcher shows and the counters.
        let mut parent = Episode::new(&cfg).unwrap();
        to_move(&mut parent, 5);
        let b = branch::branch(&parent, 5, &cfg).unwrap();
        assert_eq!(b.path(), parent.path(), "{name}");
        assert_eq!(b.counters(), parent.counters(), "{name}");
        assert_eq!(b.forced(), 5, "{name}");
        assert_eq!(
            format!("{:?}", b.decision()),
            format!("{:?}", parent.decision())
        );
    }
}

/// The pinned fingerprints of [`changed`]'s branches (seed 2026, 3 trials,
/// branched at move 6), added with branching (issue 44).
const PINNED: [u64; 4] = [
    0xed885e4b7c265ded,
    0xc89d46d11499aef6,
    0x6e2f6e9cbf62947a,
    0xaa3eb2d239538853,
];

/// Branches with another searcher setting: c and loops, the variant, and
/// another searcher (a walker, a planner that must leave its plan).
fn changed() -> Vec<(&'static str, Config, Config)> {
    let tree = small().with(&[("variant", "tree")]);
    vec![
        ("c 2 → 0.3", small(), small().with(&[("c", "0.3")])),
        (
            "tree, loops 16 → 60",
            tree.clone(),
            tree.with(&[("loops", "60")]),
        ),
        (
            "cells → pomcp",
            small(),
            small().with(&[("variant", "pomcp")]),
        ),
        ("mcts → sweep", small(), with_searcher("sweep", small())),
    ]
}

#[wasm_bindgen_test(unsupported = test)]
fn a_branch_with_another_setting_keeps_the_prefix_and_is_pinned() {
    let got: Vec<u64> = changed()
        .iter()
        .map(|(_, a, b)| branched(a, 6, b, 3))
        .collect();
    println!("{got:#018x?}");
    for ((name, a, b), (g, want)) in changed().iter().zip(got.iter().zip(PINNED)) {
        assert_eq!(
            *g, want,
            "{name}: {g:#018x} differs from the pinned {want:#018x}"
        );
        // The same inputs, the same branch; and it differs from the parent.
        assert_eq!(branched(a, 6, b, 3), *g, "{name} replays");
        assert_ne!(*g, fingerprint(a, 3).unwrap(), "{name} changed nothing");
        let mut parent = Episode::new(a).unwrap();
        parent.run();
        let mut child = branch::branch(&parent, 6, b).unwrap();
        assert_eq!(
            child.path(),
            &parent.path()[..7],
            "{name}: the shared prefix"
        );
        child.run();
        assert_eq!(&child.path()[..7], &parent.path()[..7], "{name}");
        assert_ne!(
            child.path(),
            parent.path(),
            "{name}: the branch went its own way"
        );
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_sweep_that_leaves_its_plan_sweeps_again_from_where_it_stands() {
    // Forced off its sweep by the shared prefix, the sweep plans a fresh
    // sweep: it covers the lattice rather than walking one way forever.
    let cfg = Config {
        prior: PriorKind::Uniform,
        ..with_searcher("sweep", small())
    };
    let mut parent = Episode::new(&small()).unwrap();
    to_move(&mut parent, 9);
    let mut child = branch::branch(&parent, 9, &cfg.with(&[("prior", "gaussian")])).unwrap();
    to_move(&mut child, 9 + 12 * 12);
    let rows: std::collections::BTreeSet<u32> = child.path()[9..]
        .iter()
        .map(|&c| child.torus().xy(c).1)
        .collect();
    assert!(rows.len() >= 4, "the sweep stayed on rows {rows:?}");
}

#[wasm_bindgen_test(unsupported = test)]
fn world_parameters_and_moves_past_the_run_cannot_branch() {
    let mut parent = Episode::new(&small()).unwrap();
    to_move(&mut parent, 4);
    for (key, value) in [
        ("n", "13"),
        ("sigma", "3"),
        ("prior", "uniform"),
        ("target", "3,3"),
        ("start", "2,2"),
        ("rv", "2.5"),
        ("known", "1"),
        ("seed", "7"),
        ("step_cap", "100"),
    ] {
        let child = small().with(&[(key, value)]);
        let e = branch::branch(&parent, 2, &child).err().expect(key);
        assert!(
            matches!(e, BranchError::World { key: k, .. } if k == key),
            "{key}: {e:?}"
        );
        let text = e.to_string();
        assert!(
            text.starts_with(&format!("{key} cannot change in a branch")),
            "{text}"
        );
        assert!(
            text.contains("only the searcher's parameters can branch"),
            "{text}"
        );
    }
    // Searcher parameters, the searcher included, can.
    for (key, value) in [
        ("c", "0.5"),
        ("loops", "3"),
        ("searcher", "rw"),
        ("belief", "posterior"),
    ] {
        assert!(
            branch::branch(&parent, 2, &small().with(&[(key, value)])).is_ok(),
            "{key}"
        );
    }
    let e = branch::branch(&parent, 5, &small()).err().unwrap();
    assert_eq!(e, BranchError::PastEnd { at: 5, reached: 4 });
    assert_eq!(
        e.to_string(),
        "branch at move 5 is past the run's moves: allowed moves 0 to 4"
    );
}

#[wasm_bindgen_test(unsupported = test)]
fn a_branched_race_seeks_back_into_its_prefix_and_forward() {
    let a = small().with(&[("variant", "tree")]);
    let b = a.clone().with(&[("c", "0.4")]);
    let walker = with_searcher("rw", small());
    let mut race = Race::new(&[a.clone(), walker.clone()]).unwrap();
    for _ in 0..8 {
        race.step_move();
    }
    let before = race.runs()[0].path().to_vec();
    // Past the end, or the wrong count of configs: nothing changes.
    assert_eq!(
        race.branch(&[b.clone(), walker.clone()], 9),
        Err(BranchError::PastEnd { at: 9, reached: 8 })
    );
    assert!(matches!(
        race.branch(std::slice::from_ref(&b), 3),
        Err(BranchError::Runs { given: 1, runs: 2 })
    ));
    assert!(race
        .branch(&[b.clone().with(&[("n", "13")]), walker.clone()], 3)
        .is_err());
    assert_eq!(race.runs()[0].path(), &before[..]);
    assert!(race.lineage()[0].is_empty());
    // Branch at move 5 from the end (the runs go back there first).
    race.branch(&[b.clone(), walker.clone()], 5).unwrap();
    assert_eq!(race.runs()[0].path(), &before[..6]);
    assert_eq!(race.runs()[0].config(), &b);
    assert_eq!(race.lineage()[0][0].at, 5);
    assert_eq!(race.lineage()[0][0].config, a);
    assert_eq!(race.timeline()[0].0, TimePoint::at(5, 0));
    for _ in 0..6 {
        race.step_move();
    }
    let end = race.timeline()[0].1;
    let forward = race.runs()[0].path().to_vec();
    assert_eq!(&forward[..6], &before[..6]);
    assert_ne!(forward, before[..forward.len().min(before.len())].to_vec());
    // Into the shared prefix and back to the end: the same path.
    race.seek(TimePoint::at(2, 3)).unwrap();
    assert_eq!(race.runs()[0].path(), &before[..3]);
    race.seek(TimePoint::at(8, 0)).unwrap();
    assert_eq!(race.runs()[0].path(), &forward[..9]);
    race.seek(end).unwrap();
    assert_eq!(race.runs()[0].path(), &forward[..]);
    // A branch of the branch keeps both branch points.
    race.branch(&[a.clone(), walker], 9).unwrap();
    assert_eq!(race.runs()[0].path(), &forward[..10]);
    let at: Vec<u32> = race.lineage()[0].iter().map(|p| p.at).collect();
    assert_eq!(at, [5, 9]);
}
