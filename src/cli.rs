//! The native command line: `torus-search run`, `experiment`, `merge` and `bench`.
//!
//! `run`'s flags are built from the configuration schema
//! (`config::PARAMS`): each parameter's flag, help, range and default come
//! from there, and its text is parsed there, as the page's URL is. Trials
//! run in parallel through `batch::trial`, and `--json` prints the core's
//! `batch::Report`.

use clap::{Arg, ArgAction, ArgMatches, Command};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use torus_search::analysis::bound;
use torus_search::analysis::exact;
use torus_search::analysis::stats::{self, Summary};
use torus_search::config::preset::Preset;
use torus_search::config::{self, Config, ConfigError, Kind, PARAMS, TRIALS};
use torus_search::experiment::{self, Plan, ResultSet, Shard, Spec, SpecError};
use torus_search::run::batch;
use torus_search::run::episode::{Episode, TrialResult};
use torus_search::searchers::mcts::Variant;
use torus_search::searchers::PolicyKind;

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

/// A message for stderr; the process exits with code 2.
struct UsageError(String);

/// The flag of parameter `key`, with its dashes.
fn flag(key: &str) -> String {
    config::param(key).map_or_else(|| format!("--{key}"), |p| format!("--{}", p.flag()))
}

/// A configuration error worded for the command line.
fn usage(e: ConfigError) -> UsageError {
    UsageError(format!(
        "{} must be {}, got {}",
        flag(e.field),
        e.allowed,
        e.value
    ))
}

fn command() -> Command {
    Command::new("torus-search")
        .version(env!("CARGO_PKG_VERSION"))
        .about("MCTS for a single-target search game on a periodic 2-D lattice")
        .subcommand_required(true)
        .arg_required_else_help(true)
        .subcommand(run_command())
        .subcommand(experiment_command())
        .subcommand(merge_command())
        .subcommand(bench_command())
}

/// One flag per schema parameter (`skip` names keys a command handles itself).
fn param_args(mut cmd: Command, skip: &[&str]) -> Command {
    for p in PARAMS.iter().filter(|p| !skip.contains(&p.key)) {
        let default = match p.kind {
            Kind::Bool => "off".to_string(),
            _ if p.default.text().is_empty() => "none".to_string(),
            _ => p.default.text(),
        };
        let help = match p.kind {
            Kind::Bool => format!("{} [default: {default}]", p.help),
            _ => format!("{}: {} [default: {default}]", p.help, p.kind.allowed()),
        };
        let mut arg = Arg::new(p.key).long(p.flag()).help(help);
        arg = match p.kind {
            Kind::Bool => arg.action(ArgAction::SetTrue),
            _ => arg
                .value_name(p.key.to_uppercase())
                .allow_hyphen_values(true)
                .action(ArgAction::Set),
        };
        for a in p.aliases {
            arg = arg.visible_alias(*a);
        }
        cmd = cmd.arg(arg);
    }
    cmd
}

fn preset_arg(default: &str) -> Arg {
    Arg::new("preset")
        .long("preset")
        .value_name("PRESET")
        .help(format!(
        "a reading of the paper, applied before the other flags: {}; or none [default: {default}]",
        Preset::ALL
            .iter()
            .map(|p| format!("{p} ({})", p.help()))
            .collect::<Vec<_>>()
            .join("; ")
    ))
}

/// The preset named by `--preset`: `None` for `none`, `default` when absent.
fn preset(m: &ArgMatches, default: Option<Preset>) -> Result<Option<Preset>, UsageError> {
    match m.get_one::<String>("preset").map(String::as_str) {
        None => Ok(default),
        Some("none") => Ok(None),
        Some(name) => Preset::parse(name).map(Some).ok_or_else(|| {
            UsageError(format!(
                "--preset must be one of {}, none, got {name}",
                Preset::NAMES.join(", ")
            ))
        }),
    }
}

fn threads_arg() -> Arg {
    Arg::new("threads")
        .long("threads")
        .value_name("K")
        .allow_hyphen_values(true)
        .help("worker threads: an integer in 1..=1024 [default: all cores]; results do not depend on it")
}

