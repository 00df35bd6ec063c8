//! Searchers: who decides each real move, behind one [`Searcher`] trait,
//! and the registry that names them.
//!
//! Each searcher lives in one file with its [`SearcherInfo`]; [`REGISTRY`]
//! lists them. Adding a searcher is that file plus one line in the
//! registry: the configuration's `searcher` choices, the CLI, the page's
//! controls and its frames all follow from the registry.
//!
//! The walks here (random walk, Lévy flight, NSARW, greedy) are also the
//! MCTS rollout policies ([`Policy`]).

mod beam;
mod greedy;
mod horizon;
mod improve;
pub(crate) mod kept;
mod levy;
pub mod mcts;
mod nsarw;
pub mod plan;
mod policy;
mod random_walk;
mod refine;
mod spiral;
mod sweep;

pub use beam::{Beam, DEFAULT_BEAM_DEPTH, DEFAULT_BEAM_WIDTH, MAX_BEAM};
pub use greedy::Greedy;
pub use horizon::{
    completion, Completion, FarGoal, Horizon, Lookahead, Scored, DEFAULT_HORIZON, MAX_HORIZON,
    SLICE_WORK,
};
pub use improve::{base_mean, Base, Improve};
pub use levy::{flight_end, Directions, FlightLengths, Levy};
pub use nsarw::Nsarw;
pub use policy::{NoVisit, Outcome, Policy, PolicyKind, Visit};
pub use random_walk::RandomWalk;
pub use sweep::{sweep_path, Sweep, SweepPattern};

use crate::config::Config;
use crate::display::view::Layer;
use crate::game::belief::BeliefState;
use crate::game::budget::Budget;
use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::rng::Rng;
use crate::game::traces::Traces;
use crate::run::episode::Counters;
use crate::searchers::mcts::DecisionView;
use std::fmt;

/// What a searcher works with while it decides: the trial's lattice,
/// sensor, belief and random stream, the decision's budget, and where its
/// loops are recorded.
pub struct World<'a> {
    /// The lattice.
    pub torus: &'a Torus,
    /// The detection sensor (MCTS arms it with practice targets).
    pub sensor: &'a mut Sensor,
    /// What is known about the target.
    pub belief: &'a mut BeliefState,
    /// The searcher's random stream.
    pub rng: &'a mut Rng,
    /// The searcher's cell.
    pub pos: u32,
    /// The decision's budget.
    pub budget: &'a mut Budget,
    /// Recent rollout traces, for drawing.
    pub traces: &'a mut Traces,
    /// The episode's rollout counters.
    pub counters: &'a mut Counters,
}

/// Who decides each real move.
pub trait Searcher {
    /// Works on the decision under way for at most `max_loops` loops
    /// (`max_loops` ≥ 1) and returns the move once it is decided. A searcher
    /// that does not deliberate decides at once.
    fn think(&mut self, w: &mut World<'_>, max_loops: u32) -> Option<Move>;

    /// Learns that the real move `m` took the searcher to `pos`.
    fn observe(&mut self, torus: &Torus, m: Move, pos: u32);

    /// The per-cell counts drawn as heat layer `layer`, if this searcher
    /// has them (`scratch` is room for counts it must assemble; none by
    /// default).
    fn counts<'a>(&'a self, layer: Layer, scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        let _ = (layer, scratch);
        None
    }

    /// The decision under way at `pos`, for a searcher that deliberates
    /// (none by default).
    fn decision(&self, torus: &Torus, pos: u32) -> Option<DecisionView> {
        let _ = (torus, pos);
        None
    }

    /// The cells a planner means to enter next, in order (empty for a
    /// searcher that does not plan a path); the page draws it as a layer.
    fn intent(&self) -> &[u32] {
        &[]
    }

    /// How a planner scored the four moves at its last decision, for the
    /// decision panel (`None` for a searcher that does not score moves).
    fn scores(&self) -> Option<MoveScores> {
        None
    }

    /// How far a plan being made has got, while a planner that makes its
    /// plan in slices is making one (`None` otherwise).
    fn planning(&self) -> Option<Planning> {
        None
    }
}

