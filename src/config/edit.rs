//! Reading, writing and checking a configuration by parameter key, as the
//! CLI, the URL, the page's controls and experiment sweeps do.

use super::fields::{Config, FIELDS};
use super::preset::Preset;
use super::schema::{entry, params, ConfigParam, PRESET};
use crate::game::prior::{self, PriorKind};
use crate::param::kind::{fmt_float, shown};
use crate::param::{ParamError, ParamKind, Settings};
use crate::searchers::mcts::pomcp::params::POMCP_PLAN;
use crate::searchers::mcts::search::{LOOPS, MS, ROLLOUT, VARIANT};
use crate::searchers::mcts::variant::Variant;
use crate::searchers::registry::SearcherId;
use crate::searchers::walks::policy::PolicyKind;

impl Default for Config {
    fn default() -> Config {
        // Placeholders only: every field is then set from its default.
        let mut c = Config {
            n: 0,
            prior: PriorKind::Gaussian,
            sigma: 0.0,
            paint: String::new(),
            rv: 0.0,
            start: [0, 0],
            target: None,
            known: false,
            searcher: SearcherId::parse("mcts").expect("mcts is registered"),
            step_cap: 0,
            seed: 0,
            settings: Settings::default(),
        };
        for f in FIELDS {
            (f.set)(&mut c, &f.param.default);
        }
        c
    }
}

