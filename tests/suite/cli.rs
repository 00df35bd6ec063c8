//! The native CLI: bad input gets a one-line error and exit code 2; `--json`
//! prints exactly one JSON object with the documented fields.
#![cfg(not(target_arch = "wasm32"))]

use std::process::{Command, Output};
use torus_search::experiment::provenance::strip;

fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Bad command lines, each with the start of the one-line error it gets.
const BAD_INPUT: &[(&[&str], &str)] = &[
    (
        &["run", "--n", "0"],
        "--n must be an integer in 3..=1024, got 0",
    ),
    (
        &["run", "--n", "1025"],
        "--n must be an integer in 3..=1024",
    ),
    (&["run", "--sigma", "-1"], "--sigma must be a number >= 0"),
    (&["run", "--sigma", "NaN"], "--sigma must be a number >= 0"),
    (
        &["run", "--mu", "1"],
        "--mu must be a number in (1, 3], got 1",
    ),
    (&["run", "--mu", "3.5"], "--mu must be a number in (1, 3]"),
    (
        &["run", "--loops", "0"],
        "--loops must be an integer in 1..=10000000, got 0",
    ),
    (
        &["run", "--rv", "-0.5"],
        "--rv must be a number in [0, 2048], got -0.5",
    ),
    (
        &["run", "--start", "41,1"],
        "--start must be x,y with each in 1..=40, got 41,1",
    ),
    (&["run", "--start", "a,b"], "--start must be x,y"),
    (
        &["run", "--target", "0,3"],
        "--target must be x,y with each in 1..=40",
    ),
    (
        &["run", "--searcher", "horizon", "--horizon", "0"],
        "--horizon must be an integer in 1..=9, got 0",
    ),
    (
        &["run", "--searcher", "horizon", "--horizon", "12"],
        "--horizon must be an integer in 1..=9, got 12",
    ),
    (
        &["run", "--searcher", "beam", "--beam-width", "0"],
        "--beam-width must be an integer in 1..=400, got 0",
    ),
    (
        &["run", "--searcher", "beam", "--beam-depth", "401"],
        "--beam-depth must be an integer in 1..=400, got 401",
    ),
    (
        &["run", "--searcher", "beam", "--beam-depth", "x"],
        "--beam-depth must be an integer in 1..=400, got x",
    ),
    (
        &["run", "--variant", "pomcp", "--pomcp-depth", "0"],
        "--pomcp-depth must be an integer in 1..=100000, got 0",
    ),
    (
        &["run", "--variant", "pomcp", "--pomcp-plan", "10"],
        "--pomcp-plan must be an integer in 0..=9, got 10",
    ),
    (
        &["run", "--variant", "pomcp", "--pomcp-scale", "max"],
        "--pomcp-scale must be one of range, left, best, got max",
    ),
    (
        &["run", "--searcher", "improve", "--base", "astar"],
        "--base must be one of cover, sweep, horizon, best, got astar",
    ),
    (
        &["run", "--searcher", "sweep", "--sweep-pattern", "spiral"],
        "--sweep-pattern must be one of lawnmower, helix, got spiral",
    ),
    (
        &["run", "--searcher", "rw", "--exact"],
        "--exact needs a deterministic searcher (sweep, horizon, improve, beam, spiral), got rw",
    ),
    (
        &["run", "--exact"],
        "--exact needs a deterministic searcher (sweep, horizon, improve, beam, spiral), got mcts",
    ),
    (
        &["run", "--searcher", "sweep", "--known", "--exact"],
        "--exact cannot evaluate --known",
    ),
    (
        // Two trials, so that a refusal lost runs quickly to exit 0.
        &["run", "--known", "--blind", "--trials", "2"],
        "--blind cannot evaluate --known",
    ),
    (
        &["run", "--searcher", "bogus"],
        "--searcher must be one of mcts, rw, levy, nsarw, sweep, horizon, improve, beam, spiral, got bogus",
    ),
    (
        &["run", "--loops", "5", "--decision-ms", "2"],
        "--loops does not apply to this configuration",
    ),
    (
        &["run", "--prior", "uniform", "--sigma", "3"],
        "--sigma does not apply to this configuration: it applies with prior gaussian",
    ),
    (
        &["run", "--target", "2,2", "--prior", "delta"],
        "--prior does not apply to this configuration: it applies without a fixed target",
    ),
    (
        &["run", "--searcher", "rw", "--loops", "10"],
        "--loops does not apply to this configuration: searcher rw does not read it",
    ),
    (
        &["run", "--c", "nan"],
        "--c must be a number in [0, 1000000]",
    ),
    (
        &["run", "--epsilon", "2"],
        "--epsilon must be a number in [0, 1]",
    ),
    (
        &["run", "--trials", "0"],
        "--trials must be an integer in 1..=100000000",
    ),
    (
        &["run", "--threads", "0"],
        "--threads must be an integer in 1..=1024",
    ),
    (
        &["run", "--decision-ms", "-1"],
        "--ms must be a number in [0.001, 600000], or 0 for none, got -1",
    ),
    (
        &["run", "--rollout-cap", "0"],
        "--rollout-cap must be an integer in 1..=",
    ),
    (
        &["bench", "--scale", "0"],
        "--scale must be a number in (0, 1000]",
    ),
    (
        &["bench", "--episode", "Cargo.toml", "--loops", "5..5"],
        "--loops must be FROM..TO with integers 0 <= FROM < TO",
    ),
    (
        &["bench", "--episode", "Cargo.toml", "--loops", "x..9"],
        "--loops must be FROM..TO",
    ),
    (
        &["bench", "--episode", "no/such/file.json", "--loops", "0..9"],
        "--episode no/such/file.json:",
    ),
    (
        &["bench", "--episode", "Cargo.toml", "--loops", "0..9"],
        "--episode Cargo.toml is not a torus-search config (JSON)",
    ),
    (&["bench", "--seed", "3"], "--episode <FILE>"),
    (&["bench", "--whole"], "--moves"),
];

