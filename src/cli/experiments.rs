//! `torus-search experiment` and `merge`: named experiments, shards, result files.

use super::args::{
    flag_text, invocation, param_args, preset, preset_arg, thread_pool, threads_arg, with_progress,
    Defaults,
};
use super::dry_run::dry_run;
use super::usage::{flag, usage, UsageError};
use crate::config::{self, TRIALS};
use crate::experiment::provenance::{self, Provenance};
use crate::experiment::{self, Plan, ResultSet, Shard, Spec, SpecError};
use clap::{Arg, ArgAction, ArgMatches, Command};
use std::time::Instant;

pub(super) fn experiment_command() -> Command {
    let names = experiment::DEFINITIONS
        .iter()
        .map(|d| d.name)
        .collect::<Vec<_>>()
        .join(", ");
    let cmd = Command::new("experiment")
        .about("Run a named experiment (a figure of the paper, or a custom sweep) and write DIR/<name>.json, .csv, .trials.csv, .paired.csv and .svg.")
        .after_help("Every point keeps the seed: trial i of each point uses the same random streams. \
With --shard i/n only DIR/<name>.shard-i-of-n.json is written; `torus-search merge` joins the shards \
into the files a single run writes, byte for byte (docs/cluster.md). decision-time (and any --ms) \
budgets decisions by the clock: those results depend on the machine and its load.\n\n\
The defaults shown are what every experiment starts from: the schema's, then the preset (paper-code unless \
--preset says otherwise), then the paper's setting (N = 40, r_v = 1, start 1,1, L = 100). Each experiment then \
sets its own values and its series' (known-n20: N = 20, ...); the flags given override them, and --dry-run \
prints every series' configuration.")
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
            Arg::new("json")
                .long("json")
                .action(ArgAction::SetTrue)
                .requires("list")
                .help("with --list: print the list as one JSON array of {name, title, help, kind, defaultTrials, defaultPreset}"),
        )
        .arg(
            Arg::new("dry-run")
                .long("dry-run")
                .action(ArgAction::SetTrue)
                .help("print the normalised spec, the points and units, every series' configuration and an estimated time from a short calibration run (trial 0 of the points); write nothing"),
        )
        .arg(
            Arg::new("calibration")
                .long("calibration")
                .value_name("SECONDS")
                .allow_hyphen_values(true)
                .help("with --dry-run: seconds the calibration may start units for, an integer in 0..=600 (0: no estimate) [default: 3]"),
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
    let base = experiment::common_base(Some(experiment::DEFAULT_PRESET));
    let preset_keys: Vec<&str> = experiment::DEFAULT_PRESET
        .edits()
        .iter()
        .map(|(k, _)| *k)
        .collect();
    let from = |key: &str| {
        if preset_keys.contains(&key) {
            format!("the {} preset", experiment::DEFAULT_PRESET)
        } else {
            "the paper's setting".to_string()
        }
    };
    param_args(cmd, &[], Defaults::Base(&base, &from))
}

