//! The `#[wasm_bindgen]` facade: thin handles around core types, no logic.
//!
//! The page reads the engine's buffers zero-copy: methods named `*Ptr`
//! return byte offsets into the wasm memory and `*Len` their element counts;
//! JS builds typed-array views over `memory.buffer` after its last wasm call
//! of a frame (memory growth detaches earlier views). Small structs cross as
//! plain JS objects through serde-wasm-bindgen. Every fallible method returns
//! `Result<_, JsError>` so a bad input becomes a JS exception with a message,
//! never a panic; a panic (a bug) is caught by the hook installed in
//! [`start`], logged, and its text kept for [`last_panic`].

use crate::config::Config;
use crate::episode::{Counters, Episode, Status, TrialResult};
use crate::render::{summarize, Alpha, Colorizer, Palette, Scale, Summary};
use crate::searchers::PolicyKind;
use std::sync::Mutex;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// `performance.now()` in ms (window and workers alike).
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

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

/// The crate version, so the page can show which engine it runs.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// The text of the last Rust panic, if any (read after a `RuntimeError`).
#[wasm_bindgen(js_name = lastPanic)]
pub fn last_panic() -> Option<String> {
    LAST_PANIC.lock().ok().and_then(|s| s.clone())
}

/// Panics on purpose, so tests can check that a panic reaches the page.
#[wasm_bindgen(js_name = panicForTest)]
pub fn panic_for_test(message: &str) {
    panic!("panicForTest: {message}");
}

/// The default configuration, as a plain object.
#[wasm_bindgen(js_name = defaultConfig)]
pub fn default_config() -> Result<JsValue, JsError> {
    to_js(&Config::default())
}

/// Parses and validates a configuration object; returns the resolved config.
#[wasm_bindgen(js_name = checkConfig)]
pub fn check_config(config: JsValue) -> Result<JsValue, JsError> {
    let cfg = parse_config(config)?;
    cfg.validate().map_err(|e| JsError::new(&e.to_string()))?;
    to_js(&cfg)
}

/// The 256-entry RGBA lookup table of a palette (1024 bytes), for legends.
#[wasm_bindgen(js_name = paletteLut)]
pub fn palette_lut(palette: &str) -> Result<Vec<u8>, JsError> {
    Ok(parse_palette(palette)?.lut().concat())
}

/// Colours arbitrary values (e.g. a prior being painted) into a new RGBA buffer.
#[wasm_bindgen(js_name = colorizeValues)]
pub fn colorize_values(
    values: &[f64],
    palette: &str,
    scale: &str,
    alpha_lo: u8,
    alpha_hi: u8,
) -> Result<Vec<u8>, JsError> {
    let col = Colorizer::new(parse_palette(palette)?);
    let mut out = vec![0u8; 4 * values.len()];
    let max = summarize(values).max;
    col.colorize(
        values,
        &mut out,
        parse_scale(scale, max, false)?,
        alpha(alpha_lo, alpha_hi),
    );
    Ok(out)
}

/// Benchmark workload (timed by the caller with `performance.now()`): rollouts
/// of `policy` (rw, levy, nsarw, greedy) between random cells until at least
/// `min_steps` lattice steps; returns the steps made.
#[wasm_bindgen(js_name = benchRolloutSteps)]
pub fn bench_rollout_steps(
    policy: &str,
    n: u32,
    rv: f64,
    mu: f64,
    seed: u64,
    min_steps: f64,
) -> Result<f64, JsError> {
    let kind = PolicyKind::parse(policy).ok_or_else(|| {
        JsError::new(&format!(
            "policy must be rw, levy, nsarw or greedy, got {policy:?}"
        ))
    })?;
    crate::bench::rollout_steps(kind, n, rv, mu, seed, min_steps as u64)
        .map(|s| s as f64)
        .map_err(|e| JsError::new(&e.to_string()))
}

/// Benchmark workload: `loops` MCTS loops of `config` in one call (no frame
/// loop, no drawing); returns `[loops, real moves, episodes finished]`.
#[wasm_bindgen(js_name = benchMctsLoops)]
pub fn bench_mcts_loops(config: JsValue, seed: u64, loops: f64) -> Result<Vec<f64>, JsError> {
    let cfg = parse_config(config)?;
    let (l, m, e) = crate::bench::mcts_loops(&cfg, seed, loops as u64)
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(vec![l as f64, m as f64, e as f64])
}

/// Numbers per trial in [`run_trial`]'s result and [`summarize_trials`]' input.
const TRIAL_FIELDS: usize = 7;

