//! The checker's own helpers: what it extracts, how it cuts the work, and
//! that a doc with an unknown flag or a bad value fails it.

use super::cut::value_of;
use super::markdown::slug;
use super::*;

fn words(list: &[&str]) -> Vec<String> {
    list.iter().map(|w| w.to_string()).collect()
}

const DOC: &str = r#"Inline `torus-search run --n 5` is not run.

```sh
torus-search run --n 40 \
  --sigma 5   # a comment
cargo run --release -- bench --json
echo torus-search run --not-a-command
  torus-search experiment delta --out 'my dir/' && torus-search merge x
SHARDS=8
torus-search experiment delta --shard "${SLURM_ARRAY_TASK_ID}/${SHARDS}" --series 'A B:c=2'
```

```
torus-search run --seed {} ::: $(seq 1 3)
torus-search run --seed $NOBODY
```
"#;

#[test]
fn extraction_reads_continuations_comments_quotes_and_variables() {
    let (cmds, bad) = commands("d.md", DOC);
    let got: Vec<(usize, Vec<String>)> = cmds.into_iter().map(|c| (c.line, c.args)).collect();
    assert_eq!(
        got,
        vec![
            (4, words(&["run", "--n", "40", "--sigma", "5"])),
            (6, words(&["bench", "--json"])),
            (8, words(&["experiment", "delta", "--out", "my dir/"])),
            (
                10,
                words(&[
                    "experiment",
                    "delta",
                    "--shard",
                    "1/8",
                    "--series",
                    "A B:c=2"
                ])
            ),
            (14, words(&["run", "--seed", "1"])),
        ]
    );
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert_eq!(bad[0].line, 15);
    assert!(bad[0].what.contains("$NOBODY"), "{}", bad[0]);
}

fn cut_of(tmp: &Path) -> Vec<Vec<String>> {
    let targets: BTreeSet<String> = ["priors".to_string()].into();
    let cut = Cut {
        tmp,
        targets_only: &targets,
    };
    let cases: &[&[&str]] = &[
        &["run", "--trials", "1000", "--n", "40"],
        &["run", "--n", "40"],
        &["run", "--trials", "ten"],
        &["run", "--trials=0"],
        &["run", "--searcher", "beam", "--exact"],
        &[
            "experiment",
            "delta",
            "--trials",
            "100",
            "--out",
            "results/",
        ],
        &["experiment", "priors"],
        &["experiment", "delta", "--step-cap", "big"],
        &["experiment", "--list"],
        &["bench", "--json"],
        &["bench", "--scale", "-1"],
    ];
    cases.iter().flat_map(|c| cheap(&words(c), &cut)).collect()
}

#[test]
fn the_cut_cuts_work_but_leaves_bad_values_to_the_cli() {
    let tmp = Path::new("/tmp/x");
    let got = cut_of(tmp);
    let results = tmp.join("results/").display().to_string();
    let dot = tmp.join(".").display().to_string();
    let want: Vec<Vec<String>> = [
        &["run", "--trials", "2", "--n", "40"][..],
        &["run", "--n", "40", "--trials", "2"],
        &["run", "--trials", "ten"],
        &["run", "--trials=0"],
        &["run", "--searcher", "beam", "--exact"],
        &[
            "experiment",
            "delta",
            "--trials",
            "1",
            "--out",
            &results,
            "--step-cap",
            "100",
        ],
        &["experiment", "priors", "--trials", "1", "--out", &dot],
        &[
            "experiment",
            "delta",
            "--step-cap",
            "big",
            "--trials",
            "1",
            "--out",
            &dot,
        ],
        &["experiment", "--list"],
        &["bench", "--json", "--scale", "0.01"],
        &["bench", "--scale", "-1"],
    ]
    .iter()
    .map(|c| words(c))
    .collect();
    assert_eq!(got, want);
}

#[test]
fn a_shard_becomes_every_shard_and_a_merge_reads_them_back() {
    let tmp = scratch("unit-shards");
    let targets = BTreeSet::new();
    let cut = Cut {
        tmp: &tmp,
        targets_only: &targets,
    };
    let shards = cheap(
        &words(&["experiment", "delta", "--shard", "2/3", "--out", "s/"]),
        &cut,
    );
    let given: Vec<String> = shards
        .iter()
        .map(|a| value_of(a, "--shard").expect("a shard").1)
        .collect();
    assert_eq!(given, ["1/3", "2/3", "3/3"]);
    std::fs::create_dir_all(tmp.join("s")).unwrap();
    for f in [
        "delta.shard-2-of-3.json",
        "delta.shard-1-of-3.json",
        "other.json",
    ] {
        std::fs::write(tmp.join("s").join(f), "{}").unwrap();
    }
    let merge = cheap(
        &words(&["merge", "s/delta.shard-*-of-3.json", "--out", "r/"]),
        &cut,
    );
    let s = |f: &str| tmp.join("s").join(f).display().to_string();
    let r = tmp.join("r/").display().to_string();
    assert_eq!(
        merge,
        vec![vec![
            "merge".to_string(),
            s("delta.shard-1-of-3.json"),
            s("delta.shard-2-of-3.json"),
            "--out".into(),
            r
        ]]
    );
    let _ = std::fs::remove_dir_all(&tmp);
}

