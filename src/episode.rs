//! One trial: a target, a searcher, and the moves until detection or the step cap.

use crate::config::{Belief, Config, ConfigError, SearcherKind};
use crate::lattice::{Move, Sensor, Torus};
use crate::mcts::cells::CellTable;
use crate::mcts::tree::Tree;
use crate::mcts::{self, DecisionView, LoopEnv, Variant};
use crate::prior::{Alias, PriorSpec, TargetPrior};
use crate::rng::{self, Rng};
use crate::searchers::Policy;

/// Where an episode stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Still searching.
    Running,
    /// The target was detected.
    Found,
    /// The step cap ended the episode first (a failure).
    Capped,
}

/// Rollout counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Counters {
    /// Rollouts (MCTS loops) run.
    pub rollouts: u64,
    /// Unit moves made by rollouts.
    pub rollout_steps: u64,
    /// Rollouts cut short by the rollout cap.
    pub truncated: u64,
}

impl Counters {
    fn add(&mut self, steps: u32, detected: bool) {
        self.rollouts += 1;
        self.rollout_steps += steps as u64;
        self.truncated += (!detected) as u64;
    }
}

impl std::ops::AddAssign for Counters {
    fn add_assign(&mut self, o: Counters) {
        self.rollouts += o.rollouts;
        self.rollout_steps += o.rollout_steps;
        self.truncated += o.truncated;
    }
}

/// The result of one trial.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TrialResult {
    /// Real moves made.
    pub steps: u32,
    /// Fewest moves that would have detected the target.
    pub optimal: u32,
    /// True when the target was detected.
    pub found: bool,
    /// The target cell.
    pub target: u32,
    /// Rollout counters over the whole episode.
    pub counters: Counters,
}

impl TrialResult {
    /// steps / optimal, `None` when optimal is 0.
    pub fn ratio(&self) -> Option<f64> {
        (self.optimal > 0).then(|| self.steps as f64 / self.optimal as f64)
    }
}

enum Engine {
    Cells(CellTable),
    Tree(Tree),
}

enum Agent {
    Mcts { engine: Engine, policy: Policy },
    Walker(Policy),
}

/// Recent rollout traces kept for drawing.
#[derive(Clone, Debug, Default)]
struct Traces {
    ring: Vec<Vec<u32>>,
    targets: Vec<u32>,
    next: usize,
    filled: usize,
}

/// The default clock: monotonic milliseconds natively. In wasm the facade
/// sets one that reads `performance.now()`.
#[cfg(not(target_arch = "wasm32"))]
fn default_clock() -> f64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static T0: OnceLock<Instant> = OnceLock::new();
    T0.get_or_init(Instant::now).elapsed().as_secs_f64() * 1e3
}

/// Without a host clock a decision-time budget can never expire, so the
/// episode also stops a decision after [`NO_CLOCK_LOOPS`] loops.
#[cfg(target_arch = "wasm32")]
fn default_clock() -> f64 {
    0.0
}

/// The loop count at which a decision-time budget ends even if the clock
/// never advances.
pub const NO_CLOCK_LOOPS: u32 = 10_000_000;

/// One trial, advanced move by move or loop by loop.
pub struct Episode {
    cfg: Config,
    seed: u64,
    torus: Torus,
    sensor: Sensor,
    prior: TargetPrior,
    /// The planning prior when it differs from `prior` (`known`); sharing
    /// otherwise keeps an N = 1024 episode from holding two copies.
    known_plan: Option<TargetPrior>,
    target: u32,
    start: u32,
    pos: u32,
    optimal: u32,
    path: Vec<u32>,
    status: Status,
    rng: Rng,
    agent: Agent,
    counters: Counters,
    decision: Counters,
    loops_done: u32,
    decision_t0: Option<f64>,
    clock: fn() -> f64,
    searched: Vec<u8>,
    remaining: f64,
    posterior: Vec<f64>,
    posterior_alias: Option<Alias>,
    visit_buf: Vec<u32>,
    traces: Traces,
    last_move: Option<Move>,
}

impl Episode {
    /// Trial 0 of `cfg` with `seed`.
    ///
    /// # Errors
    /// A [`ConfigError`] naming the first invalid field.
    pub fn new(cfg: &Config, seed: u64) -> Result<Episode, ConfigError> {
        Episode::trial(cfg, seed, 0)
    }