/// How far a plan being made has got, for people: the stage and, where it
/// has a known length, the steps done of it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Planning {
    /// What is being done (e.g. "beam search, depth").
    pub stage: &'static str,
    /// Steps of the stage done.
    pub done: u32,
    /// Steps in the stage (0 when not known ahead).
    pub total: u32,
    /// True for work every move's decision does (rollout improvement's
    /// completions), false for a plan made once before the moves (the beam).
    pub per_move: bool,
    /// How far the step under way has got, in `inner_unit` (0 and "" when
    /// the stage does not say): a completion of rollout improvement takes
    /// seconds on a large lattice, so its moves show the work going on.
    pub inner: u32,
    /// What `inner` counts, for people.
    pub inner_unit: &'static str,
}

impl Planning {
    /// The progress of a plan made once before the moves: `done` of `total`
    /// steps of `stage`, nothing finer.
    pub fn plan(stage: &'static str, done: u32, total: u32) -> Planning {
        Planning {
            stage,
            done,
            total,
            per_move: false,
            inner: 0,
            inner_unit: "",
        }
    }
}

/// A planner's score of each of the four moves (in `Move::ALL` order) and
/// what the score means, so the page can explain the choice without
/// computing anything.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MoveScores {
    /// What a score is, for people (e.g. "mass covered in 4 moves").
    pub meaning: &'static str,
    /// True when a larger score is better.
    pub higher_is_better: bool,
    /// The score per move (NaN for a move that was not scored).
    pub score: [f64; 4],
    /// The move taken, by index in `Move::ALL`.
    pub chosen: u8,
}

/// What a searcher is built from.
pub struct Setup<'a> {
    /// The configuration.
    pub cfg: &'a Config,
    /// The lattice.
    pub torus: &'a Torus,
    /// The start cell.
    pub start: u32,
}

impl Setup<'_> {
    /// The detection sensor of the configuration (validated before a
    /// searcher is built).
    pub fn sensor(&self) -> Sensor {
        Sensor::new(self.torus, self.cfg.rv).expect("rv was validated")
    }
}

/// A registry entry: a searcher's name, what it reads and how to build it.
pub struct SearcherInfo {
    /// The `searcher` value that selects it.
    pub name: &'static str,
    /// A short name for people.
    pub label: &'static str,
    /// How it moves, in one sentence.
    pub help: &'static str,
    /// True when it runs MCTS loops before each move.
    pub deliberates: bool,
    /// True when its path does not depend on chance: until it detects the
    /// target the path is a function of the configuration alone, so one
    /// pass along it gives its exact mean (`crate::analysis::exact`). Random walks
    /// and MCTS draw random numbers.
    pub deterministic: bool,
    /// True when it reads configuration parameter `key` under `cfg`.
    pub uses: fn(&Config, &str) -> bool,
    /// Builds it for a trial.
    pub build: fn(&Setup<'_>) -> Box<dyn Searcher>,
}

/// Every searcher, in the order the CLI and the page list them.
pub static REGISTRY: &[&SearcherInfo] = &[
    &crate::searchers::mcts::INFO,
    &random_walk::INFO,
    &levy::INFO,
    &nsarw::INFO,
    &sweep::INFO,
    &horizon::INFO,
    &improve::INFO,
    &beam::INFO,
    &spiral::INFO,
    #[cfg(test)]
    &tests::STAND_STILL,
];

/// True when the searcher of `cfg` is deterministic ([`SearcherInfo::deterministic`]).
pub fn deterministic(cfg: &Config) -> bool {
    cfg.searcher.info().deterministic
}

/// The names of the registered searchers.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|s| s.name).collect()
}

/// A registered searcher, by name.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct SearcherId(&'static str);

impl SearcherId {
    /// The registered searcher called `name`.
    pub fn parse(name: &str) -> Option<SearcherId> {
        REGISTRY
            .iter()
            .find(|s| s.name == name)
            .map(|s| SearcherId(s.name))
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        self.0
    }

    /// Its registry entry.
    pub fn info(self) -> &'static SearcherInfo {
        // An id is only made from a registry name.
        REGISTRY
            .iter()
            .find(|s| s.name == self.0)
            .copied()
            .unwrap_or(REGISTRY[0])
    }
}

impl fmt::Debug for SearcherId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "SearcherId({})", self.0)
    }
}

