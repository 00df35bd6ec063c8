//! The `#[wasm_bindgen]` facade: thin handles around core types, no logic.
//!
//! Configurations cross as plain JS objects (the core's `Config` fields;
//! the seed is a decimal string), frames as objects whose buffers are
//! `Uint8Array` copies out of this module's memory (the search worker then
//! transfers them to the page). Every fallible function returns
//! `Result<_, JsError>`, so bad input becomes a JS exception with a message,
//! never a panic; a panic (a bug) is caught by the hook installed in
//! [`start`], logged, and its text kept for [`last_panic`]. An allocation
//! that fails (the instance is out of memory) aborts with no message, so
//! the global allocator notes its size for [`last_out_of_memory`] first.

use crate::analysis::stats::Summary;
use crate::config::{self, Config};
use crate::display::render::{Alpha, Colorizer, Palette, ScaleKind};
use crate::display::view::{self, FrameBuilder, FrameRequest};
use crate::experiment::provenance::{self, CsvTable, Provenance};
use crate::experiment::{self, Plan, ResultSet, Spec};
use crate::game::prior;
use crate::run::episode::{Episode, TrialResult, TRIAL_FIELDS};
use crate::run::race::Race as CoreRace;
use crate::searchers::walks::policy::PolicyKind;
use std::sync::Mutex;
use wasm_bindgen::prelude::*;

mod branch;
mod teach;
pub use branch::branch_check;
pub use teach::{config_differences, run_paired_trial, summarize_paired};

static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

/// The system allocator, noting the size of the last allocation it could
/// not make: Rust then aborts (a bare `unreachable` trap in wasm), and the
/// page reads the size to say the engine ran out of memory.
#[cfg(target_arch = "wasm32")]
mod oom {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::sync::atomic::{AtomicUsize, Ordering};

    pub static FAILED_BYTES: AtomicUsize = AtomicUsize::new(0);

    pub struct Noting;

    #[inline]
    fn note(p: *mut u8, bytes: usize) -> *mut u8 {
        if p.is_null() {
            FAILED_BYTES.store(bytes.max(1), Ordering::Relaxed);
        }
        p
    }

    // SAFETY: every call is forwarded unchanged to `System`, which upholds
    // the `GlobalAlloc` contract; only a null result is noted.
    unsafe impl GlobalAlloc for Noting {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            note(System.alloc(layout), layout.size())
        }
        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            System.dealloc(ptr, layout)
        }
        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            note(System.realloc(ptr, layout, new_size), new_size)
        }
    }

    #[global_allocator]
    static ALLOCATOR: Noting = Noting;
}

/// Installs the panic hook (runs once when the module is instantiated).
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        if let Ok(mut slot) = LAST_PANIC.lock() {
            *slot = Some(info.to_string());
        }
        console_error_panic_hook::hook(info);
    }));
}

/// Milliseconds from the host's `performance` clock (window and workers alike).
fn performance_now() -> f64 {
    thread_local! {
        static PERFORMANCE: Option<web_sys::Performance> =
            js_sys::Reflect::get(&js_sys::global(), &JsValue::from_str("performance"))
                .ok()
                .and_then(|p| p.dyn_into::<web_sys::Performance>().ok());
    }
    PERFORMANCE.with(|p| p.as_ref().map_or(0.0, |p| p.now()))
}

/// The crate version, so the page can show which engine it runs.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// The build, for the page's footer and its exports: `{ version, commit,
/// dirty, label }` (commit: 40 hex digits or "unknown"; dirty: true, false
/// or null; label: `torus-search 0.1.0, commit 0123456789ab`).
#[wasm_bindgen(js_name = buildInfo)]
pub fn build_info() -> Result<JsValue, JsError> {
    #[derive(serde::Serialize)]
    struct Build {
        version: &'static str,
        commit: &'static str,
        dirty: Option<bool>,
        label: String,
    }
    to_js(&Build {
        version: provenance::VERSION,
        commit: provenance::COMMIT,
        dirty: provenance::dirty(),
        label: provenance::this_build(),
    })
}

