//! MCTS as a searcher: before each real move, L loops of a practice target
//! from the belief, UCT selection, a rollout and backpropagation, over a
//! variant's statistics; then the final rule's move. Its parameters, and
//! the escape from searched ground, live here.

use super::cells::{CellTable, DECAY};
use super::code::CodeTable;
use super::pomcp::params::{POMCP_DEPTH, POMCP_EXACT, POMCP_PLAN, POMCP_SCALE};
use super::pomcp::BeliefTree;
use super::tree::{Tree, TREE_NODES};
use super::uct::{final_move, FinalRule};
use super::variant::{LoopEnv, LoopReport, Stats, Variant};
use crate::game::belief::Belief;
use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Torus};
use crate::game::layer::Layer;
use crate::param::{Param, ParamKind, Settings, Value};
use crate::searchers::decision::{DecisionView, Planning};
use crate::searchers::info::{Reads, SearcherInfo};
use crate::searchers::phase::{PhaseKind, PhaseRecord, PhaseStep};
use crate::searchers::planning::far_goal::{fallback_target, toward, FarScan};
use crate::searchers::searcher::{Searcher, Setup, World};
use crate::searchers::tree_export::{TreeError, TreeExport, TreeQuery};
use crate::searchers::walks::greedy::EPSILON;
use crate::searchers::walks::levy::MU;
use crate::searchers::walks::policy::{Policy, PolicyKind};
use std::borrow::Cow;

/// Which MCTS variant keeps the statistics.
pub static VARIANT: Param = Param {
    key: "variant",
    label: "MCTS variant",
    kind: ParamKind::Choice(|| Variant::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("cells")),
    help: "MCTS statistics: cells (the paper's per-cell table), tree (a search tree with subtree reuse), code (the authors' MATLAB statistics, for the paper-code preset) or pomcp (a belief MCTS on the posterior, beyond the paper)",
    aliases: &[],
    choice_labels: &["cells (the paper's table)", "tree (a search tree)", "code (the authors' MATLAB)", "pomcp (belief MCTS)"],
    advanced: false,
};

/// The rollout (default) policy.
pub static ROLLOUT: Param = Param {
    key: "rollout",
    label: "Rollout policy",
    kind: ParamKind::Choice(|| PolicyKind::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("rw")),
    help: "MCTS rollout policy: rw, levy, nsarw or greedy (toward the practice target)",
    aliases: &[],
    choice_labels: &["random walk", "Lévy flight", "NSARW", "greedy"],
    advanced: false,
};

/// Where practice targets come from.
pub static BELIEF: Param = Param {
    key: "belief",
    label: "Practice targets from",
    kind: ParamKind::Choice(|| Belief::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("posterior")),
    help: "where practice targets come from: prior (the paper) or posterior (the prior with searched cells removed)",
    aliases: &[],
    choice_labels: &["prior (the paper)", "posterior"],
    advanced: false,
};

