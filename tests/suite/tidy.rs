//! An experiment's data beyond its per-point statistics: the per-trial CSV
//! (one row per trial, agreeing with the JSON rows), the paired
//! comparisons (checked by hand from the rows), the intervals' range, and
//! the pandas example of EXPERIMENTS.md.
#![cfg(not(target_arch = "wasm32"))]

use std::process::Command;
use torus_search::analysis::bootstrap::bca_mean;
use torus_search::experiment::{
    merge, run_units, Plan, ResultSet, Shard, PAIRED_CSV_HEADER, TRIALS_COLUMNS,
};

/// Three series × two σ, 7 trials, a cap low enough that random walks are
/// capped, and a label with a comma and a quote.
const SPEC: &str = r#"{"name":"custom","trials":7,"seed":"5","preset":null,
  "params":{"n":"8","loops":"4","step_cap":"40","start":"2,3"},
  "sweep":{"key":"sigma","values":["0","inf"]},
  "series":[{"label":"mcts","params":{"searcher":"mcts"}},
            {"label":"rw, \"plain\"","params":{"searcher":"rw"}},
            {"label":"levy","params":{"searcher":"levy","mu":"1.5"}}]}"#;

fn result(spec: &str) -> ResultSet {
    let p = Plan::from_spec_text(spec).unwrap();
    let total = p.total_units();
    let rows = run_units(&p, 0, total).unwrap();
    ResultSet::new(p, 0, total, rows).unwrap()
}

/// Splits a CSV line on commas outside quotes, unquoting fields.
fn fields(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                out.last_mut().unwrap().push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(String::new()),
            c => out.last_mut().unwrap().push(c),
        }
    }
    out
}

