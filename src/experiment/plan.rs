//! A plan: the resolved experiment. Its header says what is drawn; its
//! points are series × x values, each with its full validated configuration.
//!
//! A point's configuration is built in this order, each step overriding the
//! one before: the schema's defaults, the preset, the common defaults (N =
//! 40, r_v = 1, start (1,1), L = 100), the experiment's defaults, the spec's
//! params, the series' params, the x value. Every point keeps the spec's
//! seed, so trial i of every point draws from the same streams (common
//! random numbers: points differ by their parameters, not their luck).

use super::defs::{self, Chart, Kind, Metric, SeriesDef, COMMON_DEFAULTS};
use super::spec::{Spec, SpecError};
use crate::config::preset::Preset;
use crate::config::{self, Config};
use crate::param::ParamKind;
use crate::searchers::mcts::search::MS;

/// The x axis: the swept parameter and its values.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Axis {
    /// The parameter key; `None` when the experiment has one x value.
    pub key: Option<String>,
    /// The axis label.
    pub label: String,
    /// The values, as parameter text.
    pub values: Vec<String>,
    /// Every value is a finite number (a numeric axis).
    pub numeric: bool,
    /// A log scale fits.
    pub log: bool,
}

/// The y axis.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct YAxis {
    /// The axis label.
    pub label: String,
    /// A log scale fits.
    pub log: bool,
}

/// Published values drawn beside the results.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Reference {
    /// What they are.
    pub label: String,
    /// The x values (parameter text).
    pub x: Vec<String>,
    /// The values, in the experiment's metric.
    pub y: Vec<f64>,
}

/// What an experiment is and how it is drawn.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Header {
    /// The experiment's name.
    pub name: String,
    /// Its title.
    pub title: String,
    /// Episodes or target samples.
    pub kind: Kind,
    /// What each row's value is.
    pub metric: Metric,
    /// How it is drawn.
    pub chart: Chart,
    /// The x axis.
    pub x: Axis,
    /// The y axis.
    pub y: YAxis,
    /// The series labels, in point order.
    pub series: Vec<String>,
    /// Published values to draw beside the results.
    pub references: Vec<Reference>,
    /// A caveat (time budgets are not reproducible across machines).
    pub note: Option<String>,
}

/// One point: a series at one x value, with its configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Its position in the plan.
    pub index: usize,
    /// Which series (an index into the header's series).
    pub series: usize,
    /// Which x value (an index into the header's x values).
    pub x: usize,
    /// The full, validated configuration (with the spec's seed).
    pub config: Config,
}

/// The resolved experiment.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The normalised spec it was made from.
    pub spec: Spec,
    /// What it is and how it is drawn.
    pub header: Header,
    /// Series-major: every x value of series 0, then of series 1, …
    pub points: Vec<Point>,
    /// Paired comparisons `(series, reference)` by series index, made at
    /// every x value: each series against the first, then the definition's
    /// own pairs; none for target samples.
    pub pairs: Vec<(usize, usize)>,
}

/// The most units a plan may have: unit numbers cross to JS as doubles.
pub const MAX_UNITS: u64 = 1 << 53;

/// The keys that shape a prior: the only ones a targets experiment reads.
const PRIOR_KEYS: &[&str] = &["n", "prior", "sigma", "paint", "target"];

fn y_label(metric: Metric) -> &'static str {
    match metric {
        Metric::Steps => "steps to detection",
        Metric::Excess => "steps − optimal steps",
        Metric::Distance => "ℓ1 distance of the target from the prior's centre",
    }
}

fn numeric_key(key: &str) -> bool {
    matches!(
        config::param(key).map(|p| p.kind),
        Some(ParamKind::Int { .. } | ParamKind::Float { .. } | ParamKind::OptFloat { .. })
    )
}

fn is_numeric(key: Option<&str>, values: &[String]) -> bool {
    key.is_some_and(numeric_key)
        && values
            .iter()
            .all(|v| v.parse::<f64>().is_ok_and(f64::is_finite))
}

