//! The facade's teaching calls: a loop a phase at a time, the decision's
//! tree, the timeline and seeking on the `Race` handle; paired trials of
//! two configurations. Thin: every call forwards to the core.

use super::{config_from_js, err, from_js, to_js, RaceHandle};
use crate::analysis::paired_runs::summarize;
use crate::run::episode::{TimePoint, TrialResult, TRIAL_FIELDS};
use crate::run::paired::{differences, paired_trial};
use crate::run::timeline::{point_from_json, BackUnit, TimelineMemory};
use crate::searchers::phase::{PhaseKind, PhaseStep};
use crate::searchers::tree_export::{TreeExport, TreeQuery};
use wasm_bindgen::prelude::*;

/// What one run did on a `stepPhase` call.
#[derive(serde::Serialize)]
struct Stepped {
    /// "phase", "work" (a move without loops, or a slice of a plan) or
    /// "none" (ended, or a walker waiting for the run that paces it).
    did: &'static str,
    phase: Option<PhaseKind>,
    /// The real move made, if any.
    moved: Option<crate::game::lattice::Move>,
}

/// A run's place on its timeline.
#[derive(serde::Serialize)]
struct RunTimeline {
    #[serde(flatten)]
    point: TimePoint,
    end: TimePoint,
    memory: TimelineMemory,
}

/// The first run's point and end, and every run's.
#[derive(serde::Serialize)]
struct Timeline {
    #[serde(flatten)]
    point: TimePoint,
    end: TimePoint,
    runs: Vec<RunTimeline>,
}

impl RaceHandle {
    fn run_index(&self, run: f64) -> Result<usize, JsError> {
        let n = self.race.runs().len();
        if run.fract() == 0.0 && run >= 0.0 && (run as usize) < n {
            Ok(run as usize)
        } else {
            Err(JsError::new(&format!(
                "run must be an integer in 0..={}, got {run}",
                n - 1
            )))
        }
    }

    fn tree_of(&self, run: f64, query: JsValue) -> Result<Option<TreeExport>, JsError> {
        let i = self.run_index(run)?;
        let q: TreeQuery = if query.is_undefined() || query.is_null() {
            TreeQuery::default()
        } else {
            from_js(query, "tree query { max_nodes, min_visits, focus }")?
        };
        self.race.runs()[i].tree(&q).transpose().map_err(err)
    }
}

#[wasm_bindgen(js_class = Race)]
impl RaceHandle {
    /// One phase of the loop in flight on each unfinished run (select,
    /// expand, rollout, backup; the last back-up of a decision makes its
    /// move): `[{ did: "phase" | "work" | "none", phase, moved }]`. The
    /// frames then carry each run's `point` and `phase` (what it did).
    #[wasm_bindgen(js_name = stepPhase)]
    pub fn step_phase(&mut self) -> Result<JsValue, JsError> {
        let steps: Vec<Stepped> = self
            .race
            .step_phase()
            .into_iter()
            .map(|s| match s {
                None => Stepped {
                    did: "none",
                    phase: None,
                    moved: None,
                },
                Some(PhaseStep::Phase(k, m)) => Stepped {
                    did: "phase",
                    phase: Some(k),
                    moved: m,
                },
                Some(PhaseStep::Work(m)) => Stepped {
                    did: "work",
                    phase: None,
                    moved: m,
                },
            })
            .collect();
        to_js(&steps)
    }

    /// Where the runs stand: `{ move, loop, phase, end, runs: [{ move,
    /// loop, phase, end, memory: { bytes, cap, snapshots, work_per_byte } }] }`,
    /// the top level the first run's; `end` is the furthest point reached.
    pub fn timeline(&self) -> Result<JsValue, JsError> {
        let runs: Vec<RunTimeline> = self
            .race
            .timeline()
            .into_iter()
            .zip(self.race.memory())
            .map(|((point, end), memory)| RunTimeline { point, end, memory })
            .collect();
        let end = runs
            .iter()
            .map(|r| r.end)
            .max()
            .unwrap_or(TimePoint::at(0, 0));
        to_js(&Timeline {
            point: runs[0].point,
            end,
            runs,
        })
    }