#[test]
fn the_trials_csv_has_one_row_per_trial_agreeing_with_the_json_rows() {
    let set = result(SPEC);
    let csv = set.trials_csv();
    let mut lines = csv.lines();
    let header = fields(lines.next().unwrap());
    // The fixed columns, then the parameters that vary: σ (the sweep) and
    // the searcher; not the MCTS parameters, which only one series reads,
    // nor μ, which only the Lévy series reads.
    let mut want: Vec<String> = TRIALS_COLUMNS.iter().map(|s| s.to_string()).collect();
    want.extend(["sigma", "searcher"].map(String::from));
    assert_eq!(header, want);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let body: Vec<Vec<String>> = lines.map(fields).collect();
    assert_eq!(body.len(), set.rows.len(), "one row per trial");
    assert_eq!(body.len(), 6 * 7);
    let json: serde_json::Value = serde_json::from_str(&set.to_json()).unwrap();
    let mut capped = 0;
    for r in json["rows"].as_array().unwrap() {
        let n = |i: usize| r[i].as_u64().unwrap();
        let (point, trial) = (n(0), n(1));
        // Rows are point by point, in trial order.
        let line = &body[(point * 7 + trial) as usize];
        let get = |c: &str| line[col(c)].as_str();
        assert_eq!(
            (get("point"), get("trial")),
            (&*point.to_string(), &*trial.to_string())
        );
        assert_eq!(get("steps"), n(2).to_string());
        assert_eq!(get("optimal"), n(3).to_string());
        assert_eq!(get("capped"), if n(4) == 1 { "0" } else { "1" });
        capped += (n(4) == 0) as u32;
        assert_eq!(get("excess"), (n(2) as i64 - n(3) as i64).to_string());
        assert_eq!(get("value"), r[6].to_string());
        // The target cell y·8 + x, 1-based as --target takes it.
        let (x, y) = (n(5) % 8 + 1, n(5) / 8 + 1);
        assert_eq!(
            (get("target_x"), get("target_y")),
            (&*x.to_string(), &*y.to_string())
        );
        assert_eq!(get("seed"), "5");
        let p = &json["points"][point as usize];
        assert_eq!(get("series"), p["series"].as_str().unwrap());
        assert_eq!(get("x"), p["x"].as_str().unwrap());
        assert_eq!(get("sigma"), p["x"].as_str().unwrap());
        assert_eq!(get("searcher"), p["config"]["searcher"].as_str().unwrap());
    }
    assert!(capped > 0, "the test needs a capped trial");
    // Empty where a varying parameter does not apply: the rollout policy of
    // MCTS, which the sigma-sweep's walkers do not have.
    let sweep = Plan::from_spec_text(r#"{"name":"sigma-sweep","trials":1}"#).unwrap();
    let vary = torus_search::experiment::varying(&sweep);
    let keys: Vec<&str> = vary.iter().map(|(k, _)| *k).collect();
    assert_eq!(keys, ["sigma", "searcher", "rollout"]);
    let rollout = &vary[2].1;
    assert_eq!((rollout[0].as_str(), rollout[11].as_str()), ("rw", "levy"));
    assert_eq!(rollout[22], "", "the random walk has no rollouts");
    // A partial result lists the trials it has.
    let part = ResultSet::new(set.plan.clone(), 0, 10, set.rows[..10].to_vec()).unwrap();
    assert_eq!(part.trials_csv().lines().count(), 11);
}

#[test]
fn paired_comparisons_by_hand() {
    let set = result(SPEC);
    let json: serde_json::Value = serde_json::from_str(&set.to_json()).unwrap();
    let rows = json["rows"].as_array().unwrap();
    let values = |point: u64| -> Vec<(f64, u64)> {
        let mut v: Vec<(u64, f64, u64)> = rows
            .iter()
            .filter(|r| r[0] == point)
            .map(|r| {
                (
                    r[1].as_u64().unwrap(),
                    r[6].as_f64().unwrap(),
                    r[5].as_u64().unwrap(),
                )
            })
            .collect();
        v.sort_by_key(|t| t.0);
        v.into_iter()
            .map(|(_, value, target)| (value, target))
            .collect()
    };
    // Each series against the first (mcts), at σ = 0 then ∞: points 2 and
    // 3 (rw) against 0 and 1, then 4 and 5 (levy).
    let paired = json["paired"].as_array().unwrap();
    assert_eq!(paired.len(), 4);
    for (k, (a, b)) in [(2u64, 0u64), (3, 1), (4, 0), (5, 1)]
        .into_iter()
        .enumerate()
    {
        let c = &paired[k];
        assert_eq!(
            (c["point"].as_u64(), c["reference_point"].as_u64()),
            (Some(a), Some(b))
        );
        assert_eq!(c["reference"], "mcts");
        assert_eq!(c["x"], if k % 2 == 0 { "0" } else { "inf" });
        let (va, vb) = (values(a), values(b));
        let d: Vec<f64> = va.iter().zip(&vb).map(|(x, y)| x.0 - y.0).collect();
        assert_eq!(c["n"], 7);
        let mean = d.iter().sum::<f64>() / 7.0;
        assert!((c["difference"]["estimate"].as_f64().unwrap() - mean).abs() < 1e-12);
        let want = bca_mean(&d);
        assert_eq!(c["difference"]["lo"].as_f64(), Some(want.lo));
        let count = |f: fn(f64) -> bool| d.iter().filter(|&&x| f(x)).count() as u64;
        assert_eq!(c["wins"].as_u64(), Some(count(|x| x < 0.0)));
        assert_eq!(c["ties"].as_u64(), Some(count(|x| x == 0.0)));
        assert_eq!(c["losses"].as_u64(), Some(count(|x| x > 0.0)));
        // Common random numbers: every trial shares its target.
        assert!(va.iter().zip(&vb).all(|(x, y)| x.1 == y.1));
        assert_eq!(c["same_target"], 7);
    }
    // The paired CSV: a header and one line per comparison, the same numbers.
    let csv = set.paired_csv();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], PAIRED_CSV_HEADER);
    assert_eq!(lines.len(), 5);
    let first = fields(lines[1]);
    assert_eq!(&first[..3], ["rw, \"plain\"", "mcts", "0"]);
    assert_eq!(first[6], paired[0]["difference"]["estimate"].to_string());
    assert_eq!(first[9], paired[0]["wins"].to_string());
}