fn run_command() -> Command {
    param_args(
        Command::new("run").about("Run trials and summarise them."),
        &[],
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

fn experiment_command() -> Command {
    let names = experiment::DEFINITIONS
        .iter()
        .map(|d| d.name)
        .collect::<Vec<_>>()
        .join(", ");
    let cmd = Command::new("experiment")
        .about("Run a named experiment (a figure of the paper, or a custom sweep) and write DIR/<name>.json, .csv and .svg.")
        .after_help("Every point keeps the seed: trial i of each point uses the same random streams. \
With --shard i/n only DIR/<name>.shard-i-of-n.json is written; `torus-search merge` joins the shards \
into the files a single run writes, byte for byte (docs/cluster.md). decision-time (and any --ms) \
budgets decisions by the clock: those results depend on the machine and its load.")
        .arg(
            Arg::new("name")
                .value_name("NAME")
                .help(format!("the experiment: {names} (--list describes them)")),
        )
        .arg(
            Arg::new("list")
                .long("list")
                .action(ArgAction::SetTrue)
                .help("list the experiments with what each shows, and exit"),
        )
        .arg(
            Arg::new(TRIALS.key)
                .long(TRIALS.key)
                .value_name("COUNT")
                .allow_hyphen_values(true)
                .help(format!(
                    "trials (samples for priors) per point: {} [default: the experiment's, see --list]",
                    TRIALS.kind.allowed()
                )),
        )
        .arg(
            Arg::new("out")
                .long("out")
                .value_name("DIR")
                .help("directory for the files (created if missing) [default: .]"),
        )
        .arg(threads_arg())
        .arg(preset_arg(experiment::DEFAULT_PRESET.name()))
        .arg(
            Arg::new("shard")
                .long("shard")
                .value_name("I/N")
                .allow_hyphen_values(true)
                .help("run only shard I of N (1 <= I <= N; contiguous unit ranges) and write DIR/<name>.shard-I-of-N.json"),
        )
        .arg(
            Arg::new("sweep")
                .long("sweep")
                .value_name("KEY=V1,V2,...")
                .allow_hyphen_values(true)
                .help("custom: sweep parameter KEY over the values (separate cell values with ';', as in target=3,3;5,5)"),
        )
        .arg(
            Arg::new("series")
                .long("series")
                .value_name("LABEL:KEY=V,...")
                .action(ArgAction::Append)
                .allow_hyphen_values(true)
                .help("custom: a series with its parameter values (repeat for more series)"),
        );
    param_args(cmd, &[])
}

fn merge_command() -> Command {
    Command::new("merge")
        .about("Join shard results of one experiment into DIR/<name>.json, .csv and .svg (exactly the single run's files).")
        .arg(
            Arg::new("files")
                .value_name("FILE")
                .num_args(1..)
                .required(true)
                .help("shard JSON files written by `experiment --shard`, in any order"),
        )
        .arg(
            Arg::new("out")
                .long("out")
                .value_name("DIR")
                .help("directory for the files (created if missing) [default: .]"),
        )
}

fn bench_command() -> Command {
    Command::new("bench")
        .about("Measure this machine's throughput.")
        .arg(
            Arg::new("json")
                .long("json")
                .action(ArgAction::SetTrue)
                .help("print one JSON object"),
        )
        .arg(
            Arg::new("scale")
                .long("scale")
                .value_name("S")
                .allow_hyphen_values(true)
                .help("scale every workload (1 = about 10 s in all): a number in (0, 1000] [default: 1]"),
        )
        .arg(
            Arg::new("moves")
                .long("moves")
                .action(ArgAction::SetTrue)
                .conflicts_with("episode")
                .help("instead of the suite: the cost per real move (mean, median and longest decision) of every searcher (and MCTS variant) at N = 40 and N = 256, Gaussian prior with sigma = N/8, and the time of each slice of work done in slices (the beam and spiral plans, the belief MCTS's plan, rollout improvement's decisions)"),
        )
        .arg(
            Arg::new("whole")
                .long("whole")
                .action(ArgAction::SetTrue)
                .requires("moves")
                .help("with --moves: time every decision of trial 0, to its end, instead of about 0.4 s of moves (minutes at N = 256)"),
        )
        .arg(
            Arg::new("episode")
                .long("episode")
                .value_name("FILE")
                .requires("loops")
                .help("instead of the suite: time loops FROM..TO of one MCTS episode whose config (JSON, as the page exports it) is in this file"),
        )
        .arg(
            Arg::new("loops")
                .long("loops")
                .value_name("FROM..TO")
                .requires("episode")
                .help("the loop window for --episode"),
        )
        .arg(
            Arg::new("seed")
                .long("seed")
                .value_name("SEED")
                .requires("episode")
                .help("the seed for --episode, instead of the file's"),
        )
}

/// The config that `run`'s flags describe: each given flag is parsed by its
/// parameter, must apply to the resulting config, and the whole is validated.
fn build_config(m: &ArgMatches) -> Result<Config, UsageError> {
    let mut cfg = Config::default();
    if let Some(p) = preset(m, None)? {
        p.apply(&mut cfg);
    }
    let mut given = Vec::new();
    for p in PARAMS {
        let raw = match p.kind {
            Kind::Bool => m.get_flag(p.key).then(|| "1".to_string()),
            _ => m.get_one::<String>(p.key).cloned(),
        };
        if let Some(raw) = raw {
            cfg.set(p.key, &raw).map_err(usage)?;
            given.push(p);
        }
    }
    for p in given {
        if !p.applies_to(&cfg) {
            return Err(UsageError(format!(
                "--{} does not apply to this configuration: {}",
                p.flag(),
                p.not_applying(&cfg)
            )));
        }
    }
    cfg.validate().map_err(usage)?;
    Ok(cfg)
}

fn int_flag(m: &ArgMatches, name: &str, lo: u64, hi: u64) -> Result<Option<u64>, UsageError> {
    m.get_one::<String>(name)
        .map(|raw| {
            raw.trim()
                .parse::<u64>()
                .ok()
                .filter(|v| (lo..=hi).contains(v))
                .ok_or_else(|| {
                    UsageError(format!(
                        "--{name} must be an integer in {lo}..={hi}, got {raw}"
                    ))
                })
        })
        .transpose()
}

fn run(m: &ArgMatches) -> Result<(), UsageError> {
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
    let mean_over_bound = (lower_bound > 0.0).then(|| s.steps.mean / lower_bound);
    if m.get_flag("json") {
        let report = batch::Report {
            summary: &s,
            lower_bound,
            mean_over_bound,
            seconds,
            threads,
            seed: cfg.seed,
            config: &cfg,
        };
        out!(
            "{}",
            serde_json::to_string(&report).expect("a report serialises")
        );
    } else {
        print_table(&cfg, &s, lower_bound, seconds, threads);
    }
    Ok(())
}

/// The usage error of an exact evaluation refused: a bad configuration
/// as any other, or why the paths cannot be counted exactly.
fn exact_usage(e: exact::ExactError) -> UsageError {
    match e {
        exact::ExactError::Config(e) => usage(e),
        e => UsageError(e.to_string()),
    }
}

/// `run --exact`: the exact mean of a deterministic searcher.
fn run_exact(cfg: &Config, json: bool) -> Result<(), UsageError> {
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
        out!(
            "{}",
            serde_json::to_string(&report).expect("a report serialises")
        );
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
fn run_blind(
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
    let blind_mean = stats::MeanCi::of(each.iter().map(|e| e.mean));
    let lower_bound = bound::lower_bound_capped(cfg).map_err(usage)?;
    let report = exact::BlindReport {
        blind_mean,
        min: each.iter().map(|e| e.mean).fold(f64::INFINITY, f64::min),
        max: each
            .iter()
            .map(|e| e.mean)
            .fold(f64::NEG_INFINITY, f64::max),
        capped_probability: each.iter().map(|e| e.capped_probability).sum::<f64>() / n,
        mean_moves: each.iter().map(|e| e.moves as f64).sum::<f64>() / n,
        lower_bound,
        mean_over_bound: (lower_bound > 0.0).then(|| blind_mean.mean / lower_bound),
        seconds,
        threads,
        seed: cfg.seed,
        config: cfg,
    };
    if json {
        out!(
            "{}",
            serde_json::to_string(&report).expect("a report serialises")
        );
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
    out!(
        "{:<28}{:>10.3}   95% CI [{:.3}, {:.3}]",
        "mean steps",
        blind_mean.mean,
        blind_mean.lo,
        blind_mean.hi
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
    Ok(())
}

/// The rayon pool `--threads` asks for (all cores by default).
fn thread_pool(m: &ArgMatches) -> Result<(usize, rayon::ThreadPool), UsageError> {
    let threads = int_flag(m, "threads", 1, 1024)?.map_or_else(
        || std::thread::available_parallelism().map_or(1, |n| n.get()),
        |t| t as usize,
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| UsageError(format!("cannot start {threads} threads: {e}")))?;
    Ok((threads, pool))
}

/// Maps `work` over `items` on `pool`, in order, with a progress bar and an
/// ETA on stderr. The bar appears only once the work has taken a second, so
/// quick runs stay quiet, and indicatif hides it when stderr is not a terminal.
fn with_progress<T: Send>(
    pool: &rayon::ThreadPool,
    items: std::ops::Range<u64>,
    what: &str,
    work: impl Fn(u64) -> T + Sync,
) -> Vec<T> {
    let t0 = Instant::now();
    let bar =
        ProgressBar::with_draw_target(Some(items.end - items.start), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template(&format!(
            "{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {what}, eta {{eta}}"
        ))
        .expect("a valid template")
        .progress_chars("=> "),
    );
    let shown = AtomicBool::new(false);
    let out = pool.install(|| {
        items
            .into_par_iter()
            .map(|i| {
                let r = work(i);
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
    out
}

/// `--sweep KEY=V1,V2,...` as a spec's sweep (values split on ';' when the
/// text has one, else on ',').
fn sweep_json(text: &str) -> Result<serde_json::Value, UsageError> {
    let (key, values) = text.split_once('=').ok_or_else(|| {
        UsageError(format!(
            "--sweep must be KEY=V1,V2,... (cells: KEY=X,Y;X,Y), got {text:?}"
        ))
    })?;
    let sep = if values.contains(';') { ';' } else { ',' };
    let values: Vec<&str> = values.split(sep).map(str::trim).collect();
    Ok(serde_json::json!({ "key": key.trim(), "values": values }))
}

/// `--series 'LABEL:key=v,key=v'` as a spec series. Pairs are split on ',' or
/// ';'; a piece without '=' continues the value before it (a cell "3,3").
fn series_json(text: &str) -> Result<serde_json::Value, UsageError> {
    let bad = || {
        UsageError(format!(
            "--series must be LABEL:KEY=V,KEY=V,... with a label, got {text:?}"
        ))
    };
    let (label, pairs) = text.split_once(':').ok_or_else(bad)?;
    let mut params = serde_json::Map::new();
    let mut last: Option<String> = None;
    for piece in pairs.split([',', ';']).filter(|p| !p.trim().is_empty()) {
        match piece.split_once('=') {
            Some((k, v)) => {
                params.insert(k.trim().to_string(), v.trim().into());
                last = Some(k.trim().to_string());
            }
            None => {
                let k = last.as_ref().ok_or_else(bad)?;
                let v = params[k].as_str().unwrap_or_default().to_string();
                params.insert(k.clone(), format!("{v},{}", piece.trim()).into());
            }
        }
    }
    Ok(serde_json::json!({ "label": label.trim(), "params": params }))
}

/// A spec error worded for the command line (parameters by their flags).
fn spec_usage(e: SpecError) -> UsageError {
    match e {
        SpecError::Param { place, error } if place == "params" => usage(error),
        SpecError::Field {
            field,
            allowed,
            got,
        } if field == "trials" || field == "seed" => {
            UsageError(format!("--{field} must be {allowed}, got {got}"))
        }
        e => UsageError(e.to_string()),
    }
}

/// Writes each `(file name, text)` into `dir`: all are written to temporary
/// names first and renamed at the end, so a failure leaves no partial set.
fn write_files(dir: &str, files: &[(String, String)]) -> Result<Vec<String>, UsageError> {
    let fail = |what: &str, e: std::io::Error| UsageError(format!("{what}: {e}"));
    std::fs::create_dir_all(dir).map_err(|e| fail(dir, e))?;
    let base = std::path::Path::new(dir);
    let mut done = Vec::new();
    for (name, text) in files {
        let tmp = base.join(format!(".{name}.tmp-{}", std::process::id()));
        std::fs::write(&tmp, text).map_err(|e| fail(&tmp.display().to_string(), e))?;
    }
    for (name, _) in files {
        let tmp = base.join(format!(".{name}.tmp-{}", std::process::id()));
        let path = base.join(name);
        std::fs::rename(&tmp, &path).map_err(|e| fail(&path.display().to_string(), e))?;
        done.push(path.display().to_string());
    }
    Ok(done)
}

/// The three files of a complete result.
fn result_files(set: &ResultSet) -> Vec<(String, String)> {
    let name = &set.plan.header.name;
    vec![
        (format!("{name}.json"), set.to_json()),
        (format!("{name}.csv"), set.csv()),
        (format!("{name}.svg"), experiment::svg(set)),
    ]
}

fn list_experiments() {
    for e in experiment::list() {
        out!(
            "{:<18} {:<8} {:>6} trials  {}",
            e.name,
            e.kind,
            e.default_trials,
            e.title
        );
        out!("{:<18} {}", "", e.help);
    }
}

fn run_experiment(m: &ArgMatches) -> Result<(), UsageError> {
    if m.get_flag("list") {
        list_experiments();
        return Ok(());
    }
    let name = m.get_one::<String>("name").ok_or_else(|| {
        UsageError(format!(
            "an experiment name is required: one of {} (--list describes them)",
            experiment::DEFINITIONS
                .iter()
                .map(|d| d.name)
                .collect::<Vec<_>>()
                .join(", ")
        ))
    })?;
    let mut spec = serde_json::Map::new();
    spec.insert("name".into(), name.as_str().into());
    if let Some(t) = m.get_one::<String>(TRIALS.key) {
        spec.insert("trials".into(), t.as_str().into());
    }
    if let Some(s) = m.get_one::<String>("seed") {
        spec.insert("seed".into(), s.as_str().into());
    }
    if m.get_one::<String>("preset").is_some() {
        let p = preset(m, None)?;
        spec.insert("preset".into(), p.map_or("none", |p| p.name()).into());
    }
    let mut params = serde_json::Map::new();
    for p in PARAMS.iter().filter(|p| p.key != "seed") {
        let raw = match p.kind {
            Kind::Bool => m.get_flag(p.key).then(|| "1".to_string()),
            _ => m.get_one::<String>(p.key).cloned(),
        };
        if let Some(raw) = raw {
            params.insert(p.key.into(), raw.into());
        }
    }
    spec.insert("params".into(), params.into());
    if let Some(s) = m.get_one::<String>("sweep") {
        spec.insert("sweep".into(), sweep_json(s)?);
    }
    if let Some(list) = m.get_many::<String>("series") {
        let series = list
            .map(|s| series_json(s))
            .collect::<Result<Vec<_>, _>>()?;
        spec.insert("series".into(), series.into());
    }
    let spec = Spec::from_value(&spec.into()).map_err(spec_usage)?;
    let plan = Plan::new(&spec).map_err(spec_usage)?;
    let total = plan.total_units();
    let shard = m
        .get_one::<String>("shard")
        .map(|s| Shard::parse(s).map_err(UsageError))
        .transpose()?;
    let (from, to) = shard.map_or((0, total), |s| s.range(total));
    let (threads, pool) = thread_pool(m)?;
    let dir = m.get_one::<String>("out").map_or(".", String::as_str);
    let t0 = Instant::now();
    let rows = with_progress(&pool, from..to, "trials", |u| {
        experiment::run_unit(&plan, u, None)
    });
    let seconds = t0.elapsed().as_secs_f64();
    let set = ResultSet::new(plan, from, to, rows).expect("rows of their own plan fit it");
    let files = match shard {
        Some(s) => vec![(
            format!("{name}.shard-{}-of-{}.json", s.index, s.count),
            set.to_json(),
        )],
        None => result_files(&set),
    };
    for path in write_files(dir, &files)? {
        out!("wrote {path}");
    }
    out!(
        "{name}: units {from}..{to} of {total} ({} points × {} trials) in {seconds:.1} s on {threads} threads",
        set.plan.points.len(),
        set.plan.trials()
    );
    Ok(())
}

fn merge(m: &ArgMatches) -> Result<(), UsageError> {
    let names: Vec<&String> = m
        .get_many::<String>("files")
        .into_iter()
        .flatten()
        .collect();
    let mut texts = Vec::with_capacity(names.len());
    for name in &names {
        let text = std::fs::read_to_string(name).map_err(|e| UsageError(format!("{name}: {e}")))?;
        texts.push(text);
    }
    let files: Vec<(&str, &str)> = names
        .iter()
        .zip(&texts)
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    let set = experiment::merge(&files).map_err(|e| UsageError(e.to_string()))?;
    let dir = m.get_one::<String>("out").map_or(".", String::as_str);
    for path in write_files(dir, &result_files(&set))? {
        out!("wrote {path}");
    }
    Ok(())
}

fn print_table(cfg: &Config, s: &Summary, lower_bound: f64, seconds: f64, threads: usize) {
    let mut who = cfg.searcher.name().to_string();
    if cfg.searcher.info().deliberates {
        let budget = cfg
            .ms
            .map_or(format!("L={}", cfg.loops), |ms| format!("{ms} ms/move"));
        who += &format!(
            " {} rollout={} belief={} {budget} c={:.4} final={}",
            cfg.variant,
            cfg.rollout,
            cfg.belief,
            cfg.c,
            torus_search::searchers::mcts::final_rule(cfg)
        );
    }
    let ci = |m: &torus_search::analysis::stats::MeanCi| {
        format!("{:>10.3}   [{:.3}, {:.3}]", m.mean, m.lo, m.hi)
    };
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
    out!("{:<28}{}", "trials", s.trials);
    out!("{:<28}{}", "mean steps   [95% CI]", ci(&s.steps));
    out!("{:<28}{}", "mean optimal [95% CI]", ci(&s.optimal));
    // The bound is on the mean over the prior, not on any one trial.
    out!(
        "{:<28}{:>10.3}   (mean steps / bound {})",
        "lower bound (any searcher)",
        lower_bound,
        if lower_bound > 0.0 {
            format!("{:.3}", s.steps.mean / lower_bound)
        } else {
            "–".into()
        }
    );
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

fn bench(m: &ArgMatches) -> Result<(), UsageError> {
    let json = m.get_flag("json");
    if let (Some(file), Some(window)) =
        (m.get_one::<String>("episode"), m.get_one::<String>("loops"))
    {
        return bench_window(file, window, m.get_one::<String>("seed"), json);
    }
    let scale = match m.get_one::<String>("scale") {
        None => 1.0,
        Some(raw) => raw
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|s| s.is_finite() && *s > 0.0 && *s <= 1000.0)
            .ok_or_else(|| {
                UsageError(format!("--scale must be a number in (0, 1000], got {raw}"))
            })?,
    };
    if m.get_flag("moves") {
        return bench_moves(scale, m.get_flag("whole"), json);
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
        rollout_steps(kind, 40, 1.0, 2.0, 7, work / 20).map_err(usage)?;
        let t = Instant::now();
        let done = rollout_steps(kind, 40, 1.0, 2.0, 1, work).map_err(usage)?;
        let rate = done as f64 / t.elapsed().as_secs_f64();
        out.insert(key.into(), rate.into());
        if !json {
            out!(
                "{:<34}{:>14.3e}",
                format!("{kind} rollout lattice steps/s"),
                rate
            );
        }
    }
    for variant in [Variant::Cells, Variant::Tree] {
        for sigma in [0.0, 5.0] {
            let cfg = Config {
                variant,
                sigma,
                ..Config::default()
            };
            let loops = ((if sigma == 0.0 { 200_000.0 } else { 40_000.0 }) * scale) as u64;
            let t = Instant::now();
            let (done, _, _) = mcts_loops(&cfg, loops.max(100)).map_err(usage)?;
            let lps = done as f64 / t.elapsed().as_secs_f64();
            let trials = ((if sigma == 0.0 { 40.0 } else { 4.0 }) * scale).ceil() as u64;
            let t = Instant::now();
            for i in 0..trials {
                Episode::trial(&cfg, i).map_err(usage)?.run();
            }
            let eps = trials as f64 / t.elapsed().as_secs_f64();
            let tag = format!("mcts_{variant}_sigma{}", sigma as u32);
            out.insert(format!("{tag}_loops_per_s"), lps.into());
            out.insert(format!("{tag}_episodes_per_s"), eps.into());
            if !json {
                out!(
                    "{:<34}{:>14.1} loops/s {:>10.3} episodes/s",
                    format!("mcts {variant} N=40 L=100 sigma={sigma} posterior"),
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

/// Times real moves of every searcher at N = 40 and N = 256: each for
/// about `0.4 · scale` seconds (at least 3 moves) after one warm-up move,
/// trial 0 onwards, or with `whole` every move of trial 0 (the first
/// included). Reports the mean, the median and the longest decision (a call
/// that makes one move; setting up a trial is left out), and how many
/// episodes the window finished: 0 means only the first moves of trial 0
/// were timed.
fn bench_moves(scale: f64, whole: bool, json: bool) -> Result<(), UsageError> {
    use torus_search::bench::{move_cases, MoveRunner};
    // First, before the moves below keep trial 0's plans for the process;
    // not with `whole`, whose trial 0 makes its plans itself.
    let slices = if whole {
        Vec::new()
    } else {
        plan_slices(json)?
    };
    let mut rows = Vec::new();
    if !json {
        out!(
            "\n{:<16}{:>6}{:>14}{:>12}{:>12}{:>10}{:>10}",
            "searcher",
            "N",
            "ms per move",
            "median ms",
            "longest ms",
            "moves",
            "episodes"
        );
    }
    for n in [40, 256] {
        for (label, cfg) in move_cases(n) {
            let mut r = MoveRunner::new(&cfg).map_err(usage)?;
            if !whole {
                r.run(1).map_err(usage)?;
            }
            let (moves0, episodes0) = (r.moves, r.episodes);
            // Each decision is timed alone, without setting up the next
            // trial (`ready`), which the page does once per episode.
            let mut each = Vec::new();
            let t = Instant::now();
            let more = |r: &MoveRunner| {
                if whole {
                    r.episodes == 0
                } else {
                    t.elapsed().as_secs_f64() < 0.4 * scale || r.moves - moves0 < 3
                }
            };
            while more(&r) {
                r.ready().map_err(usage)?;
                let start = Instant::now();
                r.run(1).map_err(usage)?;
                each.push(1e3 * start.elapsed().as_secs_f64());
            }
            let moves = r.moves - moves0;
            let episodes = r.episodes - episodes0;
            let ms = each.iter().sum::<f64>() / moves.max(1) as f64;
            let (median, longest) = median_and_longest(&mut each);
            if !json {
                out!("{label:<16}{n:>6}{ms:>14.4}{median:>12.4}{longest:>12.4}{moves:>10}{episodes:>10}");
            }
            rows.push(serde_json::json!({
                "searcher": label,
                "n": n,
                "ms_per_move": ms,
                "median_ms": median,
                "longest_ms": longest,
                "moves": moves,
                "episodes": episodes,
            }));
        }
    }
    if json {
        out!(
            "{}",
            serde_json::json!({ "prior": "gaussian, sigma = N/8", "whole_trial": whole, "moves": rows, "plan_slices": slices })
        );
    }
    Ok(())
}

/// The time of each slice of a planner that makes its plan in slices, each
/// slice timed alone (one call of the page's worker makes up to
/// `PLAN_CALL_SLICES` of them), over trial 0's plan, at N = 40 and N = 256.
fn plan_slices(json: bool) -> Result<Vec<serde_json::Value>, UsageError> {
    let mut slices = Vec::new();
    if !json {
        out!(
            "{:<16}{:>6}{:>10}{:>14}{:>14}",
            "plan slices",
            "N",
            "slices",
            "median ms",
            "longest ms"
        );
    }
    for n in [40, 256] {
        for (label, cfg) in torus_search::bench::move_cases(n) {
            let mut ep = torus_search::run::episode::Episode::trial(&cfg, 0).map_err(usage)?;
            let mut ms = Vec::new();
            loop {
                let t = Instant::now();
                let moved = ep.step_loops(1);
                ms.push(1e3 * t.elapsed().as_secs_f64());
                if moved || ep.planning().is_none() {
                    break;
                }
            }
            if ms.len() < 2 {
                continue;
            }
            let (median, longest) = median_and_longest(&mut ms);
            if !json {
                out!(
                    "{label:<16}{n:>6}{:>10}{median:>14.3}{longest:>14.3}",
                    ms.len()
                );
            }
            slices.push(serde_json::json!({ "searcher": label, "n": n, "slices": ms.len(), "median_ms": median, "longest_ms": longest }));
        }
    }
    Ok(slices)
}

/// The median and the largest of `ms` (not empty), which it sorts.
fn median_and_longest(ms: &mut [f64]) -> (f64, f64) {
    ms.sort_by(f64::total_cmp);
    (ms[ms.len() / 2], ms[ms.len() - 1])
}

/// Times loops `from..to` of the episode (trials 0, 1, … of the config in `file`).
fn bench_window(
    file: &str,
    window: &str,
    seed: Option<&String>,
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
    let text =
        std::fs::read_to_string(file).map_err(|e| UsageError(format!("--episode {file}: {e}")))?;
    let mut cfg: Config = serde_json::from_str(&text).map_err(|e| {
        UsageError(format!(
            "--episode {file} is not a torus-search config (JSON): {e}"
        ))
    })?;
    if let Some(raw) = seed {
        cfg.set("seed", raw).map_err(usage)?;
    }
    // LoopRunner::new validates the config.
    let mut runner = torus_search::bench::LoopRunner::new(&cfg).map_err(usage)?;
    runner.run(from).map_err(usage)?;
    let t = Instant::now();
    runner.run(to - from).map_err(usage)?;
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
    let matches = match command().try_get_matches() {
        Ok(m) => m,
        Err(e) => {
            use clap::error::ErrorKind;
            return match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
                    let _ = e.print();
                    0
                }
                ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                    eprintln!(
                        "error: a command is required: run, experiment, merge or bench (see --help)"
                    );
                    2
                }
                // Usage errors are one line, as every other error here:
                // clap's message up to its usage block, lines joined.
                _ => {
                    let text = e.to_string();
                    let message: Vec<&str> = text
                        .lines()
                        .map(str::trim)
                        .take_while(|l| !l.is_empty() && !l.starts_with("Usage:"))
                        .collect();
                    eprintln!("{} (see --help)", message.join(" "));
                    2
                }
            };
        }
    };
    let r = match matches.subcommand() {
        Some(("run", m)) => run(m),
        Some(("experiment", m)) => run_experiment(m),
        Some(("merge", m)) => merge(m),
        Some(("bench", m)) => bench(m),
        _ => Err(UsageError(
            "a subcommand is required: run, experiment, merge or bench".into(),
        )),
    };
    match r {
        Ok(()) => 0,
        Err(UsageError(msg)) => {
            eprintln!("error: {msg}");
            2
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_command_is_well_formed() {
        super::command().debug_assert();
    }
}
