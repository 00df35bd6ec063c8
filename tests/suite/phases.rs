//! An MCTS loop run a phase at a time leaves the run exactly as the loop
//! run whole: the same fingerprints (every path cell, target and rollout
//! counter) for every variant, natively and in wasm, and the phases come
//! in their order.

use torus_search::config::preset::Preset;
use torus_search::config::Config;
use torus_search::game::layer::Layer;
use torus_search::game::prior::PriorKind;
use torus_search::game::rng;
use torus_search::run::batch::{fingerprint, fingerprint_driven};
use torus_search::run::episode::{Episode, Status};
use torus_search::searchers::phase::{PhaseKind, PhaseStep};
use wasm_bindgen_test::wasm_bindgen_test;

/// The small lattice of the pinned fingerprints (tests/suite/determinism.rs).
fn small() -> Config {
    Config {
        n: 12,
        sigma: 2.5,
        step_cap: 400,
        seed: 2026,
        ..Config::default()
    }
    .with(&[
        ("loops", "16"),
        ("rollout_cap", "400"),
        ("keep_traces", "3"),
    ])
}

/// Every variant, with the paths through each phase: escapes (moves
/// without loops), the belief MCTS's plan (slices before the loops) and
/// its cut rollouts, `code`'s expansion rollouts (loops that do not count).
fn cases() -> Vec<(&'static str, Config)> {
    let mut code = small();
    code.apply_preset(Preset::PaperCode);
    code.n = 12;
    code.sigma = 2.5;
    code.step_cap = 400;
    code.set("rollout_cap", "400").unwrap();
    let uniform = Config {
        prior: PriorKind::Uniform,
        ..small()
    };
    vec![
        ("cells", small()),
        ("cells escape", uniform.clone().with(&[("escape", "3")])),
        ("tree", small().with(&[("variant", "tree")])),
        (
            "tree greedy mean",
            small().with(&[
                ("variant", "tree"),
                ("rollout", "greedy"),
                ("final", "mean"),
            ]),
        ),
        ("code (paper-code)", code),
        ("pomcp", small().with(&[("variant", "pomcp")])),
        (
            "pomcp cut",
            uniform.with(&[
                ("variant", "pomcp"),
                ("pomcp_depth", "3"),
                ("pomcp_plan", "0"),
            ]),
        ),
    ]
}

/// Runs `ep` to its end a phase at a time, checking the phases' order.
fn by_phases(ep: &mut Episode) {
    let mut last: Option<PhaseKind> = None;
    while let Some(step) = ep.step_phase() {
        match step {
            PhaseStep::Phase(k, moved) => {
                let want =
                    last.map_or(PhaseKind::Select, |l| l.next().unwrap_or(PhaseKind::Select));
                assert_eq!(k, want, "after {last:?}");
                assert!(moved.is_none() || k == PhaseKind::Backup, "{k} moved");
                assert_eq!(ep.phase().and_then(|r| r.phase), Some(k));
                last = Some(k);
            }
            PhaseStep::Work(_) => {
                assert!(
                    last.is_none() || last == Some(PhaseKind::Backup),
                    "work in the middle of a loop, after {last:?}"
                );
                assert!(ep.phase().is_none());
            }
        }
    }
    assert_ne!(ep.status(), Status::Running);
}

#[wasm_bindgen_test(unsupported = test)]
fn a_loop_run_phase_by_phase_gives_the_whole_loops_fingerprint() {
    for (name, cfg) in cases() {
        let whole = fingerprint(&cfg, 3).unwrap();
        let phased = fingerprint_driven(&cfg, 3, by_phases).unwrap();
        assert_eq!(phased, whole, "{name}: {phased:#018x} ≠ {whole:#018x}");
    }
}

/// Steps `ep` to its end with a random mix of phases (recorded or not),
/// loops, moves and calls of k loops, as a teacher's clicks would.
fn mixed(ep: &mut Episode, seed: u64) {
    let mut r = rng::stream(seed, 0);
    while ep.status() == Status::Running {
        match rng::below(&mut r, 6) {
            0 | 1 => {
                ep.step_phase();
            }
            2 => {
                ep.step_phase_with(false);
            }
            3 => {
                ep.step_loops(1 + rng::below(&mut r, 5));
            }
            4 => {
                ep.step_move();
            }
            _ => {
                ep.advance(1 + rng::below(&mut r, 40) as u64);
            }
        }
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn phases_loops_and_moves_mixed_give_the_same_run() {
    for (name, cfg) in cases() {
        let whole = fingerprint(&cfg, 2).unwrap();
        let mut seed = 0;
        let got = fingerprint_driven(&cfg, 2, |ep| {
            seed += 1;
            mixed(ep, seed)
        })
        .unwrap();
        assert_eq!(got, whole, "{name}");
    }
}

/// What a display shows of a run (but its point): its decision, visit
/// counts, kept traces, counters and path.
fn shown(ep: &Episode) -> String {
    let mut scratch = Vec::new();
    let visits = ep.counts(Layer::Visits, &mut scratch).map(|v| v.to_vec());
    let traces: Vec<(Vec<u32>, u32)> = ep.traces().map(|(t, p)| (t.to_vec(), p)).collect();
    format!(
        "{:?} {:?} {:?} {:?} {:?}",
        ep.decision(),
        visits,
        traces,
        ep.counters(),
        ep.path()
    )
}

#[wasm_bindgen_test(unsupported = test)]
fn after_each_loop_the_statistics_and_traces_are_the_whole_loops() {
    // Loop by loop (k = 1) against four phases at a time: after every
    // back-up the decision panel, the visit counts and the kept traces
    // are the same, not only the path at the end.
    for (name, cfg) in cases() {
        let mut whole = Episode::new(&cfg).unwrap();
        let mut phased = Episode::new(&cfg).unwrap();
        for _ in 0..120 {
            if whole.status() != Status::Running {
                break;
            }
            whole.step_loops(1);
            // Up to a back-up of a loop that counts (`code`'s expansion
            // rollouts do not), or work that is not a loop.
            loop {
                match phased.step_phase().unwrap() {
                    PhaseStep::Phase(PhaseKind::Backup, _) if phased.phase().unwrap().counts => {
                        break
                    }
                    PhaseStep::Work(_) => break,
                    _ => {}
                }
            }
            assert_eq!(shown(&whole), shown(&phased), "{name}");
        }
    }
}