    /// Moves every run to the point `{ move, loop = 0, phase = null }` (see
    /// `timeline`), or run i to the i-th of an array of points, the state
    /// reached going forward; returns `timeline()`.
    ///
    /// # Errors
    /// A bad point, one past every run's end, or an array without one point
    /// per run names the value and what is allowed; the runs are then left
    /// as they were.
    pub fn seek(&mut self, point: JsValue) -> Result<JsValue, JsError> {
        let v: serde_json::Value = serde_wasm_bindgen::from_value(point)
            .map_err(|e| JsError::new(&format!("seek point: {e}")))?;
        match v.as_array() {
            Some(points) => {
                let to = points
                    .iter()
                    .map(point_from_json)
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(err)?;
                self.race.seek_each(&to).map_err(err)?;
            }
            None => self
                .race
                .seek(point_from_json(&v).map_err(err)?)
                .map_err(err)?,
        }
        self.timeline()
    }

    /// Moves every run one `unit` back ("phase", "loop" or "move") from
    /// where the first run stands: a phase, to the start of the loop (or
    /// the loop before), to the start of the decision (or the one before);
    /// at the run's start nothing moves. Returns `timeline()`.
    ///
    /// # Errors
    /// A bad unit names the allowed ones; a timed run cannot go back.
    pub fn back(&mut self, unit: &str) -> Result<JsValue, JsError> {
        let u = BackUnit::parse(unit).ok_or_else(|| {
            JsError::new(&format!(
                "back: unit must be phase, loop or move, got {:?}",
                unit.chars().take(40).collect::<String>()
            ))
        })?;
        self.race.back(u).map_err(err)?;
        self.timeline()
    }

    /// The decision's tree of run `run` cut by `query` (`{ max_nodes,
    /// min_visits, focus: "all" | "best" | node id }`, all optional):
    /// `{ shape: "tree" | "star", nodes: [{ id, parent, move, cell, depth,
    /// visits, value, mean, explore, uct, picks, gained, passes, children,
    /// hidden, leaves, best }], total_nodes, note }` in preorder, or null
    /// for a searcher without one; `mean + explore = uct` is a node's UCT
    /// split as its parent's selection would weigh it now (null at the root).
    ///
    /// # Errors
    /// A bad run index or query, or a focus on a node the tree does not hold.
    pub fn tree(&self, run: f64, query: JsValue) -> Result<JsValue, JsError> {
        match self.tree_of(run, query)? {
            Some(t) => to_js(&t),
            None => Ok(JsValue::NULL),
        }
    }

    /// As `tree`, as columns for large trees: `{ shape, total_nodes, note,
    /// id, parent (−1 at the root), move (0–3, −1 at the root), cell, depth,
    /// visits, value (NaN when unvisited), mean, explore, uct (the UCT split,
    /// NaN at the root), picks (−1 when none), children, hidden, leaves,
    /// best (0/1) }`, typed arrays of one entry per node.
    ///
    /// # Errors
    /// As `tree`.
    #[wasm_bindgen(js_name = treeColumns)]
    pub fn tree_columns(&self, run: f64, query: JsValue) -> Result<JsValue, JsError> {
        let Some(t) = self.tree_of(run, query)? else {
            return Ok(JsValue::NULL);
        };
        let out = js_sys::Object::new();
        let set = |k: &str, v: &JsValue| js_sys::Reflect::set(&out, &JsValue::from_str(k), v);
        let n = &t.nodes;
        let u32s = |f: &dyn Fn(&crate::searchers::tree_export::TreeNode) -> u32| {
            JsValue::from(js_sys::Uint32Array::from(
                &n.iter().map(f).collect::<Vec<_>>()[..],
            ))
        };
        let i32s = |f: &dyn Fn(&crate::searchers::tree_export::TreeNode) -> i32| {
            JsValue::from(js_sys::Int32Array::from(
                &n.iter().map(f).collect::<Vec<_>>()[..],
            ))
        };
        let f64s = |f: &dyn Fn(&crate::searchers::tree_export::TreeNode) -> Option<f64>| {
            JsValue::from(js_sys::Float64Array::from(
                &n.iter()
                    .map(|x| f(x).unwrap_or(f64::NAN))
                    .collect::<Vec<_>>()[..],
            ))
        };
        let columns = [
            ("shape", JsValue::from_str(t.shape.name())),
            ("total_nodes", JsValue::from(t.total_nodes)),
            ("note", JsValue::from_str(t.note)),
            ("id", u32s(&|x| x.id)),
            ("parent", i32s(&|x| x.parent.map_or(-1, |p| p as i32))),
            ("move", i32s(&|x| x.mv.map_or(-1, |m| m as i32))),
            ("cell", u32s(&|x| x.cell)),
            ("depth", u32s(&|x| x.depth)),
            ("visits", u32s(&|x| x.visits)),
            ("picks", i32s(&|x| x.picks.map_or(-1, |p| p as i32))),
            ("children", u32s(&|x| x.children as u32)),
            ("hidden", u32s(&|x| x.hidden as u32)),
            ("leaves", u32s(&|x| x.leaves)),
            ("best", u32s(&|x| x.best as u32)),
            ("value", f64s(&|x| x.value)),
            ("mean", f64s(&|x| x.mean)),
            ("explore", f64s(&|x| x.explore)),
            ("uct", f64s(&|x| x.uct)),
        ];
        for (k, v) in columns {
            set(k, &v).map_err(|_| JsError::new("tree columns: could not set a field"))?;
        }
        Ok(out.into())
    }
}

