//! Facade tests: the `#[wasm_bindgen]` functions and the `Race` handle in
//! `src/wasm.rs`, called the way the page calls them (config objects parsed
//! from JSON, frames read back as JS objects), in headless Chromium. Run with
//! `cargo test --target wasm32-unknown-unknown` (`make test` wires it up).
#![cfg(target_arch = "wasm32")]

use torus_search::config::Config;
use torus_search::run::episode::Episode as CoreEpisode;
use torus_search::wasm::{self as facade, RaceHandle as Race};
use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

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

fn message(e: wasm_bindgen::JsError) -> String {
    let v: JsValue = e.into();
    js_sys::Error::from(v).message().as_string().unwrap()
}

fn race(json: &str) -> Race {
    Race::new(js(json)).map_err(JsValue::from).unwrap()
}

/// The first run's export.
fn exported(r: &Race) -> JsValue {
    js_sys::Array::from(&r.export().map_err(JsValue::from).unwrap()).get(0)
}

/// The path of a run's export.
fn path_of(exported: &JsValue) -> Vec<u32> {
    js_sys::Array::from(&get(exported, "path"))
        .iter()
        .map(|c| c.as_f64().unwrap() as u32)
        .collect()
}

/// The frames for `requests` (a JSON array), as JS objects.
fn frames(r: &mut Race, requests: &str) -> Vec<JsValue> {
    js_sys::Array::from(&r.frames(js(requests)).map_err(JsValue::from).unwrap())
        .iter()
        .collect()
}

fn u32s(bytes: &JsValue) -> Vec<u32> {
    js_sys::Uint8Array::new(bytes)
        .to_vec()
        .chunks_exact(4)
        .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
        .collect()
}

#[wasm_bindgen_test]
fn version_schema_and_config_checks() {
    assert_eq!(facade::version(), env!("CARGO_PKG_VERSION"));
    let schema = facade::schema().map_err(JsValue::from).unwrap();
    let params = js_sys::Array::from(&get(&schema, "params"));
    let keys: Vec<String> = params
        .iter()
        .map(|p| get(&p, "key").as_string().unwrap())
        .collect();
    assert_eq!(keys.len(), torus_search::config::params().len());
    assert!(keys.contains(&"seed".to_string()));
    let loops = params
        .iter()
        .find(|p| get(p, "key").as_string().as_deref() == Some("loops"))
        .unwrap();
    assert_eq!(get(&loops, "max").as_string().as_deref(), Some("10000000"));
    assert_eq!(js_sys::Array::from(&get(&schema, "layers")).length(), 6);
    let checked = facade::check_config(js("{}"))
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(num(&checked, "loops"), 100.0);
    assert_eq!(get(&checked, "seed").as_string().as_deref(), Some("1"));
    assert!(facade::last_panic().is_none());
}