/// This build's provenance for an output made now on the page: the date
/// from the host's clock (UTC, to the second), the command the page's URL.
fn page_provenance() -> Provenance {
    let iso = String::from(js_sys::Date::new_0().to_iso_string());
    let date = format!("{}Z", iso.get(..19).unwrap_or(&iso));
    let href = js_sys::Reflect::get(&js_sys::global(), &JsValue::from_str("location"))
        .and_then(|l| js_sys::Reflect::get(&l, &JsValue::from_str("href")))
        .ok()
        .and_then(|h| h.as_string())
        .unwrap_or_else(|| "the page".into());
    Provenance::new(date, href)
}

/// How series `i` of a chart is drawn, for `i` in `0..count`: `[{ colour
/// ("#rrggbb"), dash (on, off, … pixels), marker }]`, the CLI's charts' styles.
#[wasm_bindgen(js_name = seriesStyles)]
pub fn series_styles(count: u32) -> Result<JsValue, JsError> {
    let styles: Vec<_> = (0..count.min(1000) as usize)
        .map(experiment::series_style)
        .collect();
    to_js(&styles)
}

/// The text of the last Rust panic, if any (read after a `RuntimeError`).
#[wasm_bindgen(js_name = lastPanic)]
pub fn last_panic() -> Option<String> {
    LAST_PANIC.lock().ok().and_then(|s| s.clone())
}

/// The size of this instance's linear memory in bytes (it only grows): the
/// soak test watches it.
#[wasm_bindgen(js_name = memoryBytes)]
pub fn memory_bytes() -> f64 {
    #[cfg(target_arch = "wasm32")]
    {
        (core::arch::wasm32::memory_size(0) * 65536) as f64
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        0.0
    }
}

/// The size in bytes of the last allocation that failed, if any (read
/// after a `RuntimeError`: a failed allocation aborts the instance).
#[wasm_bindgen(js_name = lastOutOfMemory)]
pub fn last_out_of_memory() -> Option<f64> {
    #[cfg(target_arch = "wasm32")]
    {
        match oom::FAILED_BYTES.load(std::sync::atomic::Ordering::Relaxed) {
            0 => None,
            b => Some(b as f64),
        }
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        None
    }
}

/// Allocates 256 MiB blocks and keeps them until an allocation fails, so
/// tests can check that running out of memory reaches the page. wasm32
/// memory ends at 4 GiB, so this aborts after at most 16 blocks.
#[wasm_bindgen(js_name = oomForTest)]
pub fn oom_for_test() {
    let mut hoard: Vec<Vec<u8>> = Vec::with_capacity(64);
    loop {
        let mut block = Vec::<u8>::with_capacity(256 << 20);
        block.push(1);
        hoard.push(block);
        if hoard.len() == hoard.capacity() {
            // Unreachable in wasm32 (64 blocks are 16 GiB); natively it
            // would only eat the host's memory.
            return;
        }
    }
}

/// Panics on purpose, so tests can check that a panic reaches the page.
#[wasm_bindgen(js_name = panicForTest)]
pub fn panic_for_test(message: &str) {
    panic!("panicForTest: {message}");
}

/// JSON-compatible objects (plain objects, numbers, null), except that byte
/// buffers stay `Uint8Array`s (frames transfer them between threads).
fn to_js<T: serde::Serialize + ?Sized>(value: &T) -> Result<JsValue, JsError> {
    value
        .serialize(
            &serde_wasm_bindgen::Serializer::json_compatible().serialize_bytes_as_arrays(false),
        )
        .map_err(|e| JsError::new(&e.to_string()))
}

fn err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// Reads a JS value as `T` strictly: through JSON, so `deny_unknown_fields`
/// rejects misspelt keys (serde-wasm-bindgen alone skips them silently).
fn from_js<T: serde::de::DeserializeOwned>(value: JsValue, what: &str) -> Result<T, JsError> {
    let json: serde_json::Value =
        serde_wasm_bindgen::from_value(value).map_err(|e| JsError::new(&format!("{what}: {e}")))?;
    serde_json::from_value(json).map_err(|e| JsError::new(&format!("{what}: {e}")))
}

/// Reads and validates a config object.
fn config_from_js(value: JsValue) -> Result<Config, JsError> {
    if !value.is_object() || js_sys::Array::is_array(&value) {
        return Err(JsError::new("config must be an object"));
    }
    let json: serde_json::Value =
        serde_wasm_bindgen::from_value(value).map_err(|e| JsError::new(&format!("config: {e}")))?;
    config::from_json(json).map_err(err)
}

