//! The lower bound on E[T] (src/bound.rs) against the true optimum, an
//! independent from-scratch reference, closed forms, and Monte Carlo.
//!
//! * On N = 3 and N = 4 the bound never exceeds the exact optimum from
//!   dynamic programming, itself checked against brute force over paths.
//! * The incremental greedy equals a naive per-move greedy written here from
//!   the definition, and that greedy equals the best set found by brute
//!   force over all subsets (greedy is exact under nested caps).
//! * The paper's delta target at N = 40 gives 39; a uniform prior gives the
//!   closed form Σ_t (1 − (5 + 3t)/N²)⁺ ≈ N²/6 − 7/6.
//! * `path_mean` of a fixed path agrees with sampled targets.
//!
//! Plausible bugs these tests were checked to catch (each tried once):
//! * caps one move late, `a·(t − m)` instead of `a·(t − m + 1)`: the bound
//!   exceeds the optimum (N = 3, r_v = 0, a delta two moves away: bound 3 >
//!   optimum 2), the paper's delta gives 40, the uniform closed form and the
//!   reference disagree;
//! * forgetting the caps on {τ ≥ m} (only the total |F| + a·t): the bound
//!   falls below the known-target optimum, which it can never do (σ = 1 at
//!   N = 40: 2.86 < 37.47), the paper's delta gives 0, and the reference
//!   disagrees;
//! * a = 3 taken from the plane on every torus (it is 2 at N = 3, r_v = 1):
//!   still a valid bound, but looser, and the reference comparison fails;
//! * an empty distance class given the next class's head (a real bug found
//!   while writing this): a delta bound below E[τ] in
//!   `bound_never_exceeds_the_optimum`.
//! * the programme's relaxation inside a covered set stopped after its
//!   first pass that changed anything: 146/28 against 144/28 for a prior
//!   whose optimal search walks back over two searched cells.
//!
//! Runs natively (`cargo test --test suite bound::`) and in Node
//! (`cargo test --target wasm32-unknown-unknown --test suite bound::`).

use crate::common::{bfs_steps, ref_dist2, ref_l1};
use torus_search::analysis::bound::{
    covered_bound, detection_times, dp_optimum, known_target_mean, lower_bound, lower_bound_capped,
    lower_bound_of, new_cells_per_move, path_mean, BoundError, DP_MAX_CELLS,
};
use torus_search::config::Config;
use torus_search::game::lattice::{Sensor, Torus};
use torus_search::game::prior::{PriorKind, PriorSpec, TargetPrior};
use torus_search::game::rng::{self, Rng};

/// Detection radii with their integer squared radius, so the reference
/// footprint compares integers.
const RADII: [(f64, i64); 3] = [(0.0, 0), (1.0, 1), (1.5, 2)];

fn xy(n: i64, c: u32) -> (i64, i64) {
    (c as i64 % n, c as i64 / n)
}

/// A boustrophedon through every cell from `start`: right along a row,
/// down one, back left, so consecutive cells are neighbours.
fn snake(torus: &Torus, start: u32) -> Vec<u32> {
    let n = torus.n() as i64;
    let (sx, sy) = xy(n, start);
    let mut path = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let dx = if y % 2 == 0 { x } else { n - 1 - x };
            path.push(torus.cell(sx + dx, sy + y));
        }
    }
    for w in path.windows(2) {
        assert_eq!(
            torus.l1(w[0], w[1]),
            1,
            "the snake moves one cell at a time"
        );
    }
    path
}

/// Normalised weights.
fn normalise(w: Vec<f64>) -> Vec<f64> {
    let total: f64 = w.iter().sum();
    w.into_iter().map(|x| x / total).collect()
}

