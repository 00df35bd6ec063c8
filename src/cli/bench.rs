//! `torus-search bench`: timed workloads of the core.

use super::usage::{usage, UsageError};
use crate::config::Config;
use crate::run::episode::Episode;
use crate::searchers::mcts::Variant;
use crate::searchers::walks::policy::PolicyKind;
use clap::{Arg, ArgAction, ArgMatches, Command};
use std::time::Instant;

pub(super) fn bench_command() -> Command {
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

pub(super) fn bench(m: &ArgMatches) -> Result<(), UsageError> {
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
    use crate::bench::{mcts_loops, rollout_steps};
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
                sigma,
                ..Config::default()
            }
            .with(&[("variant", variant.name())]);
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
    out.insert(
        "belief".into(),
        Config::default().get("belief").unwrap_or_default().into(),
    );
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
pub(super) fn bench_moves(scale: f64, whole: bool, json: bool) -> Result<(), UsageError> {
    use crate::bench::{move_cases, MoveRunner};
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
pub(super) fn plan_slices(json: bool) -> Result<Vec<serde_json::Value>, UsageError> {
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
        for (label, cfg) in crate::bench::move_cases(n) {
            let mut ep = crate::run::episode::Episode::trial(&cfg, 0).map_err(usage)?;
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
pub(super) fn median_and_longest(ms: &mut [f64]) -> (f64, f64) {
    ms.sort_by(f64::total_cmp);
    (ms[ms.len() / 2], ms[ms.len() - 1])
}

/// Times loops `from..to` of the episode (trials 0, 1, … of the config in `file`).
pub(super) fn bench_window(
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
    let mut runner = crate::bench::LoopRunner::new(&cfg).map_err(usage)?;
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