/// The configuration schema, the searcher registry, the heat layers and the
/// palette and scale names: everything the page builds its URL parser,
/// controls and legend from.
#[wasm_bindgen]
pub fn schema() -> Result<JsValue, JsError> {
    #[derive(serde::Serialize)]
    struct Out {
        #[serde(flatten)]
        schema: config::Schema,
        layers: Vec<view::LayerInfo>,
        palettes: &'static [&'static str],
        scales: &'static [&'static str],
    }
    to_js(&Out {
        schema: config::schema(),
        layers: view::layers(),
        palettes: Palette::NAMES,
        scales: ScaleKind::NAMES,
    })
}

/// Parses `[key, text]` pairs (a URL's query) into a config. A bad value
/// keeps its default: the answer is `{ config, errors: [{ field, value,
/// allowed, message }] }`.
#[wasm_bindgen(js_name = parseParams)]
pub fn parse_params(pairs: JsValue) -> Result<JsValue, JsError> {
    let pairs: Vec<(String, String)> = from_js(pairs, "params must be [key, value] string pairs")?;
    let (config, errors) = config::from_params(pairs.iter().map(|(k, v)| (k.as_str(), v.as_str())));
    #[derive(serde::Serialize)]
    struct Error {
        field: &'static str,
        value: String,
        allowed: String,
        message: String,
    }
    #[derive(serde::Serialize)]
    struct Out {
        config: Config,
        errors: Vec<Error>,
    }
    to_js(&Out {
        config,
        errors: errors
            .into_iter()
            .map(|e| Error {
                message: e.to_string(),
                field: e.field,
                value: e.value,
                allowed: e.allowed,
            })
            .collect(),
    })
}

/// Returns `config` with parameter `key` set from text, as an editor does
/// (a new n moves the start inside and rescales a painted prior).
#[wasm_bindgen(js_name = setParam)]
pub fn set_param(config: JsValue, key: &str, raw: &str) -> Result<JsValue, JsError> {
    let mut cfg = config_from_js(config)?;
    cfg.edit(key, raw).map_err(err)?;
    cfg.validate().map_err(err)?;
    to_js(&cfg)
}

/// The name of the preset whose every value `config` has, or null.
///
/// # Errors
/// When `config` is not a valid configuration.
#[wasm_bindgen(js_name = presetOf)]
pub fn preset_of(config: JsValue) -> Result<Option<String>, JsError> {
    let cfg = config_from_js(config)?;
    Ok(cfg.preset().map(|p| p.name().to_string()))
}

/// `[key, text]` pairs for a URL: every parameter with `full`, else the
/// ones that differ from the default, and the seed.
#[wasm_bindgen(js_name = configParams)]
pub fn config_params(config: JsValue, full: bool) -> Result<JsValue, JsError> {
    to_js(&config_from_js(config)?.params(full))
}

/// The keys of the parameters that affect a run of `config`.
#[wasm_bindgen]
pub fn applicable(config: JsValue) -> Result<JsValue, JsError> {
    to_js(&config_from_js(config)?.applicable())
}

/// `{ label, prior }`: short human descriptions of who searches and of the prior.
#[wasm_bindgen(js_name = describeConfig)]
pub fn describe_config(config: JsValue) -> Result<JsValue, JsError> {
    let cfg = config_from_js(config)?;
    #[derive(serde::Serialize)]
    struct Out {
        label: String,
        prior: String,
    }
    to_js(&Out {
        label: cfg.label(),
        prior: cfg.prior_label(),
    })
}

/// Validates a config object; returns it resolved (every field present).
#[wasm_bindgen(js_name = checkConfig)]
pub fn check_config(config: JsValue) -> Result<JsValue, JsError> {
    to_js(&config_from_js(config)?)
}

/// The 256-entry RGBA lookup table of a palette (1024 bytes), for legends.
#[wasm_bindgen(js_name = paletteLut)]
pub fn palette_lut(palette: &str) -> Result<Vec<u8>, JsError> {
    Ok(parse_palette(palette)?.lut().concat())
}

