//! Statistical checks against exact theory, with fixed seeds and thresholds
//! derived from standard errors (4 SE for means, chi-square and KS quantiles
//! at tail probability ≈ 1e-4). Each check also asserts its own power: that
//! the margin is small enough to reject a plausible bug (an off-by-one in
//! the hitting time, a shifted or unwrapped prior, a wrong exponent).
//!
//! Runs natively (`cargo test --test suite statistics::`) and in Node
//! (`cargo test --target wasm32-unknown-unknown --test suite statistics::`).

use crate::common::{chi2_crit_1e4, chi2_merged};
use torus_search::analysis::stats::MeanCi;
use torus_search::analysis::theory;
use torus_search::config::Config;
use torus_search::game::lattice::{Move, Sensor, Torus};
use torus_search::game::layer::Layer;
use torus_search::game::prior::{PriorKind, PriorSpec, TargetPrior};
use torus_search::game::rng;
use torus_search::run::batch;
use torus_search::run::episode::{Episode, Status};
use torus_search::searchers::walks::levy::{flight_end, Directions, FlightLengths};
use torus_search::searchers::walks::policy::{Policy, PolicyKind};
use torus_search::searchers::walks::visit::NoVisit;

fn rw_config(n: u32, rv: f64) -> Config {
    Config {
        n,
        rv,
        searcher: crate::common::searcher("rw"),
        prior: PriorKind::Uniform,
        step_cap: 100_000_000,
        ..Config::default()
    }
}