/// MCTS loops per real move.
pub static LOOPS: Param = Param {
    key: "loops",
    label: "Loops per move L",
    kind: ParamKind::Int {
        min: 1,
        max: 10_000_000,
    },
    default: Value::Int(100),
    help: "MCTS loops per real move (when ms is 0)",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// A decision-time budget per real move instead of loops.
pub static MS: Param = Param {
    key: "ms",
    label: "Time per move (ms)",
    kind: ParamKind::OptFloat {
        min: 0.001,
        max: 600_000.0,
    },
    default: Value::OptFloat(None),
    help: "MCTS decision time per real move in milliseconds instead of loops (0 = use loops; timed runs depend on the machine)",
    aliases: &["decision-ms"],
    choice_labels: &[],
    advanced: true,
};

/// The UCT exploration constant.
pub static C: Param = Param {
    key: "c",
    label: "Exploration c",
    kind: ParamKind::Float {
        min: 0.0,
        max: 1e6,
        min_open: false,
    },
    default: Value::Float(std::f64::consts::SQRT_2),
    help: "UCT exploration constant c",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// How the real move is chosen.
pub static FINAL: Param = Param {
    key: "final",
    label: "Final move rule",
    kind: ParamKind::Choice(|| FinalRule::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("auto")),
    help: "how the real move is chosen: visits (picked most this decision), mean (best mean reward), uct (best UCT value) or auto (the variant's rule: uct for the per-cell tables cells and code, visits for tree)",
    aliases: &[],
    choice_labels: &["most picks", "best mean", "best UCT", "the variant's rule"],
    advanced: false,
};

/// The rollout step cap.
pub static ROLLOUT_CAP: Param = Param {
    key: "rollout_cap",
    label: "Rollout step cap",
    kind: ParamKind::Int {
        min: 1,
        max: 1_000_000_000,
    },
    default: Value::Int(10_000),
    help: "rollout step cap (a truncated rollout earns 0 and is counted)",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// Clear the statistics before each real move.
pub static RESET_EACH_MOVE: Param = Param {
    key: "reset_each_move",
    label: "Reset each move",
    kind: ParamKind::Bool,
    default: Value::Bool(false),
    help: "cells: clear the statistics table before each real move",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// The default `escape`: stalled moves before an MCTS heads for unsearched
/// mass. Ten lets the search work its way out of a searched patch on its own
/// most of the time (a shuttle of 2 or 4 cells is well within it) and bounds
/// how long a trap can last.
pub const DEFAULT_ESCAPE: u32 = 10;

/// Stalled moves before an escape.
pub static ESCAPE: Param = Param {
    key: "escape",
    label: "Escape after stalled moves",
    kind: ParamKind::Int {
        min: 0,
        max: 1_000_000,
    },
    default: Value::Int(DEFAULT_ESCAPE as u64),
    help: "MCTS: after this many real moves in a row that search no new cell, walk straight to the cell with the most unsearched mass per step of distance, then search again (not while the belief MCTS follows its plan, which cannot trap it); 0 never (the paper)",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// Recent rollout traces kept for drawing.
pub static KEEP_TRACES: Param = Param {
    key: "keep_traces",
    label: "Rollout traces kept",
    kind: ParamKind::Int { min: 0, max: 64 },
    default: Value::Int(0),
    help: "how many recent rollout traces to keep for drawing",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

fn variant(s: &Settings) -> Variant {
    s.choice(&VARIANT)
}

fn not_pomcp(s: &Settings) -> bool {
    variant(s) != Variant::Pomcp
}

/// MCTS as a searcher: the variant keeps the statistics.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "mcts",
    label: "MCTS",
    help: "before each move it runs L loops: a practice target from the belief, UCT selection, a rollout, backpropagation",
    deterministic: false,
    deliberates: true,
    // The belief MCTS always plans on the posterior with its own rollout,
    // and plays by its own rule.
    params: &[
        Reads::always(&VARIANT),
        Reads::when(&ROLLOUT, not_pomcp, "with a variant other than pomcp"),
        Reads::when(&BELIEF, not_pomcp, "with a variant other than pomcp"),
        Reads::when(&LOOPS, |s| s.opt_float(&MS).is_none(), "when ms is 0"),
        Reads::always(&MS),
        Reads::always(&C),
        Reads::when(
            &MU,
            |s| not_pomcp(s) && s.choice::<PolicyKind>(&ROLLOUT) == PolicyKind::Levy,
            "with rollout levy",
        ),
        Reads::when(
            &EPSILON,
            |s| not_pomcp(s) && s.choice::<PolicyKind>(&ROLLOUT) == PolicyKind::Greedy,
            "with rollout greedy",
        ),
        Reads::when(&FINAL, not_pomcp, "with a variant other than pomcp"),
        Reads::always(&ROLLOUT_CAP),
        Reads::when(
            &RESET_EACH_MOVE,
            |s| matches!(variant(s), Variant::Cells | Variant::Code),
            "with variant cells or code",
        ),
        Reads::when(&DECAY, |s| variant(s) == Variant::Cells, "with variant cells"),
        Reads::always(&ESCAPE),
        Reads::when(
            &TREE_NODES,
            |s| matches!(variant(s), Variant::Tree | Variant::Pomcp),
            "with variant tree or pomcp",
        ),
        Reads::when(&POMCP_SCALE, |s| !not_pomcp(s), "with variant pomcp"),
        Reads::when(&POMCP_EXACT, |s| !not_pomcp(s), "with variant pomcp"),
        Reads::when(&POMCP_DEPTH, |s| !not_pomcp(s), "with variant pomcp"),
        Reads::when(&POMCP_PLAN, |s| !not_pomcp(s), "with variant pomcp"),
        Reads::always(&KEEP_TRACES),
    ],
    build: |s| {
        let (cells, set) = (s.torus.cells(), s.settings);
        match variant(set) {
            Variant::Cells => Box::new(Mcts::new(CellTable::with_decay(cells, set.float(&DECAY)), s)),
            Variant::Tree => Box::new(Mcts::new(Tree::new(set.u32(&TREE_NODES)), s)),
            Variant::Code => Box::new(Mcts::new(CodeTable::new(cells), s)),
            Variant::Pomcp => Box::new(Mcts::new(
                BeliefTree::new(
                    cells,
                    set.u32(&TREE_NODES),
                    set.choice(&POMCP_SCALE),
                    set.float(&POMCP_EXACT),
                    set.u32(&POMCP_DEPTH),
                    set.u32(&POMCP_PLAN),
                ),
                s,
            )),
        }
    },
};

/// The rule that picks the real move: the `final` parameter, except for
/// the belief MCTS, whose returns are exact expectations of a path it can
/// follow, so it plays the child through which the best one was found (its
/// scaled value, the `mean` rule).
///
/// `auto` is the variant's own rule. The per-cell tables (`cells`, `code`)
/// play the best UCT value, the move both of the paper's proofs pick: their
/// counts are mostly rollouts passing through, and rewards 1/τ of about
/// 10⁻³ leave UCT's selection to those counts, so the most selected child
/// is where fewest rollouts pass (ahead, whatever the target), and more
/// loops only make that choice surer. A tree's counts are its selections:
/// it plays the most selected child.
pub fn final_rule(s: &Settings) -> FinalRule {
    match (variant(s), s.choice(&FINAL)) {
        (Variant::Pomcp, _) => FinalRule::Mean,
        (Variant::Cells | Variant::Code, FinalRule::Auto) => FinalRule::Uct,
        (Variant::Tree, FinalRule::Auto) => FinalRule::Visits,
        (_, rule) => rule,
    }
}

/// A loop stepped phase by phase: its practice target, the last phase
/// done, and whether it is recorded.
#[derive(Clone, Copy, Debug)]
struct Flight {
    practice: u32,
    done: PhaseKind,
    recording: bool,
}

/// UCT search with a variant's statistics and a rollout policy.
#[derive(Clone)]
pub struct Mcts<S: Stats> {
    stats: S,
    policy: Policy,
    c: f64,
    final_rule: FinalRule,
    rollout_cap: u32,
    reset_each_move: bool,
    cells: usize,
    /// The belief's generation at the last decision.
    generation: Option<u64>,
    /// The belief's unsearched planning mass at the last decision.
    mass: Option<f64>,
    /// Moves in a row that searched no new cell.
    stalled: u32,
    /// Escape after this many stalled moves (0 = never).
    escape: u32,
    /// The cell an escape is heading for.
    escape_to: Option<u32>,
    /// An empty simulation, for the fallback target's gains.
    coverage: Coverage,
    /// Scratch for the escape's fallback scan.
    scan: FarScan,
    /// The loop in flight, when stepped phase by phase.
    flight: Option<Flight>,
    /// What the phases of the recorded loop did.
    record: PhaseRecord,
}

impl<S: Stats> Mcts<S> {
    /// A searcher with these statistics, configured by `setup`.
    pub fn new(stats: S, setup: &Setup<'_>) -> Mcts<S> {
        let s = setup.settings;
        Mcts {
            stats,
            policy: Policy::new(
                s.choice(&ROLLOUT),
                setup.torus,
                s.float(&MU),
                s.float(&EPSILON),
            ),
            c: s.float(&C),
            final_rule: final_rule(s),
            rollout_cap: s.u32(&ROLLOUT_CAP),
            reset_each_move: s.flag(&RESET_EACH_MOVE),
            cells: setup.torus.cells(),
            generation: None,
            mass: None,
            stalled: 0,
            escape: s.u32(&ESCAPE),
            escape_to: None,
            coverage: Coverage::new(setup.torus.cells()),
            scan: FarScan::default(),
            flight: None,
            record: PhaseRecord::default(),
        }
    }

    /// Opens a decision: counts stalled moves and, when stuck in searched
    /// ground, returns the escape's move instead of deliberating.
    fn open(&mut self, w: &mut World<'_>) -> Option<Move> {
        let generation = w.belief.generation();
        if self.generation == Some(generation) {
            self.stalled += 1;
        } else {
            self.stalled = 0;
            self.escape_to = None;
        }
        if self.escape > 0 && self.stalled >= self.escape && !self.stats.holds_plan() {
            // Stuck in searched ground: walk to unsearched mass without
            // deliberating (the target keeps mass until the belief
            // changes, which ends the escape).
            if self.escape_to.is_none() {
                self.escape_to = fallback_target(
                    w.torus,
                    w.sensor,
                    w.belief,
                    &self.coverage,
                    w.pos,
                    None,
                    &mut self.scan,
                    None,
                )
                .map(|(c, _)| c);
            }
            if let Some(target) = self.escape_to {
                let m = toward(w.torus, w.pos, target, Move::Up);
                self.generation = Some(generation);
                return Some(m);
            }
        }
        w.budget.open();
        // Searched cells without mass (all but the target's at a delta
        // prior) change no practice target: nothing is stale.
        let mass = w.belief.remaining();
        if let Some(before) = self.mass.filter(|&b| mass < b) {
            self.stats.belief_changed(1.0 - mass / before);
        }
        self.mass = Some(mass);
        self.generation = Some(generation);
        self.stats
            .begin_decision(w.torus, w.pos, self.reset_each_move);
        None
    }

    /// A practice target for the next loop.
    fn practice(w: &mut World<'_>) -> u32 {
        if S::POSTERIOR_TARGETS {
            w.belief.posterior_target(w.rng)
        } else {
            w.belief.practice_target(w.rng)
        }
    }

    /// Runs phase `kind` of the loop chasing `practice` (armed), recording
    /// it when `recording`; the back-up returns the loop's report.
    fn run_phase(
        &mut self,
        w: &mut World<'_>,
        practice: u32,
        kind: PhaseKind,
        recording: bool,
    ) -> Option<LoopReport> {
        // A recorded loop's trace is the record's; otherwise the ring's.
        let mut trace = std::mem::take(&mut self.record.trace);
        let pos = w.pos;
        let mut env = LoopEnv {
            torus: w.torus,
            belief: w.belief,
            sensor: w.sensor,
            mask: w.sensor.mask(),
            practice,
            policy: &mut self.policy,
            rng: w.rng,
            rollout_cap: self.rollout_cap,
            c: self.c,
            trace: if recording {
                Some(&mut trace)
            } else {
                w.traces.slot()
            },
        };
        let rec = recording.then_some(&mut self.record);
        let report = match kind {
            PhaseKind::Select => {
                self.stats.select(&mut env, pos, rec);
                None
            }
            PhaseKind::Expand => {
                self.stats.expand(&mut env, pos, rec);
                None
            }
            PhaseKind::Rollout => {
                self.stats.roll_out(&mut env, pos, rec);
                None
            }
            PhaseKind::Backup => Some(self.stats.back_up(&mut env, pos, rec)),
        };
        self.record.trace = trace;
        if recording {
            self.record.phase = Some(kind);
            if let Some(r) = report {
                self.record.counts = r.counts;
            }
        }
        report
    }

    /// Counts a finished loop (a recorded one's trace goes to the ring);
    /// returns true when it is one of the decision's loops.
    fn end_loop(
        &mut self,
        w: &mut World<'_>,
        practice: u32,
        report: LoopReport,
        recorded: bool,
    ) -> bool {
        if recorded {
            if let Some(slot) = w.traces.slot() {
                slot.clear();
                slot.extend_from_slice(&self.record.trace);
            }
        }
        w.traces.commit(practice);
        w.counters.add(report.rollout_steps, report.detected);
        if report.counts {
            w.budget.record(report.rollout_steps, report.detected);
        }
        report.counts
    }

    /// Ends the decision: the statistics' own move or the final rule's.
    fn decide(&mut self, w: &mut World<'_>) -> Move {
        let m = match self
            .stats
            .conclude(w.torus, w.sensor, w.belief, self.rollout_cap)
        {
            Some(m) => m,
            None => final_move(
                &self.stats.view(w.torus, w.pos, self.c),
                self.final_rule,
                w.rng,
            ),
        };
        w.budget.close();
        m
    }

    /// Finishes the loop in flight with the phases it has left, as a loop
    /// run whole would; returns true when it counts against the budget.
    fn land(&mut self, w: &mut World<'_>, f: Flight) -> bool {
        w.sensor.arm(f.practice);
        let mut kind = f.done;
        let report = loop {
            kind = kind.next().expect("a loop in flight has yet to back up");
            if let Some(r) = self.run_phase(w, f.practice, kind, f.recording) {
                break r;
            }
        };
        self.end_loop(w, f.practice, report, f.recording)
    }
}

impl<S: Stats + 'static> Searcher for Mcts<S> {
    fn think(&mut self, w: &mut World<'_>, max_loops: u32) -> Option<Move> {
        if !w.budget.is_open() {
            if let Some(m) = self.open(w) {
                return Some(m);
            }
        }
        if !self
            .stats
            .prepare(w.torus, w.sensor, w.belief, w.pos, self.rollout_cap)
        {
            return None;
        }
        let mut done = 0;
        if let Some(f) = self.flight.take() {
            done += u32::from(self.land(w, f));
        }
        while done < max_loops && !w.budget.spent() {
            let practice = Self::practice(w);
            w.sensor.arm(practice);
            let mut env = LoopEnv {
                torus: w.torus,
                belief: w.belief,
                sensor: w.sensor,
                mask: w.sensor.mask(),
                practice,
                policy: &mut self.policy,
                rng: w.rng,
                rollout_cap: self.rollout_cap,
                c: self.c,
                trace: w.traces.slot(),
            };
            let report = self.stats.iterate(&mut env, w.pos);
            w.traces.commit(practice);
            w.counters.add(report.rollout_steps, report.detected);
            if report.counts {
                w.budget.record(report.rollout_steps, report.detected);
                done += 1;
            }
        }
        if !w.budget.spent() {
            return None;
        }
        Some(self.decide(w))
    }

    fn think_phase(&mut self, w: &mut World<'_>, record: bool) -> PhaseStep {
        if !w.budget.is_open() {
            if let Some(m) = self.open(w) {
                return PhaseStep::Work(Some(m));
            }
        }
        if !self
            .stats
            .prepare(w.torus, w.sensor, w.belief, w.pos, self.rollout_cap)
        {
            return PhaseStep::Work(None);
        }
        let (practice, kind, recording) = match self.flight {
            Some(f) => (
                f.practice,
                f.done.next().expect("a loop in flight has yet to back up"),
                f.recording,
            ),
            None => {
                let practice = Self::practice(w);
                if record {
                    self.record.begin(practice);
                }
                (practice, PhaseKind::Select, record)
            }
        };
        w.sensor.arm(practice);
        match self.run_phase(w, practice, kind, recording) {
            None => {
                self.flight = Some(Flight {
                    practice,
                    done: kind,
                    recording,
                });
                PhaseStep::Phase(kind, None)
            }
            Some(report) => {
                self.flight = None;
                self.end_loop(w, practice, report, recording);
                let m = w.budget.spent().then(|| self.decide(w));
                PhaseStep::Phase(PhaseKind::Backup, m)
            }
        }
    }

    fn phase(&self) -> Option<&PhaseRecord> {
        self.record.phase.is_some().then_some(&self.record)
    }

    fn tree(
        &self,
        torus: &Torus,
        pos: u32,
        q: &TreeQuery,
    ) -> Option<Result<TreeExport, TreeError>> {
        Some(self.stats.tree(torus, pos, self.c, q))
    }

    fn snapshot(&self) -> Option<Box<dyn Searcher>> {
        Some(Box::new(self.clone()))
    }

    fn heap_bytes(&self) -> usize {
        self.stats.heap_bytes()
            + self.policy.heap_bytes()
            + self.coverage.heap_bytes()
            + self.scan.heap_bytes()
            + self.record.heap_bytes()
    }

    fn observe(&mut self, _torus: &Torus, m: Move, _pos: u32) {
        // The statistics move on by the move made, which in a branch's
        // shared prefix may not be the one decided.
        self.stats.advance(m);
    }

    fn counts<'a>(&'a self, layer: Layer, scratch: &'a mut Vec<u32>) -> Option<&'a [u32]> {
        (layer == Layer::Visits).then(|| self.stats.visits(self.cells, scratch))
    }

    fn decision(&self, torus: &Torus, pos: u32) -> Option<DecisionView> {
        Some(self.stats.view(torus, pos, self.c))
    }

    fn intent(&self) -> &[u32] {
        self.stats.intent()
    }

    fn planning(&self) -> Option<Planning> {
        self.stats.planning()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn only_the_belief_mcts_draws_an_intended_path() {
        use crate::config::Config;
        use crate::run::episode::Episode;
        for variant in ["cells", "tree", "code"] {
            let c = Config::default().with(&[("variant", variant), ("loops", "20")]);
            let mut ep = Episode::new(&c).unwrap();
            for _ in 0..3 {
                ep.step_move();
                assert_eq!(ep.intent(), &[] as &[u32], "{variant}");
            }
        }
        let c = Config::default().with(&[("variant", "pomcp"), ("loops", "20")]);
        let mut ep = Episode::new(&c).unwrap();
        ep.step_move();
        assert!(!ep.intent().is_empty());
    }
}
