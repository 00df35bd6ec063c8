//! How a doc's command is made cheap without hiding a bad value.

use std::collections::BTreeSet;
use std::path::Path;

/// Trials a `run` command keeps at most, and an `experiment` command.
pub const RUN_TRIALS: u64 = 2;
pub const EXPERIMENT_TRIALS: u64 = 1;
/// The step cap of an experiment's episodes, at most: a trapped MCTS
/// episode would otherwise run to its cap at L rollouts a move.
pub const EXPERIMENT_STEP_CAP: u64 = 100;
/// The scale a `bench` command runs at, at most.
pub const BENCH_SCALE: f64 = 0.01;
/// The most shards a sharded command is expanded into.
pub const MAX_SHARDS: u64 = 400;
/// The value after `flag` (as `--flag V` or `--flag=V`), with its index.
pub fn value_of(args: &[String], flag: &str) -> Option<(usize, String)> {
    let eq = format!("{flag}=");
    args.iter().enumerate().find_map(|(i, a)| {
        if a == flag {
            args.get(i + 1).map(|v| (i + 1, v.clone()))
        } else {
            a.strip_prefix(&eq).map(|v| (i, v.to_string()))
        }
    })
}

/// Sets `flag`'s value (in the form it was given), or appends the flag.
pub fn set_value(args: &mut Vec<String>, flag: &str, value: &str) {
    match value_of(args, flag) {
        Some((i, _)) if args[i].starts_with(&format!("{flag}=")) => {
            args[i] = format!("{flag}={value}")
        }
        Some((i, _)) => args[i] = value.to_string(),
        None => args.extend([flag.to_string(), value.to_string()]),
    }
}

pub fn has(args: &[String], flag: &str) -> bool {
    args.iter()
        .any(|a| a == flag || a.starts_with(&format!("{flag}=")))
}

/// Caps an integer flag at `most` when its value is a valid count; a bad
/// value is left for the CLI to refuse. Appends the flag when absent.
pub fn cap_count(args: &mut Vec<String>, flag: &str, most: u64) {
    match value_of(args, flag) {
        Some((_, v)) => {
            if let Ok(n) = v.trim().parse::<u64>() {
                if n >= 1 {
                    set_value(args, flag, &n.min(most).to_string());
                }
            }
        }
        None => set_value(args, flag, &most.to_string()),
    }
}

/// A path of the doc's, inside the temporary directory.
pub fn inside(tmp: &Path, path: &str) -> String {
    tmp.join(path.trim_start_matches('/')).display().to_string()
}

/// `I/N` with 1 ≤ I ≤ N ≤ [`MAX_SHARDS`].
pub fn shard_count(v: &str) -> Option<u64> {
    let (i, n) = v.split_once('/')?;
    let (i, n) = (i.trim().parse::<u64>().ok()?, n.trim().parse::<u64>().ok()?);
    (1 <= i && i <= n && n <= MAX_SHARDS).then_some(n)
}

/// Where a cut command writes, and which experiments sample targets only
/// (they take no episode flags such as `--step-cap`).
pub struct Cut<'a> {
    pub tmp: &'a Path,
    pub targets_only: &'a BTreeSet<String>,
}

/// The cheap argument vectors that check a doc's command: the same
/// subcommand, flags and values, with less work and outputs under the
/// temporary directory. A valid `--shard I/N` becomes every shard 1..=N; a
/// merge's files are read from under the temporary directory, globs
/// expanded.
pub fn cheap(args: &[String], cut: &Cut) -> Vec<Vec<String>> {
    let tmp = cut.tmp;
    let mut a = args.to_vec();
    match a.first().map(String::as_str) {
        Some("run") if !has(&a, "--exact") && !has(&a, "--dry-run") => {
            cap_count(&mut a, "--trials", RUN_TRIALS)
        }
        Some("experiment") if !has(&a, "--list") => {
            cap_count(&mut a, "--trials", EXPERIMENT_TRIALS);
            let name = a.get(1).cloned().unwrap_or_default();
            let swept = a
                .iter()
                .any(|w| w.starts_with("step_cap=") || w.starts_with("step-cap="));
            if !cut.targets_only.contains(&name) && !swept {
                cap_count(&mut a, "--step-cap", EXPERIMENT_STEP_CAP);
            }
            let out = value_of(&a, "--out").map_or(".".to_string(), |(_, v)| v);
            set_value(&mut a, "--out", &inside(tmp, &out));
            if let Some(n) = value_of(&a, "--shard").and_then(|(_, v)| shard_count(&v)) {
                return (1..=n)
                    .map(|i| {
                        let mut s = a.clone();
                        set_value(&mut s, "--shard", &format!("{i}/{n}"));
                        s
                    })
                    .collect();
            }
        }
        Some("merge") => {
            let out = value_of(&a, "--out").map_or(".".to_string(), |(_, v)| v);
            set_value(&mut a, "--out", &inside(tmp, &out));
            let mut files = Vec::new();
            let mut i = 1;
            while i < a.len() {
                if a[i] == "--out" {
                    i += 2;
                    continue;
                }
                if !a[i].starts_with("--") {
                    files.push(i);
                }
                i += 1;
            }
            let mut expanded: Vec<String> = Vec::new();
            for (k, word) in a.iter().enumerate() {
                if files.contains(&k) {
                    expanded.extend(glob(&inside(tmp, word)));
                } else {
                    expanded.push(word.clone());
                }
            }
            a = expanded;
        }
        Some("bench") if !has(&a, "--episode") => match value_of(&a, "--scale") {
            Some((_, v)) => {
                if v.trim()
                    .parse::<f64>()
                    .is_ok_and(|s| s > 0.0 && s <= 1000.0)
                {
                    set_value(&mut a, "--scale", &BENCH_SCALE.to_string());
                }
            }
            None => set_value(&mut a, "--scale", &BENCH_SCALE.to_string()),
        },
        _ => {}
    }
    vec![a]
}

/// The files a pattern with `*` in its last component matches, sorted; the
/// pattern itself when nothing matches (the CLI then names it).
pub fn glob(pattern: &str) -> Vec<String> {
    let path = Path::new(pattern);
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let (Some(dir), Some(name)) = (path.parent(), name) else {
        return vec![pattern.into()];
    };
    if !name.contains('*') {
        return vec![pattern.into()];
    }
    let parts: Vec<&str> = name.split('*').collect();
    let matches = |f: &str| {
        let mut rest = f;
        for (k, part) in parts.iter().enumerate() {
            let found = if k == 0 {
                rest.strip_prefix(part)
            } else if k == parts.len() - 1 {
                rest.ends_with(part).then_some("")
            } else {
                rest.find(part).map(|at| &rest[at + part.len()..])
            };
            match found {
                Some(r) => rest = r,
                None => return false,
            }
        }
        true
    };
    let mut hits: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| matches(&e.file_name().to_string_lossy()))
        .map(|e| e.path().display().to_string())
        .collect();
    hits.sort();
    if hits.is_empty() {
        vec![pattern.into()]
    } else {
        hits
    }
}
