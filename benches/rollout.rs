//! Criterion benchmarks (stable Rust): rollout throughput per policy, MCTS
//! loops and whole episodes at the paper's N = 40, L = 100, and the
//! bootstrap interval every experiment point reports.
//!
//! `cargo bench` runs them; `torus-search bench` prints the same figures
//! without criterion's statistics.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use torus_search::analysis::bootstrap::bca_mean;
use torus_search::bench::{mcts_loops, rollout_steps};
use torus_search::config::Config;
use torus_search::run::episode::Episode;
use torus_search::searchers::mcts::Variant;
use torus_search::searchers::walks::policy::PolicyKind;

const N: u32 = 40;
const RV: f64 = 1.0;

fn rollouts(c: &mut Criterion) {
    let mut g = c.benchmark_group("rollout_n40_rv1");
    for (kind, steps) in [
        (PolicyKind::Rw, 4_000_000u64),
        (PolicyKind::Levy, 500_000),
        (PolicyKind::Nsarw, 500_000),
    ] {
        // Each call overshoots `steps` by at most one rollout (~0.1%).
        g.throughput(Throughput::Elements(steps));
        let mut seed = 0u64;
        g.bench_function(BenchmarkId::new("lattice_steps", kind.name()), |b| {
            b.iter(|| {
                seed += 1;
                black_box(rollout_steps(kind, N, RV, 2.0, seed, steps).expect("valid"))
            })
        });
    }
    g.finish();
}

fn mcts(c: &mut Criterion) {
    let mut g = c.benchmark_group("mcts_n40_l100");
    g.sample_size(10);
    for variant in [Variant::Cells, Variant::Tree] {
        for sigma in [0.0, 5.0] {
            let cfg = Config {
                sigma,
                ..Config::default()
            }
            .with(&[("variant", variant.to_string().as_str())]);
            let name = format!("{}_sigma{sigma}", variant.name());
            g.throughput(Throughput::Elements(2_000));
            g.bench_function(BenchmarkId::new("loops", &name), |b| {
                b.iter(|| black_box(mcts_loops(&cfg, 2_000).expect("valid")))
            });
        }
    }
    g.throughput(Throughput::Elements(1));
    for sigma in [0.0, 5.0] {
        let cfg = Config {
            sigma,
            ..Config::default()
        };
        let mut trial = 0u64;
        g.bench_function(
            BenchmarkId::new("episode_cells", format!("sigma{sigma}")),
            |b| {
                b.iter(|| {
                    trial += 1;
                    black_box(Episode::trial(&cfg, trial).expect("valid").run())
                })
            },
        );
    }
    g.finish();
}

fn intervals(c: &mut Criterion) {
    // One bootstrap interval of the mean (2000 resamples): what an
    // experiment's point costs per interval, natively.
    let mut g = c.benchmark_group("intervals");
    for n in [100u64, 1000] {
        let xs: Vec<f64> = (0..n)
            .map(|i| ((i * 7919) % 997 + if i % 50 == 3 { 5000 } else { 0 }) as f64)
            .collect();
        g.bench_function(BenchmarkId::new("bca_mean", n), |b| {
            b.iter(|| black_box(bca_mean(black_box(&xs))))
        });
    }
    g.finish();
}

criterion_group!(benches, rollouts, mcts, intervals);
criterion_main!(benches);
