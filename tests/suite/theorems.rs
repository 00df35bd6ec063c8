//! The paper's two theorems (section 4) as statistical tests with fixed
//! seeds and thresholds set from measured frequencies and their standard
//! errors. `cargo test --test suite theorems:: -- --nocapture` prints the tables.
//!
//! * Theorem 1 (delta target): as the loops L grow, MCTS's move decreases
//!   the torus ℓ1 distance to the target with frequency → 1. With blind RW
//!   rollouts the signal fades with distance, so the asserted cases start 2–4
//!   moves from the target on a 20×20 torus, where the effect is measurable;
//!   `theorem1_far_from_target_table` (ignored; run with `--ignored`)
//!   reports the weak regime further out.
//! * Theorem 2 (uniform target, large N): the `cells` variant almost never
//!   steps back onto a visited cell while an unvisited neighbour exists, as
//!   NSARW never does, unlike a random walk.
//!
//! Runs natively and in Node (`--target wasm32-unknown-unknown`).

use crate::common::{freq_se, wilson, Z_1E4};
use torus_search::config::Config;
use torus_search::game::lattice::Move;
use torus_search::game::prior::PriorKind;
use torus_search::run::episode::{Episode, Status};
use torus_search::searchers::mcts::Variant;

// ---------------------------------------------------------------------------
// Theorem 1
// ---------------------------------------------------------------------------

const T1_N: u32 = 20;
/// The target, 1-based.
const T1_TARGET: [u32; 2] = [11, 11];

/// The first-move cases play the most selected move (`visits`, the paper
/// text's reading): at a fresh table it follows the rewards. The default
/// rule of `cells`, UCT, is slower there, since the children toward the
/// target collect the most pass-through visits and so the least exploration
/// bonus. Over whole episodes the table's history takes over and the
/// default converges
/// (`theorem1_default_searcher_excess_falls_with_loops_at_a_delta_target`).
fn t1_config(variant: Variant, rv: f64, start: [u32; 2], loops: u32) -> Config {
    Config {
        n: T1_N,
        rv,
        start,
        target: Some(T1_TARGET),
        searcher: crate::common::searcher("mcts"),
        ..Config::default()
    }
    .with(&[
        ("variant", variant.to_string().as_str()),
        ("rollout", "rw"),
        ("loops", loops.to_string().as_str()),
        ("rollout_cap", "2000"),
        ("final", "visits"),
    ])
}

/// How many of `trials` independent episodes make a first real move that
/// decreases the torus ℓ1 distance to the target.
fn first_move_decreases(cfg: &Config, seed: u64, trials: u64) -> u64 {
    (0..trials)
        .filter(|&i| {
            let mut ep = Episode::trial(
                &Config {
                    seed,
                    ..cfg.clone()
                },
                i,
            )
            .unwrap();
            let t = ep.torus().clone();
            let d0 = t.l1(ep.position(), ep.target());
            assert!(d0 > 0 && ep.status() == Status::Running);
            ep.step_move();
            t.l1(ep.position(), ep.target()) < d0
        })
        .count() as u64
}

/// The chance that a uniformly random move decreases the distance: the
/// number of distance-reducing moves over 4.
fn chance(cfg: &Config) -> f64 {
    let ep = Episode::trial(
        &Config {
            seed: 0,
            ..cfg.clone()
        },
        0,
    )
    .unwrap();
    let t = ep.torus();
    let d0 = t.l1(ep.position(), ep.target());
    Move::ALL
        .iter()
        .filter(|&&m| t.l1(t.step(ep.position(), m), ep.target()) < d0)
        .count() as f64
        / 4.0
}