    /// Trial `index` of a batch: its streams derive from `(seed, index)` only.
    ///
    /// # Errors
    /// A [`ConfigError`] naming the first invalid field.
    pub fn trial(cfg: &Config, seed: u64, index: u64) -> Result<Episode, ConfigError> {
        cfg.validate()?;
        let torus = Torus::new(cfg.n).map_err(|e| ConfigError::new("n", cfg.n, e.to_string()))?;
        let sensor = Sensor::new(&torus, cfg.rv)
            .map_err(|e| ConfigError::new("rv", cfg.rv, e.to_string()))?;
        let start = torus.cell(cfg.start[0] as i64 - 1, cfg.start[1] as i64 - 1);
        let spec = match cfg.target {
            Some([x, y]) => PriorSpec::Delta {
                cell: Some(torus.cell(x as i64 - 1, y as i64 - 1)),
            },
            None => cfg.prior.clone(),
        };
        let prior = TargetPrior::new(&torus, &spec)
            .map_err(|e| ConfigError::new("prior", "", e.to_string()))?;
        let mut world = rng::stream(seed, 2 * index);
        let target = prior.sample(&mut world);
        let known_plan = cfg.known.then(|| {
            TargetPrior::new(&torus, &PriorSpec::Delta { cell: Some(target) })
                .expect("target is on the lattice")
        });
        let cells = torus.cells();
        let policy_kind = match cfg.searcher {
            SearcherKind::Mcts => cfg.rollout,
            SearcherKind::Rw => crate::searchers::PolicyKind::Rw,
            SearcherKind::Levy => crate::searchers::PolicyKind::Levy,
            SearcherKind::Nsarw => crate::searchers::PolicyKind::Nsarw,
        };
        let mut policy = Policy::new(policy_kind, &torus, cfg.mu, cfg.epsilon);
        let agent = match cfg.searcher {
            SearcherKind::Mcts => Agent::Mcts {
                engine: match cfg.variant {
                    Variant::Cells => Engine::Cells(CellTable::new(cells)),
                    Variant::Tree => Engine::Tree(Tree::new(cfg.tree_nodes)),
                },
                policy,
            },
            _ => {
                policy.begin(start, target);
                Agent::Walker(policy)
            }
        };
        let optimal = sensor.optimal_steps(&torus, start, target);
        let keep = cfg.keep_traces as usize;
        let mut ep = Episode {
            cfg: cfg.clone(),
            seed,
            sensor,
            prior,
            known_plan,
            target,
            start,
            pos: start,
            optimal,
            path: vec![start],
            status: Status::Running,
            rng: rng::stream(seed, 2 * index + 1),
            agent,
            counters: Counters::default(),
            decision: Counters::default(),
            loops_done: 0,
            decision_t0: None,
            clock: default_clock,
            searched: vec![0; cells],
            remaining: 1.0,
            posterior: Vec::new(),
            posterior_alias: None,
            visit_buf: Vec::new(),
            traces: Traces {
                ring: vec![Vec::new(); keep],
                targets: vec![0; keep],
                next: 0,
                filled: 0,
            },
            last_move: None,
            torus,
        };
        ep.mark_searched(start);
        if ep.sensor.detects(&ep.torus, start, target) {
            ep.status = Status::Found;
        }
        Ok(ep)
    }

    /// Sets the millisecond clock used by decision-time budgets.
    pub fn set_clock(&mut self, clock: fn() -> f64) {
        self.clock = clock;
    }

    fn mark_searched(&mut self, cell: u32) {
        let mass = self.known_plan.as_ref().unwrap_or(&self.prior).mass();
        for c in self.sensor.around(cell) {
            let c = c as usize;
            if self.searched[c] == 0 {
                self.searched[c] = 1;
                self.remaining -= mass[c];
                self.posterior_alias = None;
            }
        }
    }

    /// A practice target from the belief.
    fn practice_target(&mut self) -> u32 {
        if self.cfg.belief == Belief::Prior {
            return self
                .known_plan
                .as_ref()
                .unwrap_or(&self.prior)
                .sample(&mut self.rng);
        }
        // Rejection from the prior is exact for the posterior and cheap while
        // much mass remains; past a few misses fall back to an alias table.
        for _ in 0..8 {
            let c = self
                .known_plan
                .as_ref()
                .unwrap_or(&self.prior)
                .sample(&mut self.rng);
            if self.searched[c as usize] == 0 {
                return c;
            }
        }
        if self.posterior_alias.is_none() {
            self.refresh_posterior();
            self.posterior_alias = Some(Alias::new(&self.posterior));
        }
        self.posterior_alias
            .as_ref()
            .expect("built above")
            .sample(&mut self.rng)
    }