pub(super) fn merge_command() -> Command {
    Command::new("merge")
        .about("Join shard results of one experiment into DIR/<name>.json, .csv, .trials.csv, .paired.csv and .svg (exactly the single run's files).")
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

/// `--sweep KEY=V1,V2,...` as a spec's sweep (values split on ';' when the
/// text has one, else on ',').
pub(super) fn sweep_json(text: &str) -> Result<serde_json::Value, UsageError> {
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
pub(super) fn series_json(text: &str) -> Result<serde_json::Value, UsageError> {
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
pub(super) fn spec_usage(e: SpecError) -> UsageError {
    match e {
        SpecError::Param { place, error } if place == "params" => usage(error),
        SpecError::Field {
            field,
            allowed,
            got,
        } if field == "trials" || field == "seed" => {
            UsageError(format!("--{field} must be {allowed}, got {got}"))
        }
        SpecError::NotApplying {
            key,
            series: Some(label),
            why,
        } => UsageError(format!(
            "--series {label:?}: {key} does not apply to this configuration: {why}"
        )),
        SpecError::NotApplying {
            key,
            series: None,
            why,
        } => UsageError(format!(
            "{} does not apply to any point of {why}",
            flag(&key)
        )),
        e => UsageError(e.to_string()),
    }
}

/// Writes each `(file name, text)` into `dir`: all are written to temporary
/// names first and renamed at the end, so a failure leaves no partial set.
pub(super) fn write_files(
    dir: &str,
    files: &[(String, Vec<u8>)],
) -> Result<Vec<String>, UsageError> {
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

/// The files of a complete result, each with its provenance: the result
/// JSON, the per-point, per-trial and paired CSVs, and the chart as SVG
/// and PNG.
pub(super) fn result_files(set: &ResultSet, p: &Provenance) -> Vec<(String, Vec<u8>)> {
    let name = &set.plan.header.name;
    vec![
        (format!("{name}.json"), set.stamped_json(p).into_bytes()),
        (format!("{name}.csv"), set.stamped_csv(p).into_bytes()),
        (
            format!("{name}.trials.csv"),
            set.stamped_trials_csv(p).into_bytes(),
        ),
        (
            format!("{name}.paired.csv"),
            set.stamped_paired_csv(p).into_bytes(),
        ),
        (
            format!("{name}.svg"),
            experiment::svg_stamped(set, p).into_bytes(),
        ),
        (format!("{name}.png"), experiment::png_stamped(set, p)),
    ]
}

pub(super) fn list_experiments(json: bool) {
    let list = experiment::list();
    if json {
        out!(
            "{}",
            serde_json::to_string(&list).expect("the list serialises")
        );
        return;
    }
    for e in list {
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

/// The spec that `experiment`'s flags describe, normalised.
fn spec_of(m: &ArgMatches) -> Result<Spec, UsageError> {
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
    for p in config::params().iter().map(|e| e.param()) {
        if let Some(raw) = flag_text(m, p).filter(|_| p.key != "seed") {
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
    Spec::from_value(&spec.into()).map_err(spec_usage)
}

pub(super) fn run_experiment(m: &ArgMatches) -> Result<(), UsageError> {
    if m.get_flag("list") {
        list_experiments(m.get_flag("json"));
        return Ok(());
    }
    let plan = Plan::new(&spec_of(m)?).map_err(spec_usage)?;
    let name = plan.header.name.clone();
    let total = plan.total_units();
    let shard = m
        .get_one::<String>("shard")
        .map(|s| Shard::parse(s).map_err(UsageError))
        .transpose()?;
    let (from, to) = shard.map_or((0, total), |s| s.range(total));
    let (threads, pool) = thread_pool(m)?;
    if m.get_flag("dry-run") {
        return dry_run(m, &plan, from, to, threads, &pool);
    }
    let dir = m.get_one::<String>("out").map_or(".", String::as_str);
    out!(
        "{name}: seed {}, preset {}, {} points × {} trials; {} (--dry-run prints each series' configuration)",
        plan.spec.seed,
        plan.spec.preset.map_or("none", |p| p.name()),
        plan.points.len(),
        plan.trials(),
        provenance::this_build()
    );
    let t0 = Instant::now();
    let rows = with_progress(&pool, from..to, "trials", |u| {
        experiment::run_unit(&plan, u, None)
    });
    let seconds = t0.elapsed().as_secs_f64();
    let set = ResultSet::new(plan, from, to, rows).expect("rows of their own plan fit it");
    let prov = invocation();
    let files = match shard {
        Some(s) => vec![(
            format!("{name}.shard-{}-of-{}.json", s.index, s.count),
            set.stamped_json(&prov).into_bytes(),
        )],
        None => result_files(&set, &prov),
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

pub(super) fn merge(m: &ArgMatches) -> Result<(), UsageError> {
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
    let (set, provs) = provenance::merge_stamped(&files).map_err(|e| UsageError(e.to_string()))?;
    let named: Vec<(&str, Option<&Provenance>)> = names
        .iter()
        .zip(&provs)
        .map(|(n, p)| (n.as_str(), p.as_ref()))
        .collect();
    for w in provenance::merge_warnings(&named) {
        eprintln!("warning: {w}");
    }
    let mut prov = invocation();
    prov.sources = provs
        .into_iter()
        .map(|p| p.unwrap_or_else(provenance::unknown))
        .collect();
    let dir = m.get_one::<String>("out").map_or(".", String::as_str);
    for path in write_files(dir, &result_files(&set, &prov))? {
        out!("wrote {path}");
    }
    Ok(())
}
