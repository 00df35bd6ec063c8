//! Helpers shared by the geometry, statistics and theorem tests: independent
//! reference implementations and the quantiles the statistical thresholds
//! are built from. Nothing here calls the crate's own versions of what it
//! checks.
#![allow(dead_code)]

use std::collections::VecDeque;
use torus_search::searchers::registry::SearcherId;

/// The registered searcher called `name`.
pub fn searcher(name: &str) -> SearcherId {
    SearcherId::parse(name).unwrap_or_else(|| panic!("no searcher {name:?}"))
}

/// Upper quantile of the standard normal for tail probability 1e-4.
pub const Z_1E4: f64 = 3.719_016_485_455_68;

/// The upper quantile of chi-square with `df` degrees of freedom for tail
/// probability 1e-4, by the Wilson–Hilferty approximation. It errs high
/// (16.2 vs the exact 15.14 at df = 1, 67.86 vs 67.63 at df = 30, 160.17 vs
/// 160.06 at df = 99), so a test using it fails with probability ≤ 1e-4.
pub fn chi2_crit_1e4(df: usize) -> f64 {
    assert!(df >= 1);
    let k = df as f64;
    let a = 2.0 / (9.0 * k);
    k * (1.0 - a + Z_1E4 * a.sqrt()).powi(3)
}

/// Pearson's chi-square of `counts` against probabilities `p` (summing to
/// 1), merging bins (in order of increasing expectation) until every merged
/// bin expects at least 5. Returns `(statistic, degrees of freedom)`.
///
/// # Panics
/// When a bin with zero probability has a count (an impossible outcome).
pub fn chi2_merged(counts: &[u64], p: &[f64]) -> (f64, usize) {
    assert_eq!(counts.len(), p.len());
    let total: u64 = counts.iter().sum();
    let tf = total as f64;
    for (i, (&c, &pi)) in counts.iter().zip(p).enumerate() {
        assert!(
            pi > 0.0 || c == 0,
            "bin {i} has probability 0 but {c} samples"
        );
    }
    let mut bins: Vec<(f64, u64)> = counts
        .iter()
        .zip(p)
        .filter(|(_, &pi)| pi > 0.0)
        .map(|(&c, &pi)| (pi * tf, c))
        .collect();
    bins.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut merged: Vec<(f64, u64)> = Vec::new();
    let (mut e, mut o) = (0.0, 0u64);
    for (be, bo) in bins {
        e += be;
        o += bo;
        if e >= 5.0 {
            merged.push((e, o));
            e = 0.0;
            o = 0;
        }
    }
    if e > 0.0 || o > 0 {
        match merged.last_mut() {
            Some(last) => {
                last.0 += e;
                last.1 += o;
            }
            None => merged.push((e, o)),
        }
    }
    let stat = merged
        .iter()
        .map(|&(e, o)| (o as f64 - e).powi(2) / e)
        .sum();
    (stat, merged.len().saturating_sub(1))
}

/// Squared torus Euclidean distance between 0-based `(ax, ay)` and
/// `(bx, by)`, the minimum over periodic images (independent of `Torus`).
pub fn ref_dist2(n: i64, a: (i64, i64), b: (i64, i64)) -> i64 {
    let axis = |d: i64| {
        [-1i64, 0, 1]
            .iter()
            .map(|k| (d + k * n) * (d + k * n))
            .min()
            .unwrap()
    };
    axis(b.0 - a.0) + axis(b.1 - a.1)
}

/// Torus ℓ1 distance from the definition Σ min(|d|, N − |d|).
pub fn ref_l1(n: i64, a: (i64, i64), b: (i64, i64)) -> i64 {
    let axis = |d: i64| {
        let d = d.rem_euclid(n);
        d.min(n - d)
    };
    axis(b.0 - a.0) + axis(b.1 - a.1)
}

/// The four neighbours of 0-based `(x, y)`, wrapped by hand: up, right,
/// down, left.
pub fn ref_neighbours(n: i64, (x, y): (i64, i64)) -> [(i64, i64); 4] {
    [
        (x, (y - 1).rem_euclid(n)),
        ((x + 1).rem_euclid(n), y),
        (x, (y + 1).rem_euclid(n)),
        ((x - 1).rem_euclid(n), y),
    ]
}

/// Breadth-first search over the four moves: the fewest moves from `start`
/// until a cell satisfying `goal` is entered (0 if `start` satisfies it).
pub fn bfs_steps(n: i64, start: (i64, i64), goal: impl Fn((i64, i64)) -> bool) -> Option<u32> {
    let idx = |(x, y): (i64, i64)| (y * n + x) as usize;
    let mut dist = vec![u32::MAX; (n * n) as usize];
    let mut q = VecDeque::new();
    dist[idx(start)] = 0;
    q.push_back(start);
    while let Some(c) = q.pop_front() {
        if goal(c) {
            return Some(dist[idx(c)]);
        }
        for nb in ref_neighbours(n, c) {
            if dist[idx(nb)] == u32::MAX {
                dist[idx(nb)] = dist[idx(c)] + 1;
                q.push_back(nb);
            }
        }
    }
    None
}

/// The standard error of a frequency `k / n`, floored at the value for one
/// success so that a frequency of 0 or 1 still gets a nonzero margin.
pub fn freq_se(k: u64, n: u64) -> f64 {
    let nf = n as f64;
    let p = (k as f64 / nf).clamp(1.0 / nf, 1.0 - 1.0 / nf);
    (p * (1.0 - p) / nf).sqrt()
}

/// Wilson score interval for `k` successes in `n` trials at normal quantile `z`.
pub fn wilson(k: u64, n: u64, z: f64) -> (f64, f64) {
    let nf = n as f64;
    let p = k as f64 / nf;
    let z2 = z * z;
    let centre = (p + z2 / (2.0 * nf)) / (1.0 + z2 / nf);
    let half = z / (1.0 + z2 / nf) * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt();
    (centre - half, centre + half)
}