/// The swept parameter of a plan: its key, values, label and whether the
/// definition asks for a log axis (`None`: decide from the values).
struct XSpec {
    key: Option<String>,
    values: Vec<String>,
    label: String,
    log: Option<bool>,
}

impl XSpec {
    fn of(spec: &Spec) -> XSpec {
        match (&spec.definition().x, &spec.sweep) {
            (Some(x), _) => XSpec {
                key: Some(x.key.to_string()),
                values: x.values.iter().map(|v| v.to_string()).collect(),
                label: x.label.to_string(),
                log: Some(x.log),
            },
            (None, Some(s)) => XSpec {
                key: Some(s.key.clone()),
                values: s.values.clone(),
                label: s.key.clone(),
                log: None,
            },
            (None, None) => XSpec {
                key: None,
                values: vec![String::new()],
                label: String::new(),
                log: None,
            },
        }
    }
}

/// What every experiment starts from, before its own values: the schema's
/// defaults, `preset`, then the paper's setting (N = 40, r_v = 1, start
/// (1,1), L = 100).
pub fn common_base(preset: Option<Preset>) -> Config {
    let mut base = Config::default();
    if let Some(p) = preset {
        base.apply_preset(p);
    }
    for (k, v) in COMMON_DEFAULTS {
        base.set(k, v)
            .unwrap_or_else(|e| panic!("common default {k}={v}: {e}"));
    }
    base
}

/// The configuration every point starts from: the preset, the common and
/// the definition's defaults, the spec's params and its seed.
fn base_config(spec: &Spec) -> Result<Config, SpecError> {
    let def = spec.definition();
    let mut base = common_base(spec.preset);
    for (k, v) in def.defaults {
        base.set(k, v)
            .unwrap_or_else(|e| panic!("experiment {} default {k}={v}: {e}", def.name));
    }
    for (k, v) in &spec.params {
        base.set(k, v).map_err(|error| SpecError::Param {
            place: "params".into(),
            error,
        })?;
    }
    base.seed = spec.seed;
    Ok(base)
}

/// The series: the spec's, a custom experiment's one base series, or the
/// definition's.
fn series_of(spec: &Spec, x: &XSpec, base: &Config) -> Vec<SeriesDef> {
    let def = spec.definition();
    match &spec.series {
        Some(list) => list
            .iter()
            .map(|s| SeriesDef {
                label: s.label.clone(),
                params: s
                    .params
                    .iter()
                    .map(|(k, v)| (config::param(k).expect("a canonical key").key, v.clone()))
                    .collect(),
            })
            .collect(),
        None if def.is_custom() => vec![SeriesDef {
            label: if x.key.is_some() {
                "base configuration".into()
            } else {
                base.label()
            },
            params: vec![],
        }],
        None => (def.series)(),
    }
}

/// Refuses overrides that could never take effect, rather than ignoring them.
fn check_overrides(spec: &Spec, x: &XSpec, series: &[SeriesDef]) -> Result<(), SpecError> {
    let def = spec.definition();
    let name = def.name;
    for key in spec.params.keys() {
        if x.key.as_deref() == Some(key.as_str()) {
            return Err(SpecError::Conflict(format!(
                "{key} is the x axis of {name} (values {}); it cannot be set in params",
                x.values.join(", ")
            )));
        }
        if !series.is_empty()
            && series
                .iter()
                .all(|s| s.params.iter().any(|(k, _)| k == key))
        {
            return Err(SpecError::Conflict(format!(
                "{key} is set by every series of {name}; it cannot be set in params"
            )));
        }
        if def.kind == Kind::Targets && !PRIOR_KEYS.contains(&key.as_str()) {
            return Err(SpecError::Conflict(format!(
                "{name} only samples targets, so {key} does not affect it (the keys that do: {})",
                PRIOR_KEYS.join(", ")
            )));
        }
    }
    if let (Some(key), Some(list)) = (&x.key, &spec.series) {
        if let Some(s) = list.iter().find(|s| s.params.contains_key(key)) {
            return Err(SpecError::Conflict(format!(
                "{key} is the swept parameter; series {:?} cannot set it",
                s.label
            )));
        }
    }
    Ok(())
}

