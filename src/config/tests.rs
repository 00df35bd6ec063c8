//! The configuration's tests: text and JSON round trips, errors that name
//! the key and range, and which parameters apply where.

use super::*;
use crate::game::prior::{self, PriorKind};
use crate::searchers::mcts::FinalRule;

#[test]
fn from_json_names_the_key_at_fault() {
    let ok = from_json(serde_json::json!({"n": 12, "final": "mean"})).unwrap();
    assert_eq!(
        (
            ok.n,
            ok.settings
                .choice::<crate::searchers::mcts::uct::FinalRule>(
                    &crate::searchers::mcts::search::FINAL
                )
        ),
        (12, FinalRule::Mean)
    );
    let e = from_json(serde_json::json!({"tree_nodes": "xxx"})).unwrap_err();
    assert_eq!(e.field, "tree_nodes");
    assert!(e.to_string().contains("an integer in"), "{e}");
    let e = from_json(serde_json::json!({"n": {"n": 3}})).unwrap_err();
    assert_eq!(e.field, "n");
    let e = from_json(serde_json::json!({"__proto__": {"polluted": 1}})).unwrap_err();
    assert!(e.to_string().contains("__proto__"), "{e}");
    let e = from_json(serde_json::json!({"n": 2})).unwrap_err();
    assert_eq!((e.field, e.value.as_str()), ("n", "2"));
    assert_eq!(
        from_json(serde_json::json!([1])).unwrap_err().field,
        "config"
    );
}

#[test]
fn default_is_valid_and_every_field_has_a_parameter() {
    let d = Config::default();
    d.validate().unwrap();
    let text = serde_json::to_string(&d).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut fields: Vec<&String> = json.as_object().unwrap().keys().collect();
    let mut keys: Vec<&str> = params().iter().map(|p| p.param().key).collect();
    // In schema order in the text.
    let at: Vec<usize> = keys
        .iter()
        .map(|k| text.find(&format!("\"{k}\":")).unwrap())
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{text}");
    fields.sort();
    keys.sort();
    assert_eq!(fields, keys, "the JSON lists every parameter");
    for e in params() {
        let p = e.param();
        assert_eq!(e.value(&d), p.default, "{}", p.key);
        // The default's text reads back as the default.
        assert_eq!(p.parse(&p.default.text()).unwrap(), p.default, "{}", p.key);
    }
}

#[test]
fn errors_name_the_field_and_range() {
    let bad = |key: &str, raw: &str| Config::default().set(key, raw).unwrap_err();
    assert_eq!(
        bad("n", "0").to_string(),
        "n must be an integer in 3..=1024, got 0"
    );
    assert_eq!(bad("mu", "1").field, "mu");
    assert_eq!(bad("sigma", "NaN").field, "sigma");
    assert_eq!(bad("sigma", "-1").field, "sigma");
    assert_eq!(bad("loops", "0").field, "loops");
    assert_eq!(bad("rv", "-1").field, "rv");
    assert!(bad("searcher", "astar")
        .allowed
        .starts_with("one of mcts, rw, levy, nsarw"));
    assert_eq!(
        bad("seed", "18446744073709551616").to_string(),
        "seed must be an integer in 0..=18446744073709551615, got 18446744073709551616"
    );
    assert_eq!(bad("nope", "1").field, "parameter");
    let e = Config {
        start: [41, 1],
        ..Config::default()
    }
    .validate()
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "start must be x,y with each in 1..=40, got 41,1"
    );
    let e = Config {
        prior: PriorKind::Paint,
        paint: "AAA".into(),
        ..Config::default()
    }
    .validate()
    .unwrap_err();
    assert_eq!(e.field, "paint");
}

