//! Going back: seeking to any point a run has reached gives exactly the
//! state reached going forward (path, statistics, the phase shown, the
//! tree and the whole frame), whatever the snapshots kept; bad points get
//! an error naming them and the points allowed, and change nothing.

use torus_search::config::Config;
use torus_search::display::render::{Palette, ScaleKind};
use torus_search::display::view::{FrameBuilder, FrameRequest, LayerRequest};
use torus_search::game::layer::Layer;
use torus_search::game::rng;
use torus_search::run::episode::{Episode, Status, TimePoint};
use torus_search::run::timeline::{SeekError, Timeline, DEFAULT_CAP_BYTES, WORK_PER_BYTE};
use torus_search::searchers::phase::PhaseKind;
use torus_search::searchers::tree_export::TreeQuery;
use wasm_bindgen_test::wasm_bindgen_test;

fn small(variant: &str) -> Config {
    Config {
        n: 24,
        sigma: 6.0,
        seed: 5,
        ..Config::default()
    }
    .with(&[("variant", variant), ("loops", "12"), ("keep_traces", "2")])
}

/// Everything a display could show of `ep`, as text: the frame (its
/// layers' keys and pixels, the decision, traces, the phase), the tree
/// and the decision counters.
fn shown(ep: &Episode, fb: &mut FrameBuilder) -> String {
    let layer = |layer| LayerRequest {
        layer,
        palette: Palette::Viridis,
        scale: ScaleKind::Linear,
        alpha: [0, 255],
        have: None,
    };
    let req = FrameRequest {
        layers: vec![layer(Layer::Posterior), layer(Layer::Visits)],
        traces: true,
        intent: true,
        ..FrameRequest::default()
    };
    let frame = serde_json::to_string(&fb.frame(ep, &req, 0.0)).unwrap();
    let tree = ep.tree(&TreeQuery::default()).map(|t| t.unwrap());
    format!(
        "{frame}\n{tree:?}\n{:?} {:?}",
        ep.decision_counters(),
        ep.phase()
    )
}

/// Steps `ep` with a random mix of phases, loops and moves, noting each
/// point and what it shows, until it ends or `max` points.
fn forward(
    ep: &mut Episode,
    tl: &mut Timeline,
    fb: &mut FrameBuilder,
    seed: u64,
    max: usize,
) -> Vec<(TimePoint, String)> {
    let mut r = rng::stream(seed, 1);
    let mut seen = vec![(ep.point(), shown(ep, fb))];
    while ep.status() == Status::Running && seen.len() < max {
        match rng::below(&mut r, 5) {
            0 | 1 => {
                ep.step_phase();
            }
            2 => {
                ep.step_loops(1 + rng::below(&mut r, 4));
            }
            3 => {
                ep.step_move();
            }
            _ => {
                ep.advance_observed(1 + rng::below(&mut r, 30) as u64, u64::MAX, |e| tl.note(e));
            }
        }
        tl.note(ep);
        // Slices of a plan being made before a decision's first loop are
        // not points: seeking there shows the decision before its plan.
        if ep.planning().is_none() {
            seen.push((ep.point(), shown(ep, fb)));
        }
    }
    seen
}

fn check_seeks(cfg: &Config, cap: usize, spacing: u64, seed: u64) -> Timeline {
    let mut ep = Episode::new(cfg).unwrap();
    let mut tl = Timeline::with_spacing(&ep, cap, spacing);
    let mut fb = FrameBuilder::new((cfg.n * cfg.n) as usize);
    let seen = forward(&mut ep, &mut tl, &mut fb, seed, 400);
    assert!(seen.len() > 15, "{} points", seen.len());
    // Every point, in a random order (back, forward, within a loop).
    let mut order: Vec<usize> = (0..seen.len()).collect();
    let mut r = rng::stream(seed, 2);
    for i in (1..order.len()).rev() {
        order.swap(i, rng::below(&mut r, i as u32 + 1) as usize);
    }
    for i in order {
        let (to, want) = &seen[i];
        tl.seek(&mut ep, *to)
            .unwrap_or_else(|e| panic!("{to}: {e}"));
        assert_eq!(ep.point(), *to);
        assert_eq!(&shown(&ep, &mut fb), want, "seek to {to}");
    }
    tl
}