fn parse_palette(name: &str) -> Result<Palette, JsError> {
    Palette::parse(name).ok_or_else(|| {
        JsError::new(&format!(
            "palette must be one of {}, got {name:?}",
            Palette::NAMES.join(", ")
        ))
    })
}

/// Colours arbitrary masses (a prior being painted) into a new RGBA buffer.
#[wasm_bindgen(js_name = colorizeValues)]
pub fn colorize_values(
    values: &[f64],
    palette: &str,
    scale: &str,
    alpha_lo: u8,
    alpha_hi: u8,
) -> Result<Vec<u8>, JsError> {
    let kind = ScaleKind::parse(scale).ok_or_else(|| {
        JsError::new(&format!(
            "scale must be one of {}, got {scale:?}",
            ScaleKind::NAMES.join(", ")
        ))
    })?;
    let mut out = vec![0u8; 4 * values.len()];
    Colorizer::new(parse_palette(palette)?).colorize_kind(
        values,
        &mut out,
        kind,
        false,
        Alpha::of([alpha_lo, alpha_hi]),
    );
    Ok(out)
}

/// Encodes painted levels (0–15 per cell) as the `paint` parameter's text.
#[wasm_bindgen(js_name = encodePaint)]
pub fn encode_paint(levels: &[u8]) -> String {
    prior::encode_paint(levels)
}

/// Decodes a `paint` parameter into `n * n` levels.
#[wasm_bindgen(js_name = decodePaint)]
pub fn decode_paint(text: &str, n: u32) -> Result<Vec<u8>, JsError> {
    prior::decode_paint(text, n).map_err(err)
}

/// Runs trial `index` of a batch of `config` to the end and returns its
/// [`TrialResult::fields`]. Trials depend only on (config, index), so any
/// split of a batch over Web Workers gives the same results.
#[wasm_bindgen(js_name = runTrial)]
pub fn run_trial(config: JsValue, index: f64) -> Result<Vec<f64>, JsError> {
    let cfg = config_from_js(config)?;
    if !(index >= 0.0 && index.fract() == 0.0 && index <= 9_007_199_254_740_992.0) {
        return Err(JsError::new(&format!(
            "trial index must be an integer in 0..=2^53, got {index}"
        )));
    }
    let mut ep = Episode::trial(&cfg, index as u64).map_err(err)?;
    ep.set_clock(performance_now);
    Ok(ep.run().fields().to_vec())
}

/// Reads a batch's number of trials from text, checked against its range.
#[wasm_bindgen(js_name = parseTrials)]
pub fn parse_trials(raw: &str) -> Result<f64, JsError> {
    Ok(config::TRIALS.int_value(Some(raw)).map_err(err)? as f64)
}

/// The batch statistics (the core's `stats::Summary`, serialised as the
/// CLI's `--json` fields) of trials given as concatenated [`run_trial`] results.
#[wasm_bindgen(js_name = summarizeTrials)]
pub fn summarize_trials(flat: &[f64]) -> Result<JsValue, JsError> {
    let results: Option<Vec<TrialResult>> = flat
        .chunks(TRIAL_FIELDS)
        .map(TrialResult::from_fields)
        .collect();
    match results {
        Some(r) if !r.is_empty() => to_js(&Summary::of(&r)),
        _ => Err(JsError::new(&format!(
            "trials must be a non-empty list of {TRIAL_FIELDS}-number results, got {} numbers",
            flat.len()
        ))),
    }
}

/// Every named experiment: `[{ name, title, help, kind, defaultTrials, defaultPreset }]`.
#[wasm_bindgen(js_name = experimentList)]
pub fn experiment_list() -> Result<JsValue, JsError> {
    to_js(&experiment::list())
}

/// Reads and plans an experiment spec object (strictly: unknown fields are errors).
fn plan_from_js(spec: JsValue) -> Result<Plan, JsError> {
    let v: serde_json::Value = from_js(spec, "experiment spec")?;
    Plan::new(&Spec::from_value(&v).map_err(err)?).map_err(err)
}

