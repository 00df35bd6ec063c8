//! The named experiments: what each varies, which series it compares, and
//! the parameter values it starts from.
//!
//! Every experiment starts from the paper's setting ([`COMMON_DEFAULTS`]:
//! N = 40, r_v = 1, start (1,1), L = 100) after the spec's preset, then sets
//! its own defaults; the spec's params, the series and the x value follow
//! (see `plan.rs`). "Every searcher" is MCTS with RW rollouts, MCTS with
//! Lévy rollouts, then every other searcher of the registry, so a searcher
//! added later appears in those experiments without a change here.

use crate::config::preset::Preset;
use crate::game::named::named_enum;
use crate::searchers::mcts::Variant;
use crate::searchers::REGISTRY;

named_enum! {
    /// What a unit of an experiment does.
    pub enum Kind {
        /// Runs one episode (a trial) to detection or the step cap.
        Episodes = "episodes",
        /// Draws one target from the point's prior.
        Targets = "targets",
    }
}

named_enum! {
    /// The number a row reports as its value.
    pub enum Metric {
        /// Real moves until detection (the cap for a capped trial).
        Steps = "steps",
        /// Steps minus the optimal number of steps.
        Excess = "excess",
        /// The target's torus ℓ1 distance from the prior's centre cell.
        Distance = "distance",
    }
}

named_enum! {
    /// How the results are drawn.
    pub enum Chart {
        /// Box plots per x value (or per series when there is one x value).
        Box = "box",
        /// Mean lines with 95% CI bands against a numeric x.
        Line = "line",
        /// One histogram heat map per point.
        Heatmap = "heatmap",
    }
}

named_enum! {
    /// The mark of a series at its points: a shape, so that series differ
    /// by shape as well as by colour (the page draws them with Observable
    /// Plot's symbols of the same names).
    pub enum Marker {
        /// A filled circle.
        Circle = "circle",
        /// A filled square.
        Square = "square",
        /// A filled triangle, point up.
        Triangle = "triangle",
        /// A filled diamond.
        Diamond = "diamond",
        /// An ×.
        Times = "times",
        /// A +.
        Plus = "plus",
        /// A filled five-pointed star.
        Star = "star",
        /// A filled hexagon.
        Hexagon = "hexagon",
        /// A Y of three arms.
        Wye = "wye",
        /// An asterisk of three strokes.
        Asterisk = "asterisk",
    }
}

/// Series colours: Petroff's ten-colour sequence (M. A. Petroff, "Accessible
/// Color Sequences for Data Visualization", 2021; matplotlib's `petroff10`),
/// chosen so that its colours stay apart under the common colour-vision
/// deficiencies. `defs_tests.rs` checks that they do, under simulation.
pub const PALETTE: [[u8; 3]; 10] = [
    [0x3f, 0x90, 0xda],
    [0xff, 0xa9, 0x0e],
    [0xbd, 0x1f, 0x01],
    [0x94, 0xa4, 0xa2],
    [0x83, 0x2d, 0xb6],
    [0xa9, 0x6b, 0x59],
    [0xe7, 0x63, 0x00],
    [0xb9, 0xac, 0x70],
    [0x71, 0x75, 0x81],
    [0x92, 0xda, 0xdd],
];

/// Line dash patterns (on, off, … in pixels; empty: solid), so that lines
/// differ when printed in grey or seen by anyone.
pub const DASHES: [&[u32]; 6] = [
    &[],
    &[9, 4],
    &[2, 3],
    &[10, 3, 2, 3],
    &[16, 5],
    &[6, 3, 2, 3, 2, 3],
];

/// How series `i` is drawn: its colour, line dash and marker. The three
/// cycle with periods 10, 6 and 10, and the dash also changes with each
/// round of colours, so no two of the first 60 series look alike.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SeriesStyle {
    /// Its colour, RGB.
    #[serde(serialize_with = "hex_colour")]
    pub colour: [u8; 3],
    /// Its dash pattern (empty: solid).
    pub dash: &'static [u32],
    /// Its marker.
    pub marker: Marker,
}

fn hex_colour<S: serde::Serializer>(c: &[u8; 3], s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]))
}