/// Refuses a parameter that no run would read, as `run` refuses its flag:
/// the spec's params and the swept key must apply to some point, the
/// params of a series the spec gives to some point of that series.
fn check_applies(
    spec: &Spec,
    x: &XSpec,
    series: &[SeriesDef],
    points: &[Point],
) -> Result<(), SpecError> {
    let name = spec.definition().name;
    for key in spec.params.keys().chain(x.key.iter()) {
        let p = config::schema::entry(key).expect("a canonical key");
        if !points.iter().any(|pt| p.applies_to(&pt.config)) {
            return Err(SpecError::NotApplying {
                key: key.clone(),
                series: None,
                why: format!("{name}: {}", p.not_applying(&points[0].config)),
            });
        }
    }
    // The spec's series only: a definition's series may set a key that
    // one of them ignores (rollout for every variant, pomcp's included).
    if spec.series.is_none() {
        return Ok(());
    }
    for (si, s) in series.iter().enumerate() {
        let mine: Vec<&Point> = points.iter().filter(|p| p.series == si).collect();
        for (key, _) in &s.params {
            let p = config::schema::entry(key).expect("a canonical key");
            if !mine.iter().any(|pt| p.applies_to(&pt.config)) {
                return Err(SpecError::NotApplying {
                    key: key.to_string(),
                    series: Some(s.label.clone()),
                    why: p.not_applying(&mine[0].config),
                });
            }
        }
    }
    Ok(())
}

/// Every point, series-major: the base with the series' params and the x
/// value, validated.
fn points_of(base: &Config, series: &[SeriesDef], x: &XSpec) -> Result<Vec<Point>, SpecError> {
    let mut points = Vec::with_capacity(series.len() * x.values.len());
    for (si, s) in series.iter().enumerate() {
        for (xi, xv) in x.values.iter().enumerate() {
            let mut cfg = base.clone();
            for (k, v) in &s.params {
                cfg.set(k, v).map_err(|error| SpecError::Param {
                    place: format!("series {:?}", s.label),
                    error,
                })?;
            }
            if let Some(k) = &x.key {
                cfg.set(k, xv).map_err(|error| SpecError::Param {
                    place: "sweep".into(),
                    error,
                })?;
            }
            cfg.validate().map_err(|error| SpecError::Point {
                point: match &x.key {
                    Some(k) => format!("{:?}, {k}={xv}", s.label),
                    None => format!("{:?}", s.label),
                },
                error,
            })?;
            points.push(Point {
                index: points.len(),
                series: si,
                x: xi,
                config: cfg,
            });
        }
    }
    Ok(points)
}

/// The paired comparisons of a plan: each series against the first, then
/// the definition's pairs (by label; a label not among the series, which a
/// test rules out for the named experiments, is skipped), without repeats.
fn pairs_of(spec: &Spec, series: &[SeriesDef]) -> Vec<(usize, usize)> {
    let def = spec.definition();
    if def.kind != Kind::Episodes {
        return Vec::new();
    }
    let index = |label: &str| series.iter().position(|s| s.label == label);
    let mut pairs: Vec<(usize, usize)> = (1..series.len()).map(|s| (s, 0)).collect();
    for (a, b) in def.pairs {
        if let (Some(a), Some(b)) = (index(a), index(b)) {
            if a != b && !pairs.contains(&(a, b)) {
                pairs.push((a, b));
            }
        }
    }
    pairs
}