/// A unit number from JS: an integer in 0..=2^53.
fn unit_from_js(v: f64, what: &str) -> Result<u64, JsError> {
    if v >= 0.0 && v.fract() == 0.0 && v <= experiment::MAX_UNITS as f64 {
        Ok(v as u64)
    } else {
        Err(JsError::new(&format!(
            "{what} must be an integer in 0..=2^53, got {v}"
        )))
    }
}

/// The plan of `spec`: `{ spec (normalised), experiment (header), points:
/// [{ index, series, x, config }], totalUnits, rowFields }`.
#[wasm_bindgen(js_name = experimentPlan)]
pub fn experiment_plan(spec: JsValue) -> Result<JsValue, JsError> {
    to_js(&plan_from_js(spec)?.summary())
}

/// Runs units `from..to` of `spec` and returns their rows flattened, each
/// `rowFields.length` numbers in `experiment::ROW_FIELDS` order (point,
/// trial, steps, optimal, found, target, value). Units depend only on
/// (spec, unit), so any split over Web Workers gives the CLI's rows.
#[wasm_bindgen(js_name = experimentRun)]
pub fn experiment_run(spec: JsValue, from: f64, to: f64) -> Result<Vec<f64>, JsError> {
    let plan = plan_from_js(spec)?;
    let rows = experiment::run_units_clocked(
        &plan,
        unit_from_js(from, "from")?,
        unit_from_js(to, "to")?,
        Some(performance_now),
    )
    .map_err(err)?;
    Ok(rows.iter().flat_map(|r| r.fields()).collect())
}

/// The result JSON text of `spec` with the rows given (flattened, any order,
/// any subset: a partial set gives partial statistics), with this page's
/// provenance (now, the page's URL). With every row it is byte for byte the
/// CLI's `<name>.json` but for the provenance (`provenance::strip`).
#[wasm_bindgen(js_name = experimentResult)]
pub fn experiment_result(spec: JsValue, rows: &[f64]) -> Result<String, JsError> {
    let plan = plan_from_js(spec)?;
    Ok(ResultSet::from_flat(plan, rows)
        .map_err(err)?
        .stamped_json(&page_provenance()))
}

/// The per-point CSV of a result JSON text, after the `#` lines of the
/// result's provenance (none for a file without one).
#[wasm_bindgen(js_name = experimentCsv)]
pub fn experiment_csv(result: &str) -> Result<String, JsError> {
    provenance::csv_of_result(result, CsvTable::Points).map_err(err)
}

/// The per-trial CSV of a result JSON text (the CLI's `<name>.trials.csv`).
#[wasm_bindgen(js_name = experimentTrialsCsv)]
pub fn experiment_trials_csv(result: &str) -> Result<String, JsError> {
    provenance::csv_of_result(result, CsvTable::Trials).map_err(err)
}

/// The paired comparisons' CSV of a result JSON text (the CLI's
/// `<name>.paired.csv`).
#[wasm_bindgen(js_name = experimentPairedCsv)]
pub fn experiment_paired_csv(result: &str) -> Result<String, JsError> {
    provenance::csv_of_result(result, CsvTable::Paired).map_err(err)
}

/// Reads and checks a result JSON text (the page's or the CLI's) and returns
/// it as an object, with its provenance; a foreign or damaged file is an
/// error saying what is wrong.
#[wasm_bindgen(js_name = experimentRead)]
pub fn experiment_read(text: &str) -> Result<JsValue, JsError> {
    let (set, prov) = provenance::read_stamped(text).map_err(err)?;
    let json = match prov {
        Some(p) => set.stamped_json(&p),
        None => set.to_json(),
    };
    let value: serde_json::Value =
        serde_json::from_str(&json).map_err(|e| JsError::new(&e.to_string()))?;
    to_js(&value)
}

/// Benchmark workload (timed by the caller): rollouts of `policy` between
/// random cells until at least `min_steps` lattice steps; returns the steps.
/// The seed is decimal text, read as the `seed` parameter is.
#[wasm_bindgen(js_name = benchRolloutSteps)]
pub fn bench_rollout_steps(
    policy: &str,
    n: u32,
    rv: f64,
    mu: f64,
    seed: &str,
    min_steps: f64,
) -> Result<f64, JsError> {
    let mut cfg = Config::default();
    cfg.set("seed", seed).map_err(err)?;
    let kind = PolicyKind::parse(policy).ok_or_else(|| {
        JsError::new(&format!(
            "policy must be one of {}, got {policy:?}",
            PolicyKind::NAMES.join(", ")
        ))
    })?;
    crate::bench::rollout_steps(kind, n, rv, mu, cfg.seed, min_steps as u64)
        .map(|s| s as f64)
        .map_err(err)
}

