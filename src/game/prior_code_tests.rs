//! The `code` prior against the authors' `gausstarget` on their lattice.

use super::*;

/// 1/400 off the authors' 20×20 square of targets, 0 on the 21st row and
/// column (n = 21 is their N = 20).
fn uniform_on_1_to_n(i: usize, big: usize) -> f64 {
    if i % big == big - 1 || i / big == big - 1 {
        0.0
    } else {
        1.0 / ((big - 1) * (big - 1)) as f64
    }
}

#[test]
fn code_prior_is_gausstarget_one_cell_down_on_the_n_plus_1_torus() {
    // n = 21 is the authors' N = 20: their target (10, 10) at σ = 0 is
    // 0-based (9, 9) here; at σ = 5 each axis is round(10 + 5Z) wrapped
    // with period 20 into 1..20, shifted down one cell, so the last row
    // and column are never drawn. Wrapping with period n (the paper's
    // sampler) or without the shift puts mass there and fails.
    let (n, big) = (21u32, 21usize);
    let t = Torus::new(n).unwrap();
    let delta = TargetPrior::new(&t, &PriorSpec::Code { sigma: 0.0 }).unwrap();
    assert_eq!(delta.delta_cell(), Some(9 * n + 9));
    let w = wrapped_rounded_normal(20, 10.0, 5.0);
    let p = TargetPrior::new(&t, &PriorSpec::Code { sigma: 5.0 }).unwrap();
    let mass = p.mass();
    let axis = |k: usize| if k == 20 { 0.0 } else { w[(k + 1) % 20] };
    for y in 0..big {
        for x in 0..big {
            let want = axis(x) * axis(y);
            assert!((mass[y * big + x] - want).abs() < 1e-15, "({x}, {y})");
        }
    }
    let mut r = rng::stream(11, 0);
    let mut counts = vec![0u32; big * big];
    for _ in 0..200_000 {
        counts[p.sample(&mut r) as usize] += 1;
    }
    assert_draws_follow(&counts, mass, 5.0);
}

#[test]
fn code_prior_at_infinite_sigma_is_uniform_on_the_authors_square() {
    let (n, big) = (21u32, 21usize);
    let t = Torus::new(n).unwrap();
    let spec = PriorSpec::Code {
        sigma: f64::INFINITY,
    };
    let u = TargetPrior::new(&t, &spec).unwrap();
    let want = |i: usize| uniform_on_1_to_n(i, big);
    assert!(u
        .mass()
        .iter()
        .enumerate()
        .all(|(i, &m)| (m - want(i)).abs() < 1e-15));
    let mut r = rng::stream(11, 1);
    let mut counts = vec![0u32; big * big];
    for _ in 0..100_000 {
        counts[u.sample(&mut r) as usize] += 1;
    }
    assert_draws_follow(&counts, u.mass(), 5.0);
    assert_eq!(
        TargetPrior::new(&t, &PriorSpec::Code { sigma: -1.0 }).unwrap_err(),
        PriorError::Sigma(-1.0)
    );
}
