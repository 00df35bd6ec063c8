//! The fidelity comparison with the authors' `MCTSgaussian.m`
//! (`fidelity/README.md`, which `fidelity/regenerate.sh` runs this for).
//!
//! ```text
//! fidelity mirror N SIGMA FIRST COUNT SEED [switch...]  per-trial CSV of the code
//! fidelity crate N SIGMA TRIALS SEED                     summary TSV of both readings
//! fidelity table [--write]                               the tables from fidelity/data
//! fidelity cause N SIGMA COUNT SEED                      the code with one change at a time
//! ```
//!
//! Switches of `mirror`: `torus=N` (moves and playouts wrap with period N,
//! not N+1), `detect=torus` (detection at torus ℓ1 ≤ 1, not Euclidean
//! without wrap), `target=N1` (targets centred at N/2+1, not N/2),
//! `start=X,Y` (not (1, 1)).
//!
//! Moves are the code's `length(Px) − 1` and the crate's steps; excess
//! moves subtract the fewest moves that detect the target in that run's own
//! world. Means carry the crate's interval (the expanded BCa bootstrap of
//! `analysis::bootstrap`, as `torus-search run --json` reports) and the
//! standard error; a reading agrees with the code when both means lie
//! within 3 standard errors of the difference, both runs' SEs counted.

#[path = "../fidelity/mirror.rs"]
mod mirror;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use torus_search::analysis::bootstrap::bca_means;
use torus_search::analysis::interval::{Interval, IntervalMethod, LEVEL};
use torus_search::analysis::stats::MeanCi;
use torus_search::config::Config;
use torus_search::experiment::provenance::this_build;
use torus_search::run::batch;

/// |difference| / SE of the difference above this: the means differ.
const Z_AGREE: f64 = 3.0;
/// The code's move cap.
const CAP: f64 = 10_000.0;
/// The points compared, (N, σ).
const POINTS: [(i64, f64); 4] = [(20, 0.0), (20, 5.0), (40, 0.0), (40, 5.0)];

fn main() -> ExitCode {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let r = match a.first().map(String::as_str) {
        Some("mirror") if a.len() >= 6 => mirror_cmd(&a[1..]),
        Some("crate") if a.len() == 5 => crate_cmd(&a[1..]),
        Some("table") => table_cmd(a.get(1).map(String::as_str) == Some("--write")),
        Some("cause") if a.len() == 5 => cause_cmd(&a[1..]),
        _ => Err("usage: fidelity mirror N SIGMA FIRST COUNT SEED [switch...] | crate N SIGMA TRIALS SEED | table [--write] | cause N SIGMA COUNT SEED".into()),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fidelity: {e}");
            ExitCode::from(2)
        }
    }
}

fn num<T: std::str::FromStr>(s: &str, what: &str) -> Result<T, String> {
    s.parse().map_err(|_| format!("{what}: cannot read {s:?}"))
}

/// N and σ as the mirror accepts them.
fn point(n: &str, sigma: &str) -> Result<(i64, f64), String> {
    let (n, sigma): (i64, f64) = (num(n, "N")?, num(sigma, "SIGMA")?);
    if !(3..=1000).contains(&n) || sigma.is_nan() || sigma < 0.0 {
        return Err(format!(
            "N must be in 3..=1000 and SIGMA a number >= 0, got {n} and {sigma}"
        ));
    }
    Ok((n, sigma))
}

fn switches(n: i64, args: &[String]) -> Result<mirror::Switches, String> {
    let mut sw = mirror::Switches::code(n);
    for s in args {
        match s.split_once('=') {
            Some(("torus", "N")) => sw.period = n,
            Some(("detect", "torus")) => sw.torus_detect = true,
            Some(("target", "N1")) => sw.centre_shift = 1,
            Some(("start", v)) => {
                let (x, y) = v.split_once(',').ok_or("start=X,Y")?;
                sw.start = (num(x, "start x")?, num(y, "start y")?);
                if !(0..=n).contains(&sw.start.0) || !(0..=n).contains(&sw.start.1) {
                    return Err(format!("start must lie in 0..={n}, got {v}"));
                }
            }
            _ => {
                return Err(format!(
                    "unknown switch {s:?} (torus=N, detect=torus, target=N1, start=X,Y)"
                ))
            }
        }
    }
    Ok(sw)
}

