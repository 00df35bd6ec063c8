//! The facade's teaching calls on the `Race` handle, called as the page
//! calls them (config objects from JSON, answers read back as JS objects):
//! phase stepping, the tree, the timeline and seeking, paired trials. In
//! Node.js: `cargo test --target wasm32-unknown-unknown --test suite wasm_teach::`.
#![cfg(target_arch = "wasm32")]

use torus_search::wasm::{self as facade, RaceHandle as Race};
use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

fn js(json: &str) -> JsValue {
    js_sys::JSON::parse(json).expect("valid JSON")
}

fn get(obj: &JsValue, key: &str) -> JsValue {
    js_sys::Reflect::get(obj, &JsValue::from_str(key)).expect("property")
}

fn num(obj: &JsValue, key: &str) -> f64 {
    get(obj, key)
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number"))
}

fn text(obj: &JsValue, key: &str) -> Option<String> {
    get(obj, key).as_string()
}

fn message(e: wasm_bindgen::JsError) -> String {
    let v: JsValue = e.into();
    js_sys::Error::from(v).message().as_string().unwrap()
}

fn ok<T>(r: Result<T, wasm_bindgen::JsError>) -> T {
    r.map_err(JsValue::from).unwrap()
}

const CONFIG: &str = r#"{"n":16,"sigma":3,"loops":10,"variant":"tree","seed":"4"}"#;

fn race(json: &str) -> Race {
    ok(Race::new(js(&format!("[{json}]"))))
}

fn path(r: &Race) -> JsValue {
    let runs = js_sys::Array::from(&ok(r.export()));
    get(&runs.get(0), "path")
}

fn same(a: &JsValue, b: &JsValue) -> bool {
    js_sys::JSON::stringify(a).unwrap() == js_sys::JSON::stringify(b).unwrap()
}

#[wasm_bindgen_test]
fn phases_come_in_order_and_the_frame_shows_them() {
    let mut r = race(CONFIG);
    let order = ["select", "expand", "rollout", "backup"];
    for i in 0..12 {
        let steps = js_sys::Array::from(&ok(r.step_phase()));
        let s = steps.get(0);
        assert_eq!(text(&s, "did").as_deref(), Some("phase"));
        assert_eq!(text(&s, "phase").as_deref(), Some(order[i % 4]));
        let frames = js_sys::Array::from(&ok(r.frames(js("[{}]"))));
        let f = frames.get(0);
        let phase = get(&f, "phase");
        assert_eq!(text(&phase, "phase").as_deref(), Some(order[i % 4]));
        let point = get(&f, "point");
        assert_eq!(num(&point, "loop"), (i / 4) as f64);
        assert_eq!(text(&point, "phase").as_deref(), Some(order[i % 4]));
        if i % 4 == 2 {
            // The rollout's cells, revealed in chunks.
            let cells = js_sys::Uint8Array::new(&get(&phase, "rollout")).length() / 4;
            assert_eq!(cells as f64, num(&phase, "rollout_steps"));
        }
    }
    let t = ok(r.timeline());
    assert_eq!((num(&t, "move"), num(&t, "loop")), (0.0, 2.0));
}

