//! The registry's promise: a searcher is one file plus one registry line.
//! `SHUTTLE` below stands for such a file (registered only in tests), with
//! a parameter of its own; everything else about it must follow from the
//! registry: the configuration, the CLI flag, the URL key, the JSON field,
//! the schema the page builds its controls from, episodes, frames and
//! batches.

use super::info::{Reads, SearcherInfo};
use super::registry::{names, SearcherId};
use super::searcher::{Searcher, World};
use crate::config::{self, Config};
use crate::display::view::{FrameBuilder, FrameRequest};
use crate::game::lattice::{Move, Torus};
use crate::param::{Param, ParamKind, Value};
use crate::run::episode::{Episode, Status};

/// How far the shuttle goes before it turns.
static SPAN: Param = Param {
    key: "shuttle_span",
    label: "Shuttle span",
    kind: ParamKind::Int { min: 1, max: 8 },
    default: Value::Int(1),
    help: "moves up before turning down, and back",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// Shuttles up `span` moves and back down: the simplest searcher that is
/// not a walk.
struct Shuttle {
    span: u32,
    made: u32,
}

impl Searcher for Shuttle {
    fn think(&mut self, _w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        let up = self.made % (2 * self.span) < self.span;
        self.made += 1;
        Some(if up { Move::Up } else { Move::Down })
    }
    fn observe(&mut self, _torus: &Torus, _m: Move, _pos: u32) {}
}

pub static SHUTTLE: SearcherInfo = SearcherInfo {
    name: "test-shuttle",
    label: "Shuttle (test)",
    help: "steps up, then down, for ever",
    deterministic: true,
    deliberates: false,
    params: &[Reads::always(&SPAN)],
    build: |s| {
        Box::new(Shuttle {
            span: s.settings.u32(&SPAN),
            made: 0,
        })
    },
};

#[test]
fn a_registered_searcher_reaches_every_surface() {
    // The configuration accepts its name and its parameter, from text and
    // from JSON.
    let cfg = Config::default().with(&[
        ("searcher", "test-shuttle"),
        ("shuttle_span", "3"),
        ("step_cap", "13"),
    ]);
    cfg.validate().unwrap();
    let json = serde_json::to_value(&cfg).unwrap();
    assert_eq!(json["shuttle_span"], 3);
    assert_eq!(serde_json::from_value::<Config>(json).unwrap(), cfg);
    // The URL's parser takes the key, and writes it back.
    let (url, errors) = config::from_params([("searcher", "test-shuttle"), ("shuttle_span", "3")]);
    assert!(errors.is_empty(), "{errors:?}");
    assert!(url
        .params(false)
        .contains(&("shuttle_span", "3".to_string())));
    // The CLI has its flag, checks its range, and refuses it for a searcher
    // that does not read it.
    #[cfg(not(target_arch = "wasm32"))]
    {
        let run = crate::cli::run_config;
        let cli = run(&["--searcher", "test-shuttle", "--shuttle-span", "3"]);
        assert_eq!(cli.unwrap().get("shuttle_span").unwrap(), "3");
        let e = run(&["--searcher", "test-shuttle", "--shuttle-span", "9"]).unwrap_err();
        assert!(
            e.contains("--shuttle-span must be an integer in 1..=8"),
            "{e}"
        );
        let e = run(&["--shuttle-span", "3"]).unwrap_err();
        assert!(e.contains("does not apply"), "{e}");
    }
    // The schema (which the page builds its controls from) lists the
    // searcher and its parameter, labelled, in its group; the parameter
    // applies to it alone.
    let schema = config::schema();
    let summary = schema
        .searchers
        .iter()
        .find(|s| s.name == "test-shuttle")
        .unwrap();
    assert_eq!(summary.params, ["shuttle_span"]);
    let searcher = schema.params.iter().find(|p| p.key == "searcher").unwrap();
    assert!(searcher.choices.as_ref().unwrap().contains(&"test-shuttle"));
    let span = schema
        .params
        .iter()
        .find(|p| p.key == "shuttle_span")
        .unwrap();
    assert_eq!(
        (span.label, span.group, span.kind),
        ("Shuttle span", "test-shuttle", "int")
    );
    assert_eq!(
        (span.min.as_deref(), span.max.as_deref()),
        (Some("1"), Some("8"))
    );
    assert!(cfg.applicable().contains(&"shuttle_span"));
    assert!(!cfg.applicable().contains(&"loops"));
    assert!(!Config::default().applicable().contains(&"shuttle_span"));
    assert_eq!(cfg.label(), "Shuttle (test)");
    // An episode runs it with its parameter to the step cap, and frames show it.
    let mut ep = Episode::new(&cfg).unwrap();
    let r = ep.run();
    assert_eq!(ep.status(), Status::Capped);
    assert_eq!(r.steps, 13);
    let path = ep.path();
    assert_eq!(path[6], path[0], "three up then three down returns");
    assert_ne!(path[2], path[0]);
    let mut fb = FrameBuilder::new(ep.torus().cells());
    let frame = fb.frame(&ep, &FrameRequest::default(), 0.0);
    assert!(frame.decision.is_none());
    assert_eq!(frame.steps, 13);
    // Batches and fingerprints take it like any other.
    assert_eq!(crate::run::batch::run_trials(&cfg, 0, 2).unwrap().len(), 2);
}

#[test]
fn registry_names_are_unique_and_parse() {
    let names = names();
    for (i, n) in names.iter().enumerate() {
        assert!(!names[..i].contains(n), "{n} registered twice");
        assert_eq!(SearcherId::parse(n).unwrap().info().name, *n);
    }
    assert!(SearcherId::parse("astar").is_none());
}

#[test]
fn parameter_keys_are_unique_and_every_searcher_builds_from_the_defaults() {
    let keys: Vec<&str> = config::params().iter().map(|p| p.param().key).collect();
    for (i, k) in keys.iter().enumerate() {
        assert!(!keys[..i].contains(k), "parameter {k} is declared twice");
    }
    // A choice's labels, where given, name each of its values.
    for e in config::params() {
        let p = e.param();
        if let ParamKind::Choice(names) = p.kind {
            let n = p.choice_labels.len();
            assert!(n == 0 || n == names().len(), "{}: {n} labels", p.key);
        } else {
            assert!(p.choice_labels.is_empty(), "{}", p.key);
        }
    }
    // Each searcher reads its parameters as their kinds say (a read of the
    // wrong kind fails in debug builds) and runs a few moves.
    for name in names() {
        let cfg = Config::default().with(&[("searcher", name), ("n", "12"), ("loops", "3")]);
        let mut ep = Episode::new(&cfg).unwrap();
        for _ in 0..3 {
            ep.step_move();
        }
    }
}
