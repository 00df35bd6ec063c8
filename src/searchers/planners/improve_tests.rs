//! Tests of the rollout improvement.

use super::*;
use crate::config::Config;
use crate::game::budget::Budget;
use crate::game::counters::Counters;
use crate::game::traces::Traces;
use crate::searchers::mcts::search::{BELIEF, LOOPS, MS};

/// What driving an improver for `moves` moves gave: the moves, each
/// decision's scores, the planning mass left after each move (`R_t`,
/// `R_0` first), and the improver's log.
struct Drive {
    moves: Vec<Move>,
    scores: Vec<[f64; 4]>,
    slices_per_move: Vec<usize>,
    paid: Vec<f64>,
    log: TestLog,
}

/// The exact mean of `cfg`'s base alone from its start.
fn alone_of(cfg: &Config) -> f64 {
    let g = cfg.game().unwrap();
    let mut belief = BeliefState::new(cfg.settings.choice(&BELIEF), g.prior.clone(), None);
    belief.search_around(&g.sensor, g.start);
    let (base, h) = (cfg.settings.choice(&BASE), cfg.settings.u32(&HORIZON));
    base_alone(&g.torus, &g.sensor, &belief, g.start, base, h, cfg.step_cap).0
}

/// Drives an improver for `cfg` as an episode does, one slice per call,
/// with slices of at most `slice` work.
fn drive(cfg: &Config, slice: u64, moves: usize) -> Drive {
    let g = cfg.game().unwrap();
    let mut sensor = g.sensor.clone();
    let mut belief = BeliefState::new(cfg.settings.choice(&BELIEF), g.prior.clone(), None);
    belief.search_around(&sensor, g.start);
    let (base, h) = (cfg.settings.choice(&BASE), cfg.settings.u32(&HORIZON));
    let mut imp = Improve::new(base, h, cfg.step_cap, &g.torus, &sensor, g.start);
    imp.slice = slice;
    let (mut rng, mut budget) = (
        crate::game::rng::stream(1, 1),
        Budget::new(cfg.settings.u32(&LOOPS), cfg.settings.opt_float(&MS)),
    );
    let (mut traces, mut counters) = (Traces::new(0), Counters::default());
    let mut out = Drive {
        moves: Vec::new(),
        scores: Vec::new(),
        slices_per_move: Vec::new(),
        paid: vec![left_of(&belief).r()],
        log: TestLog::default(),
    };
    let mut pos = g.start;
    while out.moves.len() < moves {
        let mut slices = 1;
        let m = loop {
            let mut w = World {
                torus: &g.torus,
                sensor: &mut sensor,
                belief: &mut belief,
                rng: &mut rng,
                pos,
                budget: &mut budget,
                traces: &mut traces,
                counters: &mut counters,
            };
            if let Some(m) = imp.think(&mut w, 1) {
                break m;
            }
            let p = imp.planning().expect("progress between slices");
            assert!(p.done < p.total, "{p:?}");
            slices += 1;
            assert!(slices < 100_000, "a decision that never ends");
        };
        assert!(
            imp.planning().is_none(),
            "no decision under way after a move"
        );
        // Completions start from the first sweep waypoint still adding
        // mass, none of those before it (re-skipping them in every
        // completion would cost a decision O(N²) more work).
        let fresh = Coverage::new(g.torus.cells());
        let adds = |&w: &u32| fresh.gain(&sensor, &belief, w) > 0.0;
        let (skipped, next) = imp.sweep.split_at(imp.sweep_from);
        assert!(!skipped.iter().any(adds) && next.first().is_none_or(adds));
        pos = g.torus.step(pos, m);
        belief.search_around(&sensor, pos);
        imp.observe(&g.torus, m, pos);
        out.moves.push(m);
        out.scores.push(imp.scores().unwrap().score);
        out.slices_per_move.push(slices);
        out.paid.push(left_of(&belief).r());
    }
    out.log = std::mem::take(&mut imp.log);
    out
}

