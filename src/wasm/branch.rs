//! The facade's branching calls: a race branched at a move with new
//! configurations, and whether a configuration may branch from another.
//! Thin: every call forwards to the core (`run::branch`, `Race::branch`).

use super::{config_from_js, err, RaceHandle};
use crate::display::view::FrameBuilder;
use crate::run::branch;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(js_class = Race)]
impl RaceHandle {
    /// Branches every run at move `at` (see `run::branch`): run i keeps
    /// its path up to that move and continues with `configs[i]` (an array
    /// of config objects, one per run), standing at (`at`, loop 0). Returns
    /// `describe()`, whose `lineage` then names the branch points.
    ///
    /// # Errors
    /// A bad config or move, a world parameter changed (its key named), a
    /// move past the first run's furthest (the range named), or a timed
    /// run; the runs are then left as they were.
    pub fn branch(&mut self, configs: JsValue, at: f64) -> Result<JsValue, JsError> {
        let list: js_sys::Array = configs
            .dyn_into()
            .map_err(|_| JsError::new("branch: configs must be an array of config objects"))?;
        let configs = list
            .iter()
            .map(config_from_js)
            .collect::<Result<Vec<_>, _>>()?;
        if !(at >= 0.0 && at.fract() == 0.0 && at <= u32::MAX as f64) {
            return Err(JsError::new(&format!(
                "branch: the move must be an integer in 0..=4294967295, got {at}"
            )));
        }
        self.race.branch(&configs, at as u32).map_err(err)?;
        self.frames = self
            .race
            .runs()
            .iter()
            .map(|r| FrameBuilder::new(r.torus().cells()))
            .collect();
        self.describe()
    }
}

/// Why a run of `child` cannot branch from a run of `parent` (a world
/// parameter changed: the message names it), or null when it can.
///
/// # Errors
/// When either is not a valid config object.
#[wasm_bindgen(js_name = branchCheck)]
pub fn branch_check(parent: JsValue, child: JsValue) -> Result<Option<String>, JsError> {
    let (a, b) = (config_from_js(parent)?, config_from_js(child)?);
    Ok(branch::check(&a, &b).err().map(|e| e.to_string()))
}
