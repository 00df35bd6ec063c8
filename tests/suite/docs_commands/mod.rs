//! The docs cannot drift from the CLI and the Makefile.
//!
//! Every `torus-search` command in a fenced code block of README.md,
//! EXPERIMENTS.md or docs/*.md (a line that starts with `torus-search ` or
//! `cargo run --release -- `, with its `\` continuations) runs through the
//! built binary and must exit 0. The work is cut first ([`cheap`]): trial
//! counts to one or two, benchmarks to a tiny scale, outputs into a
//! temporary directory, a shard into every shard of its run (so that a
//! `merge` shown after it has its files). A value the cut would replace is
//! replaced only when it is valid, so a bad value still fails.
//!
//! Inline code that starts with `torus-search SUB` may only name flags that
//! `SUB --help` lists, and every `make` target a doc names must be one of
//! the Makefile's.
#![cfg(not(target_arch = "wasm32"))]

mod cut;
mod markdown;
mod shell;

use cut::{cheap, Cut};
use markdown::{anchors, blocks, inline_spans, links};
use shell::{commands, shell_words, PREFIXES};
use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The CPU time one cut command may use before the doc is told to show a
/// cheaper one, and the wall time after which it counts as hung.
const COMMAND_CPU: Duration = Duration::from_secs(20);
const COMMAND_WALL: Duration = Duration::from_secs(600);

/// A problem found in a doc, with where it is.
#[derive(Clone, Debug, PartialEq)]
struct Finding {
    file: String,
    line: usize,
    what: String,
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.what)
    }
}

/// Clock ticks per second of `/proc/*/stat` times (USER_HZ, 100 on Linux).
const TICKS: f64 = 100.0;

/// CPU seconds from fields of `/proc/PID/stat` (1-based field numbers, as
/// in proc(5)), or `None` where there is no `/proc`.
fn proc_cpu(pid: &str, fields: [usize; 2]) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // Fields after the command name, which may hold spaces, start at 3.
    let rest: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let tick = |f: usize| rest.get(f - 3)?.parse::<f64>().ok();
    Some((tick(fields[0])? + tick(fields[1])?) / TICKS)
}

/// CPU seconds this process's finished children used (cutime + cstime).
fn children_cpu() -> Option<f64> {
    proc_cpu("self", [16, 17])
}

/// Runs the binary with `args` from the repository root: `Ok` on exit 0,
/// else what went wrong. A command that uses more than [`COMMAND_CPU`] of
/// CPU (or, where that cannot be read, of wall time), or hangs for
/// [`COMMAND_WALL`], is stopped: the doc should show a cheaper one.
fn run_binary(args: &[String]) -> Result<(), String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start the binary: {e}"))?;
    let mut pipe = child.stderr.take().expect("piped stderr");
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = std::io::Read::read_to_string(&mut pipe, &mut text);
        text
    });
    let (t0, pid) = (Instant::now(), child.id().to_string());
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        let used = proc_cpu(&pid, [14, 15]).unwrap_or_else(|| t0.elapsed().as_secs_f64());
        if used > COMMAND_CPU.as_secs_f64() || t0.elapsed() > COMMAND_WALL {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "stopped after {used:.0} s of CPU ({:.0} s) even when cut: show a cheaper command",
                t0.elapsed().as_secs_f64()
            ));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let stderr = reader.join().unwrap_or_default();
    if status.success() {
        return Ok(());
    }
    Err(format!(
        "exit {}: {}",
        status
            .code()
            .map_or("by a signal".into(), |c| c.to_string()),
        stderr.trim()
    ))
}

/// A fresh, empty temporary directory of this process.
fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("torus-docs-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    dir
}

/// A cut command as the failure message shows it: the temporary directory
/// as `$TMP`, and at most a few words of a long file list.
fn shown(args: &[String], tmp: &Path) -> String {
    let tmp = tmp.display().to_string();
    let words: Vec<String> = args.iter().map(|a| a.replace(&tmp, "$TMP")).collect();
    if words.len() <= 12 {
        return words.join(" ");
    }
    let tail = &words[words.len() - 4..];
    format!("{} … {}", words[..6].join(" "), tail.join(" "))
}

/// Runs every command of one doc (in order, so shards come before their
/// merge) and returns what failed.
fn check_doc(file: &str, text: &str, tag: &str, targets_only: &BTreeSet<String>) -> Vec<Finding> {
    let (cmds, mut bad) = commands(file, text);
    let tmp = scratch(tag);
    let cut = Cut {
        tmp: &tmp,
        targets_only,
    };
    for c in &cmds {
        for args in cheap(&c.args, &cut) {
            if let Err(why) = run_binary(&args) {
                bad.push(Finding {
                    file: c.file.clone(),
                    line: c.line,
                    what: format!(
                        "`torus-search {}` (run as `{}`) failed: {why}",
                        c.args.join(" "),
                        shown(&args, &tmp)
                    ),
                });
                break;
            }
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);
    bad
}

/// README.md, EXPERIMENTS.md and docs/*.md, with their text.
fn docs() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec!["README.md".to_string(), "EXPERIMENTS.md".to_string()];
    let mut more: Vec<String> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    more.sort();
    files.extend(more);
    files
        .into_iter()
        .map(|f| {
            let text =
                std::fs::read_to_string(root.join(&f)).unwrap_or_else(|e| panic!("{f}: {e}"));
            (f, text)
        })
        .collect()
}