/// Runs trial `index` of a batch of `config` with `seed` to the end and returns
/// `[steps, optimal, found (0/1), target, rollouts, rollout_steps, truncated]`.
/// Trial streams derive from `(seed, index)` only, so any split of a batch
/// over Web Workers gives the same results.
#[wasm_bindgen(js_name = runTrial)]
pub fn run_trial(config: JsValue, seed: u64, index: f64) -> Result<Vec<f64>, JsError> {
    let cfg = parse_config(config)?;
    let mut ep =
        Episode::trial(&cfg, seed, index as u64).map_err(|e| JsError::new(&e.to_string()))?;
    ep.set_clock(performance_now);
    let r = ep.run();
    Ok(vec![
        r.steps as f64,
        r.optimal as f64,
        r.found as u8 as f64,
        r.target as f64,
        r.counters.rollouts as f64,
        r.counters.rollout_steps as f64,
        r.counters.truncated as f64,
    ])
}

/// The batch statistics (the core's `stats::Summary`: means with 95% CIs,
/// ASOO, ratio, quartiles, capped, ...) of trials given as concatenated
/// [`run_trial`] results.
#[wasm_bindgen(js_name = summarizeTrials)]
pub fn summarize_trials(flat: &[f64]) -> Result<JsValue, JsError> {
    if flat.len() % TRIAL_FIELDS != 0 || flat.is_empty() {
        return Err(JsError::new(&format!(
            "trials must be a non-empty list of {TRIAL_FIELDS}-number results, got {} numbers",
            flat.len()
        )));
    }
    let results: Vec<TrialResult> = flat
        .chunks_exact(TRIAL_FIELDS)
        .map(|t| TrialResult {
            steps: t[0] as u32,
            optimal: t[1] as u32,
            found: t[2] != 0.0,
            target: t[3] as u32,
            counters: Counters {
                rollouts: t[4] as u64,
                rollout_steps: t[5] as u64,
                truncated: t[6] as u64,
            },
        })
        .collect();
    to_js(&crate::stats::Summary::of(&results))
}

fn parse_config(config: JsValue) -> Result<Config, JsError> {
    // serde-wasm-bindgen reads only the fields it knows, so `deny_unknown_fields`
    // never fires for a JS object: reject unknown keys (typos) here instead.
    if let Some(obj) = config.dyn_ref::<js_sys::Object>() {
        let known = js_sys::Object::keys(&to_js(&Config::default())?.into());
        for key in js_sys::Object::keys(obj).iter() {
            if !known.includes(&key, 0) {
                let names: Vec<String> = known.iter().filter_map(|k| k.as_string()).collect();
                return Err(JsError::new(&format!(
                    "config: unknown field {:?}, expected one of {}",
                    key.as_string().unwrap_or_default(),
                    names.join(", ")
                )));
            }
        }
    }
    serde_wasm_bindgen::from_value(config).map_err(|e| JsError::new(&format!("config: {e}")))
}

fn to_js<T: serde::Serialize>(value: &T) -> Result<JsValue, JsError> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| JsError::new(&e.to_string()))
}

fn parse_palette(name: &str) -> Result<Palette, JsError> {
    Palette::parse(name).ok_or_else(|| {
        JsError::new(&format!(
            "palette must be viridis, ember or cividis, got {name:?}"
        ))
    })
}

/// Log scale floor: 1 for counts; four decades below the maximum for masses.
fn parse_scale(name: &str, max: f64, counts: bool) -> Result<Scale, JsError> {
    match name {
        "linear" => Ok(Scale::Linear),
        "stretch" => Ok(Scale::Stretch),
        "log" => Ok(Scale::Log {
            floor: if counts { 1.0 } else { max * 1e-4 },
        }),
        _ => Err(JsError::new(&format!(
            "scale must be linear, stretch or log, got {name:?}"
        ))),
    }
}

fn alpha(lo: u8, hi: u8) -> Alpha {
    if lo == 255 && hi == 255 {
        Alpha::Opaque
    } else {
        Alpha::Ramp { lo, hi }
    }
}

fn status_name(s: Status) -> &'static str {
    match s {
        Status::Running => "running",
        Status::Found => "found",
        Status::Capped => "capped",
    }
}

/// The heatmap layers the page can draw.
const LAYERS: [&str; 6] = ["prior", "plan", "posterior", "visits", "searched", "walker"];

/// One episode, advanced from JS frame by frame.
#[wasm_bindgen(js_name = Episode)]
pub struct EpisodeHandle {
    ep: Episode,
    /// One RGBA buffer per entry of `LAYERS`, allocated on first use.
    rgba: Vec<Vec<u8>>,
    colorizers: Vec<Colorizer>,
    summary: Summary,
    /// Kept rollout traces, flattened newest first, with offsets.
    trace_cells: Vec<u32>,
    trace_offsets: Vec<u32>,
    trace_targets: Vec<u32>,
}

