//! The native CLI: bad input gets a one-line error and exit code 2; `--json`
//! prints exactly one JSON object with the documented fields.
#![cfg(not(target_arch = "wasm32"))]

use std::process::{Command, Output};

fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn bad_input_names_the_flag_and_range_and_exits_2() {
    let cases: &[(&[&str], &str)] = &[
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
            &["run", "--searcher", "bogus"],
            "--searcher must be one of mcts, rw, levy, nsarw, got bogus",
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
    ];
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
fn json_has_every_field_and_is_consistent() {
    let v = json(&[
        "run", "--n", "12", "--prior", "gaussian", "--sigma", "2", "--loops", "8", "--trials",
        "40", "--seed", "3", "--json",
    ]);
    for f in [
        "trials",
        "mean_steps",
        "ci95_steps",
        "mean_optimal",
        "asoo",
        "ci95_asoo",
        "mean_ratio",
        "ci95_ratio",
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
    let (ms, mo, asoo) = (
        v["mean_steps"].as_f64().unwrap(),
        v["mean_optimal"].as_f64().unwrap(),
        v["asoo"].as_f64().unwrap(),
    );
    assert!(
        (ms - mo - asoo).abs() < 1e-9,
        "ASOO is mean(steps - optimal)"
    );
    let ci = v["ci95_steps"].as_array().unwrap();
    assert!(ci[0].as_f64().unwrap() <= ms && ms <= ci[1].as_f64().unwrap());
    let q = |k: &str| v[k].as_f64().unwrap();
    assert!(q("q1_steps") <= q("median_steps") && q("median_steps") <= q("q3_steps"));
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
    assert_eq!(v["mean_steps"], 0.0);
    assert_eq!(v["zero_optimal"], 5);
    // With --known the searcher plans on the true target: near-optimal paths.
    let v = json(&[
        "run", "--n", "9", "--prior", "uniform", "--known", "--loops", "200", "--trials", "30",
        "--json",
    ]);
    assert!(v["asoo"].as_f64().unwrap() < 3.0, "{v}");
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
