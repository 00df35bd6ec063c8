//! Every committed result reloads with this build: `docs/figures/*.json`
//! is read and checked as `torus-search merge FILE` does (its spec planned
//! again, its statistics derived again from its rows), carries a well
//! formed provenance, and its CSV is the one this build writes from it. A
//! change that makes them stale fails here until `make figures`
//! (scripts/figures.sh) regenerates them.
#![cfg(not(target_arch = "wasm32"))]

use std::path::Path;
use torus_search::experiment::provenance::{is_utc_date, merge_stamped};
use torus_search::experiment::DEFINITIONS;

const REGENERATE: &str = "regenerate them with `make figures` (scripts/figures.sh)";

fn figures() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/figures")
}

/// What is wrong with the committed result `name` (a JSON file), if anything.
fn problem(name: &str) -> Option<String> {
    let dir = figures();
    let text = std::fs::read_to_string(dir.join(name)).ok()?;
    let (set, provs) = match merge_stamped(&[(name, &text)]) {
        Ok(v) => v,
        Err(e) => return Some(e.to_string()),
    };
    let Some(p) = provs.into_iter().next().flatten() else {
        return Some(format!("{name}: carries no provenance"));
    };
    if !is_utc_date(&p.date) || p.command.is_empty() {
        return Some(format!("{name}: a malformed provenance {p:?}"));
    }
    let stem = name.trim_end_matches(".json");
    match std::fs::read_to_string(dir.join(format!("{stem}.csv"))) {
        Ok(csv) if csv == set.stamped_csv(&p) => {}
        Ok(_) => {
            return Some(format!(
                "{stem}.csv: not the CSV this build writes from {name}"
            ))
        }
        Err(e) => return Some(format!("{stem}.csv: {e}")),
    }
    let tables = [
        ("trials.csv", set.stamped_trials_csv(&p)),
        ("paired.csv", set.stamped_paired_csv(&p)),
    ];
    for (ext, want) in tables {
        match std::fs::read_to_string(dir.join(format!("{stem}.{ext}"))) {
            Ok(got) if got == want => {}
            Ok(_) => return Some(format!("{stem}.{ext}: not what this build writes")),
            Err(e) => return Some(format!("{stem}.{ext}: {e}")),
        }
    }
    for ext in ["svg", "png"] {
        if !dir.join(format!("{stem}.{ext}")).exists() {
            return Some(format!("{stem}.{ext} is missing"));
        }
    }
    out_of_range(name, &set)
}

/// An interval of a committed result that leaves the range of its trials,
/// or an excess interval below 0, if any.
fn out_of_range(name: &str, set: &torus_search::experiment::ResultSet) -> Option<String> {
    for (i, s) in set.stats().iter().enumerate() {
        let (lo, hi) = (s.spread.min, s.spread.max);
        let m = &s.mean;
        if s.n > 1 && !(lo <= m.lo && m.hi <= hi && m.covers(m.estimate)) {
            return Some(format!("{name}: point {i}: mean {m:?} leaves [{lo}, {hi}]"));
        }
        if let Some(e) = s.excess_mean.filter(|e| e.lo < 0.0) {
            return Some(format!("{name}: point {i}: excess interval {e:?} below 0"));
        }
    }
    None
}

#[test]
fn every_committed_result_reloads_with_this_build() {
    let mut names: Vec<String> = std::fs::read_dir(figures())
        .expect("docs/figures exists")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    names.sort();
    assert!(!names.is_empty());
    let problems: Vec<String> = names.iter().filter_map(|n| problem(n)).collect();
    assert!(
        problems.is_empty(),
        "{} of {} committed results do not reload with this build; {REGENERATE}:\n{}",
        problems.len(),
        names.len(),
        problems.join("\n")
    );
}

#[test]
fn the_figures_script_makes_every_named_experiment() {
    let script =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/figures.sh"))
            .unwrap();
    for d in DEFINITIONS.iter().filter(|d| !d.is_custom()) {
        assert!(
            script.contains(&format!("[{}]=", d.name)),
            "scripts/figures.sh has no trial count for {}",
            d.name
        );
        assert!(
            figures().join(format!("{}.json", d.name)).exists(),
            "docs/figures/{}.json is missing; {REGENERATE}",
            d.name
        );
    }
}