    fn refresh_posterior(&mut self) {
        let mass = self.known_plan.as_ref().unwrap_or(&self.prior).mass();
        self.posterior.clear();
        self.posterior.extend(
            mass.iter()
                .zip(&self.searched)
                .map(|(&m, &s)| if s == 0 { m } else { 0.0 }),
        );
        let total: f64 = self.posterior.iter().sum();
        if total > 0.0 {
            self.posterior.iter_mut().for_each(|p| *p /= total);
        } else {
            // The prior's support is exhausted (the planner was wrong about
            // the target): fall back to uniform over unsearched cells.
            let free = self.searched.iter().filter(|&&s| s == 0).count().max(1) as f64;
            for (p, &s) in self.posterior.iter_mut().zip(&self.searched) {
                *p = if s == 0 { 1.0 / free } else { 0.0 };
            }
        }
    }

    /// Runs up to `max_loops` loops of the current decision (a walker makes
    /// its move at once). Returns true when a real move was made.
    pub fn step_loops(&mut self, max_loops: u32) -> bool {
        if self.status != Status::Running || max_loops == 0 {
            return false;
        }
        let pos = self.pos;
        let mv = match &mut self.agent {
            Agent::Walker(p) => Some(p.next_move(&self.torus, &mut self.rng, pos)),
            Agent::Mcts { .. } => self.run_loops(max_loops),
        };
        match mv {
            Some(m) => {
                self.apply(m);
                true
            }
            None => false,
        }
    }

    /// Completes the current decision and makes one real move. Returns the status.
    pub fn step_move(&mut self) -> Status {
        while self.status == Status::Running && !self.step_loops(u32::MAX) {}
        self.status
    }

    /// Runs to detection or the step cap.
    pub fn run(&mut self) -> TrialResult {
        while self.step_move() == Status::Running {}
        self.result()
    }

    fn budget_done(&self) -> bool {
        match self.cfg.decision_ms {
            None => self.loops_done >= self.cfg.loops,
            Some(ms) => {
                self.loops_done >= NO_CLOCK_LOOPS
                    || (self.loops_done > 0
                        && (self.clock)() - self.decision_t0.unwrap_or(0.0) >= ms)
            }
        }
    }

    fn run_loops(&mut self, max_loops: u32) -> Option<Move> {
        if self.decision_t0.is_none() {
            self.decision_t0 = Some((self.clock)());
            self.loops_done = 0;
            self.decision = Counters::default();
            let reset = self.cfg.reset_each_move;
            let pos = self.pos;
            if let Agent::Mcts { engine, .. } = &mut self.agent {
                match engine {
                    Engine::Cells(t) => t.begin_decision(reset),
                    Engine::Tree(t) => t.begin_decision(pos),
                }
            }
        }
        let mut done = 0;
        while done < max_loops && !self.budget_done() {
            let practice = self.practice_target();
            self.sensor.arm(practice);
            let keep = self.traces.ring.len();
            let slot = self.traces.next;
            let Agent::Mcts { engine, policy } = &mut self.agent else {
                unreachable!("walkers do not loop")
            };
            let mut env = LoopEnv {
                torus: &self.torus,
                mask: self.sensor.mask(),
                practice,
                policy,
                rng: &mut self.rng,
                rollout_cap: self.cfg.rollout_cap,
                c: self.cfg.c,
                trace: if keep > 0 {
                    Some(&mut self.traces.ring[slot])
                } else {
                    None
                },
            };
            let report = match engine {
                Engine::Cells(t) => t.iterate(&mut env, self.pos),
                Engine::Tree(t) => t.iterate(&mut env),
            };
            if keep > 0 {
                self.traces.targets[slot] = practice;
                self.traces.next = (slot + 1) % keep;
                self.traces.filled = (self.traces.filled + 1).min(keep);
            }
            self.counters.add(report.rollout_steps, report.detected);
            self.decision.add(report.rollout_steps, report.detected);
            self.loops_done += 1;
            done += 1;
        }
        if !self.budget_done() {
            return None;
        }
        let view = self.decision_view();
        let m = mcts::final_move(&view, self.cfg.final_rule, &mut self.rng);
        if let Agent::Mcts {
            engine: Engine::Tree(t),
            ..
        } = &mut self.agent
        {
            t.advance(m);
        }
        self.decision_t0 = None;
        Some(m)
    }

    fn apply(&mut self, m: Move) {
        self.pos = self.torus.step(self.pos, m);
        self.path.push(self.pos);
        self.last_move = Some(m);
        self.mark_searched(self.pos);
        if let Agent::Walker(Policy::Nsarw(w)) = &mut self.agent {
            w.enter(self.pos);
        }
        if self.sensor.detects(&self.torus, self.pos, self.target) {
            self.status = Status::Found;
        } else if self.steps() >= self.cfg.step_cap {
            self.status = Status::Capped;
        }
    }