fn unknown(key: &str) -> ParamError {
    ParamError {
        field: "parameter",
        value: shown(key),
        allowed: format!(
            "one of {}",
            params()
                .iter()
                .map(|p| p.param().key)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

impl Config {
    /// Checks every parameter against its range, the cells against n and a
    /// painted prior against the lattice.
    ///
    /// # Errors
    /// The first [`ParamError`] found, naming the parameter and its range.
    pub fn validate(&self) -> Result<(), ParamError> {
        for p in params() {
            let param = p.param();
            param.kind.check(param.key, &p.value(self))?;
        }
        let n = self.n;
        for (key, cell) in [("start", Some(self.start)), ("target", self.target)] {
            if let Some([x, y]) = cell {
                if !(1..=n).contains(&x) || !(1..=n).contains(&y) {
                    return Err(ParamError::new(
                        key,
                        format!("{x},{y}"),
                        format!("x,y with each in 1..={n}"),
                    ));
                }
            }
        }
        if self.prior == PriorKind::Paint && self.target.is_none() {
            // Without a painting the prior is at fault (a URL's fallback
            // then resets the prior, not the empty paint).
            if self.paint.is_empty() {
                return Err(ParamError::new(
                    "prior",
                    "paint",
                    "gaussian, delta, uniform or code unless a paint is given",
                ));
            }
            prior::decode_paint(&self.paint, n)
                .map_err(|e| ParamError::new("paint", e, ParamKind::Paint.allowed()))?;
        }
        Ok(())
    }

    /// Sets parameter `key` from text, checking its range (not its relation
    /// to other parameters: [`Config::validate`] does that).
    ///
    /// The key [`PRESET`] is not a parameter: it sets every value of that
    /// preset, so a URL or a form can name one.
    ///
    /// # Errors
    /// A [`ParamError`] for an unknown key or a value out of range.
    pub fn set(&mut self, key: &str, raw: &str) -> Result<(), ParamError> {
        if key == PRESET {
            self.apply_preset(Preset::from_name(raw)?);
            return Ok(());
        }
        let p = entry(key).ok_or_else(|| unknown(key))?;
        let v = p.param().parse(raw)?;
        p.assign(self, v);
        Ok(())
    }

    /// Sets `key` as an editor does: a new n also moves the start and target
    /// inside the lattice and rescales a painted prior.
    ///
    /// # Errors
    /// As [`Config::set`].
    pub fn edit(&mut self, key: &str, raw: &str) -> Result<(), ParamError> {
        let old_n = self.n;
        self.set(key, raw)?;
        let n = self.n;
        if n != old_n {
            let inside = |[x, y]: [u32; 2]| [x.min(n), y.min(n)];
            self.target = self.target.map(inside);
            self.start = inside(self.start);
            if let Ok(levels) = prior::decode_paint(&self.paint, old_n) {
                self.paint = prior::encode_paint(&prior::resize_paint(&levels, old_n, n));
            }
        }
        Ok(())
    }

    /// Parameter `key` as text.
    ///
    /// # Errors
    /// A [`ParamError`] for an unknown key.
    pub fn get(&self, key: &str) -> Result<String, ParamError> {
        let p = entry(key).ok_or_else(|| unknown(key))?;
        Ok(p.value(self).text())
    }

    /// `(key, text)` pairs for a URL: every parameter with `full`, else those
    /// that differ from the default, and the seed always (a link reproduces
    /// the run). Values that do not apply are kept too: switching back to
    /// what reads them restores them.
    pub fn params(&self, full: bool) -> Vec<(&'static str, String)> {
        let d = Config::default();
        params()
            .iter()
            .filter(|p| full || p.param().key == "seed" || p.value(self) != p.value(&d))
            .map(|p| (p.param().key, p.value(self).text()))
            .collect()
    }

    /// The keys of the parameters that affect a run of this config.
    pub fn applicable(&self) -> Vec<&'static str> {
        params()
            .iter()
            .filter(|p| p.applies_to(self))
            .map(|p| p.param().key)
            .collect()
    }

    /// Sets every value of `preset`; other values are kept.
    pub fn apply_preset(&mut self, preset: Preset) {
        for (key, value) in preset.edits() {
            // A test sets every preset's values: they are keys and values
            // of the schema.
            if let Err(e) = self.set(key, value) {
                debug_assert!(false, "preset {preset} sets {key}={value}: {e}");
            }
        }
    }

    /// The preset whose every value this config has, if any.
    pub fn preset(&self) -> Option<Preset> {
        Preset::ALL.iter().copied().find(|p| {
            p.edits()
                .iter()
                .all(|(key, value)| self.get(key).is_ok_and(|v| v == *value))
        })
    }

    /// This configuration with each `(key, value)` set as the CLI and URL
    /// would set it, for tests and examples that read best as a list of
    /// settings.
    ///
    /// # Panics
    /// If a key is unknown or a value out of its range.
    pub fn with(mut self, settings: &[(&str, &str)]) -> Config {
        for (k, v) in settings {
            self.set(k, v).unwrap_or_else(|e| panic!("{k} = {v}: {e}"));
        }
        self
    }

    /// A short human label of who searches and how, e.g.
    /// "MCTS cells · rw rollouts · L=100".
    pub fn label(&self) -> String {
        let info = self.searcher.info();
        if !info.deliberates {
            return info.label.to_string();
        }
        let s = &self.settings;
        let budget = s
            .opt_float(&MS)
            .map_or_else(|| format!("L={}", s.u32(&LOOPS)), |ms| format!("{ms} ms"));
        let variant: Variant = s.choice(&VARIANT);
        // The belief MCTS rolls out with its own walks: along its plan, or
        // the coverage walk without one.
        let rollout = match variant {
            Variant::Pomcp if s.u32(&POMCP_PLAN) > 0 => "plan",
            Variant::Pomcp => "coverage",
            _ => s.choice::<PolicyKind>(&ROLLOUT).name(),
        };
        format!("{} {variant} · {rollout} rollouts · {budget}", info.label)
    }

    /// A line that describes the prior, e.g. "gaussian sigma=5".
    pub fn prior_label(&self) -> String {
        match (self.target, self.prior) {
            (Some([x, y]), _) => format!("target ({x},{y})"),
            (None, PriorKind::Gaussian) => format!("gaussian sigma={}", fmt_float(self.sigma)),
            (None, PriorKind::Code) => format!("code sigma={}", fmt_float(self.sigma)),
            (None, k) => k.name().to_string(),
        }
    }
}

/// Parses `(key, text)` pairs into a config, as the URL does: a bad value
/// keeps its default and yields an error, so one typo does not lose the
/// rest. Unknown keys are errors too. After the pairs, the cross-field
/// rules of [`Config::validate`] reset what they reject to the default.
pub fn from_params<'a>(
    pairs: impl IntoIterator<Item = (&'a str, &'a str)>,
) -> (Config, Vec<ParamError>) {
    let mut cfg = Config::default();
    let mut errors = Vec::new();
    // A preset goes first wherever it appears, so that the other pairs
    // override it as flags after `--preset` do.
    let (presets, fields): (Vec<_>, Vec<_>) =
        pairs.into_iter().partition(|&(key, _)| key == PRESET);
    for (key, raw) in presets.into_iter().chain(fields) {
        if let Err(e) = cfg.set(key, raw) {
            errors.push(e);
        }
    }
    // Each rejected cross-field value falls back to its default; a few
    // rounds settle it (start, target and paint are independent).
    for _ in 0..params().len() {
        match cfg.validate() {
            Ok(()) => break,
            Err(e) => {
                let p: ConfigParam = entry(e.field).expect("validate names parameters");
                p.assign(&mut cfg, p.param().default.clone());
                errors.push(e);
            }
        }
    }
    (cfg, errors)
}
