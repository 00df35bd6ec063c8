//! Provenance in every CLI output, merges of results from other builds or
//! damaged files (a warning or a clear message, never an overwrite), and
//! the experiment command's consistency with `run`: applicability of
//! `--series`, the defaults its help shows, `--dry-run` and `--list --json`.
#![cfg(not(target_arch = "wasm32"))]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use torus_search::experiment::provenance::{is_utc_date, shell_line, strip, COMMIT, VERSION};
use torus_search::experiment::FORMAT_VERSION;

fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn ok(args: &[&str]) -> (String, String) {
    let o = cli(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(0), "{args:?}: {err}");
    (String::from_utf8(o.stdout).unwrap(), err)
}

fn refused(args: &[&str]) -> String {
    let o = cli(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    err
}

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("torus-prov-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `provenance` of a JSON output is well formed, and names this build and `command`.
fn check_provenance(v: &serde_json::Value, command: &str) {
    let p = &v["provenance"];
    assert_eq!(p["version"], VERSION);
    assert_eq!(p["commit"], COMMIT);
    let commit = p["commit"].as_str().unwrap();
    assert!(
        commit == "unknown"
            || (commit.len() == 40 && commit.bytes().all(|b| b.is_ascii_hexdigit()))
    );
    assert!(p["dirty"].is_boolean() || (p["dirty"].is_null() && commit == "unknown"));
    assert!(is_utc_date(p["date"].as_str().unwrap()), "{p}");
    assert_eq!(p["command"], command);
}

const SMALL: &[&str] = &[
    "experiment",
    "custom",
    "--preset",
    "none",
    "--trials",
    "4",
    "--n",
    "7",
    "--loops",
    "4",
    "--step-cap",
    "50",
    "--series",
    "MCTS:searcher=mcts",
    "--series",
    "RW:searcher=rw",
];

fn with_bin(args: &[&str]) -> String {
    let mut all = vec![env!("CARGO_BIN_EXE_torus-search")];
    all.extend(args);
    shell_line(&all)
}

#[test]
fn run_json_and_text_carry_the_build() {
    let args = ["run", "--n", "8", "--trials", "3", "--json"];
    let (out, _) = ok(&args);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    check_provenance(&v, &with_bin(&args));
    for extra in [&["--exact", "--searcher", "sweep"][..], &["--blind"][..]] {
        let args: Vec<&str> = ["run", "--n", "8", "--trials", "3", "--json"]
            .iter()
            .chain(extra)
            .copied()
            .collect();
        let v: serde_json::Value = serde_json::from_str(&ok(&args).0).unwrap();
        check_provenance(&v, &with_bin(&args));
    }
    let (table, _) = ok(&["run", "--n", "8", "--trials", "2", "--preset", "paper-code"]);
    assert!(table.contains("\npreset: paper-code"), "{table}");
    assert!(
        table.contains(&format!("torus-search {VERSION}, commit ")),
        "{table}"
    );
    let line = table.lines().find(|l| l.starts_with("searcher: ")).unwrap();
    assert!(
        line.contains(" c=2 ") && line.contains(" escape=0"),
        "{line}"
    );
    // The searcher line shows every setting the run reads, decay and escape included.
    let (table, _) = ok(&["run", "--n", "8", "--trials", "2"]);
    assert!(table.contains("\npreset: none"), "{table}");
    let line = table.lines().find(|l| l.starts_with("searcher: ")).unwrap();
    assert!(
        line.contains(" decay=0.8") && line.contains(" escape=10"),
        "{line}"
    );
    let (version, _) = ok(&["--version"]);
    assert!(
        version.contains(&COMMIT[..12.min(COMMIT.len())]),
        "{version}"
    );
}

#[test]
fn experiment_files_carry_provenance_outside_the_compared_bytes() {
    let dir = temp_dir("files");
    let d = dir.to_str().unwrap();
    let args: Vec<&str> = SMALL.iter().copied().chain(["--out", d]).collect();
    let (out, _) = ok(&args);
    assert!(
        out.starts_with(&format!(
            "custom: seed 1, preset none, 2 points × 4 trials; torus-search {VERSION}, commit "
        )),
        "{out}"
    );
    let command = with_bin(&args);
    let json = std::fs::read_to_string(dir.join("custom.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    check_provenance(&v, &command);
    let csv = std::fs::read_to_string(dir.join("custom.csv")).unwrap();
    let date = v["provenance"]["date"].as_str().unwrap();
    for line in [
        format!("# version: {VERSION}"),
        format!("# commit: {COMMIT}"),
        format!("# date: {date}"),
        format!("# command: {command}"),
    ] {
        assert!(csv.lines().any(|l| l == line), "{line} in {csv}");
    }
    assert!(csv.contains("\n# spec: {\"name\":\"custom\",\"trials\":4,\"seed\":\"1\","));
    let svg = std::fs::read_to_string(dir.join("custom.svg")).unwrap();
    assert!(
        svg.contains(&format!("made {date}")),
        "the caption has the date"
    );
    assert!(svg.contains("custom · 4 trials per point · seed 1 · preset none"));
    assert!(svg.contains("command: "));
    assert!(
        !strip(&svg).contains("command: "),
        "strip takes the caption out"
    );
    let png = std::fs::read(dir.join("custom.png")).unwrap();
    let has = |needle: &str| png.windows(needle.len()).any(|w| w == needle.as_bytes());
    assert!(has("Software") && has(&format!("torus-search {VERSION}")) && has(date));
    // SOURCE_DATE_EPOCH fixes the date (reproducible outputs).
    let o = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(["run", "--n", "6", "--trials", "1", "--json"])
        .env("SOURCE_DATE_EPOCH", "951782400")
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["provenance"]["date"], "2000-02-29T00:00:00Z");
    std::fs::remove_dir_all(&dir).ok();
}

/// Files of `dir`, name → bytes.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

/// `text` with its first row's value changed.
fn edited_row(text: &str) -> String {
    let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
    let value = v["rows"][0][6].as_i64().unwrap();
    v["rows"][0][6] = (value + 1).into();
    serde_json::to_string(&v).unwrap()
}

#[test]
fn merges_warn_about_other_commits_and_refuse_damaged_files_without_writing() {
    let dir = temp_dir("merge");
    let d = dir.to_str().unwrap();
    for i in 1..=2 {
        let shard = format!("{i}/2");
        let args: Vec<&str> = SMALL
            .iter()
            .copied()
            .chain(["--out", d, "--shard", &shard])
            .collect();
        ok(&args);
    }
    let shard = |i: u32| dir.join(format!("custom.shard-{i}-of-2.json"));
    let text = std::fs::read_to_string(shard(2)).unwrap();
    // Shard 2 from another commit: merged, with a warning naming both.
    let other = "a".repeat(40);
    let moved = text.replacen(
        &format!("\"commit\":\"{COMMIT}\""),
        &format!("\"commit\":\"{other}\""),
        1,
    );
    assert_ne!(moved, text);
    let foreign = dir.join("other-commit.json");
    std::fs::write(&foreign, &moved).unwrap();
    let out = format!("{d}/merged");
    let s1 = shard(1).display().to_string();
    let (_, err) = ok(&["merge", &s1, foreign.to_str().unwrap(), "--out", &out]);
    assert!(
        err.lines().any(|l| l.starts_with("warning: ")
            && l.contains(&format!("commit {other}"))
            && l.contains(&format!("commit {COMMIT}"))),
        "{err}"
    );
    let merged: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("merged/custom.json")).unwrap())
            .unwrap();
    let sources = merged["provenance"]["sources"].as_array().unwrap();
    assert_eq!(sources.len(), 2);
    assert_eq!(sources[1]["commit"], other.as_str());
    assert!(merged["provenance"]["command"]
        .as_str()
        .unwrap()
        .contains(" merge "));
    // Damaged files: a clear message, exit 2, and the files already in --out untouched.
    let before = snapshot(&dir.join("merged"));
    let bad: Vec<(&str, String, &str)> = vec![
        (
            "format.json",
            text.replacen(
                &format!("\"format_version\":{FORMAT_VERSION}"),
                "\"format_version\":7",
                1,
            ),
            "format_version 7 is not supported",
        ),
        (
            "truncated.json",
            text[..text.len() / 2].to_string(),
            "the file is truncated",
        ),
        (
            "version.json",
            text.replacen(
                &format!("\"version\":\"{VERSION}\",\"provenance\""),
                "\"version\":\"0.0.1\",\"provenance\"",
                1,
            ),
            "made by torus-search 0.0.1",
        ),
        (
            "spec.json",
            text.replacen("\"trials\":4", "\"trials\":5", 1),
            "units.total is 8 but the spec plans 10 units",
        ),
        ("rows.json", edited_row(&text), "rows[0] has value"),
        (
            "edited.json",
            text.replacen("\"n\":7", "\"n\":8", 1),
            "does not match what its spec plans",
        ),
    ];
    for (name, body, want) in bad {
        let path = dir.join(name);
        std::fs::write(&path, body).unwrap();
        let err = refused(&["merge", &s1, path.to_str().unwrap(), "--out", &out]);
        assert!(
            err.contains(path.to_str().unwrap()) && err.contains(want),
            "{name}: {err}"
        );
        assert_eq!(
            snapshot(&dir.join("merged")),
            before,
            "{name} changed the output"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn series_follow_runs_applicability_rules() {
    let run = refused(&["run", "--searcher", "rw", "--c", "2"]);
    assert_eq!(
        run.trim(),
        "error: --c does not apply to this configuration: searcher rw does not read it"
    );
    let exp = refused(&[
        "experiment",
        "custom",
        "--series",
        "A:searcher=rw,c=2",
        "--trials",
        "1",
    ]);
    assert_eq!(
        exp.trim(),
        "error: --series \"A\": c does not apply to this configuration: searcher rw does not read it"
    );
    let exp = refused(&[
        "experiment",
        "custom",
        "--series",
        "A:prior=uniform,sigma=3",
        "--trials",
        "1",
    ]);
    assert!(
        exp.contains("sigma does not apply to this configuration: it applies with prior gaussian"),
        "{exp}"
    );
    let base = refused(&[
        "experiment",
        "custom",
        "--searcher",
        "rw",
        "--mu",
        "2",
        "--trials",
        "1",
    ]);
    assert!(
        base.starts_with("error: --mu does not apply to any point of custom: "),
        "{base}"
    );
}

#[test]
fn experiment_help_shows_the_values_experiments_use() {
    let (help, _) = ok(&["experiment", "--help"]);
    let line = |flag: &str| {
        let at = help
            .find(&format!("      --{flag} "))
            .unwrap_or_else(|| panic!("--{flag} in help"));
        help[at..]
            .split("\n      --")
            .next()
            .unwrap()
            .replace('\n', " ")
    };
    assert!(
        line("c")
            .contains("[default: 2, from the paper-code preset; the schema's: 1.4142135623730951]"),
        "{}",
        line("c")
    );
    assert!(
        line("final").contains("[default: uct, from the paper-code preset; the schema's: auto]")
    );
    assert!(line("decay").contains("[default: 1, from the paper-code preset"));
    assert!(line("escape").contains("[default: 0, from the paper-code preset"));
    assert!(line("n").contains("[default: 40]"), "{}", line("n"));
    assert!(
        line("step-cap").contains("[default: 10000, from the paper-code preset"),
        "{}",
        line("step-cap")
    );
    assert!(line("seed").contains("[default: 1]"));
    let (run_help, _) = ok(&["run", "--help"]);
    assert!(
        run_help.contains("[default: 1.4142135623730951]"),
        "run shows the schema's"
    );
}

#[test]
fn dry_run_plans_and_estimates_without_writing() {
    let dir = temp_dir("dry");
    let d = dir.to_str().unwrap();
    let (out, _) = ok(&[
        "experiment",
        "delta",
        "--trials",
        "3",
        "--step-cap",
        "200",
        "--dry-run",
        "--calibration",
        "2",
        "--out",
        d,
    ]);
    assert!(
        out.starts_with("spec: {\"name\":\"delta\",\"trials\":3,"),
        "{out}"
    );
    assert!(
        out.contains("delta: 10 points (10 series × 1 x values) × 3 trials = 30 units"),
        "{out}"
    );
    assert!(out.contains("series \"MCTS, RW rollouts\": n=40 "), "{out}");
    assert!(
        out.contains(" c=2 ") && out.contains(" step_cap=200"),
        "the values used: {out}"
    );
    assert!(out.contains("calibration: trial 0 of "), "{out}");
    assert!(out.contains("estimated time: about "), "{out}");
    assert!(snapshot(&dir).is_empty(), "a dry run writes nothing");
    let (out, _) = ok(&[
        "experiment",
        "delta",
        "--dry-run",
        "--calibration",
        "0",
        "--shard",
        "2/4",
    ]);
    assert!(out.contains("this shard: units"), "{out}");
    assert!(out.contains("no calibration"), "{out}");
    refused(&["experiment", "delta", "--dry-run", "--calibration", "601"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn list_json_names_every_experiment() {
    let (out, _) = ok(&["experiment", "--list", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let names: Vec<&str> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["name"].as_str().unwrap())
        .collect();
    let want: Vec<&str> = torus_search::experiment::DEFINITIONS
        .iter()
        .map(|d| d.name)
        .collect();
    assert_eq!(names, want);
    assert_eq!(v[0]["defaultTrials"], 10_000);
    assert!(v[0]["title"].is_string() && v[0]["help"].is_string() && v[0]["kind"].is_string());
    let err = refused(&["experiment", "delta", "--json"]);
    assert!(err.contains("--list"), "{err}");
}
