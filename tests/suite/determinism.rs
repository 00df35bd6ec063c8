//! A run is a pure function of (config, seed) on every platform: these
//! fingerprints are pinned and checked natively and in wasm.

use torus_search::config::preset::Preset;
use torus_search::config::Config;
use torus_search::game::prior::PriorKind;
use torus_search::run::batch::{fingerprint, run_trials};
use torus_search::searchers::registry::SearcherId;
use wasm_bindgen_test::wasm_bindgen_test;

fn searcher(name: &str) -> SearcherId {
    SearcherId::parse(name).unwrap()
}

/// The pinned cases' base: the paper's `cells` table (decay 1, kept for the
/// whole trial, no escape, the most selected move), which the pinned
/// fingerprints predate.
fn small() -> Config {
    Config {
        n: 12,
        sigma: 2.5,
        step_cap: 400,
        ..Config::default()
    }
    .with(&[
        ("loops", "16"),
        ("belief", "prior"),
        ("rollout_cap", "400"),
        ("decay", "1.0"),
        ("escape", "0"),
        ("final", "visits"),
    ])
}

/// The default searcher (its belief, decay, escape and final rule) over
/// the small cases' lattice and caps.
fn default_small(prior: &str) -> Config {
    let d = Config::default();
    small().with(&[
        ("prior", prior),
        ("belief", &d.get("belief").unwrap()),
        ("decay", &d.get("decay").unwrap()),
        ("escape", &d.get("escape").unwrap()),
        ("final", &d.get("final").unwrap()),
    ])
}

fn cases() -> Vec<(&'static str, Config)> {
    let mut cases = vec![
        ("cells rw", small()),
        ("tree rw", small().with(&[("variant", "tree")])),
        (
            "cells levy",
            small().with(&[("rollout", "levy"), ("mu", "1.7")]),
        ),
        (
            "cells nsarw posterior",
            small().with(&[("rollout", "nsarw"), ("belief", "posterior")]),
        ),
        (
            "tree greedy mean",
            small().with(&[
                ("variant", "tree"),
                ("rollout", "greedy"),
                ("final", "mean"),
            ]),
        ),
        (
            "cells uct reset",
            small().with(&[("final", "uct"), ("reset_each_move", "true")]),
        ),
        (
            "levy walker",
            Config {
                searcher: searcher("levy"),
                prior: PriorKind::Uniform,
                ..small()
            },
        ),
        (
            "nsarw walker",
            Config {
                searcher: searcher("nsarw"),
                prior: PriorKind::Uniform,
                ..small()
            },
        ),
        (
            "code (the authors' statistics)",
            small().with(&[("variant", "code"), ("c", "2.0"), ("final", "uct")]),
        ),
        (
            "rw walker",
            Config {
                searcher: searcher("rw"),
                prior: PriorKind::Uniform,
                rv: 0.0,
                ..small()
            },
        ),
        (
            "cells decay (the default searcher)",
            default_small("gaussian"),
        ),
    ];
    cases.extend(planner_cases());
    // Nothing is searched but cells without mass: the table never fades.
    cases.push(("cells default, delta", default_small("delta")));
    cases
}

/// The pinned cases from "sweep" on, in their order in [`PINNED`].
fn planner_cases() -> Vec<(&'static str, Config)> {
    vec![
        (
            "sweep",
            Config {
                searcher: searcher("sweep"),
                ..small()
            },
        ),
        (
            "horizon",
            Config {
                searcher: searcher("horizon"),
                ..small()
            }
            .with(&[("horizon", "4")]),
        ),
        (
            "improve best",
            Config {
                searcher: searcher("improve"),
                prior: PriorKind::Uniform,
                ..small()
            }
            .with(&[("base", "best"), ("horizon", "3")]),
        ),
        (
            // The paper's table traps; the escape walks it out.
            "cells escape",
            Config {
                prior: PriorKind::Uniform,
                ..small()
            }
            .with(&[("escape", "3")]),
        ),
        (
            "pomcp (the belief MCTS)",
            small().with(&[("variant", "pomcp")]),
        ),
        (
            // Rollouts cut after 3 steps, finished by the reference walk;
            // no plan: coverage-walk rollouts and reference.
            "pomcp cut",
            Config {
                prior: PriorKind::Uniform,
                ..small()
            }
            .with(&[
                ("variant", "pomcp"),
                ("pomcp_depth", "3"),
                ("pomcp_plan", "0"),
            ]),
        ),
        (
            "beam",
            Config {
                searcher: searcher("beam"),
                ..small()
            }
            .with(&[("horizon", "3"), ("beam_width", "8"), ("beam_depth", "12")]),
        ),
        (
            // The plan's rollouts rejoin it, cut after 3 steps.
            "pomcp plan cut",
            Config {
                prior: PriorKind::Uniform,
                ..small()
            }
            .with(&[("variant", "pomcp"), ("pomcp_depth", "3")]),
        ),
        (
            "spiral",
            Config {
                searcher: searcher("spiral"),
                sigma: 4.0,
                ..small()
            },
        ),
    ]
}

