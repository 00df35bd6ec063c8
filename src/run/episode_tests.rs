//! The episode's tests: results between workers, accessors, calls of
//! bounded length.

use super::*;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// A blind trial of `searcher` at N = 40 (the default prior).
fn blind(searcher: &str) -> Episode {
    Episode::blind(&Config::default().with(&[("searcher", searcher)])).unwrap()
}

#[test]
fn a_trial_result_passes_between_workers_as_its_fields_and_back() {
    // A result whose every field differs (the MCTS counts its rollouts),
    // in the documented order, read back unchanged; the worker pool
    // sums batches from these numbers.
    let cfg = Config::default().with(&[("n", "12"), ("sigma", "2"), ("loops", "10")]);
    let r = Episode::trial(&cfg, 3).unwrap().run();
    let c = r.counters;
    assert!(r.found && r.steps > r.optimal && c.rollouts > c.truncated);
    let want = [
        r.steps,
        r.optimal,
        1,
        r.target,
        c.rollouts as u32,
        c.rollout_steps as u32,
        c.truncated as u32,
    ]
    .map(f64::from);
    assert_eq!(r.fields(), want);
    assert_eq!(TrialResult::from_fields(&r.fields()), Some(r));
    let capped = TrialResult { found: false, ..r };
    assert_eq!(capped.fields()[2], 0.0);
    assert_eq!(TrialResult::from_fields(&capped.fields()), Some(capped));
    // Each field at the ends of its range, then just past them.
    let u53 = 9_007_199_254_740_992.0;
    for (i, max) in [
        u32::MAX as f64,
        u32::MAX as f64,
        1.0,
        u32::MAX as f64,
        u53,
        u53,
        u53,
    ]
    .into_iter()
    .enumerate()
    {
        // 2^53 + 1 rounds to 2^53 in f64: the next number past it is 2^53 + 2.
        let past = if max == u53 { max + 2.0 } else { max + 1.0 };
        for (v, ok) in [
            (0.0, true),
            (max, true),
            (-1.0, false),
            (past, false),
            (0.5, false),
        ] {
            let mut f = r.fields();
            f[i] = v;
            assert_eq!(
                TrialResult::from_fields(&f).is_some(),
                ok,
                "field {i} = {v}"
            );
        }
    }
    assert_eq!(TrialResult::from_fields(&r.fields()[..6]), None);
    assert_eq!(TrialResult::from_fields(&[0.0; TRIAL_FIELDS + 1]), None);
}

#[test]
fn the_accessors_report_the_trial_and_its_work_as_it_goes() {
    // Start (3, 5) and target (8, 9), 1-based: 9 apart, so the fewest
    // moves that detect it (r_v = 1) are 8.
    let cfg = Config::default().with(&[
        ("n", "12"),
        ("start", "3,5"),
        ("target", "8,9"),
        ("loops", "10"),
    ]);
    let mut ep = Episode::trial(&cfg, 0).unwrap();
    let t = Torus::new(12).unwrap();
    assert_eq!(ep.config(), &cfg);
    assert_eq!((ep.start(), ep.target()), (t.cell(2, 4), t.cell(7, 8)));
    assert_eq!(ep.optimal(), 8);
    // The decision's loops and rollouts, and the episode's, as loops run
    // (a call's loops stop at the end of the decision).
    let rollouts = |ep: &Episode| (ep.decision_counters().rollouts, ep.counters().rollouts);
    assert!(!ep.step_loops(3));
    assert_eq!((ep.loops_done(), ep.work(), rollouts(&ep)), (3, 3, (3, 3)));
    assert!(ep.step_loops(100));
    assert_eq!(
        (ep.loops_done(), ep.work(), rollouts(&ep)),
        (10, 10, (10, 10))
    );
    assert!(!ep.step_loops(4));
    assert_eq!(
        (ep.loops_done(), ep.work(), rollouts(&ep)),
        (4, 14, (4, 14))
    );
    assert_eq!((ep.steps(), ep.start()), (1, t.cell(2, 4)));
    // The visit counts change with every loop, the one that makes the
    // move too: their generation must, for the page to redraw them.
    for _ in 0..25 {
        let g = ep.generation(Layer::Visits);
        ep.step_loops(1);
        assert!(ep.generation(Layer::Visits) > g, "loop {}", ep.work());
    }
    assert_eq!(ep.steps(), 3);
    // A walk's work is its moves.
    let mut walk = Episode::trial(&cfg.clone().with(&[("searcher", "rw")]), 0).unwrap();
    for _ in 0..5 {
        assert!(walk.step_loops(1));
    }
    assert_eq!(
        (walk.work(), walk.steps(), walk.counters().rollouts),
        (5, 5, 0)
    );
}

#[test]
fn an_ended_episode_and_a_call_for_no_loops_change_nothing() {
    // Found (a walk and an MCTS) and capped (at 2 moves): whatever is
    // called after the end, the result stands.
    for (searcher, cap, status) in [
        ("rw", "500", Status::Found),
        ("mcts", "500", Status::Found),
        ("rw", "2", Status::Capped),
    ] {
        let cfg = Config::default().with(&[
            ("searcher", searcher),
            ("n", "12"),
            ("sigma", "2"),
            ("loops", "10"),
            ("step_cap", cap),
        ]);
        let mut ep = Episode::trial(&cfg, 3).unwrap();
        assert!(!ep.step_loops(0), "{searcher}");
        assert_eq!((ep.steps(), ep.counters()), (0, Counters::default()));
        let r = ep.run();
        assert_eq!(ep.status(), status, "{searcher}");
        assert!(r.steps > 0);
        assert!(!ep.step_loops(1) && !ep.step_loops(u32::MAX), "{searcher}");
        assert_eq!(ep.advance(10), 0);
        assert!(ep.step_move_bounded());
        assert_eq!(ep.step_move(), status);
        assert_eq!((ep.result(), ep.path().len()), (r, r.steps as usize + 1));
    }
}

