//! `torus-search run`: a batch of trials, one episode's moves, exact means.

use super::args::{
    build_config, invocation, param_args, preset, preset_arg, thread_pool, threads_arg,
    with_progress, Defaults,
};
use super::usage::{usage, UsageError};
use crate::analysis::bootstrap::bca_mean;
use crate::analysis::bound;
use crate::analysis::exact;
use crate::analysis::interval::Interval;
use crate::analysis::report;
use crate::analysis::stats::{self, Summary};
use crate::config::preset::Preset;
use crate::config::schema::ConfigParam;
use crate::config::{self, Config, TRIALS};
use crate::experiment::provenance::{this_build, Provenance};
use crate::run::batch;
use crate::run::episode::TrialResult;
use clap::{Arg, ArgAction, ArgMatches, Command};
use std::time::Instant;

pub(super) fn run_command() -> Command {
    param_args(
        Command::new("run").about("Run trials and summarise them."),
        &[],
        Defaults::Schema,
    )
    .arg(preset_arg("none"))
    .arg(
        Arg::new(TRIALS.key)
            .long(TRIALS.key)
            .value_name("COUNT")
            .allow_hyphen_values(true)
            .help(format!(
                "{}: {} [default: {}]",
                TRIALS.help,
                TRIALS.kind.allowed(),
                TRIALS.default.text()
            )),
    )
    .arg(threads_arg())
    .arg(
        Arg::new("json")
            .long("json")
            .action(ArgAction::SetTrue)
            .help("print exactly one JSON object: the summary, how it ran, and the config"),
    )
    .arg(
        Arg::new("exact")
            .long("exact")
            .action(ArgAction::SetTrue)
            .help("deterministic searchers only: one pass along the searcher's path gives E[min(T, step cap)] exactly, instead of sampling trials"),
    )
    .arg(
        Arg::new("blind")
            .long("blind")
            .action(ArgAction::SetTrue)
            .conflicts_with("exact")
            .help("any searcher: count each trial's path exactly (Σ R_t along the path it follows until it detects the target) and report the mean over trials with its 95% CI; the target's share of the noise is removed"),
    )
    .arg(
        Arg::new("dry-run")
            .long("dry-run")
            .action(ArgAction::SetTrue)
            .help("print the resolved config as JSON and run nothing"),
    )
}

pub(super) fn run(m: &ArgMatches) -> Result<(), UsageError> {
    let cfg = build_config(m)?;
    if m.get_flag("dry-run") {
        out!(
            "{}",
            serde_json::to_string(&cfg).expect("a config serialises")
        );
        return Ok(());
    }
    let trials = TRIALS
        .int_value(m.get_one::<String>(TRIALS.key).map(String::as_str))
        .map_err(usage)?;
    if m.get_flag("exact") {
        return run_exact(&cfg, m.get_flag("json"));
    }
    let (threads, pool) = thread_pool(m)?;
    if m.get_flag("blind") {
        return run_blind(&cfg, trials, threads, &pool, m.get_flag("json"));
    }
    let t0 = Instant::now();
    let results: Vec<TrialResult> = with_progress(&pool, 0..trials, "trials", |i| {
        batch::trial(&cfg, i).expect("the config was validated above")
    });
    let seconds = t0.elapsed().as_secs_f64();
    let s = Summary::of(&results);
    let lower_bound = bound::lower_bound_capped(&cfg).map_err(usage)?;
    let mean_over_bound = (lower_bound > 0.0).then(|| s.steps.estimate / lower_bound);
    if m.get_flag("json") {
        let report = report::Report {
            summary: &s,
            lower_bound,
            mean_over_bound,
            seconds,
            threads,
            seed: cfg.seed,
            config: &cfg,
        };
        out!("{}", stamped(&report));
    } else {
        print_table(&cfg, preset(m, None)?, &s, lower_bound, seconds, threads);
    }
    Ok(())
}

/// A report with this run's provenance before its own fields.
fn stamped<T: serde::Serialize>(report: &T) -> String {
    #[derive(serde::Serialize)]
    struct Stamped<'a, T> {
        provenance: Provenance,
        #[serde(flatten)]
        report: &'a T,
    }
    serde_json::to_string(&Stamped {
        provenance: invocation(),
        report,
    })
    .expect("a report serialises")
}

/// The usage error of an exact evaluation refused: a bad configuration
/// as any other, or why the paths cannot be counted exactly.
pub(super) fn exact_usage(e: exact::ExactError) -> UsageError {
    match e {
        exact::ExactError::Config(e) => usage(e),
        e => UsageError(e.to_string()),
    }
}

/// `run --exact`: the exact mean of a deterministic searcher.
pub(super) fn run_exact(cfg: &Config, json: bool) -> Result<(), UsageError> {
    let t0 = Instant::now();
    let exact = exact::exact_mean(cfg).map_err(exact_usage)?;
    let seconds = t0.elapsed().as_secs_f64();
    let lower_bound = bound::lower_bound_capped(cfg).map_err(usage)?;
    let mean_over_bound = (lower_bound > 0.0).then(|| exact.mean / lower_bound);
    if json {
        let report = exact::ExactReport {
            exact,
            lower_bound,
            mean_over_bound,
            seconds,
            seed: cfg.seed,
            config: cfg,
        };
        out!("{}", stamped(&report));
        return Ok(());
    }
    out!(
        "torus-search: N={} r_v={} prior={} start={},{} (exact)",
        cfg.n,
        cfg.rv,
        cfg.prior_label(),
        cfg.start[0],
        cfg.start[1]
    );
    out!("searcher: {}", cfg.label());
    out!("{}", this_build());
    out!("{:<28}{:>10.3}", "exact mean steps", exact.mean);
    out!(
        "{:<28}{:>10.3}   (mean steps / bound {})",
        "lower bound (any searcher)",
        lower_bound,
        mean_over_bound.map_or("–".into(), |r| format!("{r:.4}"))
    );
    out!("{:<28}{:>10.3e}", "P(capped)", exact.capped_probability);
    out!("{:<28}{}", "moves driven", exact.moves);
    out!("{:<28}{:.3} s", "time", seconds);
    Ok(())
}