#[test]
fn text_round_trips_and_ranges_are_inclusive() {
    let mut c = Config::default();
    for (k, v) in [
        ("n", "1024"),
        ("sigma", "inf"),
        ("ms", "0.001"),
        ("mu", "3"),
        ("seed", "18446744073709551615"),
        ("target", "3,4"),
        ("known", "true"),
        ("c", "0"),
    ] {
        c.set(k, v).unwrap();
    }
    c.validate().unwrap();
    let back = from_params(c.params(true).iter().map(|(k, v)| (*k, v.as_str())));
    assert_eq!(back, (c.clone(), vec![]));
    assert_eq!(c.get("known").unwrap(), "1");
    assert_eq!(c.get("ms").unwrap(), "0.001");
    c.set("ms", "0").unwrap();
    assert_eq!(
        c.settings.opt_float(&crate::searchers::mcts::search::MS),
        None
    );
    // JSON keeps the seed and infinity exact.
    let json = serde_json::to_string(&c).unwrap();
    assert!(json.contains("\"seed\":\"18446744073709551615\""), "{json}");
    assert!(json.contains("\"sigma\":\"inf\""), "{json}");
    assert_eq!(serde_json::from_str::<Config>(&json).unwrap(), c);
    assert!(serde_json::from_str::<Config>(r#"{"seed":-1}"#).is_err());
    assert!(serde_json::from_str::<Config>(r#"{"seed":1e300}"#).is_err());
    assert_eq!(
        serde_json::from_str::<Config>(r#"{"seed":7}"#)
            .unwrap()
            .seed,
        7
    );
}

#[test]
fn url_parsing_keeps_good_values_and_defaults_bad_ones() {
    let (c, errs) = from_params([("n", "10"), ("start", "11,1"), ("loops", "x"), ("c", "2")]);
    assert_eq!(c.n, 10);
    assert_eq!(c.settings.float(&crate::searchers::mcts::search::C), 2.0);
    assert_eq!(c.start, [1, 1], "start outside the lattice falls back");
    assert_eq!(c.settings.u32(&crate::searchers::mcts::search::LOOPS), 100);
    let fields: Vec<_> = errs.iter().map(|e| e.field).collect();
    assert_eq!(fields, ["loops", "start"]);
    // prior=paint without a painting falls back to the default prior.
    let (c, errs) = from_params([("prior", "paint")]);
    assert_eq!((c.prior, errs[0].field), (PriorKind::Gaussian, "prior"));
    // Only differing values are written (applying or not), the seed always.
    assert_eq!(
        Config::default().params(false),
        vec![("seed", "1".to_string())]
    );
    let rw = from_params([("searcher", "rw"), ("c", "3")]).0;
    // Schema order: every game field (searcher, seed) before the searchers' parameters.
    let pairs = vec![
        ("searcher", "rw".into()),
        ("seed", "1".into()),
        ("c", "3".into()),
    ];
    assert_eq!(rw.params(false), pairs);
}

#[test]
fn edit_moves_cells_and_paint_into_a_new_lattice() {
    let mut c = Config {
        start: [30, 40],
        prior: PriorKind::Paint,
        paint: prior::encode_paint(&[3; 1600]),
        ..Config::default()
    };
    c.validate().unwrap();
    c.edit("n", "20").unwrap();
    assert_eq!(c.start, [20, 20]);
    assert_eq!(prior::decode_paint(&c.paint, 20).unwrap(), vec![3; 400]);
    c.validate().unwrap();
}

#[test]
fn the_mcts_parameters_apply_by_variant_and_rollout() {
    // The CLI refuses a flag that does not apply and the page hides its
    // control, so each of these must apply exactly where the searcher
    // reads it. Columns: reset_each_move, tree_nodes, decay, the four
    // pomcp_ parameters, final, rollout, then mu under a Lévy rollout
    // and epsilon under a greedy one (each false under the other).
    let keys = [
        "reset_each_move",
        "tree_nodes",
        "decay",
        "pomcp_scale",
        "pomcp_exact",
        "pomcp_depth",
        "pomcp_plan",
        "final",
        "rollout",
    ];
    let table = [
        (
            "cells",
            [true, false, true, false, false, false, false, true, true],
            true,
        ),
        (
            "tree",
            [false, true, false, false, false, false, false, true, true],
            true,
        ),
        (
            "code",
            [true, false, false, false, false, false, false, true, true],
            true,
        ),
        (
            "pomcp",
            [false, true, false, true, true, true, true, false, false],
            false,
        ),
    ];
    for (variant, applies, reads_policy) in table {
        for (rollout, mu, epsilon) in [
            ("levy", reads_policy, false),
            ("greedy", false, reads_policy),
            ("rw", false, false),
            ("nsarw", false, false),
        ] {
            let c = Config::default().with(&[("variant", variant), ("rollout", rollout)]);
            let a = c.applicable();
            assert_eq!(keys.map(|k| a.contains(&k)), applies, "{variant} {rollout}");
            assert_eq!(
                (a.contains(&"mu"), a.contains(&"epsilon")),
                (mu, epsilon),
                "{variant} {rollout}"
            );
            // What every variant reads.
            for k in ["variant", "c", "rollout_cap", "escape", "loops"] {
                assert!(a.contains(&k), "{variant} {rollout} {k}");
            }
        }
        // A time budget replaces the loop count.
        let timed = Config::default().with(&[("variant", variant), ("ms", "5")]);
        assert!(!timed.applicable().contains(&"loops"), "{variant}");
    }
}

#[test]
fn applicability_follows_the_searcher() {
    let mut c = Config::default();
    assert!(c.applicable().contains(&"c"));
    assert!(!c.applicable().contains(&"mu"));
    c.set("rollout", "levy").unwrap();
    assert!(c.applicable().contains(&"mu"));
    c.set("searcher", "rw").unwrap();
    let a = c.applicable();
    assert!(!a.contains(&"c") && !a.contains(&"mu") && !a.contains(&"loops"));
    c.set("searcher", "levy").unwrap();
    assert!(c.applicable().contains(&"mu"));
    c.set("prior", "uniform").unwrap();
    assert!(!c.applicable().contains(&"sigma"));
    // The planners: rollout improvement reads the horizon only through
    // a base that plays the horizon rule.
    let planner_keys = [
        "horizon",
        "base",
        "beam_width",
        "beam_depth",
        "sweep_pattern",
    ];
    let uses = |c: &Config| {
        let a = c.applicable();
        planner_keys.map(|k| a.contains(&k))
    };
    c.set("searcher", "horizon").unwrap();
    assert_eq!(uses(&c), [true, false, false, false, false]);
    c.set("searcher", "beam").unwrap();
    assert_eq!(uses(&c), [true, false, true, true, false]);
    c.set("searcher", "sweep").unwrap();
    assert_eq!(uses(&c), [false, false, false, false, true]);
    c.set("searcher", "improve").unwrap();
    for (base, horizon) in [
        ("cover", false),
        ("sweep", false),
        ("horizon", true),
        ("best", true),
    ] {
        c.set("base", base).unwrap();
        assert_eq!(
            uses(&c),
            [horizon, true, false, false, false],
            "base {base}"
        );
    }
}
