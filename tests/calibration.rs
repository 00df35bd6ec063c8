//! Calibration (exploration).
#![cfg(not(target_arch = "wasm32"))]

use rand::SeedableRng;
use torus_search::analysis::bootstrap::{bca_ends, resampled_means, seed_of};
use torus_search::analysis::stats::{quantile, t975, MeanCi};
use torus_search::analysis::theory::rw_hitting_law;
use torus_search::game::lattice::{Sensor, Torus};
use torus_search::game::rng;

fn sampler(law: &[f64]) -> impl Fn(&mut rng::Rng) -> f64 + '_ {
    let mut cum = Vec::with_capacity(law.len());
    let mut s = 0.0;
    for p in law {
        s += p;
        cum.push(s);
    }
    move |r: &mut rng::Rng| {
        let u = rng::unit_f64(r) * s;
        cum.partition_point(|&c| c <= u).min(law.len() - 1) as f64
    }
}

fn pareto(alpha: f64, cap: usize) -> Vec<f64> {
    // P(X >= x) = x^-alpha for x >= 1, capped.
    let mut law = vec![0.0; cap + 1];
    for x in 1..cap {
        law[x] = (x as f64).powf(-alpha) - ((x + 1) as f64).powf(-alpha);
    }
    law[cap] = (cap as f64).powf(-alpha);
    law
}

fn study(name: &str, law: &[f64], ns: &[usize], reps: u64) {
    let mean: f64 = law.iter().enumerate().map(|(t, p)| t as f64 * p).sum();
    let draw = sampler(law);
    for &n in ns {
        // [below, above] misses for: bca, expanded bca, pct, t
        let mut miss = [[0u32; 2]; 4];
        let mut tout = 0;
        for r in 0..reps {
            let mut g = rng::stream(99, r);
            let xs: Vec<f64> = (0..n).map(|_| draw(&mut g)).collect();
            let m = xs.iter().sum::<f64>() / n as f64;
            let bm = resampled_means(&xs, &mut rng::Rng::seed_from_u64(seed_of(&xs)));
            let z = 1.959963984540054;
            let e = (n as f64 / (n as f64 - 1.0)).sqrt() * t975(n as u64 - 1);
            let c = MeanCi::of(xs.iter().copied());
            let ivs = [
                bca_ends(&xs, m, &bm, (-z, z)),
                bca_ends(&xs, m, &bm, (-e, e)),
                (quantile(&bm, 0.025), quantile(&bm, 0.975)),
                (c.lo, c.hi),
            ];
            for (k, (lo, hi)) in ivs.iter().enumerate() {
                if mean < *lo {
                    miss[k][0] += 1;
                }
                if mean > *hi {
                    miss[k][1] += 1;
                }
            }
            let mn = xs.iter().copied().fold(f64::INFINITY, f64::min);
            tout += (c.lo < mn) as u32;
        }
        let f = |k: [u32; 2]| {
            format!(
                "{:.3} ({:.3}/{:.3})",
                1.0 - (k[0] + k[1]) as f64 / reps as f64,
                k[0] as f64 / reps as f64,
                k[1] as f64 / reps as f64
            )
        };
        println!(
            "{name} mean {mean:.1} capped {:.3} n {n}: bca {} ebca {} pct {} t {} (t<min {:.3})",
            law[law.len() - 1],
            f(miss[0]),
            f(miss[1]),
            f(miss[2]),
            f(miss[3]),
            tout as f64 / reps as f64
        );
    }
}

#[test]
#[ignore]
fn explore() {
    let torus = Torus::new(10).unwrap();
    let sensor = Sensor::new(&torus, 0.0).unwrap();
    let start = torus.cell(0, 0);
    let target = torus.cell(5, 5);
    for cap in [400u32, 800] {
        let law = rw_hitting_law(&torus, &sensor, start, target, cap);
        study(&format!("rw cap {cap}"), &law, &[10, 30, 100], 2000);
    }
    study("pareto 1.5", &pareto(1.5, 10000), &[30, 100], 2000);
    study("pareto 2.5", &pareto(2.5, 10000), &[30, 100], 2000);
}
