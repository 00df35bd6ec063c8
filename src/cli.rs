//! Argument parsing, parallel batches and output for the native binary.

use clap::{Args, Parser, Subcommand, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use torus_search::config::{Belief, Config, ConfigError, SearcherKind};
use torus_search::episode::{Episode, TrialResult};
use torus_search::mcts::{FinalRule, Variant};
use torus_search::prior::PriorSpec;
use torus_search::searchers::PolicyKind;
use torus_search::stats::Summary;

#[derive(Parser, Debug)]
#[command(
    name = "torus-search",
    version,
    about = "MCTS for a single-target search game on a periodic 2-D lattice"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// Run trials and summarise them.
    Run(RunArgs),
    /// Measure this machine's throughput.
    Bench {
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
        /// Scale every workload (1 = about 10 s in all).
        #[arg(long, default_value_t = 1.0)]
        scale: f64,
        /// Instead of the suite: time loops FROM..TO of one MCTS episode whose
        /// core config (JSON, as the page exports it) is in this file. The
        /// browser benchmark uses it to time the very loops the page ran.
        #[arg(long, value_name = "FILE", requires = "loops")]
        episode: Option<std::path::PathBuf>,
        /// The loop window for --episode, as FROM..TO.
        #[arg(long, value_name = "FROM..TO", requires = "episode")]
        loops: Option<String>,
        /// The seed for --episode.
        #[arg(long, default_value_t = 1, requires = "episode")]
        seed: u64,
    },
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum PriorArg {
    Delta,
    Gaussian,
    Uniform,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum SearcherArg {
    Mcts,
    Rw,
    Levy,
    Nsarw,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum VariantArg {
    Cells,
    Tree,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum RolloutArg {
    Rw,
    Levy,
    Nsarw,
    Greedy,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum BeliefArg {
    Prior,
    Posterior,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum FinalArg {
    Visits,
    Mean,
    Uct,
}

fn parse_cell(s: &str) -> Result<[u32; 2], String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("expected x,y (1-based), got '{s}'"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("expected x,y with positive integers, got '{s}'"))
    };
    Ok([p(x)?, p(y)?])
}

#[derive(Args, Debug)]
struct RunArgs {
    /// Who searches.
    #[arg(long, value_enum, default_value = "mcts")]
    searcher: SearcherArg,
    /// MCTS variant: per-cell statistics (the paper) or a search tree.
    #[arg(long, value_enum, default_value = "cells")]
    variant: VariantArg,
    /// MCTS rollout (default) policy.
    #[arg(long, value_enum, default_value = "rw")]
    rollout: RolloutArg,
    /// Where practice targets come from.
    #[arg(long, value_enum, default_value = "posterior")]
    belief: BeliefArg,
    /// Lattice side N (3..=1024).
    #[arg(long, default_value_t = 40, allow_negative_numbers = true)]
    n: i64,
    /// Target prior.
    #[arg(long, value_enum, conflicts_with = "target")]
    prior: Option<PriorArg>,
    /// Gaussian standard deviation (>= 0; inf = uniform).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "target")]
    sigma: Option<f64>,
    /// Detection radius r_v (>= 0).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    rv: f64,
    /// Start cell x,y (1-based).
    #[arg(long, default_value = "1,1", value_parser = parse_cell)]
    start: [u32; 2],
    /// A fixed target cell x,y (1-based).
    #[arg(long, value_parser = parse_cell)]
    target: Option<[u32; 2]>,
    /// Place the target by the prior but plan with a delta prior on it.
    #[arg(long)]
    known: bool,
    /// MCTS loops per real move.
    #[arg(long, allow_negative_numbers = true)]
    loops: Option<i64>,
    /// MCTS decision time per real move in milliseconds (instead of --loops).
    #[arg(long, conflicts_with = "loops", allow_negative_numbers = true)]
    decision_ms: Option<f64>,
    /// UCT exploration constant.
    #[arg(long, default_value_t = std::f64::consts::SQRT_2, allow_negative_numbers = true)]
    c: f64,
    /// Lévy exponent μ in (1, 3].
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    mu: f64,
    /// Greedy rollout noise ε in [0, 1].
    #[arg(long, default_value_t = 0.2, allow_negative_numbers = true)]
    epsilon: f64,
    /// Final-move rule.
    #[arg(long = "final", value_enum, default_value = "visits")]
    final_rule: FinalArg,
    /// Rollout step cap.
    #[arg(long, default_value_t = 10_000, allow_negative_numbers = true)]
    rollout_cap: i64,
    /// Episode step cap.
    #[arg(long, default_value_t = 100_000, allow_negative_numbers = true)]
    step_cap: i64,
    /// `cells`: clear the statistics before each real move.
    #[arg(long)]
    reset_each_move: bool,
    /// `tree`: arena cap in nodes.
    #[arg(long, default_value_t = torus_search::mcts::tree::DEFAULT_MAX_NODES as i64, allow_negative_numbers = true)]
    tree_nodes: i64,
    /// Number of trials.
    #[arg(long, default_value_t = 1000, allow_negative_numbers = true)]
    trials: i64,
    /// Seed: the run is a pure function of the config and the seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long, allow_negative_numbers = true)]
    threads: Option<i64>,
    /// Print exactly one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

struct UsageError(String);

/// `println!` that ends the process quietly when stdout is closed (as in
/// `torus-search bench | head -1`) instead of panicking.
macro_rules! out {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        if writeln!(std::io::stdout(), $($t)*).is_err() {
            std::process::exit(0);
        }
    }};
}

fn flag(field: &str) -> String {
    // Config fields are named after their flags, except the decision time.
    match field {
        "ms" => "--decision-ms".into(),
        other => format!("--{other}"),
    }
}

fn from_config(e: ConfigError) -> UsageError {
    UsageError(format!(
        "{} must be {}, got {}",
        flag(e.field),
        e.allowed,
        e.value
    ))
}

fn to_u32(name: &str, v: i64, lo: u32, hi: u32) -> Result<u32, UsageError> {
    if v < lo as i64 || v > hi as i64 {
        return Err(UsageError(format!(
            "{name} must be an integer in {lo}..={hi}, got {v}"
        )));
    }
    Ok(v as u32)
}

fn build_config(a: &RunArgs) -> Result<(Config, u64, usize), UsageError> {
    use torus_search::config::limits;
    let n = to_u32(
        "--n",
        a.n,
        torus_search::lattice::MIN_N,
        torus_search::lattice::MAX_N,
    )?;
    let prior = match (a.prior, a.sigma) {
        (Some(PriorArg::Delta), None) => PriorSpec::Delta { cell: None },
        (Some(PriorArg::Uniform), None) => PriorSpec::Uniform,
        (Some(PriorArg::Delta | PriorArg::Uniform), Some(_)) => {
            return Err(UsageError(
                "--sigma only applies to --prior gaussian".into(),
            ))
        }
        (_, s) => {
            let sigma = s.unwrap_or(5.0);
            if sigma.is_nan() || sigma < 0.0 {
                return Err(UsageError(format!(
                    "--sigma must be a number >= 0 (inf means uniform), got {sigma}"
                )));
            }
            PriorSpec::Gaussian { sigma }
        }
    };
    let is_mcts = matches!(a.searcher, SearcherArg::Mcts);
    if !is_mcts && (a.loops.is_some() || a.decision_ms.is_some()) {
        return Err(UsageError(
            "--loops and --decision-ms only apply to --searcher mcts".into(),
        ));
    }
    let loops = match a.loops {
        Some(l) => to_u32("--loops", l, limits::LOOPS.0, limits::LOOPS.1)?,
        None => 100,
    };
    let trials = to_u32("--trials", a.trials, 1, 100_000_000)? as u64;
    let threads = match a.threads {
        Some(t) => to_u32("--threads", t, 1, 1024)? as usize,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let cfg = Config {
        n,
        prior,
        rv: a.rv,
        start: a.start,
        target: a.target,
        known: a.known,
        searcher: match a.searcher {
            SearcherArg::Mcts => SearcherKind::Mcts,
            SearcherArg::Rw => SearcherKind::Rw,
            SearcherArg::Levy => SearcherKind::Levy,
            SearcherArg::Nsarw => SearcherKind::Nsarw,
        },
        variant: match a.variant {
            VariantArg::Cells => Variant::Cells,
            VariantArg::Tree => Variant::Tree,
        },
        rollout: match a.rollout {
            RolloutArg::Rw => PolicyKind::Rw,
            RolloutArg::Levy => PolicyKind::Levy,
            RolloutArg::Nsarw => PolicyKind::Nsarw,
            RolloutArg::Greedy => PolicyKind::Greedy,
        },
        belief: match a.belief {
            BeliefArg::Prior => Belief::Prior,
            BeliefArg::Posterior => Belief::Posterior,
        },
        loops,
        decision_ms: a.decision_ms,
        c: a.c,
        mu: a.mu,
        epsilon: a.epsilon,
        final_rule: match a.final_rule {
            FinalArg::Visits => FinalRule::Visits,
            FinalArg::Mean => FinalRule::Mean,
            FinalArg::Uct => FinalRule::Uct,
        },
        rollout_cap: to_u32(
            "--rollout-cap",
            a.rollout_cap,
            limits::ROLLOUT_CAP.0,
            limits::ROLLOUT_CAP.1,
        )?,
        step_cap: to_u32(
            "--step-cap",
            a.step_cap,
            limits::STEP_CAP.0,
            limits::STEP_CAP.1,
        )?,
        reset_each_move: a.reset_each_move,
        tree_nodes: to_u32(
            "--tree-nodes",
            a.tree_nodes,
            torus_search::mcts::tree::MIN_MAX_NODES,
            torus_search::mcts::tree::MAX_MAX_NODES,
        )?,
        keep_traces: 0,
    };
    cfg.validate().map_err(from_config)?;
    Ok((cfg, trials, threads))
}

fn run(a: &RunArgs) -> Result<(), UsageError> {
    let (cfg, trials, threads) = build_config(a)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| UsageError(format!("cannot start {threads} threads: {e}")))?;
    let t0 = Instant::now();
    // The bar appears only once a run has taken a second, so quick runs and
    // pipelines stay quiet.
    let bar = ProgressBar::with_draw_target(Some(trials), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} trials, eta {eta}")
            .expect("static template")
            .progress_chars("=> "),
    );
    let shown = AtomicBool::new(false);
    let results: Vec<TrialResult> = pool.install(|| {
        (0..trials)
            .into_par_iter()
            .map(|i| {
                let r = Episode::trial(&cfg, a.seed, i)
                    .expect("config validated above")
                    .run();
                if !shown.load(Ordering::Relaxed)
                    && t0.elapsed().as_secs_f64() > 1.0
                    && !shown.swap(true, Ordering::Relaxed)
                {
                    bar.set_draw_target(ProgressDrawTarget::stderr());
                }
                bar.inc(1);
                r
            })
            .collect()
    });
    bar.finish_and_clear();
    let seconds = t0.elapsed().as_secs_f64();
    let s = Summary::of(&results);
    if a.json {
        let v = serde_json::json!({
            "trials": s.trials,
            "mean_steps": s.steps.mean,
            "ci95_steps": [s.steps.lo, s.steps.hi],
            "mean_optimal": s.optimal.mean,
            "ci95_optimal": [s.optimal.lo, s.optimal.hi],
            "asoo": s.asoo.mean,
            "ci95_asoo": [s.asoo.lo, s.asoo.hi],
            "mean_ratio": s.ratio.mean,
            "ci95_ratio": [s.ratio.lo, s.ratio.hi],
            "steps_over_mean_optimal": s.steps_over_mean_optimal,
            "median_steps": s.median_steps,
            "q1_steps": s.q1_steps,
            "q3_steps": s.q3_steps,
            "zero_optimal": s.zero_optimal,
            "capped": s.capped,
            "rollouts": s.counters.rollouts,
            "rollout_steps": s.counters.rollout_steps,
            "truncated_rollouts": s.counters.truncated,
            "seconds": seconds,
            "threads": threads,
            "seed": a.seed,
            "config": cfg,
        });
        out!("{v}");
    } else {
        print_table(&cfg, a.seed, &s, seconds, threads);
    }
    Ok(())
}

fn print_table(cfg: &Config, seed: u64, s: &Summary, seconds: f64, threads: usize) {
    let prior = match &cfg.prior {
        PriorSpec::Delta { .. } => "delta".to_string(),
        PriorSpec::Gaussian { sigma } => format!("gaussian sigma={sigma}"),
        PriorSpec::Uniform => "uniform".to_string(),
        PriorSpec::Weights { .. } => "weights".to_string(),
    };
    let who = match cfg.searcher {
        SearcherKind::Mcts => {
            let budget = cfg
                .decision_ms
                .map_or(format!("L={}", cfg.loops), |ms| format!("{ms} ms/move"));
            format!(
                "mcts {} rollout={} belief={} {budget} c={:.4} final={}",
                cfg.variant.name(),
                cfg.rollout.name(),
                cfg.belief.name(),
                cfg.c,
                cfg.final_rule.name()
            )
        }
        k => k.name().to_string(),
    };
    let ci =
        |m: &torus_search::stats::MeanCi| format!("{:>10.3}   [{:.3}, {:.3}]", m.mean, m.lo, m.hi);
    out!(
        "torus-search: N={} r_v={} prior={prior} start={},{} seed={seed}",
        cfg.n,
        cfg.rv,
        cfg.start[0],
        cfg.start[1]
    );
    out!("searcher: {who}");
    out!("{:<28}{}", "trials", s.trials);
    out!("{:<28}{}", "mean steps   [95% CI]", ci(&s.steps));
    out!("{:<28}{}", "mean optimal [95% CI]", ci(&s.optimal));
    out!("{:<28}{}", "ASOO = mean(steps-opt)", ci(&s.asoo));
    out!("{:<28}{}", "mean steps/opt", ci(&s.ratio));
    out!(
        "{:<28}{:>10.3}",
        "mean steps / mean opt",
        s.steps_over_mean_optimal
    );
    out!(
        "{:<28}{:>10.1}   (q1 {:.1}, q3 {:.1})",
        "median steps",
        s.median_steps,
        s.q1_steps,
        s.q3_steps
    );
    out!("{:<28}{}", "optimal = 0 (excluded)", s.zero_optimal);
    out!("{:<28}{}", "capped episodes", s.capped);
    out!(
        "{:<28}{} ({} steps, {} truncated)",
        "rollouts",
        s.counters.rollouts,
        s.counters.rollout_steps,
        s.counters.truncated
    );
    out!("{:<28}{:.3} s on {threads} threads", "time", seconds);
}

fn bench(json: bool, scale: f64) -> Result<(), UsageError> {
    if !(scale.is_finite() && scale > 0.0 && scale <= 1000.0) {
        return Err(UsageError(format!(
            "--scale must be a number in (0, 1000], got {scale}"
        )));
    }
    use torus_search::bench::{mcts_loops, rollout_steps};
    let mut out = serde_json::Map::new();
    let steps = (2e8 * scale) as u64;
    for (kind, key, work) in [
        (PolicyKind::Rw, "rw_steps_per_s", steps),
        (PolicyKind::Levy, "levy_steps_per_s", steps / 8),
        (PolicyKind::Nsarw, "nsarw_steps_per_s", steps / 8),
    ] {
        // A short warm-up pages in the tables and lets the CPU clock up.
        rollout_steps(kind, 40, 1.0, 2.0, 7, work / 20).map_err(from_config)?;
        let t = Instant::now();
        let done = rollout_steps(kind, 40, 1.0, 2.0, 1, work).map_err(from_config)?;
        let rate = done as f64 / t.elapsed().as_secs_f64();
        out.insert(key.into(), rate.into());
        if !json {
            out!(
                "{:<34}{:>14.3e}",
                format!("{} rollout lattice steps/s", kind.name()),
                rate
            );
        }
    }
    for (variant, vname) in [(Variant::Cells, "cells"), (Variant::Tree, "tree")] {
        for sigma in [0.0, 5.0] {
            let cfg = Config {
                variant,
                prior: PriorSpec::Gaussian { sigma },
                ..Config::default()
            };
            let loops = ((if sigma == 0.0 { 200_000.0 } else { 40_000.0 }) * scale) as u64;
            let t = Instant::now();
            let (done, _, _) = mcts_loops(&cfg, 1, loops.max(100)).map_err(from_config)?;
            let lps = done as f64 / t.elapsed().as_secs_f64();
            let trials = ((if sigma == 0.0 { 40.0 } else { 4.0 }) * scale).ceil() as u64;
            let t = Instant::now();
            for i in 0..trials {
                Episode::trial(&cfg, 1, i).map_err(from_config)?.run();
            }
            let eps = trials as f64 / t.elapsed().as_secs_f64();
            let tag = format!("mcts_{vname}_sigma{}", sigma as u32);
            out.insert(format!("{tag}_loops_per_s"), lps.into());
            out.insert(format!("{tag}_episodes_per_s"), eps.into());
            if !json {
                out!(
                    "{:<34}{:>14.1} loops/s {:>10.3} episodes/s",
                    format!("mcts {vname} N=40 L=100 sigma={sigma} posterior"),
                    lps,
                    eps
                );
            }
        }
    }
    // Episodes use the default posterior belief: with the prior a `cells`
    // searcher can be trapped until the step cap, which measures the cap.
    out.insert("belief".into(), Config::default().belief.name().into());
    if json {
        out!("{}", serde_json::Value::Object(out));
    }
    Ok(())
}

/// Times loops `from..to` of the episode (trials 0, 1, … of the config in `file`).
fn bench_window(
    file: &std::path::Path,
    window: &str,
    seed: u64,
    json: bool,
) -> Result<(), UsageError> {
    let bad_window = || {
        UsageError(format!(
            "--loops must be FROM..TO with integers 0 <= FROM < TO <= 1000000000, got {window:?}"
        ))
    };
    let (from, to) = window.split_once("..").ok_or_else(bad_window)?;
    let (from, to): (u64, u64) = (
        from.trim().parse().map_err(|_| bad_window())?,
        to.trim().parse().map_err(|_| bad_window())?,
    );
    if from >= to || to > 1_000_000_000 {
        return Err(bad_window());
    }
    let text = std::fs::read_to_string(file)
        .map_err(|e| UsageError(format!("--episode {}: {e}", file.display())))?;
    let cfg: Config = serde_json::from_str(&text).map_err(|e| {
        UsageError(format!(
            "--episode {} is not a core config (JSON): {e}",
            file.display()
        ))
    })?;
    // LoopRunner::new validates the config.
    let mut runner = torus_search::bench::LoopRunner::new(&cfg, seed).map_err(from_config)?;
    runner.run(from).map_err(from_config)?;
    let t = Instant::now();
    runner.run(to - from).map_err(from_config)?;
    let secs = t.elapsed().as_secs_f64();
    let lps = (to - from) as f64 / secs;
    if json {
        out!(
            "{}",
            serde_json::json!({ "from": from, "to": to, "seconds": secs, "loops_per_s": lps })
        );
    } else {
        out!("loops {from}..{to} of the episode: {lps:.1} loops/s ({secs:.3} s)");
    }
    Ok(())
}

/// Runs the CLI and returns the process exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = e.exit_code();
            let _ = e.print();
            return code;
        }
    };
    let r = match &cli.cmd {
        Cmd::Run(a) => run(a),
        Cmd::Bench {
            episode: Some(file),
            loops: Some(window),
            seed,
            json,
            ..
        } => bench_window(file, window, *seed, *json),
        Cmd::Bench { json, scale, .. } => bench(*json, *scale),
    };
    match r {
        Ok(()) => 0,
        Err(UsageError(msg)) => {
            eprintln!("error: {msg}");
            2
        }
    }
}
