//! Geometry of the periodic lattice: wrapping moves, symmetric distances,
//! the detection sensor, and optimal steps checked against breadth-first
//! search. Every reference here is computed independently of `Torus`.
//!
//! Runs natively (`cargo test --test suite geometry::`) and in Node
//! (`cargo test --target wasm32-unknown-unknown --test suite geometry::`).

use crate::common::{bfs_steps, ref_dist2, ref_l1, ref_neighbours};
use torus_search::config::Config;
use torus_search::game::lattice::{Move, Sensor, Torus};
use torus_search::game::prior::PriorKind;
use torus_search::run::episode::{Episode, Status};

fn xy(n: i64, c: u32) -> (i64, i64) {
    (c as i64 % n, c as i64 / n)
}

fn idx(n: i64, (x, y): (i64, i64)) -> u32 {
    (y * n + x) as u32
}

/// Detection radii with their integer squared radius (the reference
/// predicate compares integers, so it cannot share a rounding bug).
const RADII: [(f64, i64); 5] = [
    (0.0, 0),
    (1.0, 1),
    (std::f64::consts::SQRT_2, 2),
    (2.0, 4),
    (2.5, 6),
];

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn every_move_wraps_at_every_edge() {
    for n in [3u32, 4, 5, 8] {
        let t = Torus::new(n).unwrap();
        let ni = n as i64;
        for c in 0..t.cells() as u32 {
            let want = ref_neighbours(ni, xy(ni, c));
            for (k, m) in Move::ALL.into_iter().enumerate() {
                let got = t.step(c, m);
                assert_eq!(xy(ni, got), want[k], "N={n}: {m:?} from {:?}", xy(ni, c));
                // The move's delta agrees with where it goes.
                let (dx, dy) = m.delta();
                assert_eq!(
                    got,
                    t.cell(xy(ni, c).0 + dx as i64, xy(ni, c).1 + dy as i64)
                );
                // Each move has an inverse.
                let back = Move::ALL[(k + 2) % 4];
                assert_eq!(t.step(got, back), c, "N={n}: {m:?} then {back:?}");
                // The hot loops' table holds 4 × the neighbour at 4 × the
                // cell + the move, and `move_to` names the move.
                assert_eq!(t.neighbours()[4 * c as usize + k], 4 * got);
                assert_eq!(t.move_to(c, got), Some(m), "N={n}: {m:?} from {c}");
            }
            // Neither the cell itself nor a diagonal is one move away.
            let (x, y) = xy(ni, c);
            assert_eq!(t.move_to(c, c), None);
            assert_eq!(t.move_to(c, t.cell(x + 1, y + 1)), None);
        }
        assert_eq!(t.neighbours().len(), 4 * t.cells());
        // The four edges, in the users' 1-based coordinates.
        let at = |x: i64, y: i64| t.cell_1based("cell", x, y).unwrap();
        assert_eq!(t.step(at(1, 1), Move::Left), at(ni, 1));
        assert_eq!(t.step(at(1, 1), Move::Up), at(1, ni));
        assert_eq!(t.step(at(ni, ni), Move::Right), at(1, ni));
        assert_eq!(t.step(at(ni, ni), Move::Down), at(ni, 1));
        assert_eq!(t.step(at(ni, 2), Move::Right), at(1, 2));
        assert_eq!(t.step(at(2, ni), Move::Down), at(2, 1));
        // Walking N times in one direction returns to the start.
        for m in Move::ALL {
            let mut c = at(2, 1);
            for _ in 0..n {
                c = t.step(c, m);
            }
            assert_eq!(c, at(2, 1), "N={n}: {m:?} x N");
        }
        // `cell` wraps arbitrary integers.
        assert_eq!(t.cell(-1, -1), at(ni, ni));
        assert_eq!(t.cell(ni, 2 * ni + 1), at(1, 2));
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn distances_are_symmetric_and_match_the_definitions() {
    for n in [3u32, 4, 5, 6] {
        let t = Torus::new(n).unwrap();
        let ni = n as i64;
        for a in 0..t.cells() as u32 {
            let pa = xy(ni, a);
            for b in 0..t.cells() as u32 {
                let pb = xy(ni, b);
                assert_eq!(t.l1(a, b), t.l1(b, a), "N={n} l1 {pa:?} {pb:?}");
                assert_eq!(t.dist2(a, b), t.dist2(b, a), "N={n} dist2 {pa:?} {pb:?}");
                assert_eq!(t.l1(a, b) as i64, ref_l1(ni, pa, pb), "N={n} {pa:?} {pb:?}");
                assert_eq!(
                    t.dist2(a, b) as i64,
                    ref_dist2(ni, pa, pb),
                    "N={n} {pa:?} {pb:?}"
                );
                // ℓ1 is the fewest moves (BFS), so it is also a metric.
                assert_eq!(
                    Some(t.l1(a, b)),
                    bfs_steps(ni, pa, |c| c == pb),
                    "N={n} BFS {pa:?} {pb:?}"
                );
                assert_eq!(t.l1(a, b) == 0, a == b);
            }
        }
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn optimal_steps_equal_breadth_first_search() {
    let mut nonzero = 0;
    for n in [3u32, 4, 5, 7] {
        let t = Torus::new(n).unwrap();
        let ni = n as i64;
        for (rv, r2) in RADII {
            let s = Sensor::new(&t, rv).unwrap();
            for target in 0..t.cells() as u32 {
                let pt = xy(ni, target);
                let detect = |c: (i64, i64)| ref_dist2(ni, c, pt) <= r2;
                for start in 0..t.cells() as u32 {
                    let ps = xy(ni, start);
                    let want = bfs_steps(ni, ps, detect).unwrap();
                    assert_eq!(
                        s.optimal_steps(&t, start, target),
                        want,
                        "N={n} rv={rv} start {ps:?} target {pt:?}"
                    );
                    assert_eq!(s.detects(&t, start, target), detect(ps));
                    nonzero += (want > 0) as u32;
                }
            }
            // With r_v = 0 the optimal steps are the ℓ1 distance.
            if r2 == 0 {
                for a in 0..t.cells() as u32 {
                    for b in 0..t.cells() as u32 {
                        assert_eq!(s.optimal_steps(&t, a, b), t.l1(a, b));
                    }
                }
            }
        }
    }
    assert!(nonzero > 1000, "the comparison must cover nontrivial pairs");
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn episodes_report_bfs_optimal_steps_in_user_coordinates() {
    // The 1-based start/target of a config reach the sensor the right way
    // round, and a start within r_v is found in 0 steps.
    let n = 5i64;
    for (rv, r2) in [(1.0, 1), (2.0, 4)] {
        for tx in 1..=n as u32 {
            for ty in 1..=n as u32 {
                for (sx, sy) in [(1u32, 1u32), (2, 4), (5, 3)] {
                    let cfg = Config {
                        n: n as u32,
                        rv,
                        start: [sx, sy],
                        target: Some([tx, ty]),
                        searcher: crate::common::searcher("rw"),
                        prior: PriorKind::Uniform,
                        ..Config::default()
                    };
                    let ep = Episode::trial(&cfg, 0).unwrap();
                    let pt = (tx as i64 - 1, ty as i64 - 1);
                    let ps = (sx as i64 - 1, sy as i64 - 1);
                    assert_eq!(ep.target(), idx(n, pt));
                    assert_eq!(ep.start(), idx(n, ps));
                    let want = bfs_steps(n, ps, |c| ref_dist2(n, c, pt) <= r2).unwrap();
                    assert_eq!(ep.optimal(), want, "rv={rv} start {ps:?} target {pt:?}");
                    assert_eq!(ep.status() == Status::Found, want == 0);
                }
            }
        }
    }
}

/// The paper's piecewise ℓ1(T²) formula for the distance from (1,1) to the
/// 1-based target (tx, ty), transcribed literally (section 4.1). `None`
/// where none of its four cases applies.
fn paper_l1(n: i64, tx: i64, ty: i64) -> Option<i64> {
    let (ax, ay) = ((1 - tx).abs(), (1 - ty).abs());
    let h = n as f64 / 2.0;
    let (fx, fy) = (ax as f64, ay as f64);
    let v = if fx <= h && fy <= h {
        fx + fy
    } else if fx > h && fy < h {
        h - fx + fy
    } else if fx < h && fy > h {
        fx + h - fy
    } else if fx > h && fy > h {
        n as f64 - fx - fy
    } else {
        return None;
    };
    Some(v as i64)
}

/// The corrected formula: each axis contributes min(|d|, N − |d|).
fn corrected_l1(n: i64, tx: i64, ty: i64) -> i64 {
    let (ax, ay) = ((1 - tx).abs(), (1 - ty).abs());
    ax.min(n - ax) + ay.min(n - ay)
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn the_papers_piecewise_l1_formula_is_wrong_off_its_first_case() {
    // Documented bug in the paper: its middle cases use N/2 where N belongs
    // (and its last case N where 2N belongs), so it disagrees with the true
    // torus ℓ1 whenever an axis offset exceeds N/2 — it even goes negative.
    // For even N its cases also leave |dx| > N/2 = |dy| uncovered.
    let mut wrong = [0u32; 4];
    let mut uncovered = 0;
    for n in 3..=12i64 {
        let t = Torus::new(n as u32).unwrap();
        let origin = t.cell(0, 0);
        for tx in 1..=n {
            for ty in 1..=n {
                let truth = t.l1(origin, t.cell(tx - 1, ty - 1)) as i64;
                assert_eq!(
                    truth,
                    bfs_steps(n, (0, 0), |c| c == (tx - 1, ty - 1)).unwrap() as i64
                );
                assert_eq!(corrected_l1(n, tx, ty), truth, "N={n} T=({tx},{ty})");
                let (ax, ay) = ((1 - tx).abs() as f64, (1 - ty).abs() as f64);
                let h = n as f64 / 2.0;
                let case = match (ax > h, ay > h) {
                    (false, false) => 0,
                    (true, false) => 1,
                    (false, true) => 2,
                    (true, true) => 3,
                };
                match paper_l1(n, tx, ty) {
                    None => uncovered += 1,
                    Some(p) if p != truth => wrong[case] += 1,
                    Some(_) => {}
                }
            }
        }
    }
    // Its first case is right; every other case gets pairs wrong.
    assert_eq!(wrong[0], 0);
    assert!(wrong[1] > 0 && wrong[2] > 0 && wrong[3] > 0, "{wrong:?}");
    assert!(uncovered > 0);
    // A concrete pair: N = 10, target (8, 1) is 3 moves left of (1, 1) on
    // the torus, but the paper's second case gives 5 − 7 + 0 = −2.
    assert_eq!(paper_l1(10, 8, 1), Some(-2));
    assert_eq!(corrected_l1(10, 8, 1), 3);
    // And (8, 8): the fourth case gives 10 − 14 = −4 instead of 6.
    assert_eq!(paper_l1(10, 8, 8), Some(-4));
    assert_eq!(corrected_l1(10, 8, 8), 6);
    // (8, 6) on N = 10 falls through all four cases.
    assert_eq!(paper_l1(10, 8, 6), None);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn sensor_offsets_are_the_cells_within_the_radius() {
    let t = Torus::new(10).unwrap();
    for (rv, want) in [(0.0, 1), (1.0, 5), (std::f64::consts::SQRT_2, 9), (2.0, 13)] {
        assert_eq!(
            Sensor::new(&t, rv).unwrap().offsets().len(),
            want,
            "rv={rv}"
        );
    }
    // On every small torus the offsets are exactly the distinct cells within
    // the radius, including when the disc wraps onto itself.
    for n in 3..=7u32 {
        let t = Torus::new(n).unwrap();
        let ni = n as i64;
        for (rv, r2) in RADII {
            let s = Sensor::new(&t, rv).unwrap();
            let mut cells: Vec<u32> = s
                .offsets()
                .iter()
                .map(|&(dx, dy)| t.cell(dx as i64, dy as i64))
                .collect();
            cells.sort_unstable();
            let mut want: Vec<u32> = (0..t.cells() as u32)
                .filter(|&c| ref_dist2(ni, (0, 0), xy(ni, c)) <= r2)
                .collect();
            want.sort_unstable();
            assert_eq!(cells, want, "N={n} rv={rv}");
            // The armed mask marks the same cells around any target.
            let mut s = s;
            let target = t.cell(ni - 1, 1);
            s.arm(target);
            for c in 0..t.cells() as u32 {
                assert_eq!(
                    s.hit(c),
                    ref_dist2(ni, xy(ni, c), xy(ni, target)) <= r2,
                    "N={n} rv={rv} mask at {:?}",
                    xy(ni, c)
                );
            }
            // Arming another target clears the first one's cells, the mask
            // is what `hit` reads, and disarming clears it all.
            let other = t.cell(1, ni - 2);
            s.arm(other);
            assert_eq!(s.mask().len(), t.cells());
            for c in 0..t.cells() as u32 {
                let want = ref_dist2(ni, xy(ni, c), xy(ni, other)) <= r2;
                assert_eq!(s.hit(c), want, "N={n} rv={rv} re-armed at {c}");
                assert_eq!(s.mask()[c as usize], want as u8);
            }
            s.disarm();
            assert!(s.mask().iter().all(|&b| b == 0), "N={n} rv={rv}");
        }
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn sensor_fronts_are_the_cells_a_move_newly_covers() {
    // The coverage planners count only a move's front: the cells within the
    // radius of the cell moved to and not of the cell moved from.
    for n in 3..=7u32 {
        let t = Torus::new(n).unwrap();
        let ni = n as i64;
        for (rv, r2) in RADII {
            let s = Sensor::new(&t, rv).unwrap();
            let mut widest = 0;
            for c in 0..t.cells() as u32 {
                let (x, y) = xy(ni, c);
                let disc: Vec<u32> = s.around(c).collect();
                let mut sorted = disc.clone();
                sorted.sort_unstable();
                let within: Vec<u32> = (0..t.cells() as u32)
                    .filter(|&d| ref_dist2(ni, (x, y), xy(ni, d)) <= r2)
                    .collect();
                assert_eq!(sorted, within, "N={n} rv={rv} around {c}");
                assert_eq!(
                    s.around_xy(x as i32, y as i32).collect::<Vec<_>>(),
                    disc,
                    "N={n} rv={rv} around_xy at {c}"
                );
                for m in Move::ALL {
                    let (dx, dy) = m.delta();
                    let from = (x - dx as i64, y - dy as i64);
                    let want: Vec<u32> = disc
                        .iter()
                        .copied()
                        .filter(|&d| ref_dist2(ni, from, xy(ni, d)) > r2)
                        .collect();
                    let got: Vec<u32> = s.front(m, c).collect();
                    assert_eq!(got, want, "N={n} rv={rv} {m:?} into {c}");
                    widest = widest.max(got.len());
                }
            }
            assert_eq!(s.front_len(), widest, "N={n} rv={rv}");
            // The largest ℓ∞ and ℓ1 lengths of a torus displacement within
            // the radius.
            let short = |d: i64| d.min(ni - d);
            let within = (0..t.cells() as u32).filter(|&c| ref_dist2(ni, (0, 0), xy(ni, c)) <= r2);
            let reach = within.clone().map(|c| {
                let (x, y) = xy(ni, c);
                (short(x).max(short(y)), short(x) + short(y))
            });
            let linf = reach.clone().map(|r| r.0).max().unwrap();
            let l1 = reach.map(|r| r.1).max().unwrap();
            assert_eq!(s.reach() as i64, linf, "N={n} rv={rv}");
            assert_eq!(s.reach_l1() as i64, l1, "N={n} rv={rv}");
        }
    }
}