/// The targets a Makefile defines.
fn make_targets(makefile: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in makefile.lines() {
        if line.starts_with(['\t', ' ', '#']) {
            continue;
        }
        let Some((names, rest)) = line.split_once(':') else {
            continue;
        };
        if rest.starts_with('=') || names.contains('=') || names.contains('$') {
            continue;
        }
        out.extend(
            names
                .split_whitespace()
                .filter(|n| !n.starts_with('.'))
                .map(String::from),
        );
    }
    out
}

/// The targets of a `make …` command (options and `VAR=value` skipped).
fn targets_named(command: &str) -> Vec<String> {
    let words = shell_words(command, &HashMap::new()).unwrap_or_default();
    words
        .iter()
        .skip(1)
        .filter(|w| !w.starts_with('-') && !w.contains('='))
        .cloned()
        .collect()
}

/// Every `make` target a doc names, in fenced blocks or inline, that the
/// Makefile does not define.
fn unknown_make_targets(file: &str, text: &str, targets: &BTreeSet<String>) -> Vec<Finding> {
    let mut named: Vec<(usize, String)> = Vec::new();
    for block in blocks(text) {
        for (k, line) in block.lines.iter().enumerate() {
            if line.trim_start().starts_with("make ") {
                named.push((block.first + k, line.trim().to_string()));
            }
        }
    }
    for (n, s) in inline_spans(text) {
        if s.starts_with("make ") {
            named.push((n, s));
        }
    }
    let mut bad = Vec::new();
    for (line, cmd) in named {
        for t in targets_named(&cmd) {
            if !targets.contains(&t) {
                bad.push(Finding {
                    file: file.into(),
                    line,
                    what: format!("`{cmd}`: the Makefile has no target {t}"),
                });
            }
        }
    }
    bad
}

/// The flags `torus-search SUB --help` lists.
fn help_flags(sub: &str) -> BTreeSet<String> {
    let out = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args([sub, "--help"])
        .output()
        .expect("the binary runs");
    assert!(out.status.success(), "`{sub} --help` failed");
    flags_in(&String::from_utf8_lossy(&out.stdout))
}

/// The `--flag` words of a text.
fn flags_in(text: &str) -> BTreeSet<String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
        .filter(|w| w.starts_with("--") && w.len() > 2)
        .map(String::from)
        .collect()
}

/// Inline `torus-search SUB …` spans that name a subcommand or a flag the
/// CLI does not have.
fn unknown_inline_flags(
    file: &str,
    text: &str,
    help: &mut dyn FnMut(&str) -> Option<BTreeSet<String>>,
) -> Vec<Finding> {
    let mut bad = Vec::new();
    for (n, s) in inline_spans(text) {
        let Some(rest) = PREFIXES.iter().find_map(|p| s.strip_prefix(p)) else {
            continue;
        };
        let sub = rest.split_whitespace().next().unwrap_or("");
        if !sub.chars().all(|c| c.is_ascii_lowercase() || c == '-') || sub.is_empty() {
            continue; // a placeholder (ARGS, …): nothing to check
        }
        let what = match help(sub) {
            None => Some(format!("`{s}`: torus-search has no subcommand {sub}")),
            Some(known) => {
                let unknown: Vec<String> = flags_in(rest).difference(&known).cloned().collect();
                (!unknown.is_empty())
                    .then(|| format!("`{s}`: `{sub} --help` lists no {}", unknown.join(", ")))
            }
        };
        if let Some(what) = what {
            bad.push(Finding {
                file: file.into(),
                line: n,
                what,
            });
        }
    }
    bad
}

/// The choices `--help` gives for `flag` ("one of a, b, c").
fn choices(help: &str, flag: &str) -> Vec<String> {
    let line = help
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{flag} <")))
        .unwrap_or_else(|| panic!("`run --help` has no {flag}"));
    let list = line
        .split("one of ")
        .nth(1)
        .and_then(|r| r.split(" [default").next())
        .unwrap_or_else(|| panic!("{flag} lists no choices: {line}"));
    list.split(", ").map(|c| c.trim().to_string()).collect()
}

