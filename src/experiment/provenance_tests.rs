use super::*;
use crate::experiment::{run_units, Plan, Shard};

/// A tiny custom experiment whose series label holds the member text
/// `,"provenance":{` (escaped in JSON, so `strip` must not take it).
const SPEC: &str = r#"{"name":"custom","trials":3,"seed":"5","preset":null,
  "params":{"n":"6","loops":"3","step_cap":"30"},
  "series":[{"label":"a,\"provenance\":{x","params":{"searcher":"mcts"}},
            {"label":"rw","params":{"searcher":"rw"}}]}"#;

fn result(from_to: Option<(u64, u64)>) -> ResultSet {
    let plan = Plan::from_spec_text(SPEC).unwrap();
    let (a, b) = from_to.unwrap_or((0, plan.total_units()));
    let rows = run_units(&plan, a, b).unwrap();
    ResultSet::new(plan, a, b, rows).unwrap()
}

fn stamp(command: &str, commit: &str, dirty: Option<bool>) -> Provenance {
    Provenance {
        version: VERSION.into(),
        commit: commit.into(),
        dirty,
        date: "2025-03-04T05:06:07Z".into(),
        command: command.into(),
        sources: vec![],
    }
}

#[test]
fn dates_are_utc_iso_8601_to_the_second() {
    for (secs, want) in [
        (0, "1970-01-01T00:00:00Z"),
        (-1, "1969-12-31T23:59:59Z"),
        (951_782_400, "2000-02-29T00:00:00Z"),
        (1_735_689_599, "2024-12-31T23:59:59Z"),
        (4_107_542_400, "2100-03-01T00:00:00Z"),
        (253_402_300_799, "9999-12-31T23:59:59Z"),
    ] {
        assert_eq!(utc_date(secs), want, "{secs}");
        assert!(is_utc_date(want));
    }
    // Day by day from 1899 to 2101 against a plain count of month lengths.
    let leap = |y: i64| (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    let mut days = -(0..71)
        .map(|k| if leap(1899 + k) { 366 } else { 365 })
        .sum::<i64>();
    for y in 1899..2101 {
        for m in 1..=12 {
            let len = [
                31,
                28 + i64::from(leap(y)),
                31,
                30,
                31,
                30,
                31,
                31,
                30,
                31,
                30,
                31,
            ];
            for d in 1..=len[m - 1] {
                let want = format!("{y:04}-{m:02}-{d:02}T00:00:07Z");
                assert_eq!(utc_date(days * 86_400 + 7), want);
                days += 1;
            }
        }
    }
    for bad in [
        "2025-03-04 05:06:07Z",
        "2025-03-04T05:06:07",
        "2025-03-04T05:06:07.123Z",
        "",
    ] {
        assert!(!is_utc_date(bad), "{bad}");
    }
}

#[test]
fn this_build_is_well_formed() {
    assert!(
        COMMIT == "unknown"
            || (COMMIT.len() == 40 && COMMIT.bytes().all(|b| b.is_ascii_hexdigit())),
        "{COMMIT}"
    );
    assert_eq!(dirty().is_none(), COMMIT == "unknown");
    #[cfg(not(target_arch = "wasm32"))]
    {
        let p = Provenance::now("torus-search run".into());
        assert!(is_utc_date(&p.date), "{}", p.date);
        assert_eq!((p.version.as_str(), p.commit.as_str()), (VERSION, COMMIT));
    }
    assert!(this_build().starts_with(&format!("torus-search {VERSION}, commit ")));
}

#[test]
fn command_lines_are_quoted_for_a_shell() {
    assert_eq!(
        shell_line(&[
            "torus-search",
            "experiment",
            "delta",
            "--trials",
            "10",
            "--out",
            "a/b"
        ]),
        "torus-search experiment delta --trials 10 --out a/b"
    );
    assert_eq!(
        shell_line(&["x", "--series", "MCTS, RW:searcher=mcts", "it's", ""]),
        r"x --series 'MCTS, RW:searcher=mcts' 'it'\''s' ''"
    );
}

#[test]
fn provenance_reads_back_and_bad_fields_are_named() {
    let mut p = stamp("torus-search merge a.json b.json", COMMIT, Some(false));
    p.sources = vec![
        stamp("a", "unknown", None),
        stamp("b", &"0".repeat(40), Some(true)),
    ];
    let v = serde_json::to_value(&p).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    assert!(keys.iter().all(|k| FIELDS.contains(k)));
    assert_eq!(Provenance::from_value(&v).unwrap(), p);
    let bad = |edit: &dyn Fn(&mut Value)| {
        let mut w = v.clone();
        edit(&mut w);
        Provenance::from_value(&w).unwrap_err()
    };
    assert_eq!(
        bad(&|w| w["commit"] = "abc".into()),
        ".commit must be 40 hex digits or \"unknown\", got \"abc\""
    );
    assert!(bad(&|w| w["date"] = "yesterday".into()).starts_with(".date must be UTC"));
    assert_eq!(
        bad(&|w| w["dirty"] = "no".into()),
        ".dirty must be true, false or null"
    );
    assert_eq!(
        bad(&|w| w["host"] = "x".into()).split(' ').next(),
        Some(".host")
    );
    assert!(bad(&|w| w["sources"][1]["command"] = 3.into()).starts_with(".sources[1].command"));
    assert!(bad(&|w| *w = 3.into()).starts_with("must be an object"));
}

#[test]
fn the_stamped_files_are_the_compared_bytes_plus_provenance() {
    let set = result(None);
    let p = stamp("torus-search experiment custom", COMMIT, dirty());
    let json = set.stamped_json(&p);
    assert!(json.contains(&format!(
        r#""version":"{VERSION}","provenance":{{"version":"{VERSION}","#
    )));
    assert_eq!(strip(&json), set.to_json());
    assert_eq!(strip(&set.to_json()), set.to_json());
    let (back, got) = read_stamped(&json).unwrap();
    assert_eq!(back, set);
    assert_eq!(got, Some(p.clone()));
    assert_eq!(read_stamped(&set.to_json()).unwrap().1, None);
    let csv = set.stamped_csv(&p);
    assert!(csv.starts_with("# torus-search results;"));
    for line in [
        format!("# version: {VERSION}"),
        format!("# commit: {COMMIT}"),
        "# date: 2025-03-04T05:06:07Z".into(),
        "# command: torus-search experiment custom".into(),
        format!("# spec: {}", set.plan.spec.to_text()),
    ] {
        assert!(csv.lines().any(|l| l == line), "{line} in\n{csv}");
    }
    assert_eq!(strip(&csv), set.csv());
    // An edited provenance is named.
    let edited = json.replacen(r#"{"version":""#, r#"{"version":"9"#, 1);
    let e = read_stamped(&edited).unwrap_err().to_string();
    assert!(e.starts_with("field provenance.version is \"9"), "{e}");
    let broken = json.replacen(&format!(r#""commit":"{COMMIT}""#), r#""commit":"x""#, 1);
    assert!(read_stamped(&broken)
        .unwrap_err()
        .to_string()
        .starts_with("field provenance commit must be 40 hex digits"));
}

#[test]
fn shards_of_other_commits_merge_with_warnings_naming_both() {
    let total = result(None).plan.total_units();
    let shards: Vec<String> = (1..=2)
        .map(|i| {
            let (a, b) = Shard { index: i, count: 2 }.range(total);
            let commit = if i == 1 {
                "1".repeat(40)
            } else {
                "2".repeat(40)
            };
            result(Some((a, b))).stamped_json(&stamp("shard", &commit, Some(false)))
        })
        .collect();
    let files = [
        ("s1.json", shards[0].as_str()),
        ("s2.json", shards[1].as_str()),
    ];
    let (set, provs) = merge_stamped(&files).unwrap();
    assert_eq!(set.to_json(), result(None).to_json());
    let named: Vec<(&str, Option<&Provenance>)> = vec![
        ("s1.json", provs[0].as_ref()),
        ("s2.json", provs[1].as_ref()),
    ];
    let warnings = merge_warnings(&named);
    let ones = format!("commit {}", "1".repeat(40));
    let twos = format!("commit {}", "2".repeat(40));
    assert!(
        warnings.iter().any(|w| w.starts_with("s2.json was made by")
            && w.contains(&twos)
            && w.contains(&format!("s1.json by {ones}"))),
        "{warnings:?}"
    );
    assert!(warnings.iter().any(|w| w.contains("this build is commit")));
    // The same commit as this build, clean: no warning. A dirty tree or a
    // file without provenance: one each.
    let same = stamp("x", COMMIT, Some(false));
    assert_eq!(
        merge_warnings(&[("a", Some(&same)), ("b", Some(&same))]),
        Vec::<String>::new()
    );
    let dirty = stamp("x", COMMIT, Some(true));
    let w = merge_warnings(&[("a", Some(&same)), ("b", Some(&dirty)), ("c", None)]);
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].starts_with("b was made by a build with uncommitted changes"));
    assert!(w[1].starts_with("c carries no provenance"));
}