#[test]
fn a_call_of_moves_makes_all_k_while_time_allows_reading_the_clock_rarely() {
    // Microsecond moves on a clock that gains 1 µs a reading (and
    // stands far from 0, as a page's does: a call counts from its own
    // start): all k moves, with the clock read log2(1024) + k/1024
    // times, not k. One reading as the call starts, one after each
    // stride of 1, 2, 4, …, 512 moves (1023 in all; each doubles the
    // stride), then one after each 1024 moves of the 8977 left.
    static READS: AtomicU64 = AtomicU64::new(0);
    let mut ep = blind("rw");
    ep.set_clock(|| 1e6 + READS.fetch_add(1, Relaxed) as f64 * 1e-3);
    assert_eq!(ep.advance(10_000), 10_000);
    assert_eq!(READS.load(Relaxed), 1 + 10 + 8, "clock readings");
    let mut one = blind("rw");
    for _ in 0..10_000 {
        one.step_move();
    }
    assert_eq!(one.path(), ep.path());
}

#[test]
fn a_call_of_moves_ends_once_its_time_is_spent_and_the_path_is_the_same() {
    // Moves that each take 5 ms on the episode's clock (a slow planner
    // on a large lattice): a call asked for 1000 moves ends after two,
    // the first reading past PLAN_CALL_MS. The moves are the same as
    // made one at a time: only the pace depends on the clock.
    static TICKS: AtomicU64 = AtomicU64::new(0);
    for searcher in ["rw", "horizon"] {
        TICKS.store(0, Relaxed);
        let mut ep = blind(searcher);
        ep.set_clock(|| 5.0 * TICKS.fetch_add(1, Relaxed) as f64);
        let mut calls = 0;
        while ep.steps() < 60 {
            TICKS.store(0, Relaxed);
            assert_eq!(ep.advance(1000), 2, "{searcher}");
            calls += 1;
        }
        assert_eq!(calls, 30);
        let mut one = blind(searcher);
        while one.steps() < 60 {
            one.step_move();
        }
        assert_eq!(one.path(), ep.path(), "{searcher}");
    }
}

#[test]
fn the_belief_mcts_plan_is_cut_into_calls_as_a_planner_plan_is() {
    // pomcp at N = 96 makes a plan of thousands of horizon moves before
    // its first loop. On a clock that stands still a call makes
    // PLAN_CALL_SLICES slices of it, whether it is asked for 1 loop or
    // 10 000 (advance) or for a move (step_move_bounded); once the plan
    // is made, the loops run and count as before.
    // (A configuration no other test plans: plans are kept for the
    // process.)
    let cfg = Config::default().with(&[
        ("variant", "pomcp"),
        ("n", "96"),
        ("sigma", "12"),
        ("rollout_cap", "9999"),
    ]);
    let progress = |ep: &Episode| ep.planning().map(|p| p.done);
    let mut one = Episode::blind(&cfg).unwrap();
    one.set_clock(|| 0.0);
    let mut per_slice = Vec::new();
    for _ in 0..PLAN_CALL_SLICES {
        assert!(!one.step_loops(1));
        per_slice.push(progress(&one).unwrap());
    }
    // A call asked for a move makes as many slices, on a clock that
    // stands at any time (a call counts from its own start).
    let mut bounded = Episode::blind(&cfg).unwrap();
    bounded.set_clock(|| 1e6);
    assert!(!bounded.step_move_bounded());
    assert_eq!(progress(&bounded), per_slice.last().copied());
    let mut ep = Episode::blind(&cfg).unwrap();
    ep.set_clock(|| 0.0);
    assert_eq!(ep.advance(1), 0);
    assert_eq!(progress(&ep), per_slice.last().copied(), "advance(1)");
    assert_eq!(ep.advance(10_000), 0);
    let two = progress(&ep).unwrap();
    assert!(
        two > per_slice[PLAN_CALL_SLICES as usize - 1],
        "advance(10 000)"
    );
    assert!(!ep.step_move_bounded());
    assert!(progress(&ep).unwrap() > two, "step_move_bounded");
    assert_eq!(ep.counters().rollouts, 0);
    // A clock that gains 5 ms a reading (the decision's budget reads it
    // too) ends a call within two slices, by PLAN_CALL_MS. (Before any
    // episode has made the whole plan: it is kept for the process.)
    static TICKS: AtomicU64 = AtomicU64::new(0);
    let mut timed = Episode::blind(&cfg).unwrap();
    timed.set_clock(|| 5.0 * TICKS.fetch_add(1, Relaxed) as f64);
    TICKS.store(0, Relaxed);
    assert_eq!(timed.advance(10_000), 0);
    let p = progress(&timed).unwrap();
    assert!(p == per_slice[0] || p == per_slice[1], "{p}: {per_slice:?}");
    // The plan done, a call runs its k loops (the default L = 100 a move).
    while ep.planning().is_some() {
        ep.advance(1);
    }
    let before = ep.counters().rollouts;
    ep.advance(250);
    assert_eq!(ep.counters().rollouts - before, 250);
    assert_eq!(ep.steps(), 2);
}
