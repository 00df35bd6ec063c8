//! The flags every command shares: one per schema parameter, the preset, the
//! thread count, and the configuration they describe.

use super::usage::{usage, UsageError};
use crate::config::preset::Preset;
use crate::config::{self, Config};
use crate::param::{Param, ParamKind};
use clap::{Arg, ArgAction, ArgMatches, Command};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Where a command's defaults come from, for its help: the schema's, or a
/// base configuration (`from` says what set a value that differs from the
/// schema's, e.g. "the paper-code preset").
pub(super) enum Defaults<'a> {
    /// The schema's defaults (`run`).
    Schema,
    /// The values a command starts from, and what set them.
    Base(&'a Config, &'a dyn Fn(&str) -> String),
}

/// A parameter value as help shows it: on/off, none, or its text.
fn shown_value(p: &Param, text: &str) -> String {
    match p.kind {
        ParamKind::Bool => if text == "1" { "on" } else { "off" }.to_string(),
        _ if text.is_empty() => "none".to_string(),
        _ => text.to_string(),
    }
}

/// One flag per schema parameter (`skip` names keys a command handles
/// itself), each with its allowed values and the default the command uses.
pub(super) fn param_args(mut cmd: Command, skip: &[&str], defaults: Defaults<'_>) -> Command {
    for e in config::params()
        .iter()
        .filter(|e| !skip.contains(&e.param().key))
    {
        let p = e.param();
        let schema = shown_value(p, &p.default.text());
        let default = match &defaults {
            Defaults::Schema => schema,
            Defaults::Base(base, from) => {
                let used = shown_value(p, &e.value(base).text());
                if used == schema {
                    used
                } else {
                    format!("{used}, from {}; the schema's: {schema}", from(p.key))
                }
            }
        };
        let help = match p.kind {
            ParamKind::Bool => format!("{} [default: {default}]", p.help),
            _ => format!("{}: {} [default: {default}]", p.help, p.kind.allowed()),
        };
        let mut arg = Arg::new(p.key).long(p.flag()).help(help);
        arg = match p.kind {
            ParamKind::Bool => arg.action(ArgAction::SetTrue),
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

/// This process's provenance: this build, now, and its command line.
pub(super) fn invocation() -> crate::experiment::Provenance {
    let args: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    crate::experiment::Provenance::now(crate::experiment::provenance::shell_line(&args))
}

pub(super) fn preset_arg(default: &str) -> Arg {
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
pub(super) fn preset(
    m: &ArgMatches,
    default: Option<Preset>,
) -> Result<Option<Preset>, UsageError> {
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

pub(super) fn threads_arg() -> Arg {
    Arg::new("threads")
        .long("threads")
        .value_name("K")
        .allow_hyphen_values(true)
        .help("worker threads: an integer in 1..=1024 [default: all cores]; results do not depend on it")
}

/// The text given for parameter `p`'s flag, if any (an on/off flag given
/// bare is "1").
pub(super) fn flag_text(m: &ArgMatches, p: &Param) -> Option<String> {
    match p.kind {
        ParamKind::Bool => m.get_flag(p.key).then(|| "1".to_string()),
        _ => m.get_one::<String>(p.key).cloned(),
    }
}

/// The config that `run`'s flags describe: each given flag is parsed by its
/// parameter, must apply to the resulting config, and the whole is validated.
pub(super) fn build_config(m: &ArgMatches) -> Result<Config, UsageError> {
    let mut cfg = Config::default();
    if let Some(p) = preset(m, None)? {
        cfg.apply_preset(p);
    }
    let mut given = Vec::new();
    for &e in config::params() {
        if let Some(raw) = flag_text(m, e.param()) {
            cfg.set(e.param().key, &raw).map_err(usage)?;
            given.push(e);
        }
    }
    for e in given {
        if !e.applies_to(&cfg) {
            return Err(UsageError(format!(
                "--{} does not apply to this configuration: {}",
                e.param().flag(),
                e.not_applying(&cfg)
            )));
        }
    }
    cfg.validate().map_err(usage)?;
    Ok(cfg)
}

pub(super) fn int_flag(
    m: &ArgMatches,
    name: &str,
    lo: u64,
    hi: u64,
) -> Result<Option<u64>, UsageError> {
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

/// The rayon pool `--threads` asks for (all cores by default).
pub(super) fn thread_pool(m: &ArgMatches) -> Result<(usize, rayon::ThreadPool), UsageError> {
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
pub(super) fn with_progress<T: Send>(
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