/// The pinned fingerprints, in `cases()` order (seed 2026, 4 trials each).
/// The `code` case was added with that variant (issue 10), the sweep,
/// horizon and improve cases with those planners, the `pomcp` case with the
/// belief MCTS (issue 11); the others
/// are unchanged.
/// They were pinned when the seed was still a separate argument: moving it
/// into the config changed no draw. The four Lévy and NSARW cases were
/// re-pinned in issue 11 when those walks became table-driven: the same laws
/// from different random draws; the two NSARW cases again when its ties
/// were broken by a random order of the moves instead of a random byte
/// (the same law). The `cells decay` case was added with the
/// table's decay, `cells escape` with the escape from searched ground (both
/// issue 11); the others set decay 1 and escape 0, the paper's MCTS, and
/// keep their values. The `pomcp` case was re-pinned when the belief MCTS
/// took its value from the best return found, cut its rollouts with a
/// reference tail and played the best child (still issue 11); `pomcp cut`
/// pins the cut, which the small lattice of the other case never reaches.
/// When the belief MCTS started from a plan (`pomcp_plan`, issue 11) the
/// `pomcp` case was re-pinned; `pomcp cut` sets `pomcp_plan` 0 and keeps
/// its value, and `pomcp plan cut` pins the plan with the cut. `beam` was
/// added with the beam planner, `spiral` with the spiral planner (both
/// issue 11). `pomcp` and `pomcp plan cut` were re-pinned when the first
/// plan became the horizon searcher's own path (its far goal compared every
/// move) and the escape stopped walking a searcher that holds a plan off
/// it (issue 11: at N = 128 the old plan and the escape cost 163 and 6
/// steps); `pomcp cut`, with no plan, kept its value. All three `pomcp`
/// cases were re-pinned again when the belief's unsearched mass, which the
/// belief MCTS normalises its returns by, became a compensated sum that is
/// exactly 0 once no cell with mass is left (issue 11: the running
/// difference from 1 left rounding dust of about 10⁻¹⁶, which late in a
/// search outweighed the mass truly left and made it plan at every move).
/// Issue 43 made the default searcher show Theorem 1: the final rule
/// `auto` (UCT for the per-cell tables) and a decay by the share of mass
/// each move searches. `cells decay` was re-pinned; the other cases pin
/// `visits` (the paper text's reading) and keep their values; `cells
/// default, delta` was added: at a delta prior the table never fades.
const PINNED: [u64; 21] = [
    0xffcde01788cd3854,
    0x2ffb758103ec3b6d,
    0xd0c17705468deac1,
    0x1151bcc6982a102c,
    0x4292b8697b437811,
    0x30e670e25ce766d9,
    0x283abe04e107336b,
    0x64682274c6a3d53a,
    0x26e4c300bda0f588,
    0x6388de00944dcf87,
    0x0caf09174687cc17,
    0xa43971504d971172,
    0xec1f7e9f227ae3a8,
    0x2f8ace8c33995f53,
    0x525ec88472ced1ec,
    0x7798266e28171dfc,
    0xa56eaa66bd3ee177,
    0x6be7bf1f2b5dfc48,
    0xb7e98bc3f324d2c8,
    0x3b1e5ef2507f25c4,
    0x6f01b6e892da6cc8,
];

#[wasm_bindgen_test(unsupported = test)]
fn fingerprints_are_pinned() {
    let got: Vec<u64> = cases()
        .iter()
        .map(|(_, c)| {
            fingerprint(
                &Config {
                    seed: 2026,
                    ..c.clone()
                },
                4,
            )
            .unwrap()
        })
        .collect();
    println!("{got:#018x?}");
    for ((name, _), (g, want)) in cases().iter().zip(got.iter().zip(PINNED)) {
        assert_eq!(
            *g, want,
            "{name}: fingerprint {g:#018x} differs from the pinned {want:#018x}"
        );
    }
}

