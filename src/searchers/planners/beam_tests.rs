//! Tests of the beam planner.

use super::*;
use crate::config::Config;

#[test]
fn a_plan_made_in_slices_is_the_plan_made_at_once() {
    // One slice per call, as the page's worker asks: the progress is
    // reported at every slice and moves through the stages in order,
    // no move is made until the plan is, and the path is the one a
    // plan made in a single call gives (made afresh, not recalled).
    let cfg = Config::default().with(&[
        ("n", "14"),
        ("searcher", "beam"),
        ("sigma", "2.25"),
        ("beam_width", "12"),
        ("beam_depth", "30"),
    ]);
    let mut sliced = crate::run::episode::Episode::blind(&cfg).unwrap();
    let (mut slices, mut stages, mut depth) = (0, Vec::new(), 0);
    while !sliced.step_loops(1) {
        slices += 1;
        let p = sliced.planning().expect("progress while the plan is made");
        assert!(p.total == 0 || p.done <= p.total, "{p:?}");
        if p.stage == "beam search, depth" {
            assert!(p.done >= depth, "the depth never goes back: {p:?}");
            depth = p.done;
        }
        if stages.last() != Some(&p.stage) {
            stages.push(p.stage);
        }
        assert_eq!(sliced.steps(), 0);
        // The path being worked on is drawn from where the searcher is.
        let sketch = sliced.intent();
        assert_eq!(sketch.first(), Some(&sliced.position()), "{p:?}");
    }
    assert!(sliced.planning().is_none());
    assert!(slices > 20, "{slices} slices");
    // The last depth seen is before the slice that finished the search.
    assert!((20..30).contains(&depth), "depth {depth}");
    let order = [
        "horizon rule's path",
        "beam search, depth",
        "finishing the beam's path",
        "refining the rule's path, pass 1",
    ];
    assert_eq!(stages[..4], order, "{stages:?}");
    assert!(
        stages.contains(&"refining the beam's path, pass 1"),
        "{stages:?}"
    );
    while sliced.steps() < 250 {
        sliced.step_move();
    }
    plan_cache::forget("beam");
    let mut whole = crate::run::episode::Episode::blind(&cfg).unwrap();
    while whole.steps() < 250 {
        whole.step_move();
    }
    assert_eq!(sliced.path(), whole.path());
}

#[test]
fn an_advance_call_makes_eight_slices_of_a_plan_whatever_k() {
    // At the slowest speed (k = 1) and when the worker asks for many
    // microsecond moves (k = 1000) alike: PLAN_CALL_SLICES slices, as
    // far as the same slices made one call each get the rule's path.
    let cfg = Config::default().with(&[
        ("n", "30"),
        ("prior", "uniform"),
        ("searcher", "beam"),
        ("beam_width", "4"),
        ("beam_depth", "10"),
        ("horizon", "8"),
    ]);
    let per = crate::run::episode::PLAN_CALL_SLICES as usize;
    // The rule's progress after each of the first slices, one a call.
    let mut one = crate::run::episode::Episode::blind(&cfg).unwrap();
    let after: Vec<u32> = (0..2 * per + 2)
        .map(|_| {
            assert!(!one.step_loops(1));
            let p = one.planning().unwrap();
            assert_eq!(p.stage, "horizon rule's path");
            p.done
        })
        .collect();
    assert!(
        after.windows(2).all(|w| w[0] < w[1]),
        "every slice moves: {after:?}"
    );
    let mut ep = crate::run::episode::Episode::blind(&cfg).unwrap();
    // A clock that stands still: only the slice count ends a call.
    ep.set_clock(|| 0.0);
    for (k, slices) in [(1, per), (1000, 2 * per)] {
        assert_eq!(ep.advance(k), 0);
        let p = ep.planning().unwrap();
        assert_eq!(
            (p.stage, p.done),
            ("horizon rule's path", after[slices - 1]),
            "k {k}"
        );
    }
    // A clock that gains 5 ms at every reading: the call stops at the
    // first reading past PLAN_CALL_MS (8 ms), after two slices.
    static TICKS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    ep.set_clock(|| 5.0 * TICKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed) as f64);
    ep.advance(1000);
    let p = ep.planning().unwrap();
    assert_eq!(p.done, after[2 * per + 1]);
}

#[test]
fn front_and_reach_follow_the_radius() {
    let t = Torus::new(12).unwrap();
    for (rv, front, reach) in [(0.0, 1, 0), (1.0, 3, 1), (1.5, 3, 2), (2.0, 5, 2)] {
        let s = Sensor::new(&t, rv).unwrap();
        assert_eq!(front_and_reach(&s), (front, reach), "rv {rv}");
    }
}

#[test]
fn the_rest_bound_never_exceeds_what_a_path_has_left() {
    // Along a planned path, at every step, the bound on the rest is at
    // most the rest's exact Σ R (with all cells and with only a few
    // heavy ones). Fails if the front were too large or the reach too
    // small.
    for (rv, sigma) in [(1.0, 2.0), (0.0, 1.5), (2.0, 3.0)] {
        let mut cfg = Config::default().with(&[
            ("n", "12"),
            ("searcher", "beam"),
            ("beam_width", "6"),
            ("beam_depth", "20"),
        ]);
        cfg.rv = rv;
        cfg.sigma = sigma;
        let g = cfg.game().unwrap();
        let mut ep = crate::run::episode::Episode::blind(&cfg).unwrap();
        while ep.steps() < 400 {
            ep.step_move();
        }
        let path = ep.path();
        let mass = g.prior.mass();
        let (front, reach) = front_and_reach(&g.sensor);
        let mut heavy: Vec<u32> = (0..g.torus.cells() as u32).collect();
        heavy.sort_by(|&a, &b| mass[b as usize].total_cmp(&mass[a as usize]));
        let heavy = with_xy(&g.torus, &heavy);
        // R_t along the path.
        let mut covered = vec![false; g.torus.cells()];
        let mut rs = Vec::new();
        let mut left = 1.0;
        for &p in path {
            for c in g.sensor.around(p) {
                if !std::mem::replace(&mut covered[c as usize], true) {
                    left -= mass[c as usize];
                }
            }
            rs.push(left.max(0.0));
        }
        covered.iter_mut().for_each(|c| *c = false);
        for (t, &p) in path.iter().enumerate().take(150) {
            for c in g.sensor.around(p) {
                covered[c as usize] = true;
            }
            let rest: f64 = rs[t + 1..].iter().sum();
            for top in [heavy.len(), 7] {
                let b = rest_bound(&g.torus, mass, &heavy[..top], front, reach, p, rs[t], |c| {
                    covered[c as usize]
                });
                assert!(
                    b <= rest + 1e-9,
                    "rv {rv} t {t} top {top}: bound {b} > rest {rest}"
                );
            }
        }
    }
}
