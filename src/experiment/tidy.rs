//! The tidy per-trial CSV of a result: one row per trial, with the
//! parameters that differ between points as columns.

use super::defs::Kind;
use super::output::{num, quote};
use super::plan::Plan;
use super::result::ResultSet;
use crate::config::{self, schema::ConfigParam};

/// The columns every trials CSV starts with; then one column per
/// parameter that varies between the points, named by its key.
pub const TRIALS_COLUMNS: [&str; 12] = [
    "point", "series", "x", "trial", "seed", "target_x", "target_y", "steps", "capped", "optimal",
    "excess", "value",
];

/// The parameters that take more than one value among the points of
/// `plan` they apply to, in schema order, with each point's value (empty
/// where the parameter does not apply: `rollout` for a random walk).
pub fn varying(plan: &Plan) -> Vec<(&'static str, Vec<String>)> {
    let shown = |e: ConfigParam, cfg: &config::Config| {
        if e.applies_to(cfg) {
            e.value(cfg).text()
        } else {
            String::new()
        }
    };
    config::params()
        .iter()
        .filter(|e| e.param().key != "seed")
        .filter_map(|&e| {
            let values: Vec<String> = plan.points.iter().map(|p| shown(e, &p.config)).collect();
            let mut applying = plan
                .points
                .iter()
                .zip(&values)
                .filter(|(p, _)| e.applies_to(&p.config))
                .map(|(_, v)| v);
            let first = applying.next()?;
            applying
                .any(|v| v != first)
                .then_some((e.param().key, values))
        })
        .collect()
}

impl ResultSet {
    /// One CSV line per trial present, point by point in trial order,
    /// after a header line ([`TRIALS_COLUMNS`], then the varying
    /// parameters). Targets are 1-based `x`, `y` as `--target` takes them;
    /// `capped` is 1 for a trial ended by the step cap; for target samples
    /// the episode columns are empty and `value` is the distance.
    pub fn trials_csv(&self) -> String {
        let vary = varying(&self.plan);
        let mut out = TRIALS_COLUMNS.join(",");
        for (key, _) in &vary {
            out.push(',');
            out.push_str(key);
        }
        out.push('\n');
        let episodes = self.plan.header.kind == Kind::Episodes;
        let seed = self.plan.spec.seed.to_string();
        for (p, rows) in self.plan.points.iter().zip(self.rows_by_point()) {
            let n = p.config.n;
            let label = quote(self.plan.series_label(p));
            let x = quote(self.plan.x_text(p));
            let params: String = vary
                .iter()
                .map(|(_, values)| format!(",{}", quote(&values[p.index])))
                .collect();
            for r in rows {
                let ep = |v: String| if episodes { v } else { String::new() };
                let fields = [
                    p.index.to_string(),
                    label.clone(),
                    x.clone(),
                    r.trial.to_string(),
                    seed.clone(),
                    (r.target % n + 1).to_string(),
                    (r.target / n + 1).to_string(),
                    ep(r.steps.to_string()),
                    ep((!r.found as u8).to_string()),
                    ep(r.optimal.to_string()),
                    ep((r.steps as i64 - r.optimal as i64).to_string()),
                    num(r.value as f64),
                ];
                out.push_str(&fields.join(","));
                out.push_str(&params);
                out.push('\n');
            }
        }
        out
    }
}