#[wasm_bindgen_test]
fn bad_configs_are_errors_naming_the_field() {
    let msg = |json: &str| match Race::new(js(&format!("[{json}]"))) {
        Ok(_) => panic!("accepted {json}"),
        Err(e) => message(e),
    };
    assert!(
        msg(r#"{"n":2}"#).starts_with("n must be"),
        "{}",
        msg(r#"{"n":2}"#)
    );
    assert!(msg(r#"{"mu":5}"#).starts_with("mu must be"));
    assert!(msg(r#"{"start":[41,1]}"#).starts_with("start must be"));
    assert!(msg(r#"{"searcher":"astar"}"#).contains("astar"));
    assert!(msg(r#"{"bogus":1}"#).contains("bogus"));
    // A seed is never wrapped or rounded.
    assert!(msg(r#"{"seed":"18446744073709551616"}"#).contains("seed must be"));
    assert!(msg(r#"{"seed":1152921504606846976}"#).contains("must be strings"));
    assert!(msg(r#"{"seed":-1}"#).contains("seed must be"));
    assert!(facade::check_config(js(r#"{"loops":0}"#)).is_err());
    assert!(Race::new(js("{}")).is_err(), "not an array");
    assert!(Race::new(js("[]")).is_err(), "no config");
}

#[wasm_bindgen_test]
fn url_parameters_parse_set_and_write_back() {
    let out = facade::parse_params(js(
        r#"[["n","12"],["loops","0"],["seed","18446744073709551615"]]"#,
    ))
    .map_err(JsValue::from)
    .unwrap();
    let cfg = get(&out, "config");
    assert_eq!(num(&cfg, "n"), 12.0);
    assert_eq!(num(&cfg, "loops"), 100.0, "a bad value keeps the default");
    assert_eq!(
        get(&cfg, "seed").as_string().as_deref(),
        Some("18446744073709551615")
    );
    let errors = js_sys::Array::from(&get(&out, "errors"));
    assert_eq!(errors.length(), 1);
    assert_eq!(
        get(&errors.get(0), "field").as_string().as_deref(),
        Some("loops")
    );
    // Editing n keeps the start inside.
    let cfg = facade::set_param(js(r#"{"n":40,"start":[30,30]}"#), "n", "20")
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(
        js_sys::Array::from(&get(&cfg, "start")).get(0).as_f64(),
        Some(20.0)
    );
    assert!(facade::set_param(cfg.clone(), "c", "-1").is_err());
    let pairs = js_sys::Array::from(
        &facade::config_params(cfg.clone(), false)
            .map_err(JsValue::from)
            .unwrap(),
    );
    let flat: Vec<String> = pairs
        .iter()
        .map(|p| js_sys::Array::from(&p).join("=").as_string().unwrap())
        .collect();
    assert_eq!(flat, ["n=20", "start=20,20", "seed=1"]);
    let applicable = js_sys::Array::from(
        &facade::applicable(js(r#"{"searcher":"rw"}"#))
            .map_err(JsValue::from)
            .unwrap(),
    );
    assert!(!applicable.includes(&JsValue::from_str("loops"), 0));
    let d = facade::describe_config(js("{}"))
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(
        get(&d, "label").as_string().as_deref(),
        Some("MCTS cells · rw rollouts · L=100")
    );
}

#[wasm_bindgen_test]
fn frames_carry_the_path_layers_decision_and_traces() {
    let mut r = race(r#"[{"n":15,"sigma":3,"loops":20,"keep_traces":2,"seed":"7"}]"#);
    let info = js_sys::Array::from(&r.describe().map_err(JsValue::from).unwrap()).get(0);
    assert_eq!(get(&info, "deliberates").as_bool(), Some(true));
    assert_eq!(num(&info, "n"), 15.0);
    r.step_loop();
    let req = r#"[{"layers":[{"layer":"prior","palette":"viridis","scale":"linear","alpha":[255,255]},
                             {"layer":"visits","palette":"ember","scale":"log","alpha":[0,235]},
                             {"layer":"walker","palette":"ember","scale":"log","alpha":[0,235]}],
                  "path_from":0,"traces":true}]"#;
    let f = frames(&mut r, req).remove(0);
    assert_eq!(get(&f, "status").as_string().as_deref(), Some("running"));
    assert_eq!(num(&f, "steps"), 0.0);
    assert_eq!(num(&f, "loops_done"), 1.0);
    let layers = js_sys::Array::from(&get(&f, "layers"));
    assert_eq!(layers.length(), 2, "MCTS has no walker counts");
    let prior = layers.get(0);
    let rgba = js_sys::Uint8Array::new(&get(&prior, "rgba"));
    assert_eq!(rgba.length(), 4 * 225);
    assert!((num(&prior, "sum") - 1.0).abs() < 1e-9);
    let key = num(&prior, "key");
    assert_eq!(u32s(&get(&f, "path")), vec![num(&info, "start") as u32]);
    let d = get(&f, "decision");
    let picked: f64 = js_sys::Array::from(&get(&d, "children"))
        .iter()
        .map(|c| num(&c, "selected"))
        .sum();
    assert_eq!(picked, 1.0);
    let leading = js_sys::Array::from(&get(&d, "leading"));
    assert!(leading.iter().any(|l| l.as_bool() == Some(true)));
    assert_eq!(js_sys::Array::from(&get(&f, "traces")).length(), 1);
    // Held layers come back as `same`; the path only from where the page is.
    r.step_move();
    let held = format!(
        r#"[{{"layers":[{{"layer":"prior","palette":"viridis","scale":"linear","alpha":[255,255],"have":{key}}}],"path_from":1}}]"#
    );
    let f = frames(&mut r, &held).remove(0);
    let prior = js_sys::Array::from(&get(&f, "layers")).get(0);
    assert_eq!(get(&prior, "same").as_bool(), Some(true));
    assert!(get(&prior, "rgba").is_null());
    assert_eq!(num(&f, "path_from"), 1.0);
    assert_eq!(u32s(&get(&f, "path")).len(), 1);
    // Requests are checked.
    assert!(r.frames(js(r#"[{"layers":[{"layer":"nope"}]}]"#)).is_err());
    assert!(r.frames(js(r#"[{"colour":1}]"#)).is_err());
}

#[wasm_bindgen_test]
fn the_facade_matches_the_core_episode_exactly() {
    let json = r#"{"n":12,"sigma":2,"loops":15,"belief":"posterior","seed":"99"}"#;
    let mut r = race(&format!("[{json}]"));
    // Loop-sized slices, as the worker runs them.
    while r.running() > 0 {
        r.advance(4.0);
    }
    let cfg: Config = serde_json::from_str(json).unwrap();
    let mut core = CoreEpisode::new(&cfg).unwrap();
    let res = core.run();
    let exported = exported(&r);
    assert_eq!(path_of(&exported), core.path());
    let result = get(&exported, "result");
    assert_eq!(num(&result, "steps"), res.steps as f64);
    assert_eq!(num(&result, "target"), res.target as f64);
    assert_eq!(
        get(&get(&exported, "config"), "seed")
            .as_string()
            .as_deref(),
        Some("99"),
        "an export carries the seed"
    );
}

#[wasm_bindgen_test]
fn step_move_on_a_planner_is_made_in_calls_of_bounded_length() {
    // The worker's Step move: askMove, then makeAskedMoves until it says
    // the move is made, answering other requests between calls.
    let json = r#"{"n":14,"searcher":"beam","beam_width":8,"beam_depth":30,"seed":"4"}"#;
    let mut r = race(&format!("[{json}]"));
    r.ask_move();
    let mut calls = 0;
    while !r.make_asked_moves() {
        calls += 1;
        let f = frames(&mut r, "[{}]").remove(0);
        assert_eq!(num(&f, "steps"), 0.0);
        assert!(!get(&f, "planning").is_null(), "still planning");
    }
    assert!(calls >= 2, "the plan took {calls} calls");
    assert_eq!(num(&frames(&mut r, "[{}]")[0], "steps"), 1.0);
    // The same move as the core makes in one call.
    let cfg: Config = serde_json::from_str(json).unwrap();
    let mut core = CoreEpisode::new(&cfg).unwrap();
    core.step_move();
    assert_eq!(path_of(&exported(&r)), core.path());
}

#[wasm_bindgen_test]
fn walkers_race_and_time_budgets() {
    let mut r = race(r#"[{"n":10,"loops":10,"seed":"2"},{"n":10,"searcher":"nsarw","seed":"2"}]"#);
    let info = js_sys::Array::from(&r.describe().map_err(JsValue::from).unwrap());
    assert_eq!(num(&info.get(0), "target"), num(&info.get(1), "target"));
    assert_eq!(get(&info.get(1), "deliberates").as_bool(), Some(false));
    // Each run names the layers it can draw: MCTS has visits, NSARW its walker counts too.
    let names = |i: u32| -> Vec<String> {
        js_sys::Array::from(&get(&info.get(i), "layer_names"))
            .iter()
            .filter_map(|v| v.as_string())
            .collect()
    };
    assert_eq!(
        names(0),
        ["prior", "plan", "posterior", "searched", "visits"]
    );
    assert_eq!(
        names(1),
        ["prior", "plan", "posterior", "searched", "visits", "walker"]
    );
    r.advance(35.0);
    let f = frames(
        &mut r,
        r#"[{}, {"layers":[{"layer":"walker","palette":"ember","scale":"linear","alpha":[0,255]}]}]"#,
    );
    assert!(
        num(&f[1], "steps") <= num(&f[0], "steps"),
        "the walker keeps pace"
    );
    assert!(get(&f[1], "decision").is_null());
    assert_eq!(js_sys::Array::from(&get(&f[1], "layers")).length(), 1);
    // A time budget reads performance.now(): 2 ms per move.
    let mut t = race(r#"[{"n":20,"ms":2}]"#);
    let before = js_sys::Date::now();
    t.step_move();
    assert!(js_sys::Date::now() - before >= 1.0);
    let f = frames(&mut t, "[{}]").remove(0);
    assert_eq!(num(&f, "steps"), 1.0);
    assert!(num(&f, "rollouts") >= 1.0);
}

#[wasm_bindgen_test]
fn benchmark_workloads() {
    let steps = facade::bench_rollout_steps("rw", 40, 1.0, 2.0, "1", 10_000.0)
        .map_err(JsValue::from)
        .unwrap();
    assert!(steps >= 10_000.0);
    assert!(facade::bench_rollout_steps("teleport", 40, 1.0, 2.0, "1", 10.0).is_err());
    assert!(facade::bench_rollout_steps("rw", 40, 1.0, 2.0, "18446744073709551616", 10.0).is_err());
    let r = facade::bench_mcts_loops(js(r#"{"n":20,"loops":10}"#), 50.0)
        .map_err(JsValue::from)
        .unwrap();
    assert!(r[0] >= 50.0 && r[1] >= 4.0, "{r:?}");
    // The move workload, with each next trial started apart (as
    // benches/moves.mjs times it), makes the core runner's moves.
    let json = r#"{"n":6,"sigma":1,"searcher":"rw"}"#;
    let mut b = facade::MoveBench::new(js(json))
        .map_err(JsValue::from)
        .unwrap();
    let mut moves = 0.0;
    for _ in 0..300 {
        b.ready().map_err(JsValue::from).unwrap();
        moves = b.run(1.0).map_err(JsValue::from).unwrap();
    }
    let mut core =
        torus_search::bench::MoveRunner::new(&serde_json::from_str(json).unwrap()).unwrap();
    core.run(300).unwrap();
    assert_eq!(
        (moves, b.episodes()),
        (core.moves as f64, core.episodes as f64)
    );
    assert!(b.episodes() >= 2.0);
    assert!(b.run(0.0).is_err());
}

#[wasm_bindgen_test]
fn batch_trials_match_the_core_and_summarize() {
    let json = r#"{"n":12,"sigma":2,"loops":10,"step_cap":500,"seed":"3"}"#;
    let cfg: Config = serde_json::from_str(json).unwrap();
    let mut flat = Vec::new();
    for i in 0..4u64 {
        let t = facade::run_trial(js(json), i as f64)
            .map_err(JsValue::from)
            .unwrap();
        let core = CoreEpisode::trial(&cfg, i).unwrap().run();
        assert_eq!(t, core.fields().to_vec());
        flat.extend(t);
    }
    assert!(facade::run_trial(js(json), -1.0).is_err());
    let s = facade::summarize_trials(&flat)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(num(&s, "trials"), 4.0);
    let want = flat.chunks(7).map(|t| t[0]).sum::<f64>() / 4.0;
    let mean = get(&s, "mean_steps");
    assert!((num(&mean, "estimate") - want).abs() < 1e-9);
    // The interval's bits are the native core's: the same resampling stream.
    let core: Vec<_> = flat
        .chunks(7)
        .map(|t| torus_search::run::episode::TrialResult::from_fields(t).unwrap())
        .collect();
    let native = torus_search::analysis::stats::Summary::of(&core).steps;
    assert_eq!((num(&mean, "lo"), num(&mean, "hi")), (native.lo, native.hi));
    assert_eq!(
        get(&mean, "method").as_string().as_deref(),
        Some("expanded-bca-bootstrap")
    );
    assert!(facade::summarize_trials(&[1.0, 2.0]).is_err());
    assert!(facade::summarize_trials(&[1.0, 2.0, 0.5, 3.0, 0.0, 0.0, 0.0]).is_err());
}

#[wasm_bindgen_test]
fn palettes_colours_and_paint() {
    assert_eq!(
        facade::palette_lut("ember")
            .map_err(JsValue::from)
            .unwrap()
            .len(),
        1024
    );
    assert!(facade::palette_lut("jet").is_err());
    let rgba = facade::colorize_values(&[0.0, 1.0, 2.0], "viridis", "linear", 0, 255)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(rgba.len(), 12);
    assert_eq!(rgba[3], 0);
    assert!(facade::colorize_values(&[1.0], "viridis", "cubic", 0, 255).is_err());
    let levels: Vec<u8> = (0..100).map(|i| (i % 16) as u8).collect();
    let text = facade::encode_paint(&levels);
    assert_eq!(
        facade::decode_paint(&text, 10)
            .map_err(JsValue::from)
            .unwrap(),
        levels
    );
    assert!(facade::decode_paint(&text, 11).is_err());
}

#[wasm_bindgen_test]
fn experiments_run_split_and_match_the_core() {
    use torus_search::experiment::{self as core, Plan, ResultSet};
    let list = js_sys::Array::from(&facade::experiment_list().map_err(JsValue::from).unwrap());
    assert_eq!(list.length() as usize, core::DEFINITIONS.len());
    assert_eq!(num(&list.get(0), "defaultTrials"), 10_000.0);
    let spec = r#"{"name":"custom","trials":3,"seed":"5","params":{"n":"8","loops":"4","step_cap":"60"},
      "sweep":{"key":"searcher","values":["mcts","nsarw"]}}"#;
    let plan = facade::experiment_plan(js(spec))
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(num(&plan, "totalUnits"), 6.0);
    assert_eq!(js_sys::Array::from(&get(&plan, "rowFields")).length(), 7);
    let points = js_sys::Array::from(&get(&plan, "points"));
    assert_eq!(get(&points.get(1), "x").as_string().unwrap(), "nsarw");
    // Two workers' halves, joined in reverse, give the core's single run.
    let a = facade::experiment_run(js(spec), 0.0, 4.0)
        .map_err(JsValue::from)
        .unwrap();
    let b = facade::experiment_run(js(spec), 4.0, 6.0)
        .map_err(JsValue::from)
        .unwrap();
    let rows: Vec<f64> = b.iter().chain(&a).copied().collect();
    let text = facade::experiment_result(js(spec), &rows)
        .map_err(JsValue::from)
        .unwrap();
    let p = Plan::from_spec_text(spec).unwrap();
    let core_rows = core::run_units(&p, 0, 6).unwrap();
    // The page's result is the core's bytes with the page's provenance.
    let core = ResultSet::new(p, 0, 6, core_rows).unwrap();
    assert_eq!(
        torus_search::experiment::provenance::strip(&text),
        core.to_json()
    );
    let (_, prov) = torus_search::experiment::provenance::read_stamped(&text).unwrap();
    let prov = prov.expect("the page's result carries its provenance");
    assert_eq!(prov.commit, torus_search::experiment::provenance::COMMIT);
    assert!(torus_search::experiment::provenance::is_utc_date(
        &prov.date
    ));
    assert!(prov.command.starts_with("http"), "{}", prov.command);
    let csv = facade::experiment_csv(&text)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(csv.lines().filter(|l| !l.starts_with('#')).count(), 3);
    assert!(csv.contains(&format!("\n# date: {}\n", prov.date)));
    // The per-trial and paired CSVs are the core's, from the result text,
    // after the same provenance lines.
    let strip = torus_search::experiment::provenance::strip;
    let trials = facade::experiment_trials_csv(&text)
        .map_err(JsValue::from)
        .unwrap();
    assert!(trials.contains(&format!("\n# date: {}\n", prov.date)));
    assert_eq!(strip(&trials), core.trials_csv());
    assert_eq!(strip(&trials).lines().count(), 7);
    let paired = facade::experiment_paired_csv(&text)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(strip(&paired), core.paired_csv());
    assert!(facade::experiment_trials_csv("{").is_err());
    let read = facade::experiment_read(&text)
        .map_err(JsValue::from)
        .unwrap();
    assert_eq!(js_sys::Array::from(&get(&read, "rows")).length(), 6);
    assert_eq!(
        get(&get(&read, "provenance"), "date").as_string(),
        Some(prov.date.clone())
    );
    let build = facade::build_info().map_err(JsValue::from).unwrap();
    assert_eq!(get(&build, "commit").as_string().unwrap(), prov.commit);
    let styles = js_sys::Array::from(&facade::series_styles(10).map_err(JsValue::from).unwrap());
    assert_eq!(styles.length(), 10);
    assert_eq!(
        get(&styles.get(0), "colour").as_string().unwrap(),
        "#3f90da"
    );
    // Bad input is an error with a message, never a panic.
    let e = facade::experiment_plan(js(r#"{"name":"nope"}"#)).unwrap_err();
    assert!(message(e).starts_with("experiment must be one of priors"));
    let e = facade::experiment_plan(js(r#"{"name":"delta","x":1}"#)).unwrap_err();
    assert!(message(e).contains("unknown field \"x\""));
    assert!(facade::experiment_run(js(spec), 0.0, 7.0).is_err());
    assert!(facade::experiment_run(js(spec), 0.5, 1.0).is_err());
    assert!(facade::experiment_result(js(spec), &[1.0, 2.0]).is_err());
    let e = facade::experiment_read("{\"format\":\"x\"}").unwrap_err();
    assert!(message(e).starts_with("not a torus-search experiment result"));
}