// ---------------------------------------------------------------------------
// Random-walk hitting times
// ---------------------------------------------------------------------------

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn rw_mean_hitting_time_of_a_uniform_target_is_kemenys_constant() {
    // r_v = 0, uniform target: the mean steps from any start is Kemeny's
    // constant Σ_{(a,b)≠0} 1/(1 − (cos 2πa/N + cos 2πb/N)/2), counting 0
    // when the target is the start (17.17 for N = 4, 47.99 for N = 6).
    for (n, trials, seed) in [(4u32, 20_000u64, 11u64), (6, 8_000, 12)] {
        let cfg = Config {
            seed,
            ..rw_config(n, 0.0)
        };
        let res = batch::run_trials(&cfg, 0, trials).unwrap();
        assert!(res.iter().all(|r| r.found), "no RW episode may be capped");
        let m = MeanCi::of(res.iter().map(|r| r.steps as f64));
        let k = theory::kemeny(n);
        println!(
            "RW uniform target N={n}: mean {:.3} ± {:.3} (SE) vs Kemeny {k:.3}",
            m.mean,
            m.se()
        );
        assert!(
            (m.mean - k).abs() < 4.0 * m.se(),
            "N={n}: mean {} vs {k}, SE {}",
            m.mean,
            m.se()
        );
        // The target lands on the start with probability 1/N²: those trials
        // take 0 steps, all others at least 1.
        let zeros = res.iter().filter(|r| r.steps == 0).count() as f64;
        let p0 = 1.0 / (n * n) as f64;
        let sd0 = (trials as f64 * p0 * (1.0 - p0)).sqrt();
        assert!(
            (zeros - trials as f64 * p0).abs() < 4.0 * sd0,
            "zeros {zeros}"
        );
        if n == 4 {
            // Power: an off-by-one in the step count would be caught.
            assert!(4.0 * m.se() < 1.0, "SE {} too large", m.se());
        }
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn rw_mean_hitting_time_of_a_fixed_target_solves_the_linear_system() {
    // A fixed target with r_v = 1 (target cell and its four neighbours):
    // the mean steps from a start is h[start], where h = 0 on the detection
    // set and h = 1 + the mean of h over the four neighbours elsewhere.
    let cases: [(u32, [u32; 2], [[u32; 2]; 3]); 3] = [
        (5, [3, 4], [[1, 1], [5, 1], [3, 2]]),
        (6, [4, 4], [[1, 1], [6, 6], [2, 4]]),
        (7, [5, 2], [[1, 1], [1, 6], [7, 7]]),
    ];
    let mut seed = 100;
    for (n, target, starts) in cases {
        let t = Torus::new(n).unwrap();
        let s = Sensor::new(&t, 1.0).unwrap();
        let tc = t
            .cell_1based("target", target[0] as i64, target[1] as i64)
            .unwrap();
        let h = theory::rw_hitting_times(&t, &s, tc);
        // The solution really solves the system (checked independently of
        // the solver, so a solver bug cannot hide behind a matching simulation).
        for c in 0..t.cells() as u32 {
            if s.detects(&t, c, tc) {
                assert_eq!(h[c as usize], 0.0);
            } else {
                let mean_nb: f64 = Move::ALL
                    .iter()
                    .map(|&m| h[t.step(c, m) as usize])
                    .sum::<f64>()
                    / 4.0;
                assert!((h[c as usize] - 1.0 - mean_nb).abs() < 1e-9);
            }
        }
        for start in starts {
            seed += 1;
            let cfg = Config {
                start,
                target: Some(target),
                seed,
                ..rw_config(n, 1.0)
            };
            // Enough trials that 4 SE < 1 step (SE ≈ h / √trials).
            let trials = if n == 7 { 16_000 } else { 6_000 };
            let res = batch::run_trials(&cfg, 0, trials).unwrap();
            let m = MeanCi::of(res.iter().map(|r| r.steps as f64));
            let sc = t
                .cell_1based("start", start[0] as i64, start[1] as i64)
                .unwrap();
            let want = h[sc as usize];
            println!(
                "RW N={n} rv=1 target {target:?} start {start:?}: mean {:.3} ± {:.3} vs exact {want:.3}",
                m.mean,
                m.se()
            );
            assert!(
                (m.mean - want).abs() < 4.0 * m.se(),
                "N={n} start {start:?}: {} vs {want} (SE {})",
                m.mean,
                m.se()
            );
            assert!(
                4.0 * m.se() < 1.0,
                "SE {} too large to see an off-by-one",
                m.se()
            );
        }
    }
}

// ---------------------------------------------------------------------------
// Target priors
// ---------------------------------------------------------------------------

/// Φ(z), the standard normal CDF.
fn phi(z: f64) -> f64 {
    0.5 * libm::erfc(-z / std::f64::consts::SQRT_2)
}

/// Reference mass of one axis: P(g(X) ≡ k mod N) for X ~ N(mu, sigma), where
/// `lo_off` is the offset of the lower edge of the interval mapped to k
/// (−0.5 for rounding, 0 for flooring) and `wrap` says whether periodic
/// images count (false: the normal is truncated to the lattice and renormalised).
fn axis_mass(n: u32, mu: f64, sigma: f64, lo_off: f64, wrap: bool) -> Vec<f64> {
    let nf = n as f64;
    let reach = (40.0 * sigma / nf).ceil() as i64 + 2;
    let images = if wrap { -reach..=reach } else { 0..=0 };
    let mut p: Vec<f64> = (0..n)
        .map(|k| {
            images
                .clone()
                .map(|m| {
                    let a = k as f64 + m as f64 * nf + lo_off;
                    phi((a + 1.0 - mu) / sigma) - phi((a - mu) / sigma)
                })
                .sum()
        })
        .collect();
    let total: f64 = p.iter().sum();
    p.iter_mut().for_each(|v| *v /= total);
    p
}

fn outer(ax: &[f64]) -> Vec<f64> {
    ax.iter()
        .flat_map(|&py| ax.iter().map(move |&px| px * py))
        .collect()
}

fn sample_counts(prior: &TargetPrior, cells: usize, draws: u64, seed: u64) -> Vec<u64> {
    let mut r = rng::stream(seed, 0);
    let mut counts = vec![0u64; cells];
    for _ in 0..draws {
        counts[prior.sample(&mut r) as usize] += 1;
    }
    counts
}

/// Asserts that `counts` fit `mass` and returns the statistic over its threshold.
fn assert_fits(what: &str, counts: &[u64], mass: &[f64]) -> f64 {
    let (stat, df) = chi2_merged(counts, mass);
    let crit = chi2_crit_1e4(df);
    println!("{what}: chi2 {stat:.1} on {df} df (threshold {crit:.1})");
    assert!(df >= 1, "{what}: nothing to test");
    assert!(
        stat < crit,
        "{what}: chi2 {stat:.1} >= {crit:.1} on {df} df"
    );
    stat / crit
}

/// Asserts that `counts` would reject the wrong `mass` (the test has power).
fn assert_rejects(what: &str, counts: &[u64], wrong: &[f64]) {
    let (stat, df) = chi2_merged(counts, wrong);
    let crit = chi2_crit_1e4(df);
    println!("  vs {what}: chi2 {stat:.1} on {df} df (must exceed {crit:.1})");
    assert!(stat > crit, "{what}: chi2 {stat:.1} does not reject");
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn gaussian_prior_samples_match_its_mass() {
    const DRAWS: u64 = 200_000;
    let mut seed = 200;
    for n in [9u32, 10] {
        let t = Torus::new(n).unwrap();
        let cells = t.cells();
        let mu = n as f64 / 2.0;
        for sigma in [0.7, 2.0, 6.0, 50.0] {
            seed += 1;
            let prior = TargetPrior::new(&t, &PriorSpec::Gaussian { sigma }).unwrap();
            // The reported mass is the paper's law: N(N/2, σ) per axis,
            // rounded to the nearest point and wrapped mod N.
            let want = outer(&axis_mass(n, mu, sigma, -0.5, true));
            let mass = prior.mass();
            assert!((mass.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            for (c, (&a, &b)) in mass.iter().zip(&want).enumerate() {
                assert!(
                    (a - b).abs() < 1e-12,
                    "N={n} σ={sigma} cell {c}: {a} vs {b}"
                );
            }
            // And the sampler draws from it.
            let counts = sample_counts(&prior, cells, DRAWS, seed);
            assert_fits(&format!("Gaussian N={n} σ={sigma}"), &counts, mass);
            // Power: plausible bugs are rejected by the same samples.
            if sigma < 3.0 {
                assert_rejects(
                    "floor instead of round",
                    &counts,
                    &outer(&axis_mass(n, mu, sigma, 0.0, true)),
                );
            }
            if n % 2 == 1 && sigma < 3.0 {
                assert_rejects(
                    "centre N/2 rounded down",
                    &counts,
                    &outer(&axis_mass(n, (n / 2) as f64, sigma, -0.5, true)),
                );
            }
            if sigma > 1.0 && sigma < 10.0 {
                assert_rejects(
                    "no wrapping",
                    &counts,
                    &outer(&axis_mass(n, mu, sigma, -0.5, false)),
                );
            }
        }
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn uniform_and_weight_grid_priors_sample_their_mass() {
    const DRAWS: u64 = 200_000;
    let t = Torus::new(10).unwrap();
    let prior = TargetPrior::new(&t, &PriorSpec::Uniform).unwrap();
    assert!(prior.mass().iter().all(|&m| (m - 0.01).abs() < 1e-15));
    let counts = sample_counts(&prior, 100, DRAWS, 301);
    assert_fits("Uniform N=10", &counts, prior.mass());
    // Power: one cell 30% likelier than the rest is detected.
    let mut wrong = prior.mass().to_vec();
    wrong[37] *= 1.3;
    let s: f64 = wrong.iter().sum();
    wrong.iter_mut().for_each(|v| *v /= s);
    assert_rejects("one cell 30% likelier", &counts, &wrong);

    // A painted grid with zeros, a hot spot and a smooth ramp (N = 7).
    let t = Torus::new(7).unwrap();
    let weights: Vec<f64> = (0..49)
        .map(|c| {
            let (x, y) = (c % 7, c / 7);
            if y == 3 {
                0.0
            } else if (x, y) == (5, 1) {
                40.0
            } else {
                (x + 1) as f64 * 0.5
            }
        })
        .collect();
    let total: f64 = weights.iter().sum();
    let prior = TargetPrior::new(
        &t,
        &PriorSpec::Weights {
            weights: weights.clone(),
        },
    )
    .unwrap();
    for (c, (&m, &w)) in prior.mass().iter().zip(&weights).enumerate() {
        assert!((m - w / total).abs() < 1e-15, "cell {c}");
    }
    // chi2_merged panics if a zero-weight cell is ever drawn.
    let counts = sample_counts(&prior, 49, DRAWS, 302);
    assert_fits("Weights N=7", &counts, prior.mass());
    // Power: the grid transposed (x and y swapped) is rejected.
    let transposed: Vec<f64> = (0..49)
        .map(|c| prior.mass()[(c % 7) * 7 + c / 7] + 1e-12)
        .collect();
    let s: f64 = transposed.iter().sum();
    let transposed: Vec<f64> = transposed.iter().map(|v| v / s).collect();
    assert_rejects("transposed grid", &counts, &transposed);
}

// ---------------------------------------------------------------------------
// Lévy flights
// ---------------------------------------------------------------------------

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn levy_flight_lengths_follow_the_power_law() {
    // With a cap far beyond reach (P(l > 1e12) ≤ 1e-6 for μ = 1.5) the law
    // is the Pareto P(l) ∝ l^−μ on [1, ∞), whose exponent has the MLE
    // μ̂ = 1 + n / Σ ln l and standard error (μ − 1)/√n.
    const DRAWS: usize = 40_000;
    for (k, mu) in [1.5f64, 2.0, 2.5].into_iter().enumerate() {
        let mut r = rng::stream(400, k as u64);
        let law = FlightLengths::new(mu, 1e12);
        let mut sum_ln = 0.0;
        for _ in 0..DRAWS {
            let l = law.sample(&mut r);
            assert!((1.0..=1e12).contains(&l), "length {l}");
            sum_ln += l.ln();
        }
        let mu_hat = 1.0 + DRAWS as f64 / sum_ln;
        let se = (mu - 1.0) / (DRAWS as f64).sqrt();
        println!("Lévy μ={mu}: MLE {mu_hat:.4} (SE {se:.4})");
        assert!(
            (mu_hat - mu).abs() < 4.0 * se,
            "μ={mu}: MLE {mu_hat} (SE {se})"
        );
        // Power: an exponent off by 0.1 would be rejected.
        assert!(4.0 * se < 0.1);
    }
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn levy_flight_lengths_capped_at_n_follow_the_truncated_law() {
    // With cap = N every length is in [1, N] and the law is the truncated
    // Pareto, F(l) = (1 − l^−(μ−1)) / (1 − N^−(μ−1)); a Kolmogorov–Smirnov
    // statistic √n·D above 2.23 has probability ≈ 1e-4.
    const DRAWS: usize = 20_000;
    for (k, (mu, n)) in [(1.5f64, 20.0f64), (2.0, 40.0), (3.0, 9.0)]
        .into_iter()
        .enumerate()
    {
        let mut r = rng::stream(500, k as u64);
        let law = FlightLengths::new(mu, n);
        let mut ls: Vec<f64> = (0..DRAWS).map(|_| law.sample(&mut r)).collect();
        assert!(
            ls.iter().all(|&l| (1.0..=n).contains(&l)),
            "μ={mu} N={n}: a length outside [1, N]"
        );
        ls.sort_by(f64::total_cmp);
        let a = mu - 1.0;
        let cdf = |l: f64| (1.0 - l.powf(-a)) / (1.0 - n.powf(-a));
        let nf = DRAWS as f64;
        let d = ls
            .iter()
            .enumerate()
            .map(|(i, &l)| {
                let f = cdf(l);
                (f - i as f64 / nf).max((i + 1) as f64 / nf - f)
            })
            .fold(0.0, f64::max);
        println!("Lévy μ={mu} cap N={n}: KS √n·D = {:.3}", d * nf.sqrt());
        assert!(d * nf.sqrt() < 2.23, "μ={mu} N={n}: KS D = {d}");
        // Power: the untruncated law would be rejected where it puts
        // enough mass, N^−(μ−1), beyond N.
        if n.powf(-a) * nf.sqrt() < 3.0 {
            continue;
        }
        let d_untrunc = ls
            .iter()
            .enumerate()
            .map(|(i, &l)| ((1.0 - l.powf(-a)) - (i + 1) as f64 / nf).abs())
            .fold(0.0, f64::max);
        assert!(d_untrunc * nf.sqrt() > 2.23);
    }
}

/// The exact law of a flight's rounded end point: P(i, j) for L from the
/// truncated Pareto law on [1, cap] and Θ uniform, by integrating over Θ
/// (midpoint rule, `m` angles) the length probability F(l_hi) − F(l_lo) of
/// each stretch of the ray that rounds to one cell. The integrand is
/// continuous in Θ, so the rule's error is far below the test's resolution.
fn end_point_law(mu: f64, cap: f64, m: usize) -> std::collections::BTreeMap<(i64, i64), f64> {
    let a = mu - 1.0;
    let cdf = |l: f64| (1.0 - l.powf(-a)) / (1.0 - cap.powf(-a));
    let mut p = std::collections::BTreeMap::new();
    let mut cuts = Vec::new();
    for k in 0..m {
        let th = 2.0 * std::f64::consts::PI * (k as f64 + 0.5) / m as f64;
        let (s, c) = th.sin_cos();
        cuts.clear();
        cuts.extend([1.0, cap]);
        for d in [c, s] {
            // Lengths where l·d crosses a half-integer.
            let mut h = 0.5;
            while h / d.abs() < cap {
                if h / d.abs() > 1.0 {
                    cuts.push(h / d.abs());
                }
                h += 1.0;
            }
        }
        cuts.sort_by(f64::total_cmp);
        for w in cuts.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            let cell = ((mid * c).round() as i64, (mid * s).round() as i64);
            *p.entry(cell).or_insert(0.0) += (cdf(w[1]) - cdf(w[0])) / m as f64;
        }
    }
    p
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn levy_flight_end_points_follow_the_rounded_continuous_law() {
    // The table-driven sampler (length bins with an alias table and
    // rejection, cos and sin from a table and polynomials) against the exact law
    // of (round(L cos Θ), round(L sin Θ)), the law of the pow/sin/cos
    // sampler it replaced, by χ² on every end point (cells with expected
    // count < 5 merged). Angles confined to a quarter turn (a wrong table
    // index), or an exponent off by 0.1, fail it (checked once with the
    // sampler broken; the exponent also below).
    const DRAWS: usize = 200_000;
    for (k, (mu, cap)) in [(2.0f64, 8.0f64), (1.3, 12.0), (3.0, 5.0)]
        .into_iter()
        .enumerate()
    {
        let law = FlightLengths::new(mu, cap);
        let dirs = Directions::new();
        let mut r = rng::stream(450, k as u64);
        let mut counts = std::collections::BTreeMap::new();
        for _ in 0..DRAWS {
            *counts
                .entry(flight_end(&law, &dirs, &mut r))
                .or_insert(0u64) += 1;
        }
        let exact = end_point_law(mu, cap, 1 << 15);
        let total: f64 = exact.values().sum();
        assert!((total - 1.0).abs() < 1e-9, "the exact law sums to {total}");
        for cell in counts.keys() {
            assert!(
                exact.contains_key(cell),
                "μ={mu}: end point {cell:?} has probability 0"
            );
        }
        let cells: Vec<(i64, i64)> = exact.keys().copied().collect();
        let obs: Vec<u64> = cells.iter().map(|c| *counts.get(c).unwrap_or(&0)).collect();
        let p: Vec<f64> = cells.iter().map(|c| exact[c]).collect();
        let (stat, df) = chi2_merged(&obs, &p);
        println!(
            "Lévy end points μ={mu} cap={cap}: χ² {stat:.1} on {df} df ({} cells)",
            cells.len()
        );
        assert!(
            stat < chi2_crit_1e4(df),
            "μ={mu} cap={cap}: χ² {stat} on {df} df"
        );
        // Power: the same draws reject the law of an exponent 0.1 larger.
        let wrong = end_point_law(mu + 0.1, cap, 1 << 12);
        let pw: Vec<f64> = cells.iter().map(|c| wrong[c]).collect();
        let (stat_w, df_w) = chi2_merged(&obs, &pw);
        assert!(
            stat_w > chi2_crit_1e4(df_w),
            "μ={mu}: χ² {stat_w} against μ + 0.1"
        );
    }
}

// ---------------------------------------------------------------------------
// Greedy rollouts and NSARW
// ---------------------------------------------------------------------------

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn greedy_rollouts_without_noise_take_exactly_the_optimal_steps() {
    // ε = 0: every move shortens the torus ℓ1 distance, so the rollout detects
    // the target after exactly the optimal steps; r_v = 0 and r_v = 1.
    for n in [5u32, 6, 7] {
        let t = Torus::new(n).unwrap();
        for rv in [0.0, 1.0] {
            let mut s = Sensor::new(&t, rv).unwrap();
            let mut policy = Policy::new(PolicyKind::Greedy, &t, 2.0, 0.0);
            let mut r = rng::stream(600 + n as u64, rv as u64);
            for target in 0..t.cells() as u32 {
                s.arm(target);
                for start in 0..t.cells() as u32 {
                    policy.begin(start, target);
                    let mut path: Vec<u32> = Vec::new();
                    let out = policy.rollout(&t, s.mask(), &mut r, start, 10_000, &mut path);
                    let opt = s.optimal_steps(&t, start, target);
                    assert!(out.detected);
                    assert_eq!(
                        out.steps,
                        opt,
                        "N={n} rv={rv} start {:?} target {:?}",
                        t.xy(start),
                        t.xy(target)
                    );
                    let mut prev = start;
                    for &c in &path {
                        assert_eq!(t.l1(c, target) + 1, t.l1(prev, target));
                        prev = c;
                    }
                }
            }
            // A sanity check on the harness: with ε = 1 it is a random walk
            // and overshoots the optimum on average.
            let mut noisy = Policy::new(PolicyKind::Greedy, &t, 2.0, 1.0);
            let target = t.cell(n as i64 / 2, n as i64 / 2);
            s.arm(target);
            let total: u32 = (0..200)
                .map(|_| {
                    noisy.begin(0, target);
                    noisy
                        .rollout(&t, s.mask(), &mut r, 0, 1_000_000, &mut NoVisit)
                        .steps
                })
                .sum();
            assert!(total > 200 * s.optimal_steps(&t, 0, target));
        }
    }
}

/// Ties met replaying NSARW walks: `[k][position of the choice among the k]`.
type Ties = [[u64; 4]; 5];

/// Replays an NSARW `path` on `t`: each step enters a neighbour with the
/// fewest visits so far (the start counts once). Records where the choice
/// fell among the tied neighbours and returns the visit counts.
fn replay_nsarw(t: &Torus, path: &[u32], ties: &mut Ties, what: &str) -> Vec<u32> {
    let mut count = vec![0u32; t.cells()];
    count[path[0] as usize] = 1;
    for w in path.windows(2) {
        let (c, next) = (w[0], w[1]);
        let nbs: Vec<u32> = Move::ALL.iter().map(|&m| t.step(c, m)).collect();
        assert!(nbs.contains(&next), "{what}: not a unit move");
        let least = nbs.iter().map(|&b| count[b as usize]).min().unwrap();
        assert_eq!(
            count[next as usize], least,
            "{what}: stepped onto a cell visited {} times while a neighbour had {least}",
            count[next as usize]
        );
        let tied: Vec<u32> = nbs
            .into_iter()
            .filter(|&b| count[b as usize] == least)
            .collect();
        let pos = tied.iter().position(|&b| b == next).unwrap();
        ties[tied.len()][pos] += 1;
        count[next as usize] += 1;
    }
    count
}

/// Among k tied neighbours each was chosen with probability 1/k (χ², in
/// up, right, down, left order), with at least `four_way` 4-way ties seen.
fn assert_uniform_ties(ties: &Ties, four_way: u64, what: &str) {
    for (k, row) in ties.iter().enumerate().skip(2) {
        let obs = &row[..k];
        if obs.iter().sum::<u64>() < 50 {
            continue;
        }
        let (stat, df) = chi2_merged(obs, &vec![1.0 / k as f64; k]);
        println!("{what}, {k}-way ties: {obs:?} chi2 {stat:.2} on {df} df");
        assert!(stat < chi2_crit_1e4(df), "{what}: {k}-way ties {obs:?}");
    }
    assert!(
        ties[4].iter().sum::<u64>() > four_way,
        "{what}: too few 4-way ties"
    );
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn nsarw_steps_to_a_least_visited_neighbour_uniformly() {
    // Standalone NSARW episodes, replayed.
    let mut ties = Ties::default();
    let mut steps = 0u64;
    for i in 0..200 {
        let cfg = Config {
            n: 11,
            rv: 0.0,
            searcher: crate::common::searcher("nsarw"),
            prior: PriorKind::Uniform,
            seed: 700,
            step_cap: 300,
            ..Config::default()
        };
        let mut ep = Episode::trial(&cfg, i).unwrap();
        ep.run();
        let t = ep.torus().clone();
        let path = ep.path().to_vec();
        let count = replay_nsarw(&t, &path, &mut ties, &format!("trial {i}"));
        steps += path.len() as u64 - 1;
        let mut scratch = Vec::new();
        assert_eq!(
            ep.counts(Layer::Walker, &mut scratch).unwrap(),
            &count[..],
            "trial {i}: walker counts"
        );
        assert!(ep.status() != Status::Running);
    }
    println!("NSARW: {steps} steps replayed");
    assert!(steps > 10_000);
    assert_uniform_ties(&ties, 300, "NSARW walker");
}

#[wasm_bindgen_test::wasm_bindgen_test(unsupported = test)]
fn nsarw_rollouts_step_to_a_least_visited_neighbour_uniformly() {
    // The MCTS rollout loop draws its tie orders ahead: replay rollouts,
    // several on one policy so that older walks' counts must be forgotten.
    let t = Torus::new(11).unwrap();
    let mask = vec![0u8; t.cells()];
    let mut policy = Policy::new(PolicyKind::Nsarw, &t, 2.0, 0.2);
    let mut r = rng::stream(701, 0);
    let mut ties = Ties::default();
    let mut steps = 0u64;
    for i in 0..200u32 {
        let start = (i * 37) % t.cells() as u32;
        policy.begin(start, start);
        let mut path = vec![start];
        policy.rollout(&t, &mask, &mut r, start, 300, &mut path);
        replay_nsarw(&t, &path, &mut ties, &format!("rollout {i}"));
        steps += path.len() as u64 - 1;
    }
    assert!(steps > 50_000);
    assert_uniform_ties(&ties, 300, "NSARW rollouts");
}
