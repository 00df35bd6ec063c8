//! Facade tests: the `#[wasm_bindgen]` handles in `src/wasm.rs`, called the
//! way the page calls them (config objects parsed from JSON), in headless
//! Chromium. Run with `cargo test --target wasm32-unknown-unknown`
//! (CHROMEDRIVER=/usr/bin/chromedriver; `make test` wires it up).
#![cfg(target_arch = "wasm32")]

use torus_search::config::Config;
use torus_search::episode::Episode as CoreEpisode;
use torus_search::wasm::{self as facade, EpisodeHandle as Episode};
use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

fn js(json: &str) -> JsValue {
    js_sys::JSON::parse(json).expect("valid JSON")
}

fn get(obj: &JsValue, key: &str) -> JsValue {
    js_sys::Reflect::get(obj, &JsValue::from_str(key)).expect("property")
}

fn small() -> JsValue {
    js(r#"{"n":15,"prior":{"kind":"gaussian","sigma":3},"loops":20,"keep_traces":2}"#)
}

/// Reads `len` u32 values at byte offset `ptr` of this module's own memory.
fn u32s(ptr: u32, len: u32) -> Vec<u32> {
    // SAFETY: the facade returned a pointer into a live buffer of that length,
    // and no facade call has happened since.
    unsafe { std::slice::from_raw_parts(ptr as *const u32, len as usize).to_vec() }
}

fn bytes(ptr: u32, len: usize) -> Vec<u8> {
    // SAFETY: as above.
    unsafe { std::slice::from_raw_parts(ptr as *const u8, len).to_vec() }
}

#[wasm_bindgen_test]
fn version_and_default_config() {
    assert_eq!(facade::version(), env!("CARGO_PKG_VERSION"));
    let d = facade::default_config().map_err(JsValue::from).unwrap();
    assert_eq!(get(&d, "n").as_f64(), Some(40.0));
    let checked = facade::check_config(d).map_err(JsValue::from).unwrap();
    assert_eq!(get(&checked, "loops").as_f64(), Some(100.0));
    assert!(facade::last_panic().is_none());
}

#[wasm_bindgen_test]
fn bad_configs_are_errors_naming_the_field() {
    let msg = |v: JsValue| match Episode::new(v, 1) {
        Ok(_) => panic!("accepted"),
        Err(e) => {
            let v: JsValue = e.into();
            js_sys::Error::from(v).message().as_string().unwrap()
        }
    };
    assert!(
        msg(js(r#"{"n":2}"#)).starts_with("n must be"),
        "{}",
        msg(js(r#"{"n":2}"#))
    );
    assert!(msg(js(r#"{"mu":5}"#)).starts_with("mu must be"));
    assert!(msg(js(r#"{"start":[41,1]}"#)).starts_with("start must be"));
    assert!(msg(js(r#"{"searcher":"astar"}"#)).contains("astar"));
    assert!(msg(js(r#"{"bogus":1}"#)).contains("bogus"));
    assert!(facade::check_config(js(r#"{"loops":0}"#)).is_err());
}

#[wasm_bindgen_test]
fn stepping_and_zero_copy_path() {
    let mut h = Episode::new(small(), 7).map_err(JsValue::from).unwrap();
    assert_eq!(h.status(), "running");
    assert_eq!(h.n(), 15);
    assert_eq!(h.path_len(), 1);
    assert_eq!(h.position(), h.start());
    // One loop at a time: the decision is under way, no move yet.
    assert!(!h.step_loops(1));
    assert_eq!(h.loops_done(), 1);
    assert_eq!(h.rollouts_total(), 1.0);
    assert_eq!(h.steps(), 0);
    // The rest of the decision, then the move.
    assert!(h.step_loops(100));
    assert_eq!(h.steps(), 1);
    assert_eq!(h.rollouts_total(), 20.0);
    assert_eq!(h.step_move(), h.status());
    assert_eq!(h.steps(), 2);
    let view = u32s(h.path_ptr(), h.path_len());
    assert_eq!(view, h.path());
    assert_eq!(view.len(), 3);
    assert_eq!(*view.last().unwrap(), h.position());
}

#[wasm_bindgen_test]
fn facade_matches_the_core_episode_exactly() {
    let cfg_json =
        r#"{"n":12,"prior":{"kind":"gaussian","sigma":2},"loops":15,"belief":"posterior"}"#;
    let mut h = Episode::new(js(cfg_json), 99)
        .map_err(JsValue::from)
        .unwrap();
    // Loop-sized slices, as a browser frame does them.
    while h.status() == "running" && h.steps() < 500 {
        h.step_loops(4);
    }
    let cfg: Config = serde_json::from_str(cfg_json).unwrap();
    let mut core = CoreEpisode::new(&cfg, 99).unwrap();
    let r = core.run();
    assert_eq!(h.path(), core.path());
    assert_eq!(h.steps(), r.steps);
    assert_eq!(h.optimal(), r.optimal);
    assert_eq!(h.target(), r.target);
    let res = h.result().map_err(JsValue::from).unwrap();
    assert_eq!(get(&res, "steps").as_f64(), Some(r.steps as f64));
}

#[wasm_bindgen_test]
fn heatmap_layers_render_to_rgba() {
    let mut h = Episode::new(small(), 3).map_err(JsValue::from).unwrap();
    h.step_move();
    let n2 = 15 * 15;
    for layer in ["prior", "plan", "posterior", "visits", "searched"] {
        for scale in ["linear", "stretch", "log"] {
            let ptr = h
                .render_layer(layer, "viridis", scale, 0, 255)
                .map_err(JsValue::from)
                .unwrap();
            assert_ne!(ptr, 0, "{layer}");
            assert!(h.layer_max() > 0.0, "{layer}");
            let px = bytes(ptr, 4 * n2);
            assert!(
                px.chunks(4).any(|p| p[3] > 0),
                "{layer} {scale} is all transparent"
            );
        }
    }
    // Prior mass sums to 1; the opaque rendering has alpha 255 everywhere.
    let ptr = h
        .render_layer("prior", "cividis", "linear", 255, 255)
        .map_err(JsValue::from)
        .unwrap();
    assert!((h.layer_sum() - 1.0).abs() < 1e-9);
    assert!(bytes(ptr, 4 * n2).chunks(4).all(|p| p[3] == 255));
    // MCTS has no walker counts: an empty layer is pointer 0.
    assert_eq!(
        h.render_layer("walker", "ember", "linear", 0, 255)
            .map_err(JsValue::from)
            .unwrap(),
        0
    );
    assert!(h.render_layer("nope", "viridis", "linear", 0, 255).is_err());
    assert!(h.render_layer("prior", "jet", "linear", 0, 255).is_err());
    assert!(h.render_layer("prior", "viridis", "cubic", 0, 255).is_err());
    assert_eq!(
        facade::palette_lut("ember")
            .map_err(JsValue::from)
            .unwrap()
            .len(),
        1024
    );
    let rgba = facade::colorize_values(&[0.0, 1.0, 2.0], "viridis", "linear", 0, 255)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(rgba.len(), 12);
    assert_eq!(rgba[3], 0);
}

#[wasm_bindgen_test]
fn traces_and_decision() {
    let mut h = Episode::new(small(), 5).map_err(JsValue::from).unwrap();
    assert_eq!(h.collect_traces(), 0);
    h.step_loops(3);
    let count = h.collect_traces();
    assert_eq!(count, 2, "keep_traces = 2");
    let offsets = u32s(h.trace_offsets_ptr(), count + 1);
    assert_eq!(offsets[0], 0);
    let cells = u32s(h.trace_cells_ptr(), offsets[count as usize]);
    // Each trace starts at the searcher's cell.
    assert_eq!(cells[0], h.position());
    let targets = u32s(h.trace_targets_ptr(), count);
    assert!(targets.iter().all(|&t| t < 225));
    let d = h.decision().map_err(JsValue::from).unwrap();
    let children = js_sys::Array::from(&get(&d, "children"));
    assert_eq!(children.length(), 4);
    let picked: f64 = children
        .iter()
        .map(|c| get(&c, "selected").as_f64().unwrap())
        .sum();
    assert_eq!(picked, 3.0);
    assert_eq!(get(&d, "c").as_f64(), Some(std::f64::consts::SQRT_2));
}

#[wasm_bindgen_test]
fn walkers_and_time_budgets() {
    let mut h = Episode::new(
        js(r#"{"n":10,"searcher":"nsarw","prior":{"kind":"uniform"}}"#),
        2,
    )
    .map_err(JsValue::from)
    .unwrap();
    assert!(h.step_loops(1), "a walker moves on every call");
    assert_eq!(h.steps(), 1);
    assert!(
        h.render_layer("walker", "ember", "linear", 0, 255)
            .map_err(JsValue::from)
            .unwrap()
            != 0
    );
    assert!(h.decision().is_ok());
    // A decision-time budget uses performance.now(): 2 ms per move.
    let mut t = Episode::new(js(r#"{"n":20,"decision_ms":2}"#), 4)
        .map_err(JsValue::from)
        .unwrap();
    let before = js_sys::Date::now();
    t.step_move();
    assert_eq!(t.steps(), 1);
    assert!(js_sys::Date::now() - before >= 1.0);
    assert!(t.rollouts_total() >= 1.0);
}

#[wasm_bindgen_test]
fn benchmark_workloads() {
    let steps = facade::bench_rollout_steps("rw", 40, 1.0, 2.0, 1, 10_000.0)
        .map_err(JsValue::from)
        .unwrap();
    assert!(steps >= 10_000.0);
    assert!(facade::bench_rollout_steps("teleport", 40, 1.0, 2.0, 1, 10.0).is_err());
    let r = facade::bench_mcts_loops(js(r#"{"n":20,"loops":10}"#), 1, 50.0)
        .map_err(JsValue::from)
        .unwrap();
    assert!(r[0] >= 50.0 && r[1] >= 4.0, "{r:?}");
}

#[wasm_bindgen_test]
fn batch_trials_match_the_core_and_summarize() {
    let json = r#"{"n":12,"prior":{"kind":"gaussian","sigma":2},"loops":10,"belief":"posterior","step_cap":500}"#;
    let cfg: Config = serde_json::from_str(json).unwrap();
    let mut flat = Vec::new();
    for i in 0..4u64 {
        let t = facade::run_trial(js(json), 3, i as f64)
            .map_err(JsValue::from)
            .unwrap();
        let core = CoreEpisode::trial(&cfg, 3, i).unwrap().run();
        assert_eq!(t[0], core.steps as f64);
        assert_eq!(t[1], core.optimal as f64);
        assert_eq!(t[3], core.target as f64);
        flat.extend(t);
    }
    let s = facade::summarize_trials(&flat)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(get(&s, "trials").as_f64(), Some(4.0));
    let mean = get(&get(&s, "steps"), "mean").as_f64().unwrap();
    let want = flat.chunks(7).map(|t| t[0]).sum::<f64>() / 4.0;
    assert!((mean - want).abs() < 1e-9);
    assert!(facade::summarize_trials(&[1.0, 2.0]).is_err());
}