/// Theorem 1 for one variant: a table over starts and L, then the asserts.
fn theorem1(variant: Variant, seed: u64) {
    const TRIALS: u64 = 100;
    const LOOPS: [u32; 3] = [20, 100, 400];
    // Offsets (dx, dy) of the start from the target: on an axis (one
    // reducing move, chance 1/4) and off it (two reducing moves, chance 1/2).
    let offsets = [(2u32, 0u32), (3, 0), (2, 1), (2, 2)];
    // The table is printed in one piece so parallel tests do not interleave it.
    let mut table = format!(
        "Theorem 1, {} variant, N={T1_N}, r_v=0, target {T1_TARGET:?}, {TRIALS} trials each\n  \
         start     d  chance  L={LOOPS:?}: frequency the first move decreases d\n",
        variant.name()
    );
    let mut checks = Vec::new();
    for (dx, dy) in offsets {
        let start = [T1_TARGET[0] - dx, T1_TARGET[1] - dy];
        let cfg0 = t1_config(variant, 0.0, start, 1);
        let p0 = chance(&cfg0);
        let ks: Vec<u64> = LOOPS
            .iter()
            .map(|&l| first_move_decreases(&t1_config(variant, 0.0, start, l), seed, TRIALS))
            .collect();
        let f: Vec<f64> = ks.iter().map(|&k| k as f64 / TRIALS as f64).collect();
        table += &format!(
            "  {start:?}  {}  {p0:.2}    {:.2}  {:.2}  {:.2}\n",
            dx + dy,
            f[0],
            f[1],
            f[2]
        );
        checks.push((dx + dy, start, p0, ks, f));
    }
    println!("{table}");
    for (d, start, p0, ks, f) in checks {
        let (k_lo, k_hi) = (ks[0], ks[2]);
        // (a) At L = 400 the move decreases the distance almost always
        // (measured 1.00 in 300 trials for each start and variant); 0.9
        // fails with probability < 1e-4 unless the true rate is below ~0.97.
        assert!(
            f[2] >= 0.9,
            "{variant:?} start {start:?}: L=400 frequency {}",
            f[2]
        );
        // ... which is far above chance: the Wilson lower bound at z = 3.72
        // clears the random-move rate by a wide margin.
        let (lo, _) = wilson(k_hi, TRIALS, Z_1E4);
        assert!(lo > p0 + 0.25, "{variant:?} start {start:?}: {lo} vs {p0}");
        // (b) The frequency grows with L: L = 400 beats L = 20 by more than
        // 4 combined standard errors (measured gaps 0.35–0.8 at d = 3, 4).
        // At d = 2 the gain is real but small for this test (L = 20 already
        // reaches 0.70–0.81, a gap of ~0.2–0.3 against a margin of ~0.17),
        // so it is printed, not asserted.
        if d < 3 {
            continue;
        }
        let margin = 4.0 * (freq_se(k_lo, TRIALS).powi(2) + freq_se(k_hi, TRIALS).powi(2)).sqrt();
        assert!(
            f[2] - f[0] > margin,
            "{variant:?} start {start:?}: L=20 {} vs L=400 {} (margin {margin})",
            f[0],
            f[2]
        );
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn theorem1_cells_first_move_decreases_distance_more_often_as_loops_grow() {
    theorem1(Variant::Cells, 1001);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn theorem1_tree_first_move_decreases_distance_more_often_as_loops_grow() {
    theorem1(Variant::Tree, 1002);
}

/// Not asserted: the weak-signal regime far from the target, for the record.
/// Theorem 1 as the page's default searcher shows it: at a delta target
/// (N = 40, start (1,1), 39 steps away, every other parameter at its
/// default) the mean excess steps over the optimum fall as the loops L go
/// 10 → 100 → 1000, each fall by more than 4 combined standard errors, and
/// at L = 1000 the excess is at most 4 with a one-sided margin of 2 SE.
/// Trials are those of `torus-search run --prior delta --loops L --seed 5`.
/// The default before issue 43 (final rule `visits`, the table decayed by
/// 0.8 at every move that searched any new cell) gave 136.4, 76.5 and
/// 414.3 over 100 trials: it fails both the fall from L = 100 to 1000 and
/// the bound. Native only: the L = 1000 trials take about 30 s.
#[cfg(not(target_arch = "wasm32"))]
#[test]
fn theorem1_default_searcher_excess_falls_with_loops_at_a_delta_target() {
    use torus_search::analysis::stats::MeanCi;
    use torus_search::run::batch::run_trials;
    let excess = |loops: u32, trials: u64| {
        let cfg = Config {
            prior: PriorKind::Delta,
            seed: 5,
            ..Config::default()
        }
        .with(&[("loops", loops.to_string().as_str())]);
        assert_eq!((cfg.n, cfg.start), (40, [1, 1]), "the defaults moved");
        let res = run_trials(&cfg, 0, trials).unwrap();
        assert!(res.iter().all(|r| r.found), "L = {loops}: a capped trial");
        MeanCi::of(res.iter().map(|r| f64::from(r.steps - r.optimal)))
    };
    let m = [excess(10, 100), excess(100, 100), excess(1000, 50)];
    for (l, m) in [10, 100, 1000].iter().zip(&m) {
        println!(
            "Theorem 1, default searcher, delta target, L = {l}: excess {:.2} ± {:.2} (SE)",
            m.mean,
            m.se()
        );
    }
    for w in m.windows(2) {
        let margin = 4.0 * (w[0].se().powi(2) + w[1].se().powi(2)).sqrt();
        assert!(
            w[0].mean - w[1].mean > margin,
            "excess {} then {} (margin {margin})",
            w[0].mean,
            w[1].mean
        );
    }
    assert!(
        m[2].mean + 2.0 * m[2].se() <= 4.0,
        "L = 1000: excess {} ± {} (SE) is not at most 4",
        m[2].mean,
        m[2].se()
    );
}

/// At a delta prior every cell the searcher leaves holds no mass, so the
/// default table never fades: after six moves the start cell (the first
/// decision's root, one visit per loop) keeps at least the loops it was
/// counted in, even at decay 0. A Gaussian prior loses mass with every
/// move, and decay 0 clears the count (a decay by "any new cell searched",
/// the old rule, clears it at the delta prior too).
#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn the_default_table_never_fades_at_a_delta_prior() {
    use torus_search::game::layer::Layer;
    let start_visits = |prior: &str| {
        let c = Config::default().with(&[
            ("variant", "cells"),
            ("prior", prior),
            ("sigma", "5"),
            ("decay", "0"),
            ("escape", "0"),
            ("loops", "30"),
            ("seed", "4"),
        ]);
        let mut ep = Episode::trial(&c, 0).unwrap();
        let start = ep.start() as usize;
        for _ in 0..6 {
            ep.step_move();
        }
        let mut scratch = Vec::new();
        ep.counts(Layer::Visits, &mut scratch).unwrap()[start]
    };
    assert!(start_visits("delta") >= 30);
    assert!(start_visits("gaussian") < 30);
}

#[cfg(not(target_arch = "wasm32"))]
#[test]
#[ignore = "report only: slow, prints frequency vs distance and L far from the target"]
fn theorem1_far_from_target_table() {
    const TRIALS: u64 = 100;
    for variant in [Variant::Cells, Variant::Tree] {
        for rv in [0.0, 1.0] {
            println!("{} r_v={rv}: d, chance, L=100 / 400 / 1600", variant.name());
            for (dx, dy) in [(4u32, 0u32), (3, 3), (6, 0), (4, 4), (8, 0), (6, 6), (9, 9)] {
                let start = [T1_TARGET[0] - dx, T1_TARGET[1] - dy];
                let p0 = chance(&t1_config(variant, rv, start, 1));
                let f: Vec<String> = [100u32, 400, 1600]
                    .iter()
                    .map(|&l| {
                        let k = first_move_decreases(&t1_config(variant, rv, start, l), 7, TRIALS);
                        format!("{:.2}", k as f64 / TRIALS as f64)
                    })
                    .collect();
                println!(
                    "  {start:?} d={} chance {p0:.2}: {}",
                    dx + dy,
                    f.join(" / ")
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Theorem 2
// ---------------------------------------------------------------------------

/// Over the first `moves` real moves of trials `0..trials`: steps that enter
/// an already-visited cell while some neighbour is unvisited, and steps at
/// which some neighbour is unvisited.
fn backtracks(cfg: &Config, seed: u64, trials: u64, moves: u32) -> (u64, u64) {
    let (mut bad, mut eligible) = (0, 0);
    for i in 0..trials {
        let mut ep = Episode::trial(
            &Config {
                seed,
                ..cfg.clone()
            },
            i,
        )
        .unwrap();
        for _ in 0..moves {
            if ep.step_move() != Status::Running {
                break;
            }
        }
        let t = ep.torus().clone();
        let path = ep.path();
        let mut seen = vec![false; t.cells()];
        seen[path[0] as usize] = true;
        for w in path.windows(2) {
            let (c, next) = (w[0], w[1]);
            if Move::ALL.iter().any(|&m| !seen[t.step(c, m) as usize]) {
                eligible += 1;
                bad += seen[next as usize] as u64;
            }
            seen[next as usize] = true;
        }
    }
    (bad, eligible)
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn theorem2_cells_variant_avoids_its_own_path_like_nsarw() {
    const N: u32 = 200;
    const TRIALS: u64 = 20;
    const MOVES: u32 = 60;
    let base = Config {
        n: N,
        rv: 1.0,
        prior: PriorKind::Uniform,
        ..Config::default()
    }
    .with(&[("loops", "50"), ("rollout_cap", "2000")]);
    let mcts = Config {
        searcher: crate::common::searcher("mcts"),
        ..base.clone()
    }
    .with(&[("variant", "cells"), ("rollout", "rw")]);
    let rw = Config {
        searcher: crate::common::searcher("rw"),
        ..base.clone()
    };
    let nsarw = Config {
        searcher: crate::common::searcher("nsarw"),
        ..base
    };
    let (mb, me) = backtracks(&mcts, 2001, TRIALS, MOVES);
    let (rb, re) = backtracks(&rw, 2002, 200, MOVES);
    let (nb, ne) = backtracks(&nsarw, 2003, 200, MOVES);
    let (fm, fr, fn_) = (
        mb as f64 / me as f64,
        rb as f64 / re as f64,
        nb as f64 / ne as f64,
    );
    println!("Theorem 2, N={N}, uniform target, first {MOVES} moves:");
    println!("  searcher          backtracks / eligible steps = fraction");
    println!("  MCTS cells L=50   {mb} / {me} = {fm:.4}");
    println!("  RW                {rb} / {re} = {fr:.4}");
    println!("  NSARW             {nb} / {ne} = {fn_:.4}");
    // The counting itself works: a random walk backtracks often (at least
    // the 1-in-4 chance of undoing its last move; measured 0.43).
    assert!(fr > 0.25, "RW fraction {fr}");
    assert_eq!(nb, 0, "NSARW never backtracks while it has a choice");
    // MCTS `cells` behaves like NSARW: measured 0 of 1200 eligible steps.
    // Allowing 2% (24 steps) keeps the test honest: a true rate of 0.5%
    // exceeds it with probability < 1e-6, while a searcher that backtracked
    // even a tenth as often as a random walk (4%) would fail.
    assert!(fm <= 0.02, "MCTS cells backtracked on {mb} of {me} steps");
    // And it is far below the random walk's rate.
    let margin = 4.0 * (freq_se(mb, me).powi(2) + freq_se(rb, re).powi(2)).sqrt();
    assert!(fr - fm > margin, "MCTS {fm} vs RW {fr} (margin {margin})");
    assert!(me >= 1000, "too few eligible steps: {me}");
}