#[wasm_bindgen_test(unsupported = test)]
fn seeking_anywhere_gives_the_state_reached_going_forward() {
    // A snapshot at every move, and at the default spacing.
    for variant in ["cells", "tree", "code", "pomcp"] {
        for seed in [1, 2] {
            let tl = check_seeks(&small(variant), DEFAULT_CAP_BYTES, 0, seed);
            assert!(tl.memory().snapshots > 0, "{variant}: no snapshot taken");
        }
        check_seeks(&small(variant), DEFAULT_CAP_BYTES, WORK_PER_BYTE, 3);
    }
    // An escape (moves without loops) and a walker.
    let escape = Config {
        prior: torus_search::game::prior::PriorKind::Uniform,
        ..small("cells")
    }
    .with(&[("escape", "2"), ("decay", "1")]);
    check_seeks(&escape, DEFAULT_CAP_BYTES, 0, 4);
    let walker = small("cells").with(&[("searcher", "nsarw")]);
    check_seeks(&walker, DEFAULT_CAP_BYTES, 0, 5);
}

#[wasm_bindgen_test(unsupported = test)]
fn seeking_replays_from_the_start_when_no_snapshot_fits() {
    // A cap of one byte keeps no snapshot; a planner cannot copy itself:
    // both replay from the start.
    let tl = check_seeks(&small("tree"), 1, 0, 6);
    assert_eq!(tl.memory().snapshots, 0);
    assert_eq!(tl.memory().bytes, 0);
    let sweep = small("cells").with(&[("searcher", "sweep")]);
    check_seeks(&sweep, DEFAULT_CAP_BYTES, 0, 7);
}

#[wasm_bindgen_test(unsupported = test)]
fn snapshots_stay_within_the_cap() {
    // Blind (it never finds the target), with long decisions.
    let cfg = small("cells").with(&[("loops", "100")]);
    let mut ep = Episode::blind(&cfg).unwrap();
    let size = ep.heap_bytes();
    let cap = 6 * size;
    let mut tl = Timeline::with_spacing(&ep, cap, 1);
    for _ in 0..60 {
        if ep.step_move() != Status::Running {
            break;
        }
        tl.note(&ep);
        let m = tl.memory();
        assert!(m.bytes <= cap, "{m:?}");
    }
    let m = tl.memory();
    assert!(m.snapshots >= 2 && m.work_per_byte > 1, "{m:?}");
}

#[wasm_bindgen_test(unsupported = test)]
fn a_bad_point_names_itself_and_the_range_and_changes_nothing() {
    let cfg = small("cells");
    let mut ep = Episode::new(&cfg).unwrap();
    let mut tl = Timeline::new(&ep, DEFAULT_CAP_BYTES);
    let mut fb = FrameBuilder::new(576);
    for _ in 0..5 {
        ep.step_move();
        tl.note(&ep);
    }
    for _ in 0..6 {
        ep.step_phase();
        tl.note(&ep);
    }
    // Move 5, loop 1 in flight after its select.
    assert_eq!(
        tl.end(),
        TimePoint {
            mv: 5,
            loop_: 1,
            phase: Some(PhaseKind::Expand)
        }
    );
    let before = shown(&ep, &mut fb);
    let past = TimePoint::at(9, 0);
    let e = tl.seek(&mut ep, past).unwrap_err();
    assert_eq!(
        e,
        SeekError::PastEnd {
            to: past,
            end: tl.end()
        }
    );
    let msg = e.to_string();
    assert!(
        msg.contains("move 9") && msg.contains("up to move 5, loop 1, phase expand"),
        "{msg}"
    );
    let in_loop = TimePoint {
        phase: Some(PhaseKind::Rollout),
        ..tl.end()
    };
    assert!(matches!(
        tl.seek(&mut ep, in_loop),
        Err(SeekError::PastEnd { .. })
    ));
    // Decision 2 ran its 12 loops: loop 12 is past it.
    let e = tl.seek(&mut ep, TimePoint::at(2, 12)).unwrap_err();
    assert_eq!(
        e,
        SeekError::PastDecision {
            to: TimePoint::at(2, 12),
            loops: 12
        }
    );
    assert!(e.to_string().contains("loops 0..=11"), "{e}");
    assert_eq!(shown(&ep, &mut fb), before, "errors change nothing");
    // The last loop's back-up is the last point of a decision.
    let last = TimePoint {
        mv: 2,
        loop_: 11,
        phase: Some(PhaseKind::Backup),
    };
    tl.seek(&mut ep, last).unwrap();
    assert_eq!((ep.steps(), ep.point()), (3, last));
    // From there, a loop past that decision is still past it.
    let e = tl
        .seek(&mut ep, TimePoint { loop_: 12, ..last })
        .unwrap_err();
    assert!(
        matches!(e, SeekError::PastDecision { loops: 12, .. }),
        "{e}"
    );
    assert_eq!((ep.steps(), ep.point()), (3, last));
    // A walker has no loops.
    let walk = small("cells").with(&[("searcher", "rw")]);
    let mut w = Episode::new(&walk).unwrap();
    let mut wt = Timeline::new(&w, DEFAULT_CAP_BYTES);
    w.advance(20);
    wt.note(&w);
    let e = wt.seek(&mut w, TimePoint::at(3, 1)).unwrap_err();
    assert!(matches!(e, SeekError::NoLoops { .. }), "{e}");
    assert_eq!(w.steps(), 20);
    // A timed run does not replay.
    let timed = small("cells").with(&[("ms", "5")]);
    let mut t = Episode::new(&timed).unwrap();
    let tt = Timeline::new(&t, DEFAULT_CAP_BYTES);
    let e = tt.seek(&mut t, TimePoint::at(0, 0)).unwrap_err();
    assert!(e.to_string().contains("ms = 5"), "{e}");
}