/// Benchmark workload: `loops` MCTS loops of `config` in one call (no frame
/// loop, no drawing); returns `[loops, real moves, episodes finished]`.
#[wasm_bindgen(js_name = benchMctsLoops)]
pub fn bench_mcts_loops(config: JsValue, loops: f64) -> Result<Vec<f64>, JsError> {
    let cfg = config_from_js(config)?;
    let (l, m, e) = crate::bench::mcts_loops(&cfg, loops as u64).map_err(err)?;
    Ok(vec![l as f64, m as f64, e as f64])
}

/// The configurations whose cost per move is benchmarked at side `n`:
/// `[{ label, config }]` (see `bench::move_cases`).
#[wasm_bindgen(js_name = benchMoveCases)]
pub fn bench_move_cases(n: u32) -> Result<JsValue, JsError> {
    let cases: Vec<serde_json::Value> = crate::bench::move_cases(n)
        .into_iter()
        .map(|(label, config)| serde_json::json!({ "label": label, "config": config }))
        .collect();
    to_js(&cases)
}

/// Benchmark workload: real moves of trials 0, 1, … of a config, each
/// with its whole deliberation, made in calls the caller times.
#[wasm_bindgen]
pub struct MoveBench {
    runner: crate::bench::MoveRunner,
}

#[wasm_bindgen]
impl MoveBench {
    /// A workload before the first move of trial 0 of `config`.
    ///
    /// # Errors
    /// A config error naming the field.
    #[wasm_bindgen(constructor)]
    pub fn new(config: JsValue) -> Result<MoveBench, JsError> {
        let cfg = config_from_js(config)?;
        Ok(MoveBench {
            runner: crate::bench::MoveRunner::new(&cfg).map_err(err)?,
        })
    }

    /// Makes `moves` more real moves; returns the moves made so far.
    ///
    /// # Errors
    /// When `moves` is not an integer in 1..=1000000000.
    pub fn run(&mut self, moves: f64) -> Result<f64, JsError> {
        if !(moves.fract() == 0.0 && (1.0..=1e9).contains(&moves)) {
            return Err(JsError::new(&format!(
                "moves must be an integer in 1..=1000000000, got {moves}"
            )));
        }
        self.runner.run(moves as u64).map_err(err)?;
        Ok(self.runner.moves as f64)
    }

    /// Starts the next trial if the last call ended one, so that timing
    /// `run(1)` after it leaves setting up an episode out.
    ///
    /// # Errors
    /// Only if a new trial's config were invalid (it was checked in `new`).
    pub fn ready(&mut self) -> Result<(), JsError> {
        self.runner.ready().map_err(err)
    }

    /// Episodes finished so far.
    pub fn episodes(&self) -> f64 {
        self.runner.episodes as f64
    }
}

/// One episode, or two racing on their own configs, advanced from JS and
/// drawn through frames.
#[wasm_bindgen(js_name = Race)]
pub struct RaceHandle {
    race: CoreRace,
    frames: Vec<FrameBuilder>,
}

#[wasm_bindgen(js_class = Race)]
impl RaceHandle {
    /// Trial 0 of each config in the array `configs` (one or two).
    #[wasm_bindgen(constructor)]
    pub fn new(configs: JsValue) -> Result<RaceHandle, JsError> {
        let list: js_sys::Array = configs
            .dyn_into()
            .map_err(|_| JsError::new("configs must be an array of config objects"))?;
        let configs = list
            .iter()
            .map(config_from_js)
            .collect::<Result<Vec<_>, _>>()?;
        let mut race = CoreRace::new(&configs).map_err(err)?;
        for r in race.runs_mut() {
            r.set_clock(performance_now);
        }
        let frames = race
            .runs()
            .iter()
            .map(|r| FrameBuilder::new(r.torus().cells()))
            .collect();
        Ok(RaceHandle { race, frames })
    }

