//! Racing any two configurations: two sides that differ only in the
//! rollout, c, L or the belief share their targets, in a race and in batch
//! trials, whose paired difference is summarised; a race steps its loops
//! a phase at a time and seeks back as one run does.

use std::collections::BTreeMap;
use torus_search::analysis::paired_runs::summarize;
use torus_search::config::Config;
use torus_search::run::batch::trial;
use torus_search::run::episode::{Episode, Status, TimePoint};
use torus_search::run::paired::{differences, paired_trial, PairError};
use torus_search::run::race::Race;
use torus_search::searchers::phase::PhaseKind;
use wasm_bindgen_test::wasm_bindgen_test;

fn base() -> Config {
    Config {
        n: 16,
        sigma: 3.0,
        seed: 21,
        ..Config::default()
    }
    .with(&[("loops", "20")])
}

#[wasm_bindgen_test(unsupported = test)]
fn sides_that_differ_in_one_parameter_race_on_the_same_target() {
    for (key, value) in [
        ("rollout", "levy"),
        ("c", "0.5"),
        ("loops", "60"),
        ("belief", "prior"),
        ("variant", "tree"),
    ] {
        let other = base().with(&[(key, value)]);
        let d = differences(&base(), &other);
        assert_eq!(d.len(), 1, "{key}: {d:?}");
        assert_eq!((d[0].key, d[0].b.as_str()), (key, value));
        let race = Race::new(&[base(), other.clone()]).unwrap();
        let [a, b] = [&race.runs()[0], &race.runs()[1]];
        assert_eq!((a.target(), a.start()), (b.target(), b.start()), "{key}");
        for i in 0..3 {
            let (ra, rb) = paired_trial(&base(), &other, i).unwrap();
            assert_eq!(ra.target, rb.target);
            assert_eq!(
                (ra, rb),
                (trial(&base(), i).unwrap(), trial(&other, i).unwrap())
            );
        }
    }
    // A parameter the run does not read is no difference.
    assert!(differences(&base(), &base().with(&[("mu", "2.5")])).is_empty());
}

#[wasm_bindgen_test(unsupported = test)]
fn batch_trials_of_both_sides_give_a_paired_summary() {
    let levy = base().with(&[("rollout", "levy")]);
    let pairs: Vec<_> = (0..24)
        .map(|i| paired_trial(&base(), &levy, i).unwrap())
        .collect();
    let s = summarize(&pairs).unwrap();
    let diff: Vec<f64> = pairs
        .iter()
        .map(|(a, b)| a.steps as f64 - b.steps as f64)
        .collect();
    let mean = diff.iter().sum::<f64>() / 24.0;
    assert!((s.difference.estimate - mean).abs() < 1e-9);
    assert_eq!(s.a_wins + s.ties + s.b_wins, 24);
    assert_eq!(s.a_wins as usize, diff.iter().filter(|&&d| d < 0.0).count());
    assert!(s.difference.covers(mean), "{s:?}");
    assert!(
        s.difference.hi > s.difference.lo,
        "distinct sides vary: {s:?}"
    );
    // Another seed draws other targets: not paired, and the error says why.
    let e = paired_trial(&base(), &base().with(&[("seed", "22")]), 0).unwrap_err();
    assert!(matches!(&e, PairError::Unpaired { index: 0, .. }), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("seed 21 ≠ 22") && msg.contains("different targets"),
        "{msg}"
    );
}

/// A run's state as text (its point left out).
fn state(ep: &Episode) -> String {
    format!(
        "{:?} {:?} {:?} {:?}",
        ep.path(),
        ep.counters(),
        ep.decision(),
        ep.phase()
    )
}

#[wasm_bindgen_test(unsupported = test)]
fn a_race_steps_phases_and_seeks_each_run_to_its_own_past() {
    let other = base().with(&[("loops", "7"), ("variant", "tree")]);
    let mut race = Race::new(&[base(), other]).unwrap();
    let mut seen: Vec<BTreeMap<TimePoint, String>> = vec![BTreeMap::new(), BTreeMap::new()];
    let mut points = Vec::new();
    for i in 0..90 {
        match i % 9 {
            0..=5 => {
                let steps = race.step_phase();
                assert!(steps.iter().all(Option::is_some));
            }
            6 => race.step_loop(),
            7 => race.step_move(),
            _ => race.advance(13),
        }
        if race.running() < 2 {
            break;
        }
        for (r, map) in race.runs().iter().zip(&mut seen) {
            map.insert(r.point(), state(r));
        }
        points.push(race.timeline()[0].0);
    }
    assert!(points.len() > 40 && race.memory().len() == 2);
    for &to in points.iter().rev().step_by(3) {
        race.seek(to).unwrap();
        assert_eq!(race.runs()[0].point(), to);
        for (r, map) in race.runs().iter().zip(&seen) {
            assert!(r.point() <= to, "{} > {to}", r.point());
            if let Some(want) = map.get(&r.point()) {
                assert_eq!(&state(r), want, "seek to {to}: at {}", r.point());
            }
        }
    }
    // Past every run's end: an error, and the runs stay where they were.
    let before: Vec<String> = race.runs().iter().map(state).collect();
    let far = TimePoint {
        mv: 10_000,
        loop_: 0,
        phase: Some(PhaseKind::Select),
    };
    let e = race.seek(far).unwrap_err();
    assert!(e.to_string().contains("move 10000"), "{e}");
    let after: Vec<String> = race.runs().iter().map(state).collect();
    assert_eq!(before, after);
}

#[wasm_bindgen_test(unsupported = test)]
fn a_walker_racing_mcts_a_phase_at_a_time_never_gets_ahead() {
    let walker = base().with(&[("searcher", "rw")]);
    let mut race = Race::new(&[base(), walker]).unwrap();
    for _ in 0..200 {
        race.step_phase();
        let [a, b] = [&race.runs()[0], &race.runs()[1]];
        if a.status() != Status::Running {
            break;
        }
        assert!(b.steps() <= a.steps());
    }
    assert!(race.runs()[1].steps() > 0);
}