#[wasm_bindgen(js_class = Episode)]
impl EpisodeHandle {
    /// A new episode from a config object (the core's `Config` fields) and a seed.
    #[wasm_bindgen(constructor)]
    pub fn new(config: JsValue, seed: u64) -> Result<EpisodeHandle, JsError> {
        let cfg = parse_config(config)?;
        let mut ep = Episode::new(&cfg, seed).map_err(|e| JsError::new(&e.to_string()))?;
        ep.set_clock(performance_now);
        Ok(EpisodeHandle {
            ep,
            rgba: vec![Vec::new(); LAYERS.len()],
            colorizers: Palette::ALL.iter().map(|&p| Colorizer::new(p)).collect(),
            summary: Summary::default(),
            trace_cells: Vec::new(),
            trace_offsets: Vec::new(),
            trace_targets: Vec::new(),
        })
    }

    /// Runs up to `k` loops of the current decision; true when the real move was made.
    #[wasm_bindgen(js_name = stepLoops)]
    pub fn step_loops(&mut self, k: u32) -> bool {
        self.ep.step_loops(k)
    }

    /// Completes the current decision and makes one real move; returns the status.
    #[wasm_bindgen(js_name = stepMove)]
    pub fn step_move(&mut self) -> String {
        status_name(self.ep.step_move()).to_string()
    }

    /// "running", "found" or "capped".
    pub fn status(&self) -> String {
        status_name(self.ep.status()).to_string()
    }

    /// Lattice side N.
    pub fn n(&self) -> u32 {
        self.ep.torus().n()
    }

    /// Real moves so far.
    pub fn steps(&self) -> u32 {
        self.ep.steps()
    }

    /// Fewest moves that detect the target.
    pub fn optimal(&self) -> u32 {
        self.ep.optimal()
    }

    /// The true target cell (0-based index).
    pub fn target(&self) -> u32 {
        self.ep.target()
    }

    /// The start cell (0-based index).
    pub fn start(&self) -> u32 {
        self.ep.start()
    }

    /// The searcher's cell (0-based index).
    pub fn position(&self) -> u32 {
        self.ep.position()
    }

    /// The seed.
    pub fn seed(&self) -> u64 {
        self.ep.seed()
    }

    /// Byte offset of the path (u32 cell indices, start first).
    #[wasm_bindgen(js_name = pathPtr)]
    pub fn path_ptr(&self) -> u32 {
        self.ep.path().as_ptr() as u32
    }

    /// Length of the path in cells (steps + 1).
    #[wasm_bindgen(js_name = pathLen)]
    pub fn path_len(&self) -> u32 {
        self.ep.path().len() as u32
    }

    /// A copy of the path, for export and tests.
    pub fn path(&self) -> Vec<u32> {
        self.ep.path().to_vec()
    }

    /// Loops done in the decision under way.
    #[wasm_bindgen(js_name = loopsDone)]
    pub fn loops_done(&self) -> u32 {
        self.ep.loops_done()
    }

    /// Rollouts over the episode (as f64: exact below 2^53).
    #[wasm_bindgen(js_name = rolloutsTotal)]
    pub fn rollouts_total(&self) -> f64 {
        self.ep.counters().rollouts as f64
    }

    /// Rollout lattice steps over the episode.
    #[wasm_bindgen(js_name = rolloutStepsTotal)]
    pub fn rollout_steps_total(&self) -> f64 {
        self.ep.counters().rollout_steps as f64
    }

    /// Truncated rollouts over the episode.
    #[wasm_bindgen(js_name = truncatedTotal)]
    pub fn truncated_total(&self) -> f64 {
        self.ep.counters().truncated as f64
    }

    /// Rollouts in the decision under way (or the last one).
    #[wasm_bindgen(js_name = decisionRollouts)]
    pub fn decision_rollouts(&self) -> f64 {
        self.ep.decision_counters().rollouts as f64
    }

    /// Rollout steps in the decision under way (or the last one).
    #[wasm_bindgen(js_name = decisionRolloutSteps)]
    pub fn decision_rollout_steps(&self) -> f64 {
        self.ep.decision_counters().rollout_steps as f64
    }

    /// Prior mass not yet searched.
    #[wasm_bindgen(js_name = remainingMass)]
    pub fn remaining_mass(&self) -> f64 {
        self.ep.remaining_mass()
    }

    /// Nodes in the `tree` arena.
    #[wasm_bindgen(js_name = treeNodes)]
    pub fn tree_nodes(&self) -> u32 {
        self.ep.tree_nodes() as u32
    }

    /// The decision under way: `{ parent_visits, c, children: [{cell, visits,
    /// reward, mean, explore, uct, selected}; 4] }` (moves up, right, down, left;
    /// an unvisited child has explore and uct = Infinity).
    pub fn decision(&self) -> Result<JsValue, JsError> {
        to_js(&self.ep.decision_view())
    }