/// The header of a plan: the definition's title and axes, the chart, the
/// series' labels and the references.
fn header_of(spec: &Spec, x: XSpec, series: &[SeriesDef], points: &[Point]) -> Header {
    let def = spec.definition();
    let numeric = is_numeric(x.key.as_deref(), &x.values);
    let log = match x.log {
        Some(log) => log,
        None => {
            let xs: Vec<f64> = x.values.iter().filter_map(|v| v.parse().ok()).collect();
            let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = xs.iter().copied().fold(0.0, f64::max);
            numeric && xs.len() > 2 && lo > 0.0 && hi / lo >= 20.0
        }
    };
    let chart = if !def.is_custom() {
        def.chart
    } else if x.key.is_none() {
        Chart::Box
    } else if numeric {
        Chart::Line
    } else {
        Chart::Box
    };
    let timed = points.iter().any(|p| {
        p.config.settings.opt_float(&MS).is_some() && p.config.searcher.info().deliberates
    });
    let note = def
        .note
        .or((timed && def.kind == Kind::Episodes).then_some(defs::TIMING_NOTE))
        .map(str::to_string);
    Header {
        name: def.name.to_string(),
        title: def.title.to_string(),
        kind: def.kind,
        metric: def.metric,
        chart,
        x: Axis {
            key: x.key,
            label: x.label,
            values: x.values,
            numeric,
            log,
        },
        y: YAxis {
            label: y_label(def.metric).to_string(),
            log: def.y_log,
        },
        series: series.iter().map(|s| s.label.clone()).collect(),
        references: def
            .references
            .iter()
            .map(|r| Reference {
                label: r.label.to_string(),
                x: r.x.iter().map(|v| v.to_string()).collect(),
                y: r.y.to_vec(),
            })
            .collect(),
        note,
    }
}

impl Plan {
    /// Resolves `spec` into a header and points.
    ///
    /// # Errors
    /// A [`SpecError`] naming the parameter, the point or the conflict.
    pub fn new(spec: &Spec) -> Result<Plan, SpecError> {
        let def = spec.definition();
        let base = base_config(spec)?;
        let x = XSpec::of(spec);
        let series = series_of(spec, &x, &base);
        check_overrides(spec, &x, &series)?;
        let points = points_of(&base, &series, &x)?;
        if def.kind == Kind::Episodes {
            check_applies(spec, &x, &series, &points)?;
        }
        let total = (points.len() as u64).checked_mul(spec.trials);
        if total.is_none_or(|t| t > MAX_UNITS) {
            return Err(SpecError::Conflict(format!(
                "{} points × {} trials is more than 2^53 units",
                points.len(),
                spec.trials
            )));
        }
        let pairs = pairs_of(spec, &series);
        let header = header_of(spec, x, &series, &points);
        Ok(Plan {
            spec: spec.clone(),
            header,
            points,
            pairs,
        })
    }

    /// Trials (samples) per point.
    pub fn trials(&self) -> u64 {
        self.spec.trials
    }

    /// The number of units: points × trials.
    pub fn total_units(&self) -> u64 {
        self.points.len() as u64 * self.spec.trials
    }

    /// A point's series label.
    pub fn series_label(&self, point: &Point) -> &str {
        &self.header.series[point.series]
    }

    /// A point's x value (empty when the experiment has one x value).
    pub fn x_text(&self, point: &Point) -> &str {
        &self.header.x.values[point.x]
    }
}

/// A point as the page and the result file show it.
#[derive(serde::Serialize)]
pub struct PointView<'a> {
    /// Its position in the plan.
    pub index: usize,
    /// Its series label.
    pub series: &'a str,
    /// Its x value as parameter text.
    pub x: &'a str,
    /// Its configuration.
    pub config: &'a Config,
}