/// Links of `file` (a path under `root`) to files that do not exist or to
/// headings they do not have.
fn broken_links(root: &Path, file: &str, text: &str) -> Vec<Finding> {
    let dir = Path::new(file).parent().unwrap_or(Path::new(""));
    let mut bad = Vec::new();
    for (line, target) in links(text) {
        let (path, anchor) = target.split_once('#').unwrap_or((&target, ""));
        let rel = if path.is_empty() {
            PathBuf::from(file)
        } else {
            dir.join(path)
        };
        let full = root.join(&rel);
        let what = if !full.exists() {
            Some(format!("({target}): no file {}", rel.display()))
        } else if !anchor.is_empty() && (path.is_empty() || path.ends_with(".md")) {
            let heads = anchors(&std::fs::read_to_string(&full).unwrap_or_default());
            (!heads.contains(anchor))
                .then(|| format!("({target}): {} has no heading #{anchor}", rel.display()))
        } else {
            None
        };
        if let Some(what) = what {
            bad.push(Finding {
                file: file.into(),
                line,
                what,
            });
        }
    }
    bad
}

fn fail_on(findings: Vec<Finding>, what: &str) {
    let list: Vec<String> = findings.iter().map(|f| f.to_string()).collect();
    assert!(list.is_empty(), "{what}:\n{}", list.join("\n"));
}

/// The experiments `experiment --list` marks as sampling targets only.
fn targets_only() -> BTreeSet<String> {
    let out = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(["experiment", "--list"])
        .output()
        .expect("the binary runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| !l.starts_with(' '))
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert!(
        rows.iter().any(|r| r.get(1) == Some(&"episodes")),
        "`experiment --list` no longer names each experiment's kind:\n{text}"
    );
    rows.iter()
        .filter(|r| r.get(1) == Some(&"targets"))
        .map(|r| r[0].to_string())
        .collect()
}

#[test]
fn every_command_in_the_docs_runs() {
    let t0 = Instant::now();
    let targets = targets_only();
    let mut bad = Vec::new();
    for (k, (file, text)) in docs().iter().enumerate() {
        bad.extend(check_doc(file, text, &format!("doc{k}"), &targets));
    }
    let cpu = children_cpu().map_or("unknown".into(), |c| format!("{c:.1} s"));
    eprintln!(
        "the docs' commands ran in {:.1} s ({cpu} of CPU)",
        t0.elapsed().as_secs_f64()
    );
    fail_on(bad, "commands in the docs that fail");
}

#[test]
fn the_docs_show_commands() {
    let total: usize = docs().iter().map(|(f, t)| commands(f, t).0.len()).sum();
    assert!(
        total >= 10,
        "only {total} commands found: is the extraction broken?"
    );
}

#[test]
fn every_make_target_in_the_docs_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let targets = make_targets(&std::fs::read_to_string(root.join("Makefile")).expect("Makefile"));
    for t in ["serve", "test", "bench", "figures"] {
        assert!(
            targets.contains(t),
            "the Makefile parse lost {t}: {targets:?}"
        );
    }
    let mut bad = Vec::new();
    for (file, text) in docs() {
        bad.extend(unknown_make_targets(&file, &text, &targets));
    }
    fail_on(bad, "make targets the docs name that the Makefile lacks");
}

/// The subcommands `torus-search --help` lists.
fn subcommands() -> BTreeSet<String> {
    let out = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .arg("--help")
        .output()
        .expect("the binary runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with(' '))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|s| *s != "help")
        .map(String::from)
        .collect()
}

#[test]
fn every_flag_in_inline_commands_exists() {
    let mut cache: HashMap<String, Option<BTreeSet<String>>> = HashMap::new();
    let subs = subcommands();
    assert!(subs.contains("run"), "`--help` lists no run: {subs:?}");
    let mut help = |sub: &str| {
        cache
            .entry(sub.to_string())
            .or_insert_with(|| subs.contains(sub).then(|| help_flags(sub)))
            .clone()
    };
    let mut bad = Vec::new();
    for (file, text) in docs() {
        bad.extend(unknown_inline_flags(&file, &text, &mut help));
    }
    fail_on(bad, "inline commands with flags the CLI lacks");
}

#[test]
fn every_searcher_and_variant_is_described() {
    let out = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(["run", "--help"])
        .output()
        .expect("the binary runs");
    let help = String::from_utf8_lossy(&out.stdout).into_owned();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let page = std::fs::read_to_string(root.join("docs/searchers.md")).expect("docs/searchers.md");
    let mut missing = Vec::new();
    for flag in ["--searcher", "--variant", "--rollout"] {
        for c in choices(&help, flag) {
            if !page.contains(&format!("`{c}`")) {
                missing.push(format!("{flag} {c}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "docs/searchers.md does not name: {}",
        missing.join(", ")
    );
}

#[test]
fn every_relative_link_in_the_docs_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut bad = Vec::new();
    for (file, text) in docs() {
        bad.extend(broken_links(root, &file, &text));
    }
    fail_on(bad, "links in the docs that lead nowhere");
}

mod unit;
