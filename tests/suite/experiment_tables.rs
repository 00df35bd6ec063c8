//! The tables of `EXPERIMENTS.md` are generated from the committed results,
//! never typed: each block between `<!-- generated: KIND NAME [| PAIRS] -->`
//! and `<!-- end generated -->` must be what this file makes from
//! `docs/figures/NAME.json`. `UPDATE_TABLES=1 cargo test --test
//! experiment_tables` rewrites the blocks after `make figures`.
//!
//! Kinds: `points` (mean steps [95% CI] of every point, with the lower
//! bound and capped trials), `excess` (the same for the excess over the
//! optimum) and `pairs` (paired differences of the listed pairs, `A − B`
//! separated by `;`, at every x value, with win/tie/loss counts and a
//! verdict).
#![cfg(not(target_arch = "wasm32"))]

use std::path::{Path, PathBuf};
use torus_search::analysis::interval::Interval;
use torus_search::experiment::{read, PairStats, ResultSet};

const BEGIN: &str = "<!-- generated: ";
const END: &str = "<!-- end generated -->";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn load(name: &str) -> Result<ResultSet, String> {
    let path = root().join(format!("docs/figures/{name}.json"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    read(&text).map_err(|e| format!("{name}.json: {e}"))
}

/// A number as the tables print it: whole above 100, one decimal below.
fn num(v: f64) -> String {
    if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

/// `mean [lo, hi]`, or the mean alone when the interval is a point (a
/// deterministic searcher at a fixed target) or unknown.
fn interval(i: &Interval) -> String {
    if i.lo.is_nan() || (i.lo == i.hi && i.lo == i.estimate) {
        num(i.estimate)
    } else {
        format!("{} [{}, {}]", num(i.estimate), num(i.lo), num(i.hi))
    }
}

fn row(cells: &[String]) -> String {
    format!("| {} |\n", cells.join(" | "))
}

fn header(cells: &[String]) -> String {
    row(cells) + &row(&vec!["---".to_string(); cells.len()])
}

/// Points as a table: one row per x value and a column per series, or one
/// row per series without an x axis.
fn points(set: &ResultSet, excess: bool) -> Result<String, String> {
    let stats = set.stats();
    let h = &set.plan.header;
    let xs = h.x.values.len();
    let cell = |p: usize| -> Result<String, String> {
        let s = &stats[p];
        let i = if excess {
            s.excess_mean
                .ok_or_else(|| format!("{}: point {p} has no excess", h.name))?
        } else {
            s.mean
        };
        let capped = if s.capped > 0 {
            format!(" ({} capped)", s.capped)
        } else {
            String::new()
        };
        Ok(interval(&i) + &capped)
    };
    let bound = |p: usize| stats[p].lower_bound.map_or("–".to_string(), num);
    if xs <= 1 {
        let mut out = if excess {
            header(&[
                "searcher".into(),
                "mean excess steps [95% CI]".into(),
                "mean steps [95% CI]".into(),
            ])
        } else {
            header(&[
                "searcher".into(),
                "mean steps [95% CI]".into(),
                "median [95% CI]".into(),
                "bound".into(),
            ])
        };
        for (si, label) in h.series.iter().enumerate() {
            let third = if excess {
                interval(&stats[si].mean)
            } else {
                interval(&stats[si].median)
            };
            let mut cells = vec![label.clone(), cell(si)?, third];
            if !excess {
                cells.push(bound(si));
            }
            out += &row(&cells);
        }
        return Ok(out);
    }
    // An excess is over the optimum, so the bound on steps is no column of it.
    let mut cols = vec![h.x.key.clone().unwrap_or_else(|| "x".into())];
    if !excess {
        cols.push("bound".into());
    }
    cols.extend(h.series.iter().cloned());
    let mut out = header(&cols);
    for (x, text) in h.x.values.iter().enumerate() {
        let mut cells = vec![text.clone()];
        if !excess {
            cells.push(bound(x));
        }
        for si in 0..h.series.len() {
            cells.push(cell(si * xs + x)?);
        }
        out += &row(&cells);
    }
    Ok(out)
}

/// `▲` when the series took more steps than the reference (the interval
/// of series − reference lies above 0), `▼` when it took fewer, `○` when
/// the interval holds 0.
fn verdict(p: &PairStats) -> &'static str {
    let d = &p.paired.difference;
    if d.lo > 0.0 {
        "▲"
    } else if d.hi < 0.0 {
        "▼"
    } else {
        "○"
    }
}

/// The listed pairs at every x value: verdict, difference [95% CI], and
/// wins/ties/losses of n.
fn pairs(set: &ResultSet, wanted: &str) -> Result<String, String> {
    let all = set.paired();
    let mut picked: Vec<(String, Vec<&PairStats>)> = Vec::new();
    for pair in wanted.split(';').map(str::trim) {
        let (a, b) = pair
            .split_once(" − ")
            .ok_or_else(|| format!("pair {pair:?} is not `A − B`"))?;
        let rows: Vec<&PairStats> = (all.iter())
            .filter(|p| p.series == a && p.reference == b)
            .collect();
        if rows.is_empty() {
            return Err(format!(
                "{}: no paired comparison {pair}",
                set.plan.header.name
            ));
        }
        picked.push((pair.to_string(), rows));
    }
    let h = &set.plan.header;
    let with_x = h.x.values.len() > 1;
    let mut cols = Vec::new();
    if with_x {
        cols.push(h.x.key.clone().unwrap_or_else(|| "x".into()));
    }
    cols.extend(picked.iter().map(|(p, _)| p.clone()));
    let mut out = header(&cols);
    for x in 0..h.x.values.len().max(1) {
        let mut cells = Vec::new();
        if with_x {
            cells.push(h.x.values[x].clone());
        }
        for (_, rows) in &picked {
            let p = rows[x];
            let q = &p.paired;
            cells.push(format!(
                "{} {}, {}/{}/{} of {}",
                verdict(p),
                interval(&q.difference),
                q.wins,
                q.ties,
                q.losses,
                q.n
            ));
        }
        out += &row(&cells);
    }
    Ok(out)
}

/// The table a marker's arguments ask for.
fn table(args: &str) -> Result<String, String> {
    let (head, rest) = args.split_once('|').unwrap_or((args, ""));
    let mut words = head.split_whitespace();
    let (kind, name) = (words.next().unwrap_or(""), words.next().unwrap_or(""));
    let set = load(name)?;
    match kind {
        "points" => points(&set, false),
        "excess" => points(&set, true),
        "pairs" => pairs(&set, rest),
        _ => Err(format!("unknown table kind {kind:?} in {args:?}")),
    }
}

/// The document with every generated block made again, and the blocks
/// that could not be made.
fn regenerate(doc: &str) -> (String, Vec<String>) {
    let (mut out, mut errors, mut rest) = (String::new(), Vec::new(), doc);
    while let Some(at) = rest.find(BEGIN) {
        let open_end = rest[at..].find("-->").map(|i| at + i + 3);
        let close = rest[at..].find(END).map(|i| at + i);
        let (Some(open_end), Some(close)) = (open_end, close) else {
            errors.push(format!(
                "an unclosed block at {:?}",
                rest[at..].chars().take(40).collect::<String>()
            ));
            break;
        };
        let args = rest[at + BEGIN.len()..open_end - 3].trim();
        out += &rest[..open_end];
        out.push('\n');
        match table(args) {
            Ok(t) => out += &t,
            Err(e) => {
                errors.push(e);
                out += rest[open_end..close].trim_start_matches('\n');
            }
        }
        out += END;
        rest = &rest[close + END.len()..];
    }
    out += rest;
    (out, errors)
}

#[test]
fn experiments_md_tables_are_the_committed_results() {
    let path = root().join("EXPERIMENTS.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    assert!(doc.contains(BEGIN), "EXPERIMENTS.md has no generated table");
    let (made, errors) = regenerate(&doc);
    if std::env::var_os("UPDATE_TABLES").is_some() {
        // The blocks that could be made are written; the rest keep their text.
        std::fs::write(&path, &made).unwrap();
        assert!(errors.is_empty(), "{}", errors.join("\n"));
        return;
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    if made != doc {
        let line = doc
            .lines()
            .zip(made.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(0);
        panic!(
            "EXPERIMENTS.md line {}: a generated table differs from the committed results \
             (regenerate: UPDATE_TABLES=1 cargo test --test suite experiment_tables::):\n  has:  {}\n  want: {}",
            line + 1,
            doc.lines().nth(line).unwrap_or(""),
            made.lines().nth(line).unwrap_or("")
        );
    }
}

#[test]
fn the_table_maker_reads_what_it_is_asked_and_refuses_the_rest() {
    // Numbers: whole from 100, one decimal below; a point interval is its value.
    assert_eq!(num(683.94), "684");
    assert_eq!(num(-52.84), "-52.8");
    let i = Interval::bare(
        39.0,
        torus_search::analysis::interval::IntervalMethod::Bootstrap,
    );
    assert_eq!(interval(&i), "39.0");
    let i = Interval {
        lo: 30.0,
        hi: 50.5,
        ..i
    };
    assert_eq!(interval(&i), "39.0 [30.0, 50.5]");
    // A block that cannot be made keeps its text and names the problem.
    let doc = "a\n<!-- generated: points no-such-figure -->\nold\n<!-- end generated -->\nb\n";
    let (made, errors) = regenerate(doc);
    assert_eq!(made, doc);
    assert!(errors[0].contains("no-such-figure"), "{errors:?}");
    let (_, errors) = regenerate("<!-- generated: bars x -->\n");
    assert!(errors[0].contains("unclosed"), "{errors:?}");
}
