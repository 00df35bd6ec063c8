//! Fidelity to the authors' `MCTSgaussian.m` at every compared point
//! (`fidelity/README.md`).
//!
//! The code's side is `fidelity/data/mirror-*.csv`: per-trial results of
//! `fidelity/mirror.rs`, which draws GNU Octave's random numbers and gives
//! the trials the script gave under Octave exactly. Written by
//! `fidelity/regenerate.sh` (`cargo run --release --example fidelity --
//! mirror N SIGMA 0 COUNT 1`). Here:
//!
//! * every Octave trial recorded in `fidelity/data/code-*.csv` is the
//!   mirror's trial, exactly, and so are sampled rows of each mirror file;
//! * the reading `--preset paper-code --n N+1 --prior code` (the code's
//!   (N+1)-lattice and `gausstarget`) agrees with the code's mean moves and
//!   mean excess moves within 3 standard errors of the difference, both
//!   runs' SEs counted (the code's from all the mirror's trials, ours from
//!   a reduced run that takes a few seconds);
//! * the plausible bug fails: the same preset on the N-torus (`--n N`,
//!   which is `paper-code` itself) has half the code's excess at N = 20,
//!   σ = 0: 2.67 against 5.78 in the 1000 trials below, z = −25, so the
//!   reading's test at that point fails with it
//!   (`the_n_torus_preset_differs_from_the_code_at_n20_delta` asserts it);
//! * (ignored, minutes) the committed crate rows of the table,
//!   `fidelity/data/crate-*.tsv`, are what this build computes, with the
//!   intervals `torus-search run --json` reports.
//!
//! Native only: the algorithm's numbers are the same in wasm (the pinned
//! fingerprints show it), and the mirror files are read from disk.
#![cfg(not(target_arch = "wasm32"))]

#[path = "../../fidelity/mirror.rs"]
mod mirror;

use std::path::{Path, PathBuf};
use torus_search::analysis::stats::{MeanCi, Summary};
use torus_search::config::Config;
use torus_search::run::batch;

/// |difference| / SE of the difference above this fails.
const Z_MAX: f64 = 3.0;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fidelity/data")
        .join(name)
}

/// The trials of a CSV of the code: (trial, N, σ, seed state, row).
fn code_rows(name: &str) -> Vec<(u64, i64, f64, u64, mirror::Row)> {
    let text = std::fs::read_to_string(data(name)).unwrap();
    text.lines()
        .skip(1)
        .map(|l| mirror::Row::parse(l).unwrap_or_else(|| panic!("{name}: {l}")))
        .collect()
}

/// Recomputes a recorded trial with the mirror.
fn assert_is_the_mirrors(name: &str, (i, n, sigma, state, row): (u64, i64, f64, u64, mirror::Row)) {
    let want = mirror::trial(n, sigma, state / 1_000_000, i, mirror::Switches::code(n));
    assert_eq!(row, want, "{name}, trial {i}");
}

/// Mean and SE of moves and of excess moves.
fn stats(rows: impl Iterator<Item = (f64, f64)>) -> [MeanCi; 2] {
    let (m, e): (Vec<f64>, Vec<f64>) = rows.unzip();
    [MeanCi::of(m), MeanCi::of(e)]
}

/// The code's moves and excess at (N, σ), from the committed mirror file.
fn code_stats(n: i64, sigma: f64) -> [MeanCi; 2] {
    let rows = code_rows(&format!("mirror-n{n}-s{sigma}.csv"));
    stats(rows.iter().filter_map(|r| r.4.moves_excess(n, (1, 1))))
}

/// `--preset paper-code --sigma σ --seed 7`, on the code's lattice
/// (`--n N+1 --prior code`) or on the N-torus (`--n N`).
fn crate_stats(n: i64, sigma: f64, code_lattice: bool, trials: u64) -> [MeanCi; 2] {
    let n = if code_lattice { n + 1 } else { n };
    let mut pairs = vec![
        ("preset", "paper-code".to_string()),
        ("n", n.to_string()),
        ("sigma", sigma.to_string()),
        ("seed", "7".to_string()),
    ];
    if code_lattice {
        pairs.push(("prior", "code".to_string()));
    }
    let pairs: Vec<(&str, &str)> = pairs.iter().map(|(k, v)| (*k, v.as_str())).collect();
    let cfg = Config::default().with(&pairs);
    assert_eq!(cfg.step_cap, 10_000, "the code's move cap");
    let rows = batch::run_trials(&cfg, 0, trials).unwrap();
    stats(
        rows.iter()
            .map(|r| (r.steps as f64, r.steps as f64 - r.optimal as f64)),
    )
}

/// z of (ours − code) for mean moves and mean excess moves.
fn z(ours: &[MeanCi; 2], code: &[MeanCi; 2]) -> [f64; 2] {
    std::array::from_fn(|i| (ours[i].mean - code[i].mean) / ours[i].se().hypot(code[i].se()))
}

fn assert_reading_agrees(n: i64, sigma: f64, trials: u64) {
    let code = code_stats(n, sigma);
    let ours = crate_stats(n, sigma, true, trials);
    for (i, what) in ["moves", "excess moves"].iter().enumerate() {
        let zi = z(&ours, &code)[i];
        println!(
            "N = {n}, σ = {sigma}: mean {what} {:.2} ± {:.2} against the code's {:.2} ± {:.2}, z = {zi:+.2}",
            ours[i].mean,
            ours[i].se(),
            code[i].mean,
            code[i].se()
        );
        assert!(
            zi.abs() <= Z_MAX,
            "N = {n}, σ = {sigma}: mean {what} {:.2} against the code's {:.2} (z = {zi:+.2})",
            ours[i].mean,
            code[i].mean
        );
    }
}