/// `run --blind`: the exact means of the trials' blind paths.
pub(super) fn run_blind(
    cfg: &Config,
    trials: u64,
    threads: usize,
    pool: &rayon::ThreadPool,
    json: bool,
) -> Result<(), UsageError> {
    exact::check_blind(cfg).map_err(exact_usage)?;
    let t0 = Instant::now();
    let each: Vec<exact::Exact> = with_progress(pool, 0..trials, "trials", |i| {
        exact::blind_mean(cfg, i).expect("the config was validated above")
    });
    let seconds = t0.elapsed().as_secs_f64();
    let n = each.len().max(1) as f64;
    let means: Vec<f64> = each.iter().map(|e| e.mean).collect();
    let blind_mean = bca_mean(&means);
    let lower_bound = bound::lower_bound_capped(cfg).map_err(usage)?;
    let report = exact::BlindReport {
        trials,
        blind_mean,
        sd: stats::MeanCi::of(means.iter().copied()).sd,
        min: each.iter().map(|e| e.mean).fold(f64::INFINITY, f64::min),
        max: each
            .iter()
            .map(|e| e.mean)
            .fold(f64::NEG_INFINITY, f64::max),
        capped_probability: each.iter().map(|e| e.capped_probability).sum::<f64>() / n,
        mean_moves: each.iter().map(|e| e.moves as f64).sum::<f64>() / n,
        lower_bound,
        mean_over_bound: (lower_bound > 0.0).then(|| blind_mean.estimate / lower_bound),
        seconds,
        threads,
        seed: cfg.seed,
        config: cfg,
    };
    if json {
        out!("{}", stamped(&report));
        return Ok(());
    }
    out!(
        "torus-search: N={} r_v={} prior={} start={},{} ({} blind paths, counted exactly)",
        cfg.n,
        cfg.rv,
        cfg.prior_label(),
        cfg.start[0],
        cfg.start[1],
        trials
    );
    out!("searcher: {}", cfg.label());
    out!("{}", this_build());
    out!(
        "{:<28}{}",
        "mean steps   [95% interval]",
        interval(&blind_mean)
    );
    out!(
        "{:<28}{:>10.3} to {:.3}",
        "trials' exact means",
        report.min,
        report.max
    );
    out!(
        "{:<28}{:>10.3}   (mean steps / bound {})",
        "lower bound (any searcher)",
        lower_bound,
        report
            .mean_over_bound
            .map_or("–".into(), |r| format!("{r:.4}"))
    );
    out!("{:<28}{:>10.3e}", "P(capped)", report.capped_probability);
    out!("{:<28}{:.1}", "moves driven per trial", report.mean_moves);
    out!("{:<28}{:.3} s ({} threads)", "time", seconds, threads);
    out!("{METHODS}");
    Ok(())
}

/// How the text reports' intervals are made.
const METHODS: &str = "95% intervals: means by a seeded BCa bootstrap with expanded tails, medians by order statistics (EXPERIMENTS.md, Intervals).";

/// An estimate and its interval, as the text tables show them.
fn interval(m: &Interval) -> String {
    let end = |v: f64| {
        if v.is_finite() {
            format!("{v:.3}")
        } else {
            "–".into()
        }
    };
    format!("{:>10.3}   [{}, {}]", m.estimate, end(m.lo), end(m.hi))
}

pub(super) fn print_table(
    cfg: &Config,
    preset: Option<Preset>,
    s: &Summary,
    lower_bound: f64,
    seconds: f64,
    threads: usize,
) {
    let mut who = cfg.searcher.name().to_string();
    // Every setting the searcher reads, as the flags would give it.
    for e in config::params() {
        if matches!(e, ConfigParam::Setting(_)) && e.applies_to(cfg) {
            who += &format!(" {}={}", e.param().key, e.value(cfg).text());
        }
    }
    out!(
        "torus-search: N={} r_v={} prior={} start={},{} seed={}",
        cfg.n,
        cfg.rv,
        cfg.prior_label(),
        cfg.start[0],
        cfg.start[1],
        cfg.seed
    );
    out!("searcher: {who}");
    out!(
        "preset: {} (the flags given override it)",
        preset.map_or("none", Preset::name)
    );
    out!("{}", this_build());
    out!("{:<28}{}", "trials", s.trials);
    out!(
        "{:<28}{}",
        "mean steps   [95% interval]",
        interval(&s.steps)
    );
    out!(
        "{:<28}{}",
        "mean optimal [95% interval]",
        interval(&s.optimal)
    );
    // The bound is on the mean over the prior, not on any one trial.
    out!(
        "{:<28}{:>10.3}   (mean steps / bound {})",
        "lower bound (any searcher)",
        lower_bound,
        if lower_bound > 0.0 {
            format!("{:.3}", s.steps.estimate / lower_bound)
        } else {
            "–".into()
        }
    );
    out!("{:<28}{}", "ASOO = mean(steps-opt)", interval(&s.asoo));
    out!("{:<28}{}", "mean steps/opt", interval(&s.ratio));
    out!(
        "{:<28}{:>10.3}",
        "mean steps / mean opt",
        s.steps_over_mean_optimal
    );
    out!(
        "{:<28}{}   (q1 {:.1}, q3 {:.1})",
        "median steps [95% interval]",
        interval(&s.median_steps),
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
    out!("{METHODS}");
}