    /// What stays fixed for each run: `[{ label, config, searcher, deliberates,
    /// help, n, start, target, optimal, lower_bound, layer_names, lineage }]`;
    /// `lower_bound` is the bound on any searcher's mean steps
    /// (`bound::lower_bound_capped`), `layer_names` the names of the layers
    /// the run can draw, `lineage` where it branched (`[{ move, config }]`,
    /// oldest first: the moves kept and the parent's config).
    ///
    /// # Errors
    /// None in practice: every run's config was validated by the constructor.
    pub fn describe(&self) -> Result<JsValue, JsError> {
        #[derive(serde::Serialize)]
        struct Run<'a> {
            label: String,
            config: &'a Config,
            searcher: &'static str,
            deliberates: bool,
            help: &'static str,
            n: u32,
            start: u32,
            target: u32,
            optimal: u32,
            lower_bound: f64,
            layer_names: Vec<&'static str>,
            lineage: &'a [crate::run::race::BranchPoint],
        }
        let runs: Vec<Run> = self
            .race
            .runs()
            .iter()
            .zip(self.race.lineage())
            .map(|(r, lineage)| {
                let info = r.searcher_info();
                Ok(Run {
                    label: r.config().label(),
                    config: r.config(),
                    searcher: info.name,
                    deliberates: info.deliberates,
                    help: info.help,
                    n: r.torus().n(),
                    start: r.start(),
                    target: r.target(),
                    optimal: r.optimal(),
                    lower_bound: crate::analysis::bound::lower_bound_capped(r.config())
                        .map_err(err)?,
                    layer_names: view::layers_of(r),
                    lineage,
                })
            })
            .collect::<Result<_, JsError>>()?;
        to_js(&runs)
    }

    /// `k` loops of work on each unfinished run (moves for a walker, paced
    /// by a racing MCTS run).
    pub fn advance(&mut self, k: f64) {
        self.race.advance(k.max(0.0) as u64);
    }

    /// One MCTS loop (one move for a walker) on each unfinished run.
    #[wasm_bindgen(js_name = stepLoop)]
    pub fn step_loop(&mut self) {
        self.race.step_loop();
    }

    /// Finishes the decision under way and makes one move, on each unfinished run.
    #[wasm_bindgen(js_name = stepMove)]
    pub fn step_move(&mut self) {
        self.race.step_move();
    }

    /// Asks each unfinished run for one more real move; `makeAskedMoves` makes it.
    #[wasm_bindgen(js_name = askMove)]
    pub fn ask_move(&mut self) {
        self.race.ask_move();
    }

    /// One call of bounded length toward the moves asked for; true once all are made.
    #[wasm_bindgen(js_name = makeAskedMoves)]
    pub fn make_asked_moves(&mut self) -> bool {
        self.race.make_asked_moves()
    }

    /// How many runs are still searching.
    pub fn running(&self) -> u32 {
        self.race.running() as u32
    }

    /// One frame per run for the array of frame requests (see `view::FrameRequest`).
    pub fn frames(&mut self, requests: JsValue) -> Result<JsValue, JsError> {
        let requests: Vec<FrameRequest> = from_js(requests, "frame requests")?;
        let now = performance_now();
        let default = FrameRequest::default();
        let frames: Vec<view::Frame> = self
            .frames
            .iter_mut()
            .zip(self.race.runs())
            .enumerate()
            .map(|(i, (fb, ep))| fb.frame(ep, requests.get(i).unwrap_or(&default), now))
            .collect();
        to_js(&frames)
    }

    /// Each run for export: `[{ label, config, path, result, status }]`.
    pub fn export(&self) -> Result<JsValue, JsError> {
        #[derive(serde::Serialize)]
        struct Run<'a> {
            label: String,
            config: &'a Config,
            path: &'a [u32],
            result: TrialResult,
            status: crate::run::episode::Status,
        }
        let runs: Vec<Run> = self
            .race
            .runs()
            .iter()
            .map(|r| Run {
                label: r.config().label(),
                config: r.config(),
                path: r.path(),
                result: r.result(),
                status: r.status(),
            })
            .collect();
        to_js(&runs)
    }
}