/// The paper presets keep the paper's table whatever the defaults: over
/// today's defaults (the table's decay included), each preset with the
/// small cases' lattice and caps is exactly its pinned case, and replays
/// its pinned fingerprint. Fails if a preset leaves `decay` at its default.
#[wasm_bindgen_test(unsupported = test)]
fn paper_presets_replay_their_pinned_cases() {
    for (preset, case) in [(Preset::PaperText, 0), (Preset::PaperCode, 8)] {
        let mut cfg = small().with(&[("decay", &Config::default().get("decay").unwrap())]);
        cfg.apply_preset(preset);
        cfg.set("rollout_cap", &small().get("rollout_cap").unwrap())
            .unwrap();
        cfg.step_cap = small().step_cap;
        let (name, want) = &cases()[case];
        assert_eq!(&cfg, want, "{preset} is not the pinned case {name}");
        let got = fingerprint(&Config { seed: 2026, ..cfg }, 4).unwrap();
        assert_eq!(got, PINNED[case], "{preset}: fingerprint {got:#018x}");
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn same_seed_replays_and_other_seeds_differ() {
    let seeded = |seed| Config { seed, ..small() };
    assert_eq!(
        fingerprint(&seeded(5), 3).unwrap(),
        fingerprint(&seeded(5), 3).unwrap()
    );
    assert_ne!(
        fingerprint(&seeded(5), 3).unwrap(),
        fingerprint(&seeded(6), 3).unwrap()
    );
}

#[wasm_bindgen_test(unsupported = test)]
fn trials_do_not_depend_on_how_a_batch_is_split() {
    let c = Config { seed: 9, ..small() };
    let whole = run_trials(&c, 0, 6).unwrap();
    let mut parts = run_trials(&c, 0, 2).unwrap();
    parts.extend(run_trials(&c, 2, 4).unwrap());
    assert_eq!(whole, parts);
}

/// The benchmark's loop windows are the page's loops: running FROM then
/// TO − FROM more loops lands exactly where one run of TO loops does, and
/// the episode (trial 0) stepped in uneven chunks, as the page does, makes
/// the same moves.
#[wasm_bindgen_test(unsupported = test)]
fn loop_windows_replay_the_page_episode() {
    use torus_search::bench::LoopRunner;
    use torus_search::run::episode::{Episode, Status};
    let cfg = Config { seed: 9, ..small() }.with(&[("loops", "30")]);
    let mut split = LoopRunner::new(&cfg).unwrap();
    split.run(457).unwrap();
    split.run(1234 - 457).unwrap();
    let mut whole = LoopRunner::new(&cfg).unwrap();
    whole.run(1234).unwrap();
    assert_eq!(
        (split.loops, split.moves, split.episodes),
        (1234, whole.moves, whole.episodes)
    );
    assert!(whole.moves > 0);

    let mut page = Episode::new(&cfg).unwrap();
    let mut moves = 0u64;
    let mut loops = 0u64;
    let mut chunk = 1u32;
    while loops < 1234 && page.status() == Status::Running {
        let before = page.counters().rollouts;
        if page.step_loops(chunk.min((1234 - loops) as u32)) {
            moves += 1;
        }
        loops += page.counters().rollouts - before;
        chunk = chunk % 37 + 5;
    }
    // The same loops through the benchmark runner: the same moves, and the
    // episode ends at the same loop if it ended.
    let mut bench = LoopRunner::new(&cfg).unwrap();
    bench.run(loops).unwrap();
    let ended = u64::from(page.status() != Status::Running);
    assert_eq!((bench.moves, bench.episodes), (moves, ended));
    assert!(moves > 10, "{moves} moves");
}

/// The intervals every result reports are a pure function of the values:
/// pinned bits, checked natively and in wasm (the page's results must be
/// the CLI's byte for byte).
#[wasm_bindgen_test(unsupported = test)]
fn intervals_are_pinned() {
    use torus_search::analysis::bootstrap::bca_mean;
    use torus_search::analysis::median::median_interval;
    use torus_search::analysis::normal;
    let b = bca_mean(&[3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0, 6.0, 5.0, 3.0]);
    assert_eq!(b.estimate, 3.9);
    assert_eq!(
        (b.lo.to_bits(), b.hi.to_bits()),
        (PIN_LO_10, PIN_HI_10),
        "{b:?}"
    );
    // 200 skewed trials with three at a cap of 5000.
    let xs: Vec<f64> = (0..200u64)
        .map(|i| match i % 67 {
            13 => 5000.0,
            k => (40 + (k * k * 7 + i) % 400) as f64,
        })
        .collect();
    let b = bca_mean(&xs);
    assert_eq!(
        (b.lo.to_bits(), b.hi.to_bits()),
        (PIN_LO_200, PIN_HI_200),
        "{b:?}"
    );
    let mut sorted = xs.clone();
    sorted.sort_by(f64::total_cmp);
    let m = median_interval(&sorted);
    assert_eq!((m.lo, m.estimate, m.hi), (PIN_MED.0, PIN_MED.1, PIN_MED.2));
    assert_eq!(normal::quantile(0.975).to_bits(), PIN_Z975);
}

const PIN_LO_10: u64 = 4612811918334230528;
const PIN_HI_10: u64 = 4618761310118564096;
const PIN_LO_200: u64 = 4642603825677868583;
const PIN_HI_200: u64 = 4646163961901569658;
const PIN_MED: (f64, f64, f64) = (182.0, 216.0, 233.0);
const PIN_Z975: u64 = 4611505712243081091;