fn mirror_cmd(a: &[String]) -> Result<(), String> {
    let (n, sigma) = point(&a[0], &a[1])?;
    let (first, count, seed): (u64, u64, u64) = (
        num(&a[2], "FIRST")?,
        num(&a[3], "COUNT")?,
        num(&a[4], "SEED")?,
    );
    let sw = switches(n, &a[5..])?;
    println!("trial,n,sigma,seed,steps,mopt,tx,ty");
    for i in first..first + count {
        let r = mirror::trial(n, sigma, seed, i, sw);
        let s = seed * 1_000_000 + i;
        println!(
            "{i},{n},{sigma},{s},{},{},{},{}",
            r.steps, r.mopt, r.tx, r.ty
        );
    }
    Ok(())
}

/// Means of moves and excess moves over trials, with intervals and SEs.
struct Sample {
    trials: usize,
    moves: (Interval, f64),
    excess: (Interval, f64),
    capped: usize,
    errors: usize,
}

impl Sample {
    fn of(moves: &[f64], excess: &[f64], errors: usize) -> Sample {
        let iv = bca_means(&[moves, excess]);
        let se = |x: &[f64]| MeanCi::of(x.iter().copied()).se();
        Sample {
            trials: moves.len(),
            moves: (iv[0], se(moves)),
            excess: (iv[1], se(excess)),
            capped: moves.iter().filter(|&&m| m >= CAP).count(),
            errors,
        }
    }

    /// The code's trials: moves and excess per trial, from `start`.
    fn of_code(n: i64, rows: &[mirror::Row], start: (i64, i64)) -> Sample {
        let (mut moves, mut excess, mut errors) = (vec![], vec![], 0);
        for r in rows {
            match r.moves_excess(n, start) {
                Some((m, e)) => {
                    moves.push(m);
                    excess.push(e);
                }
                None => errors += 1,
            }
        }
        Sample::of(&moves, &excess, errors)
    }

    fn cell(&self, q: usize) -> String {
        let (iv, _) = if q == 0 { self.moves } else { self.excess };
        format!("{:.2} [{:.2}, {:.2}]", iv.estimate, iv.lo, iv.hi)
    }

    /// z of (self − code) for moves and excess.
    fn z(&self, code: &Sample) -> [f64; 2] {
        let z =
            |a: (Interval, f64), b: (Interval, f64)| (a.0.estimate - b.0.estimate) / a.1.hypot(b.1);
        [z(self.moves, code.moves), z(self.excess, code.excess)]
    }
}

/// The crate's two readings at the code's (N, σ): the preset on the
/// N-torus, and the code's lattice (`--n N+1 --prior code`).
fn readings(n: i64, sigma: f64, seed: u64) -> Result<[(&'static str, Config); 2], String> {
    let make = |extra: &[(&str, String)]| -> Result<Config, String> {
        let mut cfg = Config::default();
        cfg.set("preset", "paper-code").map_err(|e| e.to_string())?;
        cfg.set("sigma", &sigma.to_string())
            .map_err(|e| e.to_string())?;
        cfg.set("seed", &seed.to_string())
            .map_err(|e| e.to_string())?;
        for (k, v) in extra {
            cfg.set(k, v).map_err(|e| e.to_string())?;
        }
        cfg.validate().map_err(|e| e.to_string())?;
        Ok(cfg)
    };
    Ok([
        ("preset", make(&[("n", n.to_string())])?),
        (
            "reading",
            make(&[("n", (n + 1).to_string()), ("prior", "code".into())])?,
        ),
    ])
}

fn crate_sample(cfg: &Config, trials: u64) -> Result<Sample, String> {
    let rows = batch::run_trials(cfg, 0, trials).map_err(|e| e.to_string())?;
    let moves: Vec<f64> = rows.iter().map(|r| r.steps as f64).collect();
    let excess: Vec<f64> = rows
        .iter()
        .map(|r| r.steps as f64 - r.optimal as f64)
        .collect();
    Ok(Sample::of(&moves, &excess, 0))
}

const TSV_HEADER: &str = "kind\tn\tsigma\tseed\ttrials\tmoves\tmoves_lo\tmoves_hi\tmoves_se\texcess\texcess_lo\texcess_hi\texcess_se\tcapped\tbuild";

fn crate_cmd(a: &[String]) -> Result<(), String> {
    let (n, sigma) = point(&a[0], &a[1])?;
    let (trials, seed): (u64, u64) = (num(&a[2], "TRIALS")?, num(&a[3], "SEED")?);
    println!("{TSV_HEADER}");
    for (kind, cfg) in readings(n, sigma, seed)? {
        let s = crate_sample(&cfg, trials)?;
        let f =
            |(iv, se): (Interval, f64)| format!("{}\t{}\t{}\t{}", iv.estimate, iv.lo, iv.hi, se);
        println!(
            "{kind}\t{n}\t{sigma}\t{seed}\t{}\t{}\t{}\t{}\t{}",
            s.trials,
            f(s.moves),
            f(s.excess),
            s.capped,
            this_build()
        );
    }
    Ok(())
}

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fidelity/data")
}