/// Trial `index` of `configA` and of `configB` on the same target:
/// `2 × TRIAL_FIELDS` numbers, A's `runTrial` fields then B's.
///
/// # Errors
/// A bad config or index, or two configs that draw different targets
/// (they must share seed, n, prior, sigma, paint, target and start).
#[wasm_bindgen(js_name = runPairedTrial)]
pub fn run_paired_trial(
    config_a: JsValue,
    config_b: JsValue,
    index: f64,
) -> Result<Vec<f64>, JsError> {
    let (a, b) = (config_from_js(config_a)?, config_from_js(config_b)?);
    if !(index >= 0.0 && index.fract() == 0.0 && index <= 9_007_199_254_740_992.0) {
        return Err(JsError::new(&format!(
            "trial index must be an integer in 0..=2^53, got {index}"
        )));
    }
    let (ra, rb) = paired_trial(&a, &b, index as u64).map_err(err)?;
    Ok(ra.fields().into_iter().chain(rb.fields()).collect())
}

/// The paired summary of trials given as concatenated `runPairedTrial`
/// results: `{ trials, mean_a, mean_b, difference: { estimate, lo, hi,
/// level, method } (A − B steps), sd_difference, a_wins, ties, b_wins,
/// found_a, found_b }`.
///
/// # Errors
/// When the numbers are not whole pairs of trial results, or a pair's
/// targets differ.
#[wasm_bindgen(js_name = summarizePaired)]
pub fn summarize_paired(flat: &[f64]) -> Result<JsValue, JsError> {
    let pair = 2 * TRIAL_FIELDS;
    let pairs: Option<Vec<(TrialResult, TrialResult)>> = flat
        .chunks(pair)
        .map(|c| {
            let (a, b) = c.split_at(TRIAL_FIELDS.min(c.len()));
            Some((TrialResult::from_fields(a)?, TrialResult::from_fields(b)?))
        })
        .collect();
    match pairs {
        Some(p) if !p.is_empty() && flat.len() % pair == 0 => to_js(&summarize(&p).map_err(err)?),
        _ => Err(JsError::new(&format!(
            "paired trials must be a non-empty list of {pair}-number pairs of results, got {} numbers",
            flat.len()
        ))),
    }
}

/// What differs between two configs, among the parameters either reads:
/// `[{ key, label, a, b }]` (values as text), for a race's titles.
#[wasm_bindgen(js_name = configDifferences)]
pub fn config_differences(config_a: JsValue, config_b: JsValue) -> Result<JsValue, JsError> {
    let (a, b) = (config_from_js(config_a)?, config_from_js(config_b)?);
    to_js(&differences(&a, &b))
}
