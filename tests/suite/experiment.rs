//! Experiments end to end through the core: plans, units, shards and their
//! merge, reading results back, statistics on known data.
#![cfg(not(target_arch = "wasm32"))]

use torus_search::analysis::bootstrap::bca_means;
use torus_search::experiment::{
    merge, read, run_units, Plan, ResultSet, Row, Shard, Spec, ROW_FIELDS,
};

/// A small custom experiment: 3 series × 2 x values, 5 trials, with a step
/// cap low enough that random walks are capped.
const SMALL: &str = r#"{"name":"custom","trials":5,"seed":"7","preset":null,
  "params":{"n":"8","loops":"4","step_cap":"40"},
  "sweep":{"key":"sigma","values":["0","inf"]},
  "series":[{"label":"mcts","params":{"searcher":"mcts"}},
            {"label":"rw, \"plain\"","params":{"searcher":"rw"}},
            {"label":"nsarw","params":{"searcher":"nsarw"}}]}"#;

fn plan(text: &str) -> Plan {
    Plan::from_spec_text(text).unwrap()
}

fn single_run(text: &str) -> String {
    let p = plan(text);
    let total = p.total_units();
    let rows = run_units(&p, 0, total).unwrap();
    ResultSet::new(p, 0, total, rows).unwrap().to_json()
}

/// The JSON of shard `i` of `n`.
fn shard(text: &str, index: u64, count: u64) -> String {
    let p = plan(text);
    let (a, b) = Shard { index, count }.range(p.total_units());
    let rows = run_units(&p, a, b).unwrap();
    ResultSet::new(p, a, b, rows).unwrap().to_json()
}

#[test]
fn merged_shards_are_the_single_run_byte_for_byte() {
    let single = single_run(SMALL);
    let total = plan(SMALL).total_units();
    assert_eq!(total, 30);
    for count in [1, 2, 3, 4, 7, 30, 33] {
        let shards: Vec<(String, String)> = (1..=count)
            .map(|i| (format!("s{i}.json"), shard(SMALL, i, count)))
            .collect();
        // In order, reversed, and interleaved.
        let mut orders: Vec<Vec<usize>> = vec![(0..shards.len()).collect()];
        orders.push((0..shards.len()).rev().collect());
        orders.push(
            (0..shards.len())
                .step_by(2)
                .chain((1..shards.len()).step_by(2))
                .collect(),
        );
        for order in orders {
            let files: Vec<(&str, &str)> = order
                .iter()
                .map(|&i| (shards[i].0.as_str(), shards[i].1.as_str()))
                .collect();
            let merged = merge(&files).unwrap_or_else(|e| panic!("{count} shards: {e}"));
            assert_eq!(merged.to_json(), single, "{count} shards, order {order:?}");
        }
    }
    // The page's way: rows flattened, in any order, give the same bytes.
    let p = plan(SMALL);
    let mut rows = run_units(&p, 0, total).unwrap();
    rows.reverse();
    let flat: Vec<f64> = rows.iter().flat_map(|r| r.fields()).collect();
    assert_eq!(ResultSet::from_flat(p, &flat).unwrap().to_json(), single);
}