#[test]
fn intervals_stay_in_range_and_excess_intervals_above_zero() {
    let set = result(SPEC);
    for (p, s) in set.plan.points.iter().zip(set.stats()) {
        let (min, max) = (s.spread.min, s.spread.max);
        for i in [s.mean, s.median] {
            if i.lo.is_finite() {
                assert!(
                    min <= i.lo && i.lo <= i.hi && i.hi <= max,
                    "point {}: {i:?}",
                    p.index
                );
            }
        }
        let e = s.excess_mean.unwrap();
        assert!(e.lo >= 0.0, "point {}: {e:?}", p.index);
    }
}

#[test]
fn the_named_experiments_pair_what_their_claims_compare() {
    let plan = Plan::from_spec_text(r#"{"name":"sigma-sweep"}"#).unwrap();
    let label = |i: usize| plan.header.series[i].as_str();
    let pairs: Vec<(&str, &str)> = plan
        .pairs
        .iter()
        .map(|&(a, b)| (label(a), label(b)))
        .collect();
    assert_eq!(pairs.len(), plan.header.series.len() - 1 + 2);
    assert!(pairs.iter().all(|&(a, _)| a != "MCTS, RW rollouts"));
    for want in [
        ("Lévy flight", "MCTS, RW rollouts"),
        ("Random walk", "MCTS, RW rollouts"),
        ("MCTS, Lévy rollouts", "MCTS, RW rollouts"),
        ("Lévy flight", "MCTS, Lévy rollouts"),
        ("Random walk", "MCTS, Lévy rollouts"),
    ] {
        assert!(pairs.contains(&want), "{want:?} in {pairs:?}");
    }
    // One series: nothing to pair; target samples: nothing either.
    assert!(Plan::from_spec_text(r#"{"name":"levy-mu"}"#)
        .unwrap()
        .pairs
        .is_empty());
    assert!(Plan::from_spec_text(r#"{"name":"priors"}"#)
        .unwrap()
        .pairs
        .is_empty());
}

#[test]
fn merged_shards_give_the_same_csvs() {
    let single = result(SPEC);
    let shards: Vec<(String, String)> = (1..=3)
        .map(|i| {
            let p = Plan::from_spec_text(SPEC).unwrap();
            let (a, b) = Shard { index: i, count: 3 }.range(p.total_units());
            let rows = run_units(&p, a, b).unwrap();
            (
                format!("s{i}.json"),
                ResultSet::new(p, a, b, rows).unwrap().to_json(),
            )
        })
        .collect();
    let files: Vec<(&str, &str)> = shards
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    let merged = merge(&files).unwrap();
    assert_eq!(merged.trials_csv(), single.trials_csv());
    assert_eq!(merged.paired_csv(), single.paired_csv());
    assert_eq!(merged.csv(), single.csv());
}

/// The pandas example of EXPERIMENTS.md (scripts/trials_example.py) on a
/// small sigma-sweep: its means are the per-point CSV's. Needs python3 with
/// pandas (`pip install pandas`); without them it says so and checks nothing.
#[test]
fn the_pandas_example_reproduces_the_figure_means() {
    let has_pandas = Command::new("python3")
        .args(["-c", "import pandas"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !has_pandas {
        eprintln!("SKIPPED: python3 with pandas is not installed (pip install pandas)");
        return;
    }
    let dir = std::env::temp_dir().join(format!("torus-tidy-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_torus-search"))
        .args([
            "experiment",
            "sigma-sweep",
            "--trials",
            "2",
            "--n",
            "8",
            "--loops",
            "6",
        ])
        .args(["--step-cap", "300", "--threads", "2", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run = Command::new("python3")
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scripts/trials_example.py"
        ))
        .arg(dir.join("sigma-sweep"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        run.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        stdout.contains("Lévy flight") && stdout.contains("lfs_more"),
        "{stdout}"
    );
}