    /// The result so far: `{ steps, optimal, found, target, counters }`.
    pub fn result(&self) -> Result<JsValue, JsError> {
        to_js(&self.ep.result())
    }

    /// The resolved configuration.
    pub fn config(&self) -> Result<JsValue, JsError> {
        to_js(self.ep.config())
    }

    /// Colours one heatmap layer into this handle's RGBA buffer for it and
    /// returns its byte offset (0 when the layer is empty for this searcher).
    /// Layers: prior, plan, posterior, visits, searched, walker. Scale: linear
    /// stretch (min to max) or log. Alpha `255,255` is opaque; otherwise zero is transparent and the
    /// rest ramps from `alpha_lo` to `alpha_hi`. The layer's value summary is
    /// then available from `layerMax` / `layerSum`.
    #[wasm_bindgen(js_name = renderLayer)]
    pub fn render_layer(
        &mut self,
        layer: &str,
        palette: &str,
        scale: &str,
        alpha_lo: u8,
        alpha_hi: u8,
    ) -> Result<u32, JsError> {
        let li = LAYERS.iter().position(|&l| l == layer).ok_or_else(|| {
            JsError::new(&format!(
                "layer must be one of {}, got {layer:?}",
                LAYERS.join(", ")
            ))
        })?;
        let pal = parse_palette(palette)?;
        let col = &self.colorizers[Palette::ALL.iter().position(|&p| p == pal).unwrap_or(0)];
        let cells = self.ep.torus().cells();
        let buf = &mut self.rgba[li];
        if buf.len() != 4 * cells {
            *buf = vec![0u8; 4 * cells];
        }
        let a = alpha(alpha_lo, alpha_hi);
        let ep = &mut self.ep;
        self.summary = match layer {
            "prior" => {
                let v = ep.prior_mass();
                col.colorize(v, buf, parse_scale(scale, summarize(v).max, false)?, a)
            }
            "plan" => {
                let v = ep.plan_mass();
                col.colorize(v, buf, parse_scale(scale, summarize(v).max, false)?, a)
            }
            "posterior" => {
                let v = ep.posterior_mass();
                col.colorize(v, buf, parse_scale(scale, summarize(v).max, false)?, a)
            }
            "visits" | "walker" => {
                let v = if layer == "visits" {
                    ep.visit_counts()
                } else {
                    ep.walker_counts()
                };
                if v.is_empty() {
                    self.summary = Summary::default();
                    return Ok(0);
                }
                col.colorize(v, buf, parse_scale(scale, 0.0, true)?, a)
            }
            _ => col.colorize(ep.searched(), buf, Scale::Linear, a),
        };
        Ok(buf.as_ptr() as u32)
    }

    /// Largest value of the last rendered layer.
    #[wasm_bindgen(js_name = layerMax)]
    pub fn layer_max(&self) -> f64 {
        self.summary.max
    }

    /// Sum of the last rendered layer.
    #[wasm_bindgen(js_name = layerSum)]
    pub fn layer_sum(&self) -> f64 {
        self.summary.sum
    }

    /// Smallest nonzero value of the last rendered layer (0 if all are zero).
    #[wasm_bindgen(js_name = layerMin)]
    pub fn layer_min(&self) -> f64 {
        self.summary.min_nonzero
    }

    /// Gathers the kept rollout traces (newest first) into flat buffers and
    /// returns how many there are; read them with `traceCellsPtr`,
    /// `traceOffsetsPtr` (count + 1 offsets) and `traceTargetsPtr`.
    #[wasm_bindgen(js_name = collectTraces)]
    pub fn collect_traces(&mut self) -> u32 {
        self.trace_cells.clear();
        self.trace_offsets.clear();
        self.trace_targets.clear();
        self.trace_offsets.push(0);
        for (cells, target) in self.ep.traces() {
            self.trace_cells.extend_from_slice(cells);
            self.trace_offsets.push(self.trace_cells.len() as u32);
            self.trace_targets.push(target);
        }
        self.trace_targets.len() as u32
    }

    /// Byte offset of the flattened trace cells.
    #[wasm_bindgen(js_name = traceCellsPtr)]
    pub fn trace_cells_ptr(&self) -> u32 {
        self.trace_cells.as_ptr() as u32
    }

    /// Byte offset of the trace offsets (count + 1 entries).
    #[wasm_bindgen(js_name = traceOffsetsPtr)]
    pub fn trace_offsets_ptr(&self) -> u32 {
        self.trace_offsets.as_ptr() as u32
    }

    /// Byte offset of the practice targets, one per trace.
    #[wasm_bindgen(js_name = traceTargetsPtr)]
    pub fn trace_targets_ptr(&self) -> u32 {
        self.trace_targets.as_ptr() as u32
    }
}