impl Plan {
    /// The points as the page and the result file show them.
    pub fn point_views(&self) -> Vec<PointView<'_>> {
        self.points
            .iter()
            .map(|p| PointView {
                index: p.index,
                series: self.series_label(p),
                x: self.x_text(p),
                config: &p.config,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(json: &str) -> Result<Plan, SpecError> {
        Plan::new(&Spec::from_text(json)?)
    }

    #[test]
    fn every_named_experiment_plans_and_validates() {
        for d in defs::DEFINITIONS {
            let p = plan(&format!(r#"{{"name":"{}"}}"#, d.name)).unwrap();
            assert!(!p.points.is_empty(), "{}", d.name);
            for pt in &p.points {
                pt.config.validate().unwrap();
                assert_eq!(pt.config.seed, 1);
            }
            assert_eq!(
                p.points.len(),
                p.header.series.len() * p.header.x.values.len()
            );
            for r in &p.header.references {
                assert_eq!(r.x.len(), r.y.len());
                assert!(r.x.iter().all(|x| p.header.x.values.contains(x)));
            }
            // Every pair the definition names is made.
            let label = |i: usize| p.header.series[i].as_str();
            for &(a, b) in d.pairs {
                assert!(
                    p.pairs.iter().any(|&(x, y)| (label(x), label(y)) == (a, b)),
                    "{}: pair ({a}, {b}) names a series it does not have",
                    d.name
                );
            }
        }
    }

    #[test]
    fn configs_follow_the_documented_order() {
        let p = plan(r#"{"name":"known-n20","preset":"paper-code","params":{"c":"3"}}"#).unwrap();
        let c = &p.points[0].config;
        assert_eq!(
            (c.n, c.start, c.target, c.rv),
            (20, [11, 11], Some([3, 3]), 0.0)
        );
        assert_eq!(
            c.settings.float(&crate::searchers::mcts::search::C),
            3.0,
            "spec params override the preset"
        );
        assert_eq!(
            c.settings.u32(&crate::searchers::mcts::search::LOOPS),
            100,
            "the x value sets loops"
        );
        assert_eq!(
            p.points[1]
                .config
                .settings
                .u32(&crate::searchers::mcts::search::LOOPS),
            200
        );
        assert_eq!(
            c.settings
                .choice::<crate::searchers::mcts::uct::FinalRule>(
                    &crate::searchers::mcts::search::FINAL
                )
                .name(),
            "uct",
            "the preset applies"
        );
        let p = plan(r#"{"name":"sigma-sweep","seed":"9"}"#).unwrap();
        assert_eq!(p.points.len(), 10 * 11);
        assert_eq!(p.header.series[0], "MCTS, RW rollouts");
        let last = &p.points[p.points.len() - 1].config;
        assert_eq!(
            (last.searcher.name(), last.sigma, last.seed),
            ("spiral", 10.0, 9)
        );
        assert_eq!(
            p.points[11]
                .config
                .settings
                .choice::<crate::searchers::walks::policy::PolicyKind>(
                    &crate::searchers::mcts::search::ROLLOUT
                )
                .name(),
            "levy"
        );
    }

    #[test]
    fn custom_sweeps_any_parameter() {
        for (key, values) in [
            ("n", r#"["10","20"]"#),
            ("variant", r#"["cells","tree"]"#),
            ("target", r#"["3,3","5,5"]"#),
            ("sigma", r#"["1","inf"]"#),
            ("final", r#"["visits","uct"]"#),
            ("step_cap", r#"["50","100"]"#),
        ] {
            let p = plan(&format!(
                r#"{{"name":"custom","sweep":{{"key":"{key}","values":{values}}}}}"#
            ))
            .unwrap_or_else(|e| panic!("{key}: {e}"));
            assert_eq!(p.points.len(), 2, "{key}");
            assert_eq!(p.points[1].config.get(key).unwrap(), p.header.x.values[1]);
        }
        let p = plan(r#"{"name":"custom","sweep":{"key":"loops","values":["10","100","1000"]},"series":[{"label":"a","params":{"rollout":"levy"}},{"label":"b","params":{"searcher":"mcts"}}]}"#).unwrap();
        assert_eq!(p.header.chart, Chart::Line);
        assert!(p.header.x.numeric && p.header.x.log);
        assert_eq!(
            p.points[0]
                .config
                .settings
                .choice::<crate::searchers::walks::policy::PolicyKind>(
                    &crate::searchers::mcts::search::ROLLOUT
                )
                .name(),
            "levy"
        );
        assert_eq!(
            p.points[5]
                .config
                .settings
                .u32(&crate::searchers::mcts::search::LOOPS),
            1000
        );
    }

    #[test]
    fn custom_sweeps_every_schema_parameter() {
        let paint = crate::game::prior::encode_paint(&[1; 36]);
        for e in config::params().iter().filter(|e| e.param().key != "seed") {
            let p = e.param();
            // The searcher that declares it (`mcts` for the game's own).
            let owner = match e.group() {
                "game" => r#""searcher":"mcts""#.to_string(),
                g => format!(r#""searcher":"{g}""#),
            };
            // Params that make the swept key apply, and a value to sweep.
            let (params, value): (&str, String) = match p.key {
                "mu" => (r#""rollout":"levy""#, "1.5".into()),
                "epsilon" => (r#""rollout":"greedy""#, "0.3".into()),
                "tree_nodes" => (r#""variant":"tree""#, p.default.text()),
                "decay" => (r#""variant":"cells""#, "0.5".into()),
                "pomcp_scale" => (r#""variant":"pomcp""#, "left".into()),
                "pomcp_exact" => (r#""variant":"pomcp""#, "0.5".into()),
                "pomcp_depth" => (r#""variant":"pomcp""#, "20".into()),
                "pomcp_plan" => (r#""variant":"pomcp""#, "3".into()),
                "paint" => (r#""prior":"paint""#, paint.clone()),
                "sigma" | "known" | "prior" => (r#""searcher":"mcts""#, p.default.text()),
                "target" => (r#""searcher":"mcts""#, "2,2".into()),
                "loops" => (r#""ms":"0""#, "7".into()),
                "searcher" => (r#""rv":"1""#, "nsarw".into()),
                "horizon" => (r#""searcher":"horizon""#, "3".into()),
                "base" => (r#""searcher":"improve""#, "sweep".into()),
                "beam_width" => (r#""searcher":"beam""#, "7".into()),
                "beam_depth" => (r#""searcher":"beam""#, "9".into()),
                "sweep_pattern" => (r#""searcher":"sweep""#, "helix".into()),
                _ => (owner.as_str(), p.default.text()),
            };
            let n = if p.key == "n" { "" } else { r#""n":"6","# };
            let json = format!(
                r#"{{"name":"custom","trials":1,"params":{{{n}{params}}},"sweep":{{"key":"{}","values":["{value}"]}}}}"#,
                p.key
            );
            let plan = plan(&json).unwrap_or_else(|e| panic!("{}: {e}", p.key));
            assert_eq!(
                plan.points[0].config.get(p.key).unwrap(),
                value,
                "{}",
                p.key
            );
            assert_eq!(plan.header.x.key.as_deref(), Some(p.key));
        }
    }

    #[test]
    fn conflicts_and_bad_values_are_named() {
        let err = |j: &str| plan(j).unwrap_err().to_string();
        assert!(err(r#"{"name":"sigma-sweep","params":{"sigma":"3"}}"#)
            .starts_with("sigma is the x axis of sigma-sweep"));
        assert!(err(r#"{"name":"delta","params":{"searcher":"rw"}}"#)
            .starts_with("searcher is set by every series of delta"));
        assert!(err(r#"{"name":"priors","params":{"loops":"5"}}"#)
            .starts_with("priors only samples targets, so loops does not affect it"));
        assert!(err(
            r#"{"name":"custom","params":{"searcher":"rw"},"sweep":{"key":"mu","values":["2"]}}"#
        )
        .starts_with("mu does not apply to any point of custom: "));
        assert_eq!(
            err(r#"{"name":"custom","series":[{"label":"A","params":{"searcher":"rw","c":"2"}}]}"#),
            "c does not apply to series \"A\": searcher rw does not read it"
        );
        // A series key read at some of its points is kept (sigma, where the prior is Gaussian).
        assert!(plan(r#"{"name":"custom","sweep":{"key":"prior","values":["gaussian","uniform"]},"series":[{"label":"B","params":{"searcher":"rw","sigma":"3"}}]}"#).is_ok());
        assert_eq!(
            err(r#"{"name":"custom","sweep":{"key":"prior","values":["delta","uniform"]},"series":[{"label":"B","params":{"sigma":"3"}}]}"#),
            "sigma does not apply to series \"B\": it applies with prior gaussian or code and no fixed target"
        );
        assert_eq!(
            err(r#"{"name":"known-n20","params":{"n":"10"}}"#),
            "start must be x,y with each in 1..=10, got 11,11 (at point \"MCTS cells\", loops=100)"
        );
        assert!(err(r#"{"name":"custom","sweep":{"key":"n","values":["5"]},"series":[{"label":"a","params":{"n":"6"}}]}"#)
            .contains("series \"a\" cannot set it"));
    }
}