/// What a state holds, whatever point names it (the state after a loop's
/// back-up is the next loop's start).
fn state_of(ep: &Episode) -> String {
    format!(
        "{:?} {:?} {:?} {:?}",
        ep.path(),
        ep.counters(),
        ep.decision_counters(),
        ep.decision()
    )
}

#[wasm_bindgen_test(unsupported = test)]
fn stepping_back_retraces_the_states_stepped_through() {
    use torus_search::run::race::Race;
    use torus_search::run::timeline::BackUnit;
    for variant in ["cells", "tree"] {
        let cfg = small(variant).with(&[("loops", "3")]);
        let mut race = Race::new(std::slice::from_ref(&cfg)).unwrap();
        let mut states = vec![state_of(&race.runs()[0])];
        let mut loop_starts = vec![0];
        for _ in 0..30 {
            let step = race.step_phase()[0];
            states.push(state_of(&race.runs()[0]));
            if step.and_then(|s| s.phase()) == Some(PhaseKind::Backup) {
                loop_starts.push(states.len() - 1);
            }
        }
        assert!(race.runs()[0].steps() >= 2, "{variant}: crosses moves");
        // Back a phase at a time: every state in reverse, to the start.
        for want in states.iter().rev().skip(1) {
            assert!(race.back(BackUnit::Phase).unwrap(), "{variant}");
            assert_eq!(&state_of(&race.runs()[0]), want, "{variant}: back a phase");
        }
        assert!(
            !race.back(BackUnit::Phase).unwrap(),
            "{variant}: at the start"
        );
        assert_eq!(race.runs()[0].point(), TimePoint::at(0, 0));
        // Forward again, then back a loop at a time: the loops' starts.
        for _ in 0..30 {
            race.step_phase();
        }
        assert!(race.back(BackUnit::Loop).unwrap());
        let last = *loop_starts.last().unwrap();
        assert_eq!(
            state_of(&race.runs()[0]),
            states[last],
            "{variant}: back to the loop's start"
        );
        for &want in loop_starts.iter().rev().skip(1) {
            assert!(race.back(BackUnit::Loop).unwrap());
            assert_eq!(
                state_of(&race.runs()[0]),
                states[want],
                "{variant}: back a loop"
            );
        }
        // A move back from mid-decision: its start; then the one before.
        race.seek(TimePoint {
            mv: 2,
            loop_: 1,
            phase: Some(PhaseKind::Expand),
        })
        .unwrap();
        race.back(BackUnit::Move).unwrap();
        assert_eq!(race.runs()[0].point(), TimePoint::at(2, 0));
        race.back(BackUnit::Move).unwrap();
        assert_eq!(race.runs()[0].point(), TimePoint::at(1, 0));
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_race_seeks_each_board_to_its_own_point() {
    use torus_search::run::race::Race;
    // A moves every 5 loops, B every 40: after 12 loops they stand apart.
    let a = small("tree").with(&[("loops", "5")]);
    let b = a.clone().with(&[("loops", "40")]);
    let mut race = Race::new(&[a, b]).unwrap();
    for _ in 0..12 {
        race.step_loop();
    }
    let points: Vec<TimePoint> = race.runs().iter().map(|r| r.point()).collect();
    assert_ne!(points[0], points[1], "the boards stand apart");
    let want: Vec<String> = race.runs().iter().map(state_of).collect();
    for _ in 0..20 {
        race.step_loop();
    }
    race.seek_each(&points).unwrap();
    let got: Vec<String> = race.runs().iter().map(state_of).collect();
    assert_eq!(got, want, "each board where it stood");
    // One point for both: B, yet to reach A's move 2, shows its latest point
    // before it (the 32 loops it ran), not where it stood.
    race.seek(points[0]).unwrap();
    assert_eq!(race.runs()[1].point(), TimePoint::at(0, 32));
    // A point for each board, or none: the count is named.
    let e = race.seek_each(&points[..1]).unwrap_err().to_string();
    assert!(e.contains("one per run (2)"), "{e}");
}
