//! Property test of the CLI: any argument vector exits 0, or 2 with exactly
//! one line on stderr; never 101 (a panic) or a signal. Arguments are drawn
//! from the real flags (every schema parameter's and the subcommands' own)
//! with arbitrary and near-valid values. Runs are kept small by appending
//! `--trials 1 --n 5 --step-cap 3 --loops 2 --rollout-cap 10` to every `run`
//! and `experiment` (a generated duplicate of one of these is itself a
//! usage error, exit 2, which is a case too).
//!
//! Cases: `CLI_CASES` (default 3 000, each a process: about 10 s of the suite; `make
//! fuzz` runs 100 000), seed fixed by proptest's deterministic RNG.
#![cfg(not(target_arch = "wasm32"))]

use proptest::prelude::*;
use proptest::test_runner::{Config as PtConfig, RngAlgorithm, TestRng, TestRunner};
use std::process::Command;

fn flags() -> Vec<String> {
    let mut f: Vec<String> = torus_search::config::params()
        .iter()
        .map(|p| format!("--{}", p.param().flag()))
        .collect();
    for extra in [
        "--json",
        "--trials",
        "--seed",
        "--exact",
        "--preset",
        "--shard",
        "--out",
        "--threads",
        "--sweep",
        "--series",
        "--list",
        "--help",
        "--bogus",
        "-x",
        "--",
    ] {
        f.push(extra.to_string());
    }
    f
}

fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(String::new()),
        Just("NaN".to_string()),
        Just("inf".to_string()),
        Just("-1".to_string()),
        Just("1e999".to_string()),
        Just("0".to_string()),
        Just("18446744073709551616".to_string()),
        Just("1/0".to_string()),
        Just("2/2".to_string()),
        Just("none".to_string()),
        Just("paper-code".to_string()),
        Just("sigma:0 1".to_string()),
        Just("/nonexistent/x.json".to_string()),
        (0u32..2000).prop_map(|v| v.to_string()),
        (-10.0f64..10.0).prop_map(|v| v.to_string()),
        "[a-z_,:=. 0-9-]{0,12}",
        any::<String>().prop_map(|s| s.chars().filter(|&c| c != '\0').take(20).collect()),
    ]
}

fn argv(flags: Vec<String>) -> impl Strategy<Value = Vec<String>> {
    let sub = prop_oneof![
        Just("run"),
        Just("experiment"),
        Just("merge"),
        Just("help"),
        Just(""),
        Just("bogus"),
    ];
    let token = prop_oneof![
        3 => proptest::sample::select(flags).prop_map(|f| f.to_string()),
        2 => value(),
        1 => proptest::sample::select(
            torus_search::experiment::DEFINITIONS.iter().map(|d| d.name.to_string()).collect::<Vec<_>>()
        ),
    ];
    (sub, proptest::collection::vec(token, 0..6)).prop_map(|(sub, tokens)| {
        let mut v = Vec::new();
        if !sub.is_empty() {
            v.push(sub.to_string());
        }
        v.extend(tokens);
        if matches!(sub, "run" | "experiment") {
            for a in [
                "--trials",
                "1",
                "--n",
                "5",
                "--step-cap",
                "3",
                "--loops",
                "2",
                "--rollout-cap",
                "10",
            ] {
                v.push(a.to_string());
            }
        }
        v
    })
}

#[test]
fn any_argument_vector_exits_0_or_2_with_one_line() {
    let cases: u32 = std::env::var("CLI_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3_000);
    // Experiments write their files under the working directory: a fresh one.
    let out = std::env::temp_dir().join(format!("torus-cli-prop-{}", std::process::id()));
    std::fs::create_dir_all(&out).expect("a scratch directory");
    let mut runner = TestRunner::new_with_rng(
        PtConfig {
            cases,
            failure_persistence: None,
            ..PtConfig::default()
        },
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let t0 = std::time::Instant::now();
    runner
        .run(&argv(flags()), |args| {
            let o = Command::new(env!("CARGO_BIN_EXE_torus-search"))
                .args(&args)
                .current_dir(&out)
                .output()
                .expect("the binary runs");
            let code = o.status.code();
            prop_assert!(
                matches!(code, Some(0) | Some(2)),
                "exit {code:?} for {args:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            if code == Some(2) {
                let err = String::from_utf8_lossy(&o.stderr);
                prop_assert_eq!(
                    err.trim_end().lines().count(),
                    1,
                    "one line on stderr for {:?}: {}",
                    args,
                    err
                );
                prop_assert!(err.starts_with("error: "), "{}", err);
            }
            Ok(())
        })
        .unwrap();
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "cli property: {cases} cases, {:.0} cases/s",
        cases as f64 / secs
    );
    let _ = std::fs::remove_dir_all(&out);
}