impl fmt::Display for SearcherId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

impl serde::Serialize for SearcherId {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

impl<'de> serde::Deserialize<'de> for SearcherId {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<SearcherId, D::Error> {
        let s = String::deserialize(d)?;
        SearcherId::parse(&s).ok_or_else(|| {
            serde::de::Error::custom(format!("expected one of {}, got {s:?}", names().join(", ")))
        })
    }
}

/// A walk used as a searcher: one real move per decision, no deliberation.
pub struct Walker {
    policy: Policy,
}

impl Walker {
    /// A walker that starts at `start`.
    pub fn new(mut policy: Policy, start: u32) -> Walker {
        // A walk never sees the target: the second argument only steers a
        // greedy walk, which is not a standalone searcher.
        policy.begin(start, start);
        Walker { policy }
    }
}

impl Searcher for Walker {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        Some(self.policy.next_move(w.torus, w.rng, w.pos))
    }

    fn observe(&mut self, _torus: &Torus, _m: Move, pos: u32) {
        self.policy.observe(pos);
    }

    fn counts<'a>(&'a self, layer: Layer, _scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        match layer {
            Layer::Visits | Layer::Walker => self.policy.counts(),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The registry's promise: a searcher is one file plus one registry
    //! line. `STAND_STILL` below stands for such a file (registered only in
    //! tests); everything else about it must follow from the registry.
    use super::*;
    use crate::display::view::{FrameBuilder, FrameRequest};
    use crate::run::episode::{Episode, Status};

    /// Shuttles up and down: the simplest searcher that is not a walk.
    struct StandStill {
        up: bool,
    }

    impl Searcher for StandStill {
        fn think(&mut self, _w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
            self.up = !self.up;
            Some(if self.up { Move::Up } else { Move::Down })
        }
        fn observe(&mut self, _torus: &Torus, _m: Move, _pos: u32) {}
    }

    pub static STAND_STILL: SearcherInfo = SearcherInfo {
        name: "test-shuttle",
        label: "Shuttle (test)",
        help: "steps up, then down, for ever",
        deterministic: true,
        deliberates: false,
        uses: |_, _| false,
        build: |_| Box::new(StandStill { up: false }),
    };

    #[test]
    fn a_registered_searcher_reaches_every_surface() {
        // The configuration accepts its name, from text and from JSON.
        let mut cfg = Config::default();
        cfg.set("searcher", "test-shuttle").unwrap();
        cfg.set("step_cap", "7").unwrap();
        cfg.validate().unwrap();
        let json = serde_json::to_string(&cfg).unwrap();
        assert_eq!(serde_json::from_str::<Config>(&json).unwrap(), cfg);
        // The schema lists it, and parameters it does not read do not apply.
        let schema = crate::config::schema();
        assert!(schema.searchers.iter().any(|s| s.name == "test-shuttle"));
        let searcher = schema.params.iter().find(|p| p.key == "searcher").unwrap();
        assert!(searcher.choices.as_ref().unwrap().contains(&"test-shuttle"));
        assert!(!cfg.applicable().contains(&"loops"));
        assert_eq!(cfg.label(), "Shuttle (test)");
        // An episode runs it to the step cap, and frames show it.
        let mut ep = Episode::new(&cfg).unwrap();
        let r = ep.run();
        assert_eq!(ep.status(), Status::Capped);
        assert_eq!(r.steps, 7);
        let path = ep.path();
        assert_eq!(path[2], path[0], "up then down returns");
        let mut fb = FrameBuilder::new(ep.torus().cells());
        let frame = fb.frame(&ep, &FrameRequest::default(), 0.0);
        assert!(frame.decision.is_none());
        assert_eq!(frame.steps, 7);
        // Batches and fingerprints take it like any other.
        assert_eq!(crate::run::batch::run_trials(&cfg, 0, 2).unwrap().len(), 2);
    }

    #[test]
    fn registry_names_are_unique_and_parse() {
        let names = names();
        for (i, n) in names.iter().enumerate() {
            assert!(!names[..i].contains(n), "{n} registered twice");
            assert_eq!(SearcherId::parse(n).unwrap().info().name, *n);
        }
        assert!(SearcherId::parse("astar").is_none());
    }
}