#[test]
fn bad_input_names_the_flag_and_range_and_exits_2() {
    let cases = BAD_INPUT;
    for (args, want) in cases {
        let o = cli(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: expected {want:?} in {err:?}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?} printed to stdout");
    }
}

fn json(args: &[&str]) -> serde_json::Value {
    let o = cli(args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    let text = String::from_utf8(o.stdout).expect("utf-8");
    assert_eq!(
        text.trim().lines().count(),
        1,
        "exactly one line of JSON: {text}"
    );
    serde_json::from_str(text.trim()).expect("valid JSON")
}

#[test]
fn blind_paths_of_a_planner_give_its_exact_mean() {
    let base = [
        "run",
        "--searcher",
        "horizon",
        "--sigma",
        "3",
        "--n",
        "16",
        "--json",
    ];
    let exact = json(&[&base[..], &["--exact"]].concat());
    let blind = json(&[&base[..], &["--blind", "--trials", "3"]].concat());
    let want = exact["exact"]["mean"].as_f64().unwrap();
    assert_eq!(blind["trials"], 3);
    // Every trial's path is the same: a point interval at the exact mean.
    for end in ["estimate", "lo", "hi"] {
        assert_eq!(blind["blind_mean"][end].as_f64().unwrap(), want, "{end}");
    }
    assert_eq!(blind["blind_mean"]["method"], "expanded-bca-bootstrap");
    assert_eq!(blind["sd"].as_f64().unwrap(), 0.0);
    assert!(blind["lower_bound"].as_f64().unwrap() <= want);
    let o = cli(&["run", "--blind", "--exact"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn json_has_every_field_and_is_consistent() {
    let v = json(&[
        "run", "--n", "12", "--prior", "gaussian", "--sigma", "2", "--loops", "8", "--trials",
        "40", "--seed", "3", "--json",
    ]);
    for f in [
        "trials",
        "mean_steps",
        "mean_optimal",
        "asoo",
        "mean_ratio",
        "steps_over_mean_optimal",
        "median_steps",
        "q1_steps",
        "q3_steps",
        "zero_optimal",
        "capped",
        "rollouts",
        "rollout_steps",
        "truncated_rollouts",
        "lower_bound",
        "mean_over_bound",
        "seconds",
        "seed",
        "config",
    ] {
        assert!(v.get(f).is_some(), "missing {f} in {v}");
    }
    assert_eq!(v["trials"], 40);
    assert_eq!(v["seed"], 3);
    assert_eq!(v["config"]["n"], 12);
    // Every interval has one shape: estimate, ends, level, method.
    for (f, method) in [
        ("mean_steps", "expanded-bca-bootstrap"),
        ("mean_optimal", "expanded-bca-bootstrap"),
        ("asoo", "expanded-bca-bootstrap"),
        ("mean_ratio", "expanded-bca-bootstrap"),
        ("median_steps", "order-statistic"),
    ] {
        let i = v[f]
            .as_object()
            .unwrap_or_else(|| panic!("{f} is not an interval: {v}"));
        let mut keys: Vec<&str> = i.keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(keys, ["estimate", "hi", "level", "lo", "method"], "{f}");
        assert_eq!(
            (&i["level"], &i["method"]),
            (&0.95.into(), &method.into()),
            "{f}"
        );
        let (e, lo, hi) = (
            i["estimate"].as_f64().unwrap(),
            i["lo"].as_f64().unwrap(),
            i["hi"].as_f64().unwrap(),
        );
        assert!(lo <= e && e <= hi, "{f}: {i:?}");
    }
    let est = |k: &str| v[k]["estimate"].as_f64().unwrap();
    let (ms, mo, asoo) = (est("mean_steps"), est("mean_optimal"), est("asoo"));
    assert!(
        (ms - mo - asoo).abs() < 1e-9,
        "ASOO is mean(steps - optimal)"
    );
    let q = |k: &str| v[k].as_f64().unwrap();
    assert!(q("q1_steps") <= est("median_steps") && est("median_steps") <= q("q3_steps"));
    assert!((q("mean_over_bound") - ms / q("lower_bound")).abs() < 1e-12);
}

#[test]
fn run_reports_the_lower_bound() {
    // The paper's delta target at N = 40 from (1,1): 39 moves, which no
    // searcher beats; a uniform prior's bound is about N²/6 (265.5).
    let v = json(&[
        "run",
        "--sigma",
        "0",
        "--searcher",
        "rw",
        "--trials",
        "2",
        "--json",
    ]);
    assert_eq!(v["lower_bound"], 39.0);
    let v = json(&[
        "run",
        "--prior",
        "uniform",
        "--searcher",
        "rw",
        "--trials",
        "2",
        "--json",
    ]);
    let lb = v["lower_bound"].as_f64().unwrap();
    assert!((lb - 265.50125).abs() < 1e-9, "{lb}");
    let table = String::from_utf8(cli(&["run", "--sigma", "0", "--trials", "2"]).stdout).unwrap();
    assert!(
        table.contains("lower bound (any searcher)      39.000"),
        "{table}"
    );
}

#[test]
fn results_do_not_depend_on_threads() {
    let strip = |mut v: serde_json::Value| {
        v.as_object_mut().unwrap().remove("seconds");
        v.as_object_mut().unwrap().remove("threads");
        // The command line names the thread count.
        v.as_object_mut().unwrap().remove("provenance");
        v
    };
    let base = [
        "run", "--n", "10", "--loops", "6", "--trials", "24", "--seed", "11", "--json",
    ];
    let a = strip(json(&[&base[..], &["--threads", "1"]].concat()));
    let b = strip(json(&[&base[..], &["--threads", "2"]].concat()));
    assert_eq!(a, b);
}

#[test]
fn fixed_and_known_targets() {
    // A target next to the start: optimal is 0 with r_v = 1, so every trial
    // ends at once and is excluded from the ratio.
    let v = json(&[
        "run", "--n", "9", "--target", "2,1", "--trials", "5", "--json",
    ]);
    assert_eq!(v["mean_steps"]["estimate"], 0.0);
    assert_eq!(v["zero_optimal"], 5);
    // With --known the searcher plans on the true target: near-optimal paths.
    let v = json(&[
        "run", "--n", "9", "--prior", "uniform", "--known", "--loops", "200", "--trials", "30",
        "--json",
    ]);
    assert!(v["asoo"]["estimate"].as_f64().unwrap() < 3.0, "{v}");
}

#[test]
fn table_output_is_readable() {
    let o = cli(&["run", "--n", "8", "--searcher", "nsarw", "--trials", "10"]);
    assert_eq!(o.status.code(), Some(0));
    let t = String::from_utf8(o.stdout).unwrap();
    for want in [
        "mean steps",
        "ASOO",
        "median steps",
        "capped episodes",
        "searcher: nsarw",
    ] {
        assert!(t.contains(want), "{want} missing from\n{t}");
    }
}

#[test]
fn bench_json_names_what_it_measures() {
    let v = json(&["bench", "--json", "--scale", "0.002"]);
    for f in [
        "rw_steps_per_s",
        "levy_steps_per_s",
        "nsarw_steps_per_s",
        "mcts_cells_sigma0_loops_per_s",
        "mcts_cells_sigma5_episodes_per_s",
        "mcts_tree_sigma0_episodes_per_s",
        "mcts_tree_sigma5_loops_per_s",
    ] {
        assert!(v[f].as_f64().is_some_and(|x| x > 0.0), "{f} in {v}");
    }
}

#[test]
fn bench_moves_reports_each_searchers_mean_median_and_longest_decision() {
    let v = json(&["bench", "--moves", "--json", "--scale", "0.002"]);
    let rows = v["moves"].as_array().unwrap();
    for n in [40, 256] {
        for (label, _) in torus_search::bench::move_cases(n) {
            let row = rows
                .iter()
                .find(|r| r["searcher"] == label.as_str() && r["n"] == n)
                .unwrap_or_else(|| panic!("{label} at N = {n} missing from {v}"));
            let f = |k: &str| row[k].as_f64().unwrap_or_else(|| panic!("{k} in {row}"));
            let (mean, median, longest) = (f("ms_per_move"), f("median_ms"), f("longest_ms"));
            assert!(row["moves"].as_u64().is_some_and(|m| m >= 3), "{row}");
            assert!(row["episodes"].as_u64().is_some(), "{row}");
            assert!(mean > 0.0 && median > 0.0, "{row}");
            // The longest decision bounds the others, and so their mean:
            // here every decision makes one move (no trial's target lies in
            // the start's disc, about 4σ from the prior's centre on each axis).
            assert!(median <= longest && mean <= longest * 1.0001, "{row}");
        }
    }
}

#[test]
fn bench_times_a_window_of_an_episode() {
    let dir = std::env::temp_dir().join(format!("torus-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("core.json");
    std::fs::write(&file, r#"{"n": 30, "sigma": 4, "loops": 50}"#).unwrap();
    let f = file.to_str().unwrap();
    let v = json(&[
        "bench",
        "--json",
        "--episode",
        f,
        "--loops",
        "100..600",
        "--seed",
        "3",
    ]);
    assert_eq!(v["from"], 100);
    assert_eq!(v["to"], 600);
    assert!(v["loops_per_s"].as_f64().is_some_and(|x| x > 0.0), "{v}");
    // A walker has no loops.
    std::fs::write(&file, r#"{"searcher": "rw"}"#).unwrap();
    let o = cli(&["bench", "--episode", f, "--loops", "0..10"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(
            "--searcher must be a searcher that deliberates (mcts) for a loop benchmark, got rw"
        ),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A fresh empty directory under the system's temp dir.
fn temp_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("torus-cli-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A small custom experiment: 2 searchers × 2 lattice sizes, 6 trials.
const SMALL: &[&str] = &[
    "experiment",
    "custom",
    "--preset",
    "none",
    "--trials",
    "6",
    "--seed",
    "4",
    "--loops",
    "4",
    "--step-cap",
    "60",
    "--sweep",
    "n=6,9",
    "--series",
    "mcts:searcher=mcts,rollout=levy",
    "--series",
    "walk, \"rw\":searcher=rw",
];

fn ok(args: &[&str]) -> String {
    let o = cli(args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn experiment_writes_json_csv_and_svg() {
    let dir = temp_dir("exp");
    let d = dir.to_str().unwrap();
    let out = ok(&[SMALL, &["--out", d]].concat());
    assert!(
        out.contains("custom: units 0..24 of 24 (4 points × 6 trials)"),
        "{out}"
    );
    let json = std::fs::read_to_string(dir.join("custom.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["spec"]["series"][1]["label"], "walk, \"rw\"");
    assert_eq!(v["points"][3]["config"]["n"], 9);
    assert_eq!(v["rows"].as_array().unwrap().len(), 24);
    let csv = std::fs::read_to_string(dir.join("custom.csv")).unwrap();
    let csv = strip(&csv);
    assert_eq!(csv.lines().count(), 5);
    assert!(
        csv.lines()
            .nth(3)
            .unwrap()
            .starts_with("2,\"walk, \"\"rw\"\"\",\"6\",6,"),
        "{csv}"
    );
    let svg = std::fs::read_to_string(dir.join("custom.svg")).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.contains("<text"),
        "{}",
        &svg[..200]
    );
    assert!(svg.contains("walk, &quot;rw&quot;") || svg.contains("walk, \"rw\""));
    let png = std::fs::read(dir.join("custom.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 20_000);
    // The same spec with another thread count: the same results, but for
    // the provenance (its command line names the thread count).
    let again = temp_dir("exp1");
    ok(&[SMALL, &["--out", again.to_str().unwrap(), "--threads", "1"]].concat());
    let json1 = std::fs::read_to_string(again.join("custom.json")).unwrap();
    assert_ne!(json1, json);
    assert_eq!(strip(&json1), strip(&json));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::remove_dir_all(&again).ok();
}

#[test]
fn shards_merge_into_the_single_run_files() {
    let dir = temp_dir("shards");
    let d = dir.to_str().unwrap();
    ok(&[SMALL, &["--out", &format!("{d}/single")]].concat());
    for i in 1..=3 {
        let shard = format!("{i}/3");
        let out = ok(&[SMALL, &["--out", d, "--shard", &shard]].concat());
        assert!(
            out.contains(&format!("custom.shard-{i}-of-3.json")),
            "{out}"
        );
    }
    assert!(
        !dir.join("custom.json").exists(),
        "a shard writes only its JSON"
    );
    let shard = |i: u32| format!("{d}/custom.shard-{i}-of-3.json");
    ok(&[
        "merge",
        &shard(3),
        &shard(1),
        &shard(2),
        "--out",
        &format!("{d}/merged"),
    ]);
    // The merged files are the single run's but for their provenance.
    for ext in ["json", "csv", "trials.csv", "paired.csv", "svg"] {
        let read =
            |d: &str| std::fs::read_to_string(dir.join(format!("{d}/custom.{ext}"))).unwrap();
        let (merged, single) = (read("merged"), read("single"));
        assert_ne!(merged, single, "{ext}: the provenance differs");
        assert_eq!(strip(&merged), strip(&single), "{ext}");
    }
    // Bad merges name the file, exit 2 and write nothing.
    let bad = format!("{d}/bad");
    let cases: Vec<(Vec<String>, String)> = vec![
        (
            vec![shard(1), shard(3)],
            "units 8..16 of 0..24 are in none of the files (a shard is missing)".into(),
        ),
        (
            vec![shard(1), shard(2), shard(2), shard(3)],
            format!(
                "{}: its units 8..16 overlap {}'s units 8..16",
                shard(2),
                shard(2)
            ),
        ),
        (
            vec![shard(1), format!("{d}/single/custom.csv")],
            format!("{d}/single/custom.csv: not JSON"),
        ),
        (
            vec![shard(1), format!("{d}/nope.json")],
            format!("{d}/nope.json: "),
        ),
    ];
    for (files, want) in cases {
        let mut args = vec!["merge".to_string()];
        args.extend(files);
        args.extend(["--out".to_string(), bad.clone()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = cli(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(&want),
            "{args:?}: expected {want:?} in {err:?}"
        );
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(!std::path::Path::new(&bad).exists(), "{args:?} wrote files");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_experiments_exit_2_with_one_line() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["experiment", "sigma"],
            "experiment must be one of priors, sigma-sweep, delta, loops, decision-time, sigma-tail, goals, uniform, nsarw-convergence, known-n20, belief, levy-mu, c-sweep, custom, got \"sigma\"",
        ),
        (&["experiment"], "an experiment name is required"),
        (&["experiment", "delta", "--n", "0"], "--n must be an integer in 3..=1024, got 0"),
        (&["experiment", "delta", "--trials", "0"], "--trials must be an integer in 1..=100000000, got 0"),
        (&["experiment", "delta", "--seed", "x"], "--seed must be an integer in 0..=18446744073709551615"),
        (&["experiment", "delta", "--preset", "paper"], "--preset must be one of paper-text, paper-code, none, got paper"),
        (&["experiment", "delta", "--shard", "4/3"], "--shard must be i/n with integers 1 <= i <= n"),
        (&["experiment", "delta", "--shard", "0/3"], "--shard must be i/n"),
        (&["experiment", "delta", "--threads", "0"], "--threads must be an integer in 1..=1024"),
        (&["experiment", "sigma-sweep", "--sigma", "3"], "sigma is the x axis of sigma-sweep"),
        (&["experiment", "delta", "--sweep", "n=10,20"], "sweep is for the custom experiment only"),
        (&["experiment", "custom", "--sweep", "n"], "--sweep must be KEY=V1,V2,..."),
        (&["experiment", "custom", "--sweep", "mu=1,2"], "mu must be a number in (1, 3], got 1 (in sweep)"),
        (&["experiment", "custom", "--sweep", "bogus=1"], "parameter must be one of n, prior"),
        (&["experiment", "custom", "--series", "nolabel"], "--series must be LABEL:KEY=V"),
        (&["experiment", "custom", "--series", "a:loops=0"], "loops must be an integer in 1..=10000000, got 0 (in series \"a\")"),
        (&["experiment", "priors", "--loops", "5"], "priors only samples targets, so loops does not affect it"),
        (&["run", "--preset", "paper"], "--preset must be one of paper-text, paper-code, none, got paper"),
    ];
    for (args, want) in cases {
        let o = cli(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: expected {want:?} in {err:?}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?} printed to stdout");
    }
}

#[test]
fn presets_apply_before_the_other_flags() {
    let v = json(&["run", "--preset", "paper-code", "--c", "3", "--dry-run"]);
    assert_eq!(
        (v["c"].as_f64(), v["final"].as_str()),
        (Some(3.0), Some("uct"))
    );
    let v = json(&["run", "--preset", "none", "--dry-run"]);
    assert_eq!(v["final"], "auto");
    assert_eq!(v["belief"], "posterior");
    let list = ok(&["experiment", "--list"]);
    assert!(
        list.contains("known-n20") && list.contains("10000 trials"),
        "{list}"
    );
}