#[test]
fn results_read_back_and_hold_what_they_claim() {
    let single = single_run(SMALL);
    let set = read(&single).unwrap();
    assert_eq!(set.to_json(), single);
    let v: serde_json::Value = serde_json::from_str(&single).unwrap();
    assert_eq!(v["format"], "torus-search-experiment");
    assert_eq!(v["format_version"], 2);
    assert_eq!(
        v["units"],
        serde_json::json!({"total": 30, "from": 0, "to": 30})
    );
    assert_eq!(v["row_fields"].as_array().unwrap().len(), ROW_FIELDS.len());
    assert!(!single.contains("seconds") && !single.contains("threads"));
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 6);
    for p in points {
        assert_eq!(p["n"], 5);
        assert_eq!(p["config"]["seed"], "7");
        assert_eq!(
            p["capped"].as_u64().unwrap() + p["found"].as_u64().unwrap(),
            5
        );
    }
    // Common random numbers: trial i of every σ = 0 point has the same target.
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 30);
    assert_eq!(rows[0][5], rows[10][5]);
    // Random walks at N = 8 with a cap of 40 are capped sometimes, and a
    // capped trial stays in the statistics at its cap.
    let capped: u64 = points.iter().map(|p| p["capped"].as_u64().unwrap()).sum();
    assert!(capped > 0, "the test needs a capped trial");
    for (i, p) in points.iter().enumerate() {
        let mine: Vec<f64> = rows
            .iter()
            .filter(|r| r[0] == i)
            .map(|r| r[6].as_f64().unwrap())
            .collect();
        let mean = mine.iter().sum::<f64>() / mine.len() as f64;
        assert!((p["mean"]["estimate"].as_f64().unwrap() - mean).abs() < 1e-9);
    }
    // The CSV quotes labels and has one line per point.
    let csv = set.csv();
    assert_eq!(csv.lines().count(), 7);
    assert!(csv.contains(r#","rw, ""plain""","0","#), "{csv}");
}

#[test]
fn partial_results_give_partial_statistics_but_do_not_merge() {
    let p = plan(SMALL);
    let rows = run_units(&p, 3, 12).unwrap();
    let keep: Vec<Row> = rows.into_iter().step_by(2).collect();
    let flat: Vec<f64> = keep.iter().flat_map(|r| r.fields()).collect();
    let part = ResultSet::from_flat(p, &flat).unwrap();
    assert_eq!((part.from, part.to), (3, 12));
    assert!(!part.is_complete());
    let text = part.to_json();
    let back = read(&text).unwrap();
    assert_eq!(back.rows.len(), 5);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    // Units are trial-major over 6 points: units 3, 5, 7, 9, 11 are points
    // 3, 5, 1, 3, 5.
    assert_eq!(v["points"][3]["n"], 2, "units 3 and 9 (point 3)");
    assert_eq!(v["points"][1]["n"], 1, "unit 7 (point 1)");
    assert_eq!(v["points"][0]["n"], 0);
    assert_eq!(v["points"][0]["mean"]["estimate"], serde_json::Value::Null);
    let e = merge(&[("part.json", &text)]).unwrap_err().to_string();
    assert_eq!(
        e,
        "part.json: covers units 3..12 but has no row for unit 4: a partial result cannot be merged"
    );
}

#[test]
fn merge_names_the_offending_file() {
    let a = shard(SMALL, 1, 3);
    let b = shard(SMALL, 2, 3);
    let c = shard(SMALL, 3, 3);
    let other = shard(&SMALL.replace(r#""trials":5"#, r#""trials":6"#), 2, 3);
    let err = |files: &[(&str, &str)]| merge(files).unwrap_err().to_string();
    assert_eq!(
        err(&[("a.json", &a), ("c.json", &c)]),
        "units 10..20 of 0..30 are in none of the files (a shard is missing)"
    );
    assert_eq!(
        err(&[("a.json", &a), ("b.json", &b)]),
        "units 20..30 of 0..30 are in none of the files (a shard is missing)"
    );
    assert_eq!(
        err(&[
            ("a.json", &a),
            ("b.json", &b),
            ("b2.json", &b),
            ("c.json", &c)
        ]),
        "b2.json: its units 10..20 overlap b.json's units 10..20"
    );
    let two_of_two = shard(SMALL, 2, 2);
    assert_eq!(
        err(&[("a.json", &a), ("b.json", &b), ("h.json", &two_of_two)]),
        "h.json: its units 15..30 overlap b.json's units 10..20"
    );
    assert_eq!(
        err(&[("a.json", &a), ("o.json", &other)]),
        "o.json: its spec differs from a.json's (spec.trials is 5 there, 6 here)"
    );
    let foreign = r#"{"format":"something-else"}"#;
    assert_eq!(
        err(&[("a.json", &a), ("f.json", foreign)]),
        "f.json: not a torus-search experiment result (its format is \"something-else\")"
    );
    let truncated = &b[..b.len() / 2];
    assert!(err(&[("a.json", &a), ("t.json", truncated)])
        .starts_with("t.json: not JSON: EOF while parsing"));
    assert!(err(&[]).contains("no result files"));
}

#[test]
fn damaged_results_are_refused_with_the_reason() {
    let good = single_run(SMALL);
    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v: serde_json::Value = serde_json::from_str(&good).unwrap();
        f(&mut v);
        read(&v.to_string()).unwrap_err().to_string()
    };
    assert!(read("[]")
        .unwrap_err()
        .to_string()
        .starts_with("not a torus-search experiment result"));
    assert!(read("not json")
        .unwrap_err()
        .to_string()
        .starts_with("not JSON"));
    assert_eq!(
        edit(&|v| v["format_version"] = 1.into()),
        "format_version 1 is not supported (this build reads format_version 2): rerun the experiment with this build"
    );
    assert!(edit(&|v| v["version"] = "0.0.1".into())
        .starts_with("made by torus-search 0.0.1, but this is"));
    assert!(edit(&|v| v["spec"]["name"] = "bogus".into())
        .starts_with("its spec does not plan here: experiment must be one of"));
    assert!(edit(&|v| v["experiment"]["title"] = "x".into())
        .starts_with("the experiment header (experiment.title) does not match"));
    assert!(edit(&|v| v["points"][2]["mean"]["lo"] = 1.5.into())
        .starts_with("points[2].mean.lo (statistics are derived from the rows) does not match"));
    assert!(edit(&|v| v["paired"][1]["wins"] = 99.into())
        .starts_with("paired[1].wins (statistics are derived from the rows) does not match"));
    assert!(edit(&|v| v["points"][1]["config"]["c"] = 3.into()).starts_with("points[1].config.c"));
    assert_eq!(
        edit(&|v| v["rows"][3][6] = 999.into()),
        "rows[3] has value 999 but its numbers give 18".replace("18", &{
            let v: serde_json::Value = serde_json::from_str(&good).unwrap();
            v["rows"][3][2].to_string()
        })
    );
    assert_eq!(
        edit(&|v| v["rows"][4] = v["rows"][3].clone()),
        "unit 3 (point 3, trial 0) has two rows"
    );
    assert!(edit(&|v| v["rows"][0] = serde_json::json!([0, 0, 1]))
        .starts_with("rows[0] must be [point, trial"));
    assert!(edit(&|v| v["units"]["to"] = 31.into()).starts_with("units must be a range"));
    assert!(edit(&|v| v["units"]["total"] = 31.into())
        .starts_with("units.total is 31 but the spec plans 30 units"));
    assert!(edit(&|v| v["units"]["to"] = 20.into())
        .starts_with("rows[20] is unit 20, outside the units 0..20"));
    assert!(edit(&|v| {
        v.as_object_mut().unwrap().remove("rows");
    })
    .starts_with("field rows is missing"));
}

#[test]
fn statistics_on_known_data_keep_the_capped_trial() {
    // One point with step cap 10 and five trials whose steps are 2, 3, 3, 5
    // and a capped 10. Dropping the capped trial (a plausible bug) gives a
    // mean of 3.25, not 4.6, and capped 0.
    let p = plan(
        r#"{"name":"custom","trials":5,"preset":null,"params":{"n":"8","searcher":"rw","step_cap":"10"}}"#,
    );
    let steps = [2u32, 3, 3, 5, 10];
    let rows: Vec<Row> = steps
        .iter()
        .enumerate()
        .map(|(i, &s)| Row {
            point: 0,
            trial: i as u64,
            steps: s,
            optimal: 1,
            found: s < 10,
            target: 0,
            value: s as i64,
        })
        .collect();
    let set = ResultSet::new(p, 0, 5, rows).unwrap();
    let s = &set.stats()[0];
    assert_eq!((s.n, s.capped, s.found), (5, 1, 4));
    assert!((s.mean.estimate - 4.6).abs() < 1e-12);
    let sd = (41.2f64 / 4.0).sqrt();
    assert!((s.sd - sd).abs() < 1e-12);
    // The mean's interval is the bootstrap of the values in trial order,
    // within their range; the median's needs six trials.
    let steps = [2.0, 3.0, 3.0, 5.0, 10.0];
    let excess = [1.0, 2.0, 2.0, 4.0, 9.0];
    assert_eq!(s.mean, bca_means(&[&steps, &excess])[0]);
    assert!(2.0 <= s.mean.lo && s.mean.hi <= 10.0, "{:?}", s.mean);
    assert_eq!(s.median.estimate, 3.0);
    assert!(s.median.lo.is_nan());
    // q1 = 3, q3 = 5, IQR 2: the upper fence is 8, so 10 is past the whisker.
    let b = &s.spread;
    assert_eq!((b.median, b.q1, b.q3), (3.0, 3.0, 5.0));
    assert_eq!(
        (b.whisker_low, b.whisker_high, b.min, b.max),
        (2.0, 5.0, 2.0, 10.0)
    );
    assert_eq!(s.mean_optimal, Some(1.0));
    let excess = s.excess_mean.unwrap();
    assert!((excess.estimate - 3.6).abs() < 1e-12);
    assert_eq!(excess, bca_means(&[&steps, &[1.0, 2.0, 2.0, 4.0, 9.0]])[1]);
    // A capped row must sit at the cap; a row cannot exceed it.
    let bad = |steps, found| {
        let p = plan(
            r#"{"name":"custom","trials":5,"preset":null,"params":{"n":"8","searcher":"rw","step_cap":"10"}}"#,
        );
        let row = Row {
            point: 0,
            trial: 0,
            steps,
            optimal: 1,
            found,
            target: 0,
            value: steps as i64,
        };
        ResultSet::new(p, 0, 5, vec![row]).unwrap_err().to_string()
    };
    assert_eq!(
        bad(7, false),
        "rows[0] has 7 steps, capped, with step cap 10"
    );
    assert_eq!(
        bad(11, true),
        "rows[0] has 11 steps, found, with step cap 10"
    );
}

#[test]
fn priors_sample_the_targets_episodes_draw() {
    let p = plan(r#"{"name":"priors","trials":300,"params":{"n":"12"}}"#);
    assert_eq!(p.points.len(), 4);
    let rows = run_units(&p, 0, p.total_units()).unwrap();
    let set = ResultSet::new(p.clone(), 0, p.total_units(), rows).unwrap();
    let stats = set.stats();
    for s in &stats {
        let h = s.histogram.as_ref().unwrap();
        assert_eq!(h.len(), 144);
        assert_eq!(h.iter().sum::<u64>(), 300);
        assert_eq!(s.lower_bound, None);
    }
    // σ = 0: every sample at the centre (7,7), distance 0.
    assert_eq!(stats[0].histogram.as_ref().unwrap()[6 * 12 + 6], 300);
    assert_eq!(stats[0].spread.max, 0.0);
    // Sample i is the target of episode i with that point's configuration.
    for i in [0u64, 17, 299] {
        let ep = torus_search::run::episode::Episode::trial(&p.points[2].config, i).unwrap();
        // Units are trial-major: sample i of point 2 of 4 is unit 4i + 2.
        assert_eq!(set.rows[(4 * i + 2) as usize].target, ep.target());
    }
    // σ = ∞ is uniform: the mean ℓ1 distance from the centre of a 12-torus
    // is 6 exactly; 300 samples have sd ≈ 2.45, so ±5 standard errors is
    // ±0.71 (sampling σ = 10 instead, a plausible bug, still passes; the
    // σ = 0 check above catches a prior that ignores σ).
    assert!(
        (stats[3].mean.estimate - 6.0).abs() < 0.71,
        "{:?}",
        stats[3].mean
    );
}

#[test]
fn plans_and_specs_survive_a_round_trip() {
    for info in torus_search::experiment::list() {
        let p = plan(&format!(r#"{{"name":"{}"}}"#, info.name));
        let again = Plan::new(&Spec::from_text(&p.spec.to_text()).unwrap()).unwrap();
        assert_eq!(again, p, "{}", info.name);
    }
}

#[test]
fn every_chart_kind_draws_with_text() {
    let specs = [
        // heatmap
        r#"{"name":"priors","trials":50,"params":{"n":"6"}}"#,
        // line, log x, with published references
        r#"{"name":"known-n20","trials":2,"preset":null,"params":{"n":"6","target":"2,2","start":"4,4","belief":"posterior"}}"#,
        // box per x value, and box per series (one x value)
        SMALL,
        r#"{"name":"custom","trials":3,"preset":null,"params":{"n":"6","searcher":"nsarw"}}"#,
    ];
    for (spec, kind) in specs.iter().zip(["heatmap", "line", "box", "box"]) {
        let p = plan(spec);
        assert_eq!(p.header.chart.name(), kind, "{spec}");
        let total = p.total_units();
        let rows = run_units(&p, 0, total).unwrap();
        let set = ResultSet::new(p, 0, total, rows).unwrap();
        let svg = torus_search::experiment::svg(&set);
        assert!(svg.starts_with("<svg"), "{kind}");
        assert!(!svg.contains("could not be drawn"), "{kind}: {svg}");
        assert!(
            svg.contains(&set.plan.header.title),
            "{kind}: the title is drawn as text"
        );
        // A partial result says so.
        let half = ResultSet::new(
            set.plan.clone(),
            0,
            total / 2,
            set.rows[..(total / 2) as usize].to_vec(),
        )
        .unwrap();
        assert!(
            torus_search::experiment::svg(&half).contains("partial:"),
            "{kind}"
        );
    }
}