#[wasm_bindgen_test]
fn the_tree_counts_match_the_decision_panel() {
    let mut r = race(CONFIG);
    for _ in 0..6 {
        r.step_loop();
    }
    let tree = ok(r.tree(0.0, JsValue::UNDEFINED));
    assert_eq!(text(&tree, "shape").as_deref(), Some("tree"));
    let nodes = js_sys::Array::from(&get(&tree, "nodes"));
    let root = nodes.get(0);
    assert!(get(&root, "parent").is_null() && get(&root, "move").is_null());
    assert_eq!(num(&root, "visits"), 6.0);
    let frames = js_sys::Array::from(&ok(r.frames(js("[{}]"))));
    let decision = get(&frames.get(0), "decision");
    assert_eq!(num(&decision, "parent_visits"), 6.0);
    let children = js_sys::Array::from(&get(&decision, "children"));
    let mut sum = 0.0;
    for n in nodes
        .iter()
        .filter(|n| get(n, "parent").as_f64() == Some(0.0))
    {
        let m = ["up", "right", "down", "left"]
            .iter()
            .position(|&m| text(&n, "move").as_deref() == Some(m))
            .unwrap();
        let ch = children.get(m as u32);
        assert_eq!(num(&n, "visits"), num(&ch, "visits"));
        assert_eq!(num(&n, "picks"), num(&ch, "selected"));
        // A root child's UCT split is the decision panel's.
        for k in ["mean", "explore", "uct"] {
            assert_eq!(num(&n, k), num(&ch, k), "{k}");
        }
        sum += num(&n, "visits");
    }
    assert_eq!(sum, 6.0);
    // Columns hold the same nodes.
    let cols = ok(r.tree_columns(0.0, js(r#"{"max_nodes": 3}"#)));
    assert_eq!(js_sys::Uint32Array::new(&get(&cols, "visits")).length(), 3);
    assert_eq!(
        js_sys::Int32Array::new(&get(&cols, "parent")).get_index(0),
        -1
    );
    // The split's columns: NaN at the root, the terms adding up below it.
    let col = |k: &str| js_sys::Float64Array::new(&get(&cols, k)).to_vec();
    let (mean, explore, uct) = (col("mean"), col("explore"), col("uct"));
    assert!(mean[0].is_nan() && explore[0].is_nan() && uct[0].is_nan());
    for i in 1..3 {
        assert_eq!(uct[i], mean[i] + explore[i]);
    }
    // Bad queries name what is wrong.
    let e = message(r.tree(0.0, js(r#"{"focus": 999}"#)).unwrap_err());
    assert!(e.contains("node 999") && e.contains("0..="), "{e}");
    assert!(message(r.tree(2.0, JsValue::NULL).unwrap_err()).contains("run must be"));
    assert!(message(r.tree(0.0, js(r#"{"maxNodes": 3}"#)).unwrap_err()).contains("maxNodes"));
}

#[wasm_bindgen_test]
fn seeking_back_then_forward_gives_the_same_path() {
    let mut r = race(CONFIG);
    for _ in 0..6 {
        r.step_move();
    }
    for _ in 0..5 {
        ok(r.step_phase());
    }
    let end = ok(r.timeline());
    let forward = path(&r);
    let frames = |r: &mut Race| js_sys::Array::from(&ok(r.frames(js("[{}]")))).get(0);
    let at_end = frames(&mut r);
    let back = ok(r.seek(js(r#"{"move": 2, "loop": 3, "phase": "rollout"}"#)));
    assert_eq!((num(&back, "move"), num(&back, "loop")), (2.0, 3.0));
    assert_eq!(js_sys::Array::from(&path(&r)).length(), 3);
    ok(r.seek(js(&format!(
        r#"{{"move": {}, "loop": {}, "phase": "{}"}}"#,
        num(&end, "move"),
        num(&end, "loop"),
        text(&end, "phase").unwrap()
    ))));
    assert!(same(&path(&r), &forward));
    let again = frames(&mut r);
    for key in ["decision", "point", "rollouts", "rollout_steps"] {
        assert!(same(&get(&again, key), &get(&at_end, key)), "{key}");
    }
    // Bad points: an error naming the value and the range, nothing moves.
    for (point, words) in [
        (
            r#"{"move": 99}"#,
            vec!["move 99", "past the end", "up to move 6"],
        ),
        (r#"{"move": -1}"#, vec!["move must be", "-1"]),
        (r#"{"move": 1.5}"#, vec!["move must be", "1.5"]),
        (
            r#"{"move": 1, "phase": "think"}"#,
            vec!["phase must be", "think"],
        ),
        (r#"{"move": 1, "loop": 10}"#, vec!["loop 10", "loops 0..=9"]),
        (r#"{"mv": 1}"#, vec!["mv"]),
    ] {
        let e = message(r.seek(js(point)).unwrap_err());
        for w in words {
            assert!(e.contains(w), "{point}: {e}");
        }
        assert!(same(&path(&r), &forward), "{point} moved the run");
    }
}

#[wasm_bindgen_test]
fn paired_trials_share_targets_and_summarise() {
    let a = js(CONFIG);
    let b = js(r#"{"n":16,"sigma":3,"loops":10,"variant":"tree","seed":"4","rollout":"levy"}"#);
    let mut flat = Vec::new();
    for i in 0..6 {
        let t = ok(facade::run_paired_trial(a.clone(), b.clone(), i as f64));
        assert_eq!(t.len(), 14);
        assert_eq!(t[3], t[7 + 3], "the same target");
        flat.extend(t);
    }
    let s = ok(facade::summarize_paired(&flat));
    assert_eq!(num(&s, "trials"), 6.0);
    assert_eq!(num(&s, "a_wins") + num(&s, "ties") + num(&s, "b_wins"), 6.0);
    assert!(message(facade::summarize_paired(&flat[..13]).unwrap_err()).contains("14-number"));
    let d = js_sys::Array::from(&ok(facade::config_differences(a.clone(), b.clone())));
    assert_eq!(d.length(), 1);
    assert_eq!(text(&d.get(0), "key").as_deref(), Some("rollout"));
    let other = js(r#"{"n":16,"sigma":3,"seed":"5"}"#);
    let e = message(facade::run_paired_trial(a, other, 0.0).unwrap_err());
    assert!(
        e.contains("different targets") && e.contains("seed 4 ≠ 5"),
        "{e}"
    );
}

#[wasm_bindgen_test]
fn branching_keeps_the_path_so_far_and_names_bad_values() {
    let mut r = race(CONFIG);
    for _ in 0..6 {
        r.step_move();
    }
    let before = js_sys::Array::from(&path(&r));
    let changed = r#"{"n":16,"sigma":3,"loops":10,"variant":"tree","seed":"4","c":0.3}"#;
    let world = r#"{"n":17,"sigma":3,"loops":10,"variant":"tree","seed":"4","c":0.3}"#;
    assert!(ok(facade::branch_check(js(CONFIG), js(changed))).is_none());
    let why = ok(facade::branch_check(js(CONFIG), js(world))).unwrap();
    assert!(
        why.starts_with("n cannot change in a branch (16 → 17)"),
        "{why}"
    );
    // Bad values name themselves and the range; the runs stay as they were.
    for (configs, at, words) in [
        (format!("[{world}]"), 3.0, "n cannot change"),
        (format!("[{changed}]"), 9.0, "allowed moves 0 to 6"),
        (
            format!("[{changed}]"),
            1.5,
            "must be an integer in 0..=4294967295, got 1.5",
        ),
        (format!("[{changed},{changed}]"), 3.0, "2 given for 1 runs"),
    ] {
        let e = message(r.branch(js(&configs), at).unwrap_err());
        assert!(e.contains(words), "{configs} at {at}: {e}");
        assert!(same(&path(&r), &before), "{configs} at {at} moved the run");
    }
    let runs = js_sys::Array::from(&ok(r.branch(js(&format!("[{changed}]")), 3.0)));
    let lineage = js_sys::Array::from(&get(&runs.get(0), "lineage"));
    assert_eq!(lineage.length(), 1);
    assert_eq!(num(&lineage.get(0), "move"), 3.0);
    assert_eq!(num(&get(&lineage.get(0), "config"), "c"), 2.0_f64.sqrt());
    assert!(same(&path(&r), &before.slice(0, 4)));
    let t = ok(r.timeline());
    assert_eq!((num(&t, "move"), num(&t, "loop")), (3.0, 0.0));
}