/// The whole check, over a doc with one good command and five that must
/// fail: an unknown flag, bad values (one of them a value the cut would
/// otherwise replace), an unknown subcommand and an unknown name.
#[test]
fn a_doc_with_an_unknown_flag_or_a_bad_value_fails_the_check() {
    let doc = "```sh\n\
               torus-search run --n 10 --sigma 2 --trials 500\n\
               torus-search run --n 10 --no-such-flag 3\n\
               torus-search run --n 0\n\
               torus-search run --n 10 --trials ten\n\
               torus-search walk --n 10\n\
               cargo run --release -- run --searcher nobody\n\
               ```\n";
    let bad = check_doc("bad.md", doc, "unit-bad", &BTreeSet::new());
    let lines: Vec<usize> = bad.iter().map(|f| f.line).collect();
    assert_eq!(lines, [3, 4, 5, 6, 7], "{bad:#?}");
    assert!(bad[0].what.contains("--no-such-flag"), "{}", bad[0]);
    assert!(bad[1].what.contains("--n must be"), "{}", bad[1]);
    assert!(bad[2].what.contains("--trials"), "{}", bad[2]);
    let good = check_doc(
        "good.md",
        "```\ntorus-search run --n 10 --trials 500\n```\n",
        "unit-good",
        &BTreeSet::new(),
    );
    assert!(good.is_empty(), "{good:?}");
}

#[test]
fn make_targets_are_read_from_the_makefile_and_unknown_ones_fail() {
    let makefile = "SHELL := bash\n.PHONY: a b\nX ?= 1\nhelp:\n\t@echo\nbuild: setup _build\n_build:\nserve test: build\n\tthing: not a target\n";
    let targets = make_targets(makefile);
    assert_eq!(
        targets,
        ["_build", "build", "help", "serve", "test"]
            .map(String::from)
            .into()
    );
    let doc = "Run `make serve`, or `make -j2 test X=1`, `make nope`.\n\n```sh\nmake build   # comment\nmake lint\n```\n";
    let bad = unknown_make_targets("d.md", doc, &targets);
    let got: Vec<(usize, &str)> = bad.iter().map(|f| (f.line, f.what.as_str())).collect();
    assert_eq!(got.len(), 2, "{got:?}");
    assert_eq!(got[0].0, 5);
    assert!(got[0].1.ends_with("no target lint"), "{}", got[0].1);
    assert_eq!(got[1].0, 1);
    assert!(got[1].1.ends_with("no target nope"), "{}", got[1].1);
}

#[test]
fn inline_commands_may_only_name_flags_the_help_lists() {
    let doc = "See `torus-search run --n N --exact`, `torus-search run --nope`,\n\
               `torus-search walk`, `cargo run --release -- bench --json`, `cargo run --release -- ARGS`.\n\
               ```\ntorus-search run --fenced-is-run-not-listed\n```\n";
    let mut help = |sub: &str| match sub {
        "run" => Some(["--n", "--exact"].map(String::from).into()),
        "bench" => Some(["--json"].map(String::from).into()),
        _ => None,
    };
    let bad = unknown_inline_flags("d.md", doc, &mut help);
    let got: Vec<String> = bad.iter().map(|f| f.to_string()).collect();
    assert_eq!(got.len(), 2, "{got:?}");
    assert!(got[0].contains("lists no --nope"), "{}", got[0]);
    assert!(got[1].contains("no subcommand walk"), "{}", got[1]);
}

#[test]
fn links_lead_to_files_and_headings_that_exist() {
    assert_eq!(
        slug(" Two readings: `paper-text` and `paper-code`"),
        "two-readings-paper-text-and-paper-code"
    );
    assert_eq!(slug("The project's searchers"), "the-projects-searchers");
    let root = scratch("unit-links");
    std::fs::create_dir_all(root.join("docs")).unwrap();
    let b = "# B\n\n## Some part\n\n```\n# not a heading\n```\n";
    std::fs::write(root.join("docs/b.md"), b).unwrap();
    let doc = "# A\n\nSee [b](b.md), [part](b.md#some-part), [self](#a),\n\
               [web](https://example.org/x), [gone](c.md), [no](b.md#not-a-heading), [here](#nope).\n";
    std::fs::write(root.join("docs/a.md"), doc).unwrap();
    let bad = broken_links(&root, "docs/a.md", doc);
    let got: Vec<String> = bad.iter().map(|f| f.to_string()).collect();
    assert_eq!(got.len(), 3, "{got:#?}");
    assert!(got[0].contains("no file docs/c.md"), "{}", got[0]);
    assert!(
        got[1].contains("has no heading #not-a-heading"),
        "{}",
        got[1]
    );
    assert!(got[2].contains("has no heading #nope"), "{}", got[2]);
    let _ = std::fs::remove_dir_all(&root);
}