/// Priors for the small-lattice tests: a delta at a random cell, uniform,
/// flat Dirichlet (normalised exponentials), a few random cells, and mass
/// far from `start` (where the caps bind).
fn priors(n: u32, start: u32, rng: &mut Rng) -> Vec<(&'static str, Vec<f64>)> {
    let cells = (n * n) as usize;
    let ni = n as i64;
    let mut out = Vec::new();
    let mut delta = vec![0.0; cells];
    delta[rng::below(rng, cells as u32) as usize] = 1.0;
    out.push(("delta", delta));
    out.push(("uniform", vec![1.0 / cells as f64; cells]));
    for _ in 0..3 {
        let w = (0..cells)
            .map(|_| -(1.0 - rng::unit_f64(rng)).ln())
            .collect();
        out.push(("dirichlet", normalise(w)));
    }
    for _ in 0..2 {
        let mut w = vec![0.0; cells];
        for _ in 0..3 {
            w[rng::below(rng, cells as u32) as usize] += rng::unit_f64(rng) + 0.01;
        }
        out.push(("sparse", normalise(w)));
    }
    let far = (0..cells as u32)
        .map(|c| {
            let d = ref_l1(ni, xy(ni, start), xy(ni, c));
            (d * d * d) as f64 * (0.5 + rng::unit_f64(rng))
        })
        .collect();
    out.push(("far", normalise(far)));
    out
}

/// Brute force over paths on a tiny torus, independent of the dynamic programme.
struct Brute<'a> {
    /// Footprint of each position as a bit set of cells.
    foot: Vec<u32>,
    nbrs: Vec<[u32; 4]>,
    mass: &'a [f64],
    best: f64,
}