// One test per point, each 2–5 s of a core in the test profile (measured
// under load); the trial counts balance the time: a trial at N = 40, σ = 5
// costs about 40 of those at N = 20, σ = 0. With these counts the N-torus
// fails at N = 20, σ = 0 (excess z ≈ −20, the test below); at N = 40,
// σ = 0 its 200 trials give 8.92 ± 0.72 against the code's 10.67 ± 0.20,
// z = −2.3, too few to tell (the table's 3000 trials do).

#[test]
fn the_code_lattice_reading_agrees_with_the_code_at_n20_delta() {
    assert_reading_agrees(20, 0.0, 600);
}

#[test]
fn the_code_lattice_reading_agrees_with_the_code_at_n20_sigma5() {
    assert_reading_agrees(20, 5.0, 200);
}

#[test]
fn the_code_lattice_reading_agrees_with_the_code_at_n40_delta() {
    assert_reading_agrees(40, 0.0, 200);
}

#[test]
fn the_code_lattice_reading_agrees_with_the_code_at_n40_sigma5() {
    assert_reading_agrees(40, 5.0, 30);
}

#[test]
fn the_n_torus_preset_differs_from_the_code_at_n20_delta() {
    // The plausible bug, and `paper-code` as it stands: the code's selection
    // and statistics on the N-torus. Its centre target is antipodal to the
    // start, so no first move is wrong; on the code's (N+1)-torus one way
    // round is 3 moves longer per axis, and the code's searcher often takes
    // it. Its mean excess is about half the code's.
    let code = code_stats(20, 0.0);
    let ours = crate_stats(20, 0.0, false, 1000);
    let [_, ze] = z(&ours, &code);
    println!(
        "N-torus at N = 20, σ = 0: excess {:.2} against {:.2}, z = {ze:+.2}",
        ours[1].mean, code[1].mean
    );
    assert!(ze < -Z_MAX, "z = {ze:+.2}");
}

#[test]
fn every_octave_trial_is_the_mirrors_trial_exactly() {
    let mut names: Vec<String> = std::fs::read_dir(data(""))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|f| f.starts_with("code-") && f.ends_with(".csv"))
        .collect();
    names.sort();
    let mut checked = std::collections::BTreeSet::new();
    for name in &names {
        for r in code_rows(name) {
            assert_is_the_mirrors(name, r);
            checked.insert((r.1, r.2.to_bits()));
        }
    }
    // Octave pins N = 8 and both σ at N = 20 (an Octave trial at N = 40
    // takes hours of a shared core; the mirror's only dependence on N is
    // arithmetic, checked at N = 8 and 20).
    for (n, sigma) in [(8, 2.0f64), (20, 0.0), (20, 5.0)] {
        assert!(
            checked.contains(&(n, sigma.to_bits())),
            "no Octave trial at N = {n}, σ = {sigma}"
        );
    }
}

#[test]
fn the_committed_mirror_rows_are_the_mirrors() {
    // The three shortest trials of each file, cheap to recompute, and the
    // trials are 0..k in order: a stale or edited file fails.
    for (n, sigma) in [(20, 0.0), (20, 5.0), (40, 0.0), (40, 5.0)] {
        let name = format!("mirror-n{n}-s{sigma}.csv");
        let mut rows = code_rows(&name);
        assert!(rows.len() >= 500, "{name}: {} trials", rows.len());
        assert!(rows
            .iter()
            .enumerate()
            .all(|(k, r)| r.0 == k as u64 && (r.1, r.2) == (n, sigma)));
        rows.sort_by_key(|r| r.4.steps);
        for r in rows.into_iter().take(3) {
            assert_is_the_mirrors(&name, r);
        }
    }
}

#[test]
#[ignore = "minutes of a core: reruns every crate trial of the fidelity table"]
fn the_committed_crate_rows_are_this_builds() {
    for (n, sigma) in [(20, 0.0), (20, 5.0), (40, 0.0), (40, 5.0)] {
        let name = format!("crate-n{n}-s{sigma}.tsv");
        let text = std::fs::read_to_string(data(&name)).unwrap();
        for line in text.lines().skip(1) {
            let f: Vec<&str> = line.split('\t').collect();
            let x = |i: usize| f[i].parse::<f64>().unwrap();
            let (n_code, trials) = (x(1) as i64, x(4) as u64);
            let code_lattice = f[0] == "reading";
            let mut cfg = Config::default().with(&[
                ("preset", "paper-code"),
                ("sigma", f[2]),
                ("seed", f[3]),
            ]);
            let side = if code_lattice { n_code + 1 } else { n_code };
            cfg.set("n", &side.to_string()).unwrap();
            if code_lattice {
                cfg.set("prior", "code").unwrap();
            }
            let s = Summary::of(&batch::run_trials(&cfg, 0, trials).unwrap());
            let got = [s.steps.estimate, s.steps.lo, s.steps.hi];
            let want = [x(5), x(6), x(7)];
            assert_eq!(got, want, "{name}, {}: moves", f[0]);
            let got = [s.asoo.estimate, s.asoo.lo, s.asoo.hi];
            assert_eq!(got, [x(9), x(10), x(11)], "{name}, {}: excess", f[0]);
        }
    }
}