fn read(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))
}

/// The trials of a CSV of the code (header skipped): (trial, seed state, row).
fn csv_rows(path: &Path) -> Result<Vec<(u64, u64, mirror::Row)>, String> {
    read(path)?
        .lines()
        .skip(1)
        .map(|l| {
            mirror::Row::parse(l)
                .map(|(i, _, _, s, r)| (i, s, r))
                .ok_or_else(|| format!("{}: cannot read the row {l:?}", path.display()))
        })
        .collect()
}

/// A crate summary row of `crate-nN-sS.tsv` as a sample.
fn tsv_sample(line: &str) -> Result<(String, Sample), String> {
    let f: Vec<&str> = line.split('\t').collect();
    if f.len() != 15 {
        return Err(format!("a crate summary row has 15 fields: {line:?}"));
    }
    let x = |i: usize| num::<f64>(f[i], "a crate summary field");
    let iv = |i: usize| -> Result<(Interval, f64), String> {
        let v = Interval {
            estimate: x(i)?,
            lo: x(i + 1)?,
            hi: x(i + 2)?,
            level: LEVEL,
            method: IntervalMethod::Bootstrap,
        };
        Ok((v, x(i + 3)?))
    };
    Ok((
        f[0].to_string(),
        Sample {
            trials: num(f[4], "trials")?,
            moves: iv(5)?,
            excess: iv(9)?,
            capped: num(f[13], "capped")?,
            errors: 0,
        },
    ))
}

/// Checks every Octave trial of `code-nN-sS*.csv` against the mirror
/// (recomputed here); returns a line per file.
fn pins(n: i64, sigma: f64) -> Result<Vec<String>, String> {
    let prefix = format!("code-n{n}-s{sigma}");
    let mut names: Vec<String> = std::fs::read_dir(data_dir())
        .map_err(|e| e.to_string())?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|f| f.starts_with(&prefix) && f.ends_with(".csv"))
        .collect();
    names.sort();
    let mut out = vec![];
    for name in names {
        let rows = csv_rows(&data_dir().join(&name))?;
        let mut same = 0;
        for &(i, state, row) in &rows {
            let want = mirror::trial(n, sigma, state / 1_000_000, i, mirror::Switches::code(n));
            same += usize::from(want == row);
        }
        let trials: Vec<String> = rows.iter().map(|r| r.0.to_string()).collect();
        out.push(format!(
            "`{name}`: trials {} — the mirror gives {same} of {} exactly",
            trials.join(", "),
            rows.len()
        ));
        if same != rows.len() {
            return Err(out.pop().unwrap_or_default());
        }
    }
    Ok(out)
}

fn table_cmd(write: bool) -> Result<(), String> {
    let mut md = String::new();
    let mut pin_lines = vec![];
    md.push_str("| N | σ | quantity | the code (mirror) | `paper-code` `--n N` | z | `paper-code` `--n N+1 --prior code` | z |\n|---|---|---|---|---|---|---|---|\n");
    let mut verdicts = String::new();
    for (n, sigma) in POINTS {
        let rows = csv_rows(&data_dir().join(format!("mirror-n{n}-s{sigma}.csv")))?;
        let rows: Vec<mirror::Row> = rows.into_iter().map(|r| r.2).collect();
        let code = Sample::of_code(n, &rows, (1, 1));
        let tsv = read(&data_dir().join(format!("crate-n{n}-s{sigma}.tsv")))?;
        let crate_rows: Vec<(String, Sample)> = tsv
            .lines()
            .skip(1)
            .map(tsv_sample)
            .collect::<Result<_, _>>()?;
        let [(_, preset), (_, reading)] = &crate_rows[..] else {
            return Err(format!(
                "crate-n{n}-s{sigma}.tsv: want the rows preset, reading"
            ));
        };
        let (zp, zr) = (preset.z(&code), reading.z(&code));
        for (q, name) in ["moves", "excess"].iter().enumerate() {
            let _ = writeln!(
                md,
                "| {n} | {sigma} | {name} | {} n={} | {} n={} | {:+.1} | {} n={} | {:+.1} |",
                code.cell(q),
                code.trials,
                preset.cell(q),
                preset.trials,
                zp[q],
                reading.cell(q),
                reading.trials,
                zr[q]
            );
        }
        let word = |z: [f64; 2]| match (z[0].abs() <= Z_AGREE, z[1].abs() <= Z_AGREE) {
            (true, true) => "agrees",
            (false, true) => "excess agrees, moves differ",
            (true, false) => "moves agree, excess differs",
            (false, false) => "differs",
        };
        let verdict = |z, s: &Sample| format!("{} ({} of {} capped)", word(z), s.capped, s.trials);
        let _ = writeln!(
            verdicts,
            "| {n} | {sigma} | {} ({} capped, {} index errors) | {} | {} |",
            code.trials + code.errors,
            code.capped,
            code.errors,
            verdict(zp, preset),
            verdict(zr, reading),
        );
        for l in pins(n, sigma)? {
            pin_lines.push(format!("* N = {n}, σ = {sigma}: {l}"));
        }
    }
    for l in pins(8, 2.0)? {
        pin_lines.push(format!("* N = 8, σ = 2: {l}"));
    }
    md.push_str("\n| N | σ | the code's trials | `paper-code` `--n N` | `--n N+1 --prior code` |\n|---|---|---|---|---|\n");
    md.push_str(&verdicts);
    let pins = format!(
        "\nOctave trials, each recomputed by the mirror:\n\n{}\n",
        pin_lines.join("\n")
    );
    print!("{md}{pins}");
    if write {
        splice("fidelity/README.md", "results", &format!("{md}{pins}"))?;
        splice("EXPERIMENTS.md", "fidelity", &md)?;
        let mut cause = String::new();
        for (n, sigma) in [(20, 0.0), (40, 0.0)] {
            if let Ok(t) = read(&data_dir().join(format!("cause-n{n}-s{sigma}.md"))) {
                cause.push_str(&t);
                cause.push('\n');
            }
        }
        splice("fidelity/README.md", "cause", &cause)?;
    }
    Ok(())
}