impl Brute<'_> {
    /// The least Σ R_t over all paths of at most `depth` moves that cover
    /// every cell with mass.
    fn optimum(n: i64, r2: i64, mass: &[f64], start: u32, depth: u32) -> f64 {
        let cells = (n * n) as u32;
        let mut b = Brute {
            foot: (0..cells)
                .map(|p| {
                    (0..cells)
                        .filter(|&c| ref_dist2(n, xy(n, p), xy(n, c)) <= r2)
                        .fold(0, |m, c| m | 1 << c)
                })
                .collect(),
            nbrs: (0..cells)
                .map(|p| {
                    crate::common::ref_neighbours(n, xy(n, p)).map(|(x, y)| (y * n + x) as u32)
                })
                .collect(),
            mass,
            best: f64::INFINITY,
        };
        b.go(start, b.foot[start as usize], 0.0, depth);
        b.best
    }

    fn go(&mut self, pos: u32, set: u32, acc: f64, left: u32) {
        let r: f64 = (0..self.mass.len())
            .filter(|&c| set & 1 << c == 0)
            .map(|c| self.mass[c])
            .sum();
        if r == 0.0 {
            self.best = self.best.min(acc);
            return;
        }
        if left == 0 || acc + r >= self.best {
            return;
        }
        for q in self.nbrs[pos as usize] {
            self.go(q, set | self.foot[q as usize], acc + r, left - 1);
        }
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn dynamic_programme_matches_brute_force_on_3x3_and_4x4() {
    let mut rng = rng::stream(31, 0);
    // (N, radii with their r², starts, brute-force depth). 4 × 4 is the
    // largest lattice the tiny-lattice planner tests take the optimum on
    // (README, Planners); r_v = 0 there is too slow to brute-force for
    // these random priors (the next test takes one prior that prunes fast).
    let lattices = [
        (3u32, &[(0.0, 0i64), (1.0, 1)][..], &[0u32, 4][..], 12u32),
        (4, &[(1.0, 1)][..], &[0, 5, 15][..], 9),
    ];
    for (n, radii, starts, depth) in lattices {
        let torus = Torus::new(n).unwrap();
        for &(rv, r2) in radii {
            let sensor = Sensor::new(&torus, rv).unwrap();
            for &start in starts {
                for (name, mass) in priors(n, start, &mut rng) {
                    let dp = dp_optimum(&torus, &sensor, &mass, start).unwrap();
                    let brute = Brute::optimum(n as i64, r2, &mass, start, depth);
                    assert!(
                        (dp - brute).abs() < 1e-12,
                        "n {n}, rv {rv}, start {start}, {name}: dp {dp} vs brute force {brute}"
                    );
                }
            }
        }
    }
    let torus = Torus::new(3).unwrap();
    // A Hamiltonian path visits the 9 cells one by one: Σ_{t<9} (1 − (t+1)/9) = 4.
    let sensor = Sensor::new(&torus, 0.0).unwrap();
    let dp = dp_optimum(&torus, &sensor, &[1.0 / 9.0; 9], 0).unwrap();
    assert!((dp - 4.0).abs() < 1e-12, "{dp}");
}

/// A prior whose optimal search walks back over two searched cells, so
/// the programme's shortest paths inside a covered set need more than one
/// relaxation pass.
///
/// 4 × 4, r_v = 0, start 0, cell weights out of 28 with a massless 2 × 2
/// block (cells 4, 5, 8, 9). Brute force's optimal path is 0, 12, 15, 3,
/// 7, 6, 10, 14, 13, 1, 2, 3, 7, 11: from 2 it walks back over 3 and 7 to
/// reach 11, and `Σ R_t = 144/28`. A relaxation that stops after its first
/// pass that changed anything leaves position 2 with the way out it found
/// before 3 and 7 (later in the pass) were relaxed: through 1 and the
/// massless block, two moves longer with 1/28 left, so 146/28. (Random priors
/// with weights 0–3 tell the two apart in 5 of 3 000; the random priors
/// of the test above never do.)
#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn dynamic_programme_walks_back_over_searched_cells() {
    let w = [1, 3, 1, 3, 0, 0, 3, 3, 0, 0, 2, 1, 3, 2, 3, 3];
    let mass: Vec<f64> = w.iter().map(|&k| k as f64 / 28.0).collect();
    let torus = Torus::new(4).unwrap();
    let sensor = Sensor::new(&torus, 0.0).unwrap();
    let dp = dp_optimum(&torus, &sensor, &mass, 0).unwrap();
    let brute = Brute::optimum(4, 0, &mass, 0, 16);
    assert!((brute - 144.0 / 28.0).abs() < 1e-12, "brute force {brute}");
    assert!((dp - brute).abs() < 1e-12, "dp {dp} vs brute force {brute}");
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn bound_never_exceeds_the_optimum() {
    let mut rng = rng::stream(2026, 1);
    let (mut cases, mut worst_gap, mut best_ratio) = (0, 0.0f64, f64::INFINITY);
    for n in [3u32, 4] {
        let torus = Torus::new(n).unwrap();
        for (rv, _) in RADII {
            let sensor = Sensor::new(&torus, rv).unwrap();
            for _ in 0..2 {
                let start = rng::below(&mut rng, n * n);
                for (name, mass) in priors(n, start, &mut rng) {
                    let opt = dp_optimum(&torus, &sensor, &mass, start).unwrap();
                    let lb = lower_bound_of(&torus, &sensor, &mass, start);
                    let known = known_target_mean(&torus, &sensor, &mass, start);
                    let lawn = path_mean(&torus, &sensor, &mass, &snake(&torus, start));
                    let ctx = format!("n {n}, rv {rv}, start {start}, {name}");
                    assert!(lb <= opt + 1e-9, "{ctx}: bound {lb} > optimum {opt}");
                    assert!(known <= lb + 1e-9, "{ctx}: known {known} > bound {lb}");
                    assert_eq!(lawn.uncovered, 0.0, "{ctx}");
                    assert!(
                        opt <= lawn.mean + 1e-9,
                        "{ctx}: {opt} > snake {}",
                        lawn.mean
                    );
                    if name == "delta" {
                        let target = mass.iter().position(|&m| m == 1.0).unwrap() as u32;
                        let steps = sensor.optimal_steps(&torus, start, target) as f64;
                        assert_eq!(opt, steps, "{ctx}");
                        assert_eq!(lb, steps, "{ctx}: the bound is exact for a delta");
                    }
                    cases += 1;
                    worst_gap = worst_gap.max(opt - lb);
                    if opt > 0.0 {
                        best_ratio = best_ratio.min(lb / opt);
                    }
                }
            }
        }
    }
    println!("{cases} priors: optimum − bound ≤ {worst_gap:.3}, bound / optimum ≥ {best_ratio:.3}");
    assert_eq!(cases, 2 * 3 * 2 * 8);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn dynamic_programme_refuses_large_lattices() {
    let torus = Torus::new(5).unwrap();
    let sensor = Sensor::new(&torus, 1.0).unwrap();
    let err = dp_optimum(&torus, &sensor, &[0.04; 25], 0).unwrap_err();
    assert_eq!(
        err,
        BoundError::TooManyCells {
            cells: 25,
            max: DP_MAX_CELLS
        }
    );
    assert!(err.to_string().contains("at most 16 cells"), "{err}");
}

/// M_t for t in 0..moves from the definition: τ by breadth-first search, a
/// from the footprint as a set of cells, and for each t a greedy pass from
/// scratch over the cells by (mass desc, index asc) with the cap
/// a·(t − m + 1)⁺ on {τ ≥ m} checked for every m ≤ τ(c).
fn reference_covered(n: i64, r2: i64, mass: &[f64], start: u32, moves: usize) -> Vec<f64> {
    let cells = (n * n) as usize;
    let s = xy(n, start);
    let detects = |p: (i64, i64), c: (i64, i64)| ref_dist2(n, p, c) <= r2;
    let tau: Vec<i64> = (0..cells as u32)
        .map(|c| bfs_steps(n, s, |p| detects(p, xy(n, c))).unwrap() as i64)
        .collect();
    let inside = |c: (i64, i64)| detects((0, 0), c);
    let a = [(1, 0), (-1, 0), (0, 1), (0, -1)]
        .iter()
        .map(|&(ex, ey)| {
            (0..cells as u32)
                .map(|c| xy(n, c))
                .filter(|&(x, y)| inside((x, y)) && !inside((x + ex, y + ey)))
                .count() as i64
        })
        .max()
        .unwrap();
    let mut order: Vec<usize> = (0..cells).filter(|&c| mass[c] > 0.0).collect();
    order.sort_by(|&x, &y| mass[y].partial_cmp(&mass[x]).unwrap().then(x.cmp(&y)));
    let kmax = *tau.iter().max().unwrap() as usize;
    (0..moves as i64)
        .map(|t| {
            let cap = |m: i64| {
                if m == 0 {
                    i64::MAX
                } else {
                    a * (t - m + 1).max(0)
                }
            };
            let mut taken = vec![0i64; kmax + 1];
            let mut m_t = 0.0;
            for &c in &order {
                let k = tau[c];
                if (1..=k).all(|m| taken[m as usize] < cap(m)) {
                    for m in 1..=k {
                        taken[m as usize] += 1;
                    }
                    m_t += mass[c];
                }
            }
            m_t
        })
        .collect()
}

/// The best mass of any cell set obeying the caps, by enumerating subsets.
fn subset_max(n: i64, r2: i64, mass: &[f64], start: u32, t: i64, a: i64) -> f64 {
    let cells = (n * n) as usize;
    let s = xy(n, start);
    let tau: Vec<i64> = (0..cells as u32)
        .map(|c| bfs_steps(n, s, |p| ref_dist2(n, p, xy(n, c)) <= r2).unwrap() as i64)
        .collect();
    let kmax = *tau.iter().max().unwrap();
    let mut best = 0.0f64;
    for set in 0u32..1 << cells {
        let ok = (1..=kmax).all(|m| {
            let count = (0..cells)
                .filter(|&c| set & 1 << c != 0 && tau[c] >= m)
                .count() as i64;
            count <= a * (t - m + 1).max(0)
        });
        if ok {
            let w: f64 = (0..cells)
                .filter(|&c| set & 1 << c != 0)
                .map(|c| mass[c])
                .sum();
            best = best.max(w);
        }
    }
    best
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn incremental_greedy_matches_a_naive_reference() {
    let mut rng = rng::stream(77, 2);
    let radii = [(0.0, 0), (1.0, 1), (1.5, 2), (2.5, 6), (3.0, 9)];
    for n in [3u32, 4, 5, 7, 10] {
        let torus = Torus::new(n).unwrap();
        let ni = n as i64;
        for (rv, r2) in radii {
            let sensor = Sensor::new(&torus, rv).unwrap();
            let start = rng::below(&mut rng, n * n);
            for (name, mass) in priors(n, start, &mut rng) {
                let moves = (n * n) as usize + 2;
                let got = covered_bound(&torus, &sensor, &mass, start, moves);
                let want = reference_covered(ni, r2, &mass, start, moves);
                assert_eq!(got.len(), moves, "n {n}, rv {rv}, {name}: one M_t a move");
                for (t, (g, w)) in got.iter().zip(&want).enumerate() {
                    assert!(
                        (g - w).abs() < 1e-12,
                        "n {n}, rv {rv}, {name}, t {t}: M_t {g} vs reference {w}"
                    );
                }
                let sum: f64 = want.iter().map(|m| (1.0 - m).max(0.0)).sum();
                let lb = lower_bound_of(&torus, &sensor, &mass, start);
                assert!(
                    (lb - sum).abs() < 1e-9,
                    "n {n}, rv {rv}, {name}: {lb} vs {sum}"
                );
                if n == 3 {
                    let a = new_cells_per_move(&torus, &sensor) as i64;
                    for (t, w) in want.iter().enumerate().take(4) {
                        let best = subset_max(ni, r2, &mass, start, t as i64, a);
                        assert!(
                            (best - w).abs() < 1e-12,
                            "rv {rv}, {name}, t {t}: greedy {w} vs best subset {best}"
                        );
                    }
                }
            }
        }
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn footprint_geometry_counts_the_wrap() {
    // On the plane a move of the plus adds 3 cells; on the 3-torus the cell
    // two steps ahead is the one behind, already covered.
    let cases = [
        (3, 1.0, 2),
        (4, 1.0, 3),
        (40, 1.0, 3),
        (40, 0.0, 1),
        (40, 2.0, 5),
    ];
    for (n, rv, want) in cases {
        let t = Torus::new(n).unwrap();
        let s = Sensor::new(&t, rv).unwrap();
        assert_eq!(new_cells_per_move(&t, &s), want, "n {n}, rv {rv}");
    }
    let t = Torus::new(5).unwrap();
    assert_eq!(new_cells_per_move(&t, &Sensor::new(&t, 10.0).unwrap()), 0);
    // τ is the sensor's optimal steps for every target.
    let t = Torus::new(9).unwrap();
    for rv in [0.0, 1.0, 2.5] {
        let s = Sensor::new(&t, rv).unwrap();
        let tau = detection_times(&t, &s, 10);
        for c in 0..81 {
            assert_eq!(
                tau[c as usize],
                s.optimal_steps(&t, 10, c),
                "rv {rv}, cell {c}"
            );
        }
    }
}

fn paper_config() -> Config {
    Config {
        n: 40,
        prior: PriorKind::Gaussian,
        sigma: 0.0,
        rv: 1.0,
        start: [1, 1],
        ..Config::default()
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn paper_delta_target_gives_39() {
    // σ = 0 puts the target on (21, 21), torus ℓ1 distance 40 from (1, 1);
    // the plus around it is first reached after 39 moves.
    assert_eq!(lower_bound(&paper_config()).unwrap(), 39.0);
    let fixed = Config {
        target: Some([21, 21]),
        sigma: 5.0,
        ..paper_config()
    };
    assert_eq!(lower_bound(&fixed).unwrap(), 39.0);
    let known = Config {
        known: true,
        ..paper_config()
    };
    assert_eq!(lower_bound(&known).unwrap(), 39.0);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn known_target_bound_is_the_mean_optimal_steps() {
    let cfg = Config {
        n: 20,
        sigma: 3.0,
        start: [3, 17],
        ..paper_config()
    };
    let torus = Torus::new(20).unwrap();
    let sensor = Sensor::new(&torus, 1.0).unwrap();
    let prior = TargetPrior::new(&torus, &PriorSpec::Gaussian { sigma: 3.0 }).unwrap();
    let start = torus.cell(2, 16);
    let want: f64 = (0..400u32)
        .map(|c| prior.mass()[c as usize] * sensor.optimal_steps(&torus, start, c) as f64)
        .sum();
    let known = lower_bound(&Config {
        known: true,
        ..cfg.clone()
    })
    .unwrap();
    assert!((known - want).abs() < 1e-9, "{known} vs {want}");
    let direct = known_target_mean(&torus, &sensor, prior.mass(), start);
    assert!((direct - want).abs() < 1e-9, "{direct} vs {want}");
    let blind = lower_bound(&cfg).unwrap();
    assert!(
        blind > known + 1.0,
        "not knowing the target costs: {blind} vs {known}"
    );
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn bad_configs_are_refused() {
    let err = lower_bound(&Config {
        start: [41, 1],
        ..paper_config()
    })
    .unwrap_err();
    assert_eq!(err.field, "start");
    let err = lower_bound(&Config {
        prior: PriorKind::Paint,
        ..paper_config()
    })
    .unwrap_err();
    assert_eq!(err.field, "prior");
}

/// Σ_t (1 − (f + a·t)/N²)⁺: the bound when no cap on {τ ≥ m} binds.
fn uniform_closed_form(n: u32, f: u64, a: u64) -> f64 {
    let cells = (n * n) as u64;
    (0..)
        .map(|t| f + a * t)
        .take_while(|&c| c < cells)
        .map(|c| (cells - c) as f64 / cells as f64)
        .sum()
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn uniform_bound_is_about_n_squared_over_6() {
    // With r_v = 1 the caps never bind for a uniform prior (the cells with
    // τ < m outnumber 5 + 3(m − 1)), so the bound is the closed form. With
    // A = N² − 5 it is (A²/6 + A/2 + O(1))/N² = N²/6 − 7/6 + O(1/N²): within
    // 1.2 of N²/6 at every N, and 265.5 at N = 40.
    for n in [10u32, 17, 40, 64, 101] {
        let cfg = Config {
            n,
            prior: PriorKind::Uniform,
            ..paper_config()
        };
        let lb = lower_bound(&cfg).unwrap();
        let closed = uniform_closed_form(n, 5, 3);
        assert!(
            (lb - closed).abs() < 1e-9 * closed,
            "n {n}: {lb} vs {closed}"
        );
        let sixth = (n * n) as f64 / 6.0;
        assert!(
            (lb - (sixth - 7.0 / 6.0)).abs() < 0.2,
            "n {n}: {lb} vs N²/6 − 7/6 = {}",
            sixth - 7.0 / 6.0
        );
        if n == 40 {
            // 424 802 / 1600 = 265.501 25, the 265.5 quoted in the issue.
            assert!((lb - 265.501_25).abs() < 1e-9, "{lb}");
        }
    }
    // r_v = 0: a snake visits each cell once and attains the bound (N² − 1)/2.
    let torus = Torus::new(12).unwrap();
    let sensor = Sensor::new(&torus, 0.0).unwrap();
    let mass = vec![1.0 / 144.0; 144];
    let lb = lower_bound_of(&torus, &sensor, &mass, 5);
    let snake = path_mean(&torus, &sensor, &mass, &snake(&torus, 5));
    assert!((lb - 71.5).abs() < 1e-9, "{lb}");
    assert!((snake.mean - 71.5).abs() < 1e-9, "{}", snake.mean);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn capped_bound_keeps_the_terms_before_the_cap() {
    // A capped trial counts as step_cap moves, so a batch's mean is
    // E[min(T, cap)] = Σ_{t < cap} R_t.
    let delta = |step_cap, known| Config {
        step_cap,
        known,
        ..paper_config()
    };
    assert_eq!(lower_bound_capped(&delta(10, false)).unwrap(), 10.0);
    assert_eq!(lower_bound_capped(&delta(10, true)).unwrap(), 10.0);
    assert_eq!(lower_bound_capped(&delta(10_000, false)).unwrap(), 39.0);
    let uniform = |step_cap| Config {
        step_cap,
        prior: PriorKind::Uniform,
        ..paper_config()
    };
    let want: f64 = (0..100)
        .map(|t| 1.0 - (5.0 + 3.0 * t as f64) / 1600.0)
        .sum();
    let got = lower_bound_capped(&uniform(100)).unwrap();
    assert!((got - want).abs() < 1e-9, "{got} vs {want}");
    let full = lower_bound(&uniform(100)).unwrap();
    assert_eq!(lower_bound_capped(&uniform(10_000)).unwrap(), full);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn path_mean_matches_sampled_targets() {
    // A wrong R_t (say, counting the start's footprint as uncovered, or
    // adding R after the first position twice) moves the mean by ≥ 1, over
    // 20 standard errors here.
    let torus = Torus::new(12).unwrap();
    let sensor = Sensor::new(&torus, 1.0).unwrap();
    let prior = TargetPrior::new(&torus, &PriorSpec::Gaussian { sigma: 2.5 }).unwrap();
    let full = snake(&torus, 0);
    let trials = 40_000u64;
    for len in [full.len(), 30] {
        let path = &full[..len];
        let exact = path_mean(&torus, &sensor, prior.mass(), path);
        let mut rng = rng::stream(4242, len as u64);
        let (mut sum, mut sum2, mut missed) = (0.0, 0.0, 0u64);
        for _ in 0..trials {
            let target = prior.sample(&mut rng);
            // min(T, len): the index of the first detecting position.
            let t = path
                .iter()
                .position(|&p| sensor.detects(&torus, p, target))
                .unwrap_or_else(|| {
                    missed += 1;
                    len
                }) as f64;
            sum += t;
            sum2 += t * t;
        }
        let nf = trials as f64;
        let mean = sum / nf;
        let se = ((sum2 / nf - mean * mean) / (nf - 1.0)).sqrt();
        assert!(
            (mean - exact.mean).abs() < 4.0 * se,
            "len {len}: sampled {mean} ± {se} vs exact {}",
            exact.mean
        );
        let p = missed as f64 / nf;
        let pse = (exact.uncovered * (1.0 - exact.uncovered) / nf)
            .sqrt()
            .max(1.0 / nf);
        assert!(
            (p - exact.uncovered).abs() < 4.0 * pse,
            "len {len}: missed {p} vs uncovered {}",
            exact.uncovered
        );
        if len == full.len() {
            assert_eq!(exact.uncovered, 0.0);
        } else {
            assert!(exact.uncovered > 0.1, "{}", exact.uncovered);
        }
    }
    let empty = path_mean(&torus, &sensor, prior.mass(), &[]);
    assert_eq!(empty.mean, 0.0);
    assert!((empty.uncovered - 1.0).abs() < 1e-12);
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn bound_stays_below_exact_fixed_paths_on_the_paper_lattice() {
    // The paper's Gaussian priors at N = 40: every fixed path is a searcher,
    // so the snake's exact mean is an upper witness for the optimum.
    let torus = Torus::new(40).unwrap();
    let sensor = Sensor::new(&torus, 1.0).unwrap();
    for sigma in [1.0, 2.5, 5.0, 10.0] {
        let prior = TargetPrior::new(&torus, &PriorSpec::Gaussian { sigma }).unwrap();
        let lb = lower_bound_of(&torus, &sensor, prior.mass(), 0);
        let snake = path_mean(&torus, &sensor, prior.mass(), &snake(&torus, 0));
        println!("sigma {sigma}: bound {lb:.2}, snake {:.2}", snake.mean);
        assert!(lb <= snake.mean, "sigma {sigma}: {lb} > {}", snake.mean);
        // No cell with τ > t can be in the relaxed set after t moves, so the
        // bound is at least the known-target optimum E[τ].
        let known = known_target_mean(&torus, &sensor, prior.mass(), 0);
        assert!(lb >= known - 1e-9, "sigma {sigma}: {lb} < known {known}");
    }
}

/// Times the bound at N = 256 (uniform, the longest sum: 21 845 moves) and
/// N = 1024. `cargo test --release --test suite bound:: -- --ignored --nocapture`.
#[cfg(not(target_arch = "wasm32"))]
#[test]
#[ignore]
fn bound_timing() {
    for (n, spec) in [
        (256, PriorSpec::Uniform),
        (256, PriorSpec::Gaussian { sigma: 20.0 }),
        (1024, PriorSpec::Uniform),
    ] {
        let torus = Torus::new(n).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let prior = TargetPrior::new(&torus, &spec).unwrap();
        let t0 = std::time::Instant::now();
        let lb = lower_bound_of(&torus, &sensor, prior.mass(), 0);
        let dt = t0.elapsed();
        println!("n {n}, {spec:?}: bound {lb:.3} in {dt:?}");
    }
}