    /// The configuration.
    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// The seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The lattice.
    pub fn torus(&self) -> &Torus {
        &self.torus
    }

    /// Where the episode stands.
    pub fn status(&self) -> Status {
        self.status
    }

    /// Real moves made so far.
    pub fn steps(&self) -> u32 {
        (self.path.len() - 1) as u32
    }

    /// Fewest moves that detect the target from the start.
    pub fn optimal(&self) -> u32 {
        self.optimal
    }

    /// The true target cell.
    pub fn target(&self) -> u32 {
        self.target
    }

    /// The start cell.
    pub fn start(&self) -> u32 {
        self.start
    }

    /// The searcher's cell.
    pub fn position(&self) -> u32 {
        self.pos
    }

    /// The last real move.
    pub fn last_move(&self) -> Option<Move> {
        self.last_move
    }

    /// Every cell occupied, start first.
    pub fn path(&self) -> &[u32] {
        &self.path
    }

    /// The true target's prior mass per cell.
    pub fn prior_mass(&self) -> &[f64] {
        self.prior.mass()
    }

    /// The planning prior (differs from the prior with `known`).
    pub fn plan_mass(&self) -> &[f64] {
        self.known_plan.as_ref().unwrap_or(&self.prior).mass()
    }

    /// The posterior: the planning prior with searched cells zeroed, renormalised.
    pub fn posterior_mass(&mut self) -> &[f64] {
        self.refresh_posterior();
        &self.posterior
    }

    /// Prior mass not yet searched.
    pub fn remaining_mass(&self) -> f64 {
        self.remaining.max(0.0)
    }

    /// 1 for each cell within r_v of any position occupied so far.
    pub fn searched(&self) -> &[u8] {
        &self.searched
    }

    /// MCTS visit counts per cell: the table for `cells`, the tree projected
    /// onto cells for `tree`, the walk's own counts for NSARW, else empty.
    pub fn visit_counts(&mut self) -> &[u32] {
        match &self.agent {
            Agent::Mcts {
                engine: Engine::Cells(t),
                ..
            } => t.visits(),
            Agent::Mcts {
                engine: Engine::Tree(t),
                ..
            } => {
                self.visit_buf.resize(self.torus.cells(), 0);
                t.project(&mut self.visit_buf);
                &self.visit_buf
            }
            Agent::Walker(p) => p.counts().unwrap_or(&[]),
        }
    }

    /// The NSARW searcher's own visit counts (empty for other searchers).
    pub fn walker_counts(&self) -> &[u32] {
        match &self.agent {
            Agent::Walker(p) => p.counts().unwrap_or(&[]),
            Agent::Mcts { .. } => &[],
        }
    }

    /// The decision under way (all zero for walkers).
    pub fn decision_view(&self) -> DecisionView {
        match &self.agent {
            Agent::Mcts {
                engine: Engine::Cells(t),
                ..
            } => t.view(&self.torus, self.pos, self.cfg.c),
            Agent::Mcts {
                engine: Engine::Tree(t),
                ..
            } => t.view(&self.torus, self.pos, self.cfg.c),
            Agent::Walker(_) => DecisionView {
                c: self.cfg.c,
                ..DecisionView::default()
            },
        }
    }

    /// Loops done in the decision under way.
    pub fn loops_done(&self) -> u32 {
        self.loops_done
    }

    /// Rollout counters for the whole episode.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// Rollout counters for the decision under way (or the last one).
    pub fn decision_counters(&self) -> Counters {
        self.decision
    }

    /// Nodes in the `tree` arena (0 for other searchers).
    pub fn tree_nodes(&self) -> usize {
        match &self.agent {
            Agent::Mcts {
                engine: Engine::Tree(t),
                ..
            } => t.len(),
            _ => 0,
        }
    }

    /// Kept rollout traces, newest first, each with its practice target.
    pub fn traces(&self) -> impl Iterator<Item = (&[u32], u32)> + '_ {
        let k = self.traces.ring.len();
        (0..self.traces.filled).map(move |i| {
            let slot = (self.traces.next + k - 1 - i) % k;
            (self.traces.ring[slot].as_slice(), self.traces.targets[slot])
        })
    }

    /// The result so far.
    pub fn result(&self) -> TrialResult {
        TrialResult {
            steps: self.steps(),
            optimal: self.optimal,
            found: self.status == Status::Found,
            target: self.target,
            counters: self.counters,
        }
    }
}