#[test]
fn a_decision_made_in_slices_of_bounded_work_is_the_decision_made_at_once() {
    // Every base, on a wide prior (long completions) and a narrow one:
    // the same moves and the same scores, bit for bit, as decisions
    // made in one go; every slice stops within one simulated move of
    // the budget; and with a small budget decisions take several slices.
    for (base, sigma, moves) in [
        ("horizon", "10", 12),
        ("cover", "10", 40),
        ("sweep", "10", 40),
        ("best", "2.5", 25),
    ] {
        let cfg = Config::default().with(&[
            ("searcher", "improve"),
            ("base", base),
            ("horizon", "4"),
            ("sigma", sigma),
        ]);
        let whole = drive(&cfg, u64::MAX, moves);
        assert!(whole.slices_per_move.iter().all(|&s| s == 1));
        // The page's slices, and slices cut finer (more places to resume).
        for budget in [SLICE_WORK, 500] {
            let sliced = drive(&cfg, budget, moves);
            assert_eq!(sliced.moves, whole.moves, "base {base}");
            for (a, b) in sliced.scores.iter().zip(&whole.scores) {
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "base {base}");
            }
            // One move's most work: the lookahead at h = 4, or a sweep
            // move's skipped waypoints, and a far-goal scan of the 1600 cells.
            let most = budget + 2 * 81 + 1600;
            let longest = sliced.log.slices.iter().map(|s| s.0).max().unwrap();
            assert!(
                longest <= most,
                "base {base}: a slice of {longest} > {most}"
            );
            // Every simulated move and every waypoint skipped costs at
            // least one unit: the work counted bounds what a slice does.
            for &(work, steps) in &sliced.log.slices {
                assert!(steps <= work, "base {base}: {steps} steps for {work} work");
            }
            let slices: usize = sliced.slices_per_move.iter().sum();
            if budget == 500 {
                assert!(
                    slices > 2 * moves,
                    "base {base}: {slices} slices for {moves} moves"
                );
            }
            eprintln!("base {base}, budget {budget}: {slices} slices for {moves} moves, the longest {longest}");
        }
    }
}

#[test]
fn the_incumbent_is_kept_and_costs_what_was_promised_less_the_move_paid() {
    // The fortified rollout: the first decision starts from the base's
    // own path (the cheapest base's, with `best`), whose cost is the
    // base's mean less R_0; after that the incumbent always holds, and
    // what is left of it costs what the decision before promised (its
    // cheapest completion) less the R_t the move just paid. With
    // `best` on the uniform prior at h = 1 the sweep's own path is the
    // cheapest (45.86 against 48.61 for the cover walk and the
    // horizon rule), not the last base's.
    for (base, prior, sigma, n, h, moves) in [
        ("cover", "gaussian", "10", "40", "4", 30),
        ("sweep", "gaussian", "10", "40", "4", 30),
        ("horizon", "gaussian", "5", "24", "4", 20),
        ("best", "gaussian", "2.5", "20", "4", 25),
        ("best", "uniform", "0", "16", "1", 25),
    ] {
        let cfg = Config::default().with(&[
            ("searcher", "improve"),
            ("base", base),
            ("horizon", h),
            ("prior", prior),
            ("sigma", sigma),
            ("n", n),
        ]);
        let d = drive(&cfg, u64::MAX, moves);
        let case = format!("base {base} {prior} σ = {sigma}");
        let decided = &d.log.decisions;
        assert_eq!(decided.len(), moves, "{case}");
        let (fresh, inc, cheapest) = decided[0];
        let alone = alone_of(&cfg);
        assert!(fresh && cheapest <= inc, "{case}: {:?}", decided[0]);
        assert!(
            (inc - (alone - d.paid[0])).abs() <= 1e-12 * alone,
            "{case}: the first incumbent costs {inc}, the base {alone} less R_0 {}",
            d.paid[0]
        );
        for (k, w) in decided.windows(2).enumerate() {
            let ((_, _, promised), (fresh, inc, cheapest)) = (w[0], w[1]);
            let paid = d.paid[k + 1];
            assert!(!fresh, "{case}: decision {} started afresh", k + 1);
            assert!(
                (inc - (promised - paid)).abs() <= 1e-12 * promised,
                "{case}: decision {}: the incumbent costs {inc}, {promised} was promised and {paid} paid",
                k + 1
            );
            assert!(cheapest <= inc, "{case}");
        }
        eprintln!(
            "{case}: the base {alone:.4}, promised at the first move {:.4}",
            d.paid[0] + decided[0].2
        );
    }
}

#[test]
fn with_every_base_each_move_scores_its_cheapest_completion() {
    // At the first move (the same state whatever the base) `best`
    // scores each move by the cheapest of the three bases' completions.
    for sigma in ["2.5", "10"] {
        let first = |base| {
            let cfg = Config::default().with(&[
                ("searcher", "improve"),
                ("base", base),
                ("horizon", "3"),
                ("sigma", sigma),
                ("n", "24"),
            ]);
            drive(&cfg, u64::MAX, 1).scores[0]
        };
        let singles = ["cover", "sweep", "horizon"].map(first);
        let best = first("best");
        for m in 0..4 {
            let each = singles.map(|s| s[m]);
            let cheapest = each.iter().copied().fold(f64::INFINITY, f64::min);
            assert_eq!(
                best[m].to_bits(),
                cheapest.to_bits(),
                "σ = {sigma}, move {m}: {each:?}"
            );
        }
        // Some move is scored by a base other than the first.
        assert!(
            (0..4).any(|m| singles[0][m] > best[m]),
            "σ = {sigma}: {singles:?}"
        );
    }
}