/// Replaces the text between `<!-- NAME:begin -->` and `<!-- NAME:end -->`
/// in `file` (relative to the crate).
fn splice(file: &str, name: &str, body: &str) -> Result<(), String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let text = read(&path)?;
    let (b, e) = (
        format!("<!-- {name}:begin -->\n"),
        format!("<!-- {name}:end -->"),
    );
    let (Some(i), Some(j)) = (text.find(&b), text.find(&e)) else {
        return Err(format!("{} has no {b:?} … {e:?}", path.display()));
    };
    let out = format!("{}{b}{body}{}", &text[..i], &text[j..]);
    std::fs::write(&path, out).map_err(|e| format!("{}: {e}", path.display()))
}

/// The code with one of its departures from the crate changed at a time.
fn cause_cmd(a: &[String]) -> Result<(), String> {
    let (n, sigma) = point(&a[0], &a[1])?;
    let (count, seed): (u64, u64) = (num(&a[2], "COUNT")?, num(&a[3], "SEED")?);
    let args = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let variants = [
        (
            "the code: (N+1)-torus, Euclidean detection without wrap",
            args(&[]),
        ),
        ("detection at torus ℓ1 ≤ 1", args(&["detect=torus"])),
        ("… and the N-torus", args(&["detect=torus", "torus=N"])),
        (
            "… and targets centred at N/2+1: the preset's world",
            args(&["detect=torus", "torus=N", "target=N1"]),
        ),
    ];
    let mut md = format!("| the code at N = {n}, σ = {sigma}, changed | trials | moves | excess moves |\n|---|---|---|---|\n");
    for (name, sw) in variants {
        let sw = switches(n, &sw)?;
        let rows: Vec<mirror::Row> = (0..count)
            .map(|i| mirror::trial(n, sigma, seed, i, sw))
            .collect();
        let s = if sw.torus_detect {
            torus_sample(&rows, sw)
        } else {
            Sample::of_code(n, &rows, sw.start)
        };
        let _ = writeln!(
            md,
            "| {name} | {} | {} | {} |",
            s.trials,
            s.cell(0),
            s.cell(1)
        );
    }
    print!("{md}");
    Ok(())
}

/// Moves and excess with torus detection: the optimum is the torus ℓ1
/// distance less the one cell the sensor covers. Index errors are counted
/// and left out, as in [`Sample::of_code`].
fn torus_sample(rows: &[mirror::Row], sw: mirror::Switches) -> Sample {
    let p = sw.period;
    let d = |a: i64, b: i64| (a - b).rem_euclid(p).min((b - a).rem_euclid(p));
    let ok: Vec<&mirror::Row> = rows.iter().filter(|r| r.steps >= 0).collect();
    let moves: Vec<f64> = ok.iter().map(|r| (r.steps - 1).max(0) as f64).collect();
    let excess: Vec<f64> = ok
        .iter()
        .zip(&moves)
        .map(|(r, m)| m - (d(r.tx, sw.start.0) + d(r.ty, sw.start.1) - 1).max(0) as f64)
        .collect();
    Sample::of(&moves, &excess, rows.len() - ok.len())
}