/// The style of series `i`.
pub fn series_style(i: usize) -> SeriesStyle {
    let round = i / PALETTE.len();
    SeriesStyle {
        colour: PALETTE[i % PALETTE.len()],
        dash: DASHES[(i + round) % DASHES.len()],
        marker: Marker::ALL[(i + 3 * round) % Marker::ALL.len()],
    }
}

/// The preset of the paper's figures: the authors' code made them.
pub const PAPER: Preset = Preset::PaperCode;

/// Values every experiment starts from (after the preset): the paper's setting.
pub const COMMON_DEFAULTS: &[(&str, &str)] =
    &[("n", "40"), ("rv", "1"), ("start", "1,1"), ("loops", "100")];

/// The x axis of a named experiment.
pub struct XDef {
    /// The swept parameter.
    pub key: &'static str,
    /// The axis label.
    pub label: &'static str,
    /// The values, as parameter text.
    pub values: &'static [&'static str],
    /// Drawn on a log scale.
    pub log: bool,
}

/// Published values drawn beside the results.
pub struct ReferenceDef {
    /// What they are.
    pub label: &'static str,
    /// The x values (parameter text), one per y value.
    pub x: &'static [&'static str],
    /// The values, in the experiment's metric.
    pub y: &'static [f64],
}

/// One series: its label and the parameter values that make it.
#[derive(Clone, Debug, PartialEq)]
pub struct SeriesDef {
    /// The label.
    pub label: String,
    /// Parameter values (schema text).
    pub params: Vec<(&'static str, String)>,
}

/// A named experiment.
pub struct Definition {
    /// The name (CLI argument, file name, spec name).
    pub name: &'static str,
    /// A title for charts.
    pub title: &'static str,
    /// What it shows, in a sentence or two.
    pub help: &'static str,
    /// Episodes or target samples.
    pub kind: Kind,
    /// The value each row reports.
    pub metric: Metric,
    /// How it is drawn.
    pub chart: Chart,
    /// Trials (samples) per point unless the spec says otherwise.
    pub default_trials: u64,
    /// Parameter values after `COMMON_DEFAULTS`, before the spec's params.
    pub defaults: &'static [(&'static str, &'static str)],
    /// The swept parameter; `None` for one x value.
    pub x: Option<XDef>,
    /// The series compared.
    pub series: fn() -> Vec<SeriesDef>,
    /// Paired comparisons `(series, reference)`, by label, besides each
    /// series against the first: those the claims about this experiment
    /// rest on.
    pub pairs: &'static [(&'static str, &'static str)],
    /// A log y axis fits.
    pub y_log: bool,
    /// Published values drawn beside the results.
    pub references: &'static [ReferenceDef],
    /// A caveat shown with the results.
    pub note: Option<&'static str>,
    /// The preset a spec without one gets: the paper's figures default to
    /// the authors' code; the project's own comparisons to none.
    pub default_preset: Option<Preset>,
}

impl Definition {
    /// True for `custom`, whose sweep and series come from the spec.
    pub fn is_custom(&self) -> bool {
        self.name == "custom"
    }
}

fn mcts(rollout: &str, label: &str) -> SeriesDef {
    SeriesDef {
        label: label.to_string(),
        params: vec![("searcher", "mcts".into()), ("rollout", rollout.into())],
    }
}

fn mcts_rw() -> SeriesDef {
    mcts("rw", "MCTS, RW rollouts")
}

fn mcts_levy() -> SeriesDef {
    mcts("levy", "MCTS, Lévy rollouts")
}

fn searcher(name: &str) -> Option<SeriesDef> {
    REGISTRY.iter().find(|s| s.name == name).map(|s| SeriesDef {
        label: s.label.to_string(),
        params: vec![("searcher", s.name.to_string())],
    })
}

/// MCTS with RW and with Lévy rollouts, then every other registered
/// searcher (entries named `test-…` exist only in unit tests and are left out).
pub fn every_searcher() -> Vec<SeriesDef> {
    let mut v = vec![mcts_rw(), mcts_levy()];
    v.extend(
        REGISTRY
            .iter()
            .filter(|s| {
                s.name != crate::searchers::mcts::search::INFO.name && !s.name.starts_with("test-")
            })
            .filter_map(|s| searcher(s.name)),
    );
    v
}

/// The project's searchers, beyond the paper: MCTS as the page runs it
/// (every MCTS variant that is not the paper's code, at the defaults), then
/// every deterministic planner of the registry.
pub fn best_searchers() -> Vec<SeriesDef> {
    let mut v: Vec<SeriesDef> = Variant::ALL
        .iter()
        .filter(|&&var| var != Variant::Code)
        .map(|var| SeriesDef {
            label: format!("MCTS {var}"),
            params: vec![("searcher", "mcts".into()), ("variant", var.name().into())],
        })
        .collect();
    v.extend(
        REGISTRY
            .iter()
            .filter(|s| s.deterministic && !s.name.starts_with("test-"))
            .filter_map(|s| searcher(s.name)),
    );
    v
}

fn mcts_both() -> Vec<SeriesDef> {
    vec![mcts_rw(), mcts_levy()]
}

fn mcts_and_nsarw() -> Vec<SeriesDef> {
    vec![mcts_rw()]
        .into_iter()
        .chain(searcher("nsarw"))
        .collect()
}

fn each_variant() -> Vec<SeriesDef> {
    Variant::ALL
        .iter()
        .map(|v| SeriesDef {
            label: format!("MCTS {v}"),
            params: vec![
                ("searcher", "mcts".into()),
                ("variant", v.name().into()),
                ("rollout", "rw".into()),
            ],
        })
        .collect()
}

fn beliefs() -> Vec<SeriesDef> {
    crate::game::belief::Belief::ALL
        .iter()
        .map(|b| SeriesDef {
            label: format!("MCTS, practice targets from the {b}"),
            params: vec![
                ("searcher", "mcts".into()),
                ("rollout", "rw".into()),
                ("belief", b.name().into()),
            ],
        })
        .collect()
}

fn levy_searchers() -> Vec<SeriesDef> {
    searcher("levy").into_iter().collect()
}

fn targets() -> Vec<SeriesDef> {
    vec![SeriesDef {
        label: "sampled targets".into(),
        params: vec![],
    }]
}

fn none() -> Vec<SeriesDef> {
    Vec::new()
}

/// The paper's claims that MCTS beats the random walk and the Lévy flight,
/// for MCTS with Lévy rollouts (MCTS with RW rollouts is the first series).
const MCTS_AGAINST_WALKS: &[(&str, &str)] = &[
    ("Random walk", "MCTS, Lévy rollouts"),
    ("Lévy flight", "MCTS, Lévy rollouts"),
];

const SIGMA_LABEL: &str = "σ (standard deviation of the target prior)";
const LOOPS_LABEL: &str = "L (MCTS loops per move)";

/// The note every time-budget experiment carries.
pub const TIMING_NOTE: &str = "decision time is measured on the running machine: results depend on its speed and load, and are not reproducible bit for bit across machines or runs";

/// Every named experiment, in the order the CLI and the page list them.
pub static DEFINITIONS: &[Definition] = &[
    Definition {
        name: "priors",
        title: "Sampled targets of the Gaussian prior",
        help: "histograms of sampled targets for σ = 0, 2.5, 10 and ∞ (the paper's Gaussian histograms); trial i draws the target episode i would",
        kind: Kind::Targets,
        metric: Metric::Distance,
        chart: Chart::Heatmap,
        default_trials: 10_000,
        defaults: &[("prior", "gaussian")],
        x: Some(XDef {
            key: "sigma",
            label: SIGMA_LABEL,
            values: &["0", "2.5", "10", "inf"],
            log: false,
        }),
        series: targets,
        pairs: &[],
        y_log: false,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "sigma-sweep",
        title: "Steps against the prior's σ",
        help: "box plots of steps against σ = 0, 1, …, 10 for every searcher (the paper's Gaussian figure)",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Box,
        default_trials: 100,
        defaults: &[("prior", "gaussian")],
        x: Some(XDef {
            key: "sigma",
            label: SIGMA_LABEL,
            values: &["0", "1", "2", "3", "4", "5", "6", "7", "8", "9", "10"],
            log: false,
        }),
        series: every_searcher,
        pairs: MCTS_AGAINST_WALKS,
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "delta",
        title: "A known target: steps of every searcher",
        help: "a delta prior at the centre (a known target), every searcher: steps and excess steps with 95% CIs (the paper's delta figure)",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Box,
        default_trials: 100,
        defaults: &[("prior", "delta")],
        x: None,
        series: every_searcher,
        pairs: MCTS_AGAINST_WALKS,
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "loops",
        title: "Steps against MCTS loops per move (delta target)",
        help: "L = 10 … 1600 loops per move, MCTS with RW and with Lévy rollouts, delta target (the paper's resource-limit figure, loops)",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[("prior", "delta")],
        x: Some(XDef {
            key: "loops",
            label: LOOPS_LABEL,
            values: &["10", "20", "50", "100", "200", "400", "800", "1600"],
            log: true,
        }),
        series: mcts_both,
        pairs: &[],
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "decision-time",
        title: "Steps against decision time per move (delta target)",
        help: "0.1 … 10 ms per move, MCTS with RW and with Lévy rollouts, delta target (the paper's resource-limit figure, time); timed: results depend on the machine",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[("prior", "delta")],
        x: Some(XDef {
            key: "ms",
            label: "decision time per move (ms)",
            values: &["0.1", "0.2", "0.5", "1", "2", "5", "10"],
            log: true,
        }),
        series: mcts_both,
        pairs: &[],
        y_log: true,
        references: &[],
        note: Some(TIMING_NOTE),
        default_preset: Some(PAPER),
    },
    Definition {
        name: "sigma-tail",
        title: "Beyond σ = 10: does MCTS level out to the unknown target?",
        help: "MCTS with RW rollouts and NSARW at σ = 10, 12, 15, 20, 30 and a uniform target (σ = inf): the paper's claims that performance levels out to match the unknown-target case and that returns diminish for σ > 10",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Box,
        default_trials: 100,
        defaults: &[("prior", "gaussian")],
        x: Some(XDef {
            key: "sigma",
            label: SIGMA_LABEL,
            values: &["10", "12", "15", "20", "30", "inf"],
            log: false,
        }),
        series: mcts_and_nsarw,
        pairs: &[],
        y_log: false,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "goals",
        title: "The project's searchers against the lower bound",
        help: "N = 40 from (1,1): a delta target, Gaussian σ = 2.5, 5, 10 and a uniform target; MCTS as the page runs it (each variant) and every planner, beside the lower bound on any searcher's mean (issue 11's goals); step cap 20·N²",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Box,
        default_trials: 100,
        defaults: &[("prior", "gaussian"), ("step_cap", "32000")],
        x: Some(XDef {
            key: "sigma",
            label: SIGMA_LABEL,
            values: &["0", "2.5", "5", "10", "inf"],
            log: false,
        }),
        series: best_searchers,
        pairs: &[],
        y_log: true,
        references: &[],
        note: None,
        default_preset: None,
    },
    Definition {
        name: "uniform",
        title: "An unknown target: steps of every searcher",
        help: "a uniform prior (an unknown target), every searcher (the paper's unknown-target figure)",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Box,
        default_trials: 100,
        defaults: &[("prior", "uniform")],
        x: None,
        series: every_searcher,
        pairs: MCTS_AGAINST_WALKS,
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "nsarw-convergence",
        title: "MCTS and NSARW against lattice size (uniform target)",
        help: "mean steps of MCTS with RW rollouts and of NSARW against N = 10, 20, …, 100, uniform target, with 95% CIs (the paper's convergence figure)",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[("prior", "uniform")],
        x: Some(XDef {
            key: "n",
            label: "N (lattice side)",
            values: &["10", "20", "30", "40", "50", "60", "70", "80", "90", "100"],
            log: false,
        }),
        series: mcts_and_nsarw,
        pairs: &[],
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "known-n20",
        title: "Excess steps against loops, N = 20, known target (3,3)",
        help: "the authors' loops study (MCTSKnown_Hottovy.m): N = 20, target (3,3) known, start (11,11), r_v = 0, L = 100 … 3200, each MCTS variant, beside the authors' published means",
        kind: Kind::Episodes,
        metric: Metric::Excess,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[
            ("n", "20"),
            ("target", "3,3"),
            ("start", "11,11"),
            ("rv", "0"),
            ("step_cap", "1000"),
        ],
        x: Some(XDef {
            key: "loops",
            label: LOOPS_LABEL,
            values: &["100", "200", "400", "800", "1600", "3200"],
            log: true,
        }),
        series: each_variant,
        pairs: &[],
        y_log: true,
        references: &[ReferenceDef {
            label: "authors' published means (PlotMCTsKnownN20.m)",
            x: &["100", "200", "400", "800", "1600", "3200"],
            y: &[19.21, 11.29, 6.54, 3.87, 2.03, 1.0],
        }],
        note: Some("step cap 1000 (60× the optimal 16 moves; the authors used 10 000): a trapped tree-variant episode costs L rollouts per move, so --step-cap 10000 can take hours"),
        default_preset: Some(PAPER),
    },
    Definition {
        name: "belief",
        title: "Practice targets from the prior or the posterior, across σ",
        help: "MCTS with RW rollouts drawing practice targets from the prior (the paper) or from the posterior (searched cells removed), σ = 0 … ∞",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Box,
        default_trials: 100,
        defaults: &[("prior", "gaussian")],
        x: Some(XDef {
            key: "sigma",
            label: SIGMA_LABEL,
            values: &["0", "1", "2.5", "5", "10", "inf"],
            log: false,
        }),
        series: beliefs,
        pairs: &[],
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "levy-mu",
        title: "Lévy flight search against μ (uniform target)",
        help: "steps of the Lévy flight searcher against μ in (1, 3], uniform target, to test the μ ≈ 2 optimum on this torus (MCTS with Lévy rollouts takes minutes per episode at μ = 3 under paper-text: sweep it with custom --rollout levy --sweep mu=…)",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[("prior", "uniform")],
        x: Some(XDef {
            key: "mu",
            label: "Lévy exponent μ",
            values: &["1.1", "1.25", "1.5", "1.75", "2", "2.25", "2.5", "2.75", "3"],
            log: false,
        }),
        series: levy_searchers,
        pairs: &[],
        y_log: false,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "c-sweep",
        title: "Steps against the exploration constant c (delta target)",
        help: "MCTS with RW and with Lévy rollouts against the UCT constant c = 0.25 … 16, delta target",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[("prior", "delta")],
        x: Some(XDef {
            key: "c",
            label: "UCT exploration constant c",
            values: &["0.25", "0.5", "1", "1.4142135623730951", "2", "4", "8", "16"],
            log: true,
        }),
        series: mcts_both,
        pairs: &[],
        y_log: true,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
    Definition {
        name: "custom",
        title: "Custom experiment",
        help: "a sweep of any parameter (spec sweep, --sweep KEY=V1,V2,…) across series (spec series, --series 'LABEL:key=v,…'); without series, one series of the base configuration",
        kind: Kind::Episodes,
        metric: Metric::Steps,
        chart: Chart::Line,
        default_trials: 100,
        defaults: &[],
        x: None,
        series: none,
        pairs: &[],
        y_log: false,
        references: &[],
        note: None,
        default_preset: Some(PAPER),
    },
];

/// The names of every experiment.
pub fn names() -> Vec<&'static str> {
    DEFINITIONS.iter().map(|d| d.name).collect()
}

/// The experiment called `name`.
pub fn find(name: &str) -> Option<&'static Definition> {
    DEFINITIONS.iter().find(|d| d.name == name)
}

#[cfg(test)]
#[path = "defs_tests.rs"]
mod palette_tests;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_searcher_follows_the_registry() {
        let all = every_searcher();
        let labels: Vec<&str> = all.iter().map(|s| s.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "MCTS, RW rollouts",
                "MCTS, Lévy rollouts",
                "Random walk",
                "Lévy flight",
                "NSARW",
                "Sweep",
                "Receding horizon",
                "Rollout improvement",
                "Beam planner",
                "Spiral planner"
            ]
        );
        // The unit tests' shuttle searcher is registered here but left out.
        assert!(REGISTRY.iter().any(|s| s.name == "test-shuttle"));
    }

    #[test]
    fn names_are_unique() {
        let n = names();
        for (i, a) in n.iter().enumerate() {
            assert!(!n[..i].contains(a), "{a} twice");
        }
    }
}
