//! The native command line: `torus-search run`, `experiment`, `merge` and
//! `bench`.
//!
//! `run`'s flags are built from the configuration schema
//! ([`crate::config::params`]): each parameter's flag, help, range and
//! default come from there, and its text is parsed there, as the page's URL
//! is. Trials run in parallel through `batch::trial`, and `--json` prints
//! the core's `analysis::report::Report`.

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

mod args;
mod bench;
mod dry_run;
mod experiments;
mod run;
#[cfg(test)]
mod tests;
mod usage;

use bench::{bench, bench_command};
use clap::Command;
use experiments::{experiment_command, merge, merge_command, run_experiment};
use run::{run, run_command};
use usage::UsageError;

fn command() -> Command {
    Command::new("torus-search")
        .version(
            crate::experiment::provenance::this_build()
                .trim_start_matches("torus-search ")
                .to_string(),
        )
        .about("MCTS for a single-target search game on a periodic 2-D lattice")
        .subcommand_required(true)
        .arg_required_else_help(true)
        .subcommand(run_command())
        .subcommand(experiment_command())
        .subcommand(merge_command())
        .subcommand(bench_command())
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

/// The configuration `torus-search run ARGS` would run, or its error
/// message, for tests of the surfaces a parameter reaches.
#[cfg(test)]
pub(crate) fn run_config(args: &[&str]) -> Result<crate::config::Config, String> {
    let m = command()
        .try_get_matches_from(["torus-search", "run"].iter().chain(args))
        .map_err(|e| e.to_string())?;
    let (_, m) = m.subcommand().expect("run was given");
    args::build_config(m).map_err(|UsageError(e)| e)
}
