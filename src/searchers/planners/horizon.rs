//! The receding-horizon planner: the lookahead's first move each step, or
//! a step toward the far goal when that is better
//! ([`crate::searchers::planning::completion`]).
//!
//! The planner is deterministic: its path depends only on the belief, so
//! `run --exact` evaluates it exactly.

use crate::game::coverage::Coverage;
use crate::game::lattice::{Move, Torus};
use crate::searchers::decision::MoveScores;
use crate::searchers::info::{Reads, SearcherInfo};
use crate::searchers::planning::completion::{decide, walk_to, FarGoal};
use crate::searchers::planning::far_goal::FarScan;
use crate::searchers::planning::lookahead::{Lookahead, Scored, HORIZON};
use crate::searchers::searcher::{Searcher, World};

/// What the decision panel says the scores are.
const MEANING: &str =
    "mass covered over the horizon, earlier moves weighted more: Σ_k (h−k+1)·gain_k";

/// The receding-horizon planner as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "horizon",
    label: "Receding horizon",
    help: "tries every move sequence of depth h and takes the first move of the one that covers planning mass earliest; heads for the best far cell when that is better; on priors much wider than the sensor (σ of 30 cells or more) it runs on into the tail, where the spiral planner does better",
    deterministic: true,
    deliberates: false,
    params: &[Reads::always(&HORIZON)],
    build: |s| Box::new(Horizon::new(s.settings.u32(&HORIZON), s.torus)),
};

/// The receding-horizon searcher.
pub struct Horizon {
    look: Lookahead,
    cov: Coverage,
    last: Option<Move>,
    intent: Vec<u32>,
    scores: Option<MoveScores>,
    /// Its number among the process's runs of far-goal scans: a searcher
    /// plays one episode, whose searched cells only grow, so each scan
    /// may keep what the one before read ([`FarScan`]).
    run: u64,
}

impl Horizon {
    /// A planner of horizon `h` for a lattice like `torus`.
    pub fn new(h: u32, torus: &Torus) -> Horizon {
        Horizon {
            look: Lookahead::new(h),
            cov: Coverage::new(torus.cells()),
            last: None,
            intent: Vec::with_capacity(2 * torus.n() as usize + h as usize),
            scores: None,
            run: FarScan::new_run(),
        }
    }
}

impl Searcher for Horizon {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        self.cov.clear();
        let (m, found, goal) = decide(
            &mut self.look,
            w.torus,
            w.sensor,
            w.belief,
            &mut self.cov,
            w.pos,
            self.last,
            FarGoal::Compared,
            Scored::Every,
            Some(self.run),
        );
        self.intent.clear();
        match goal {
            Some(g) => walk_to(w.torus, w.pos, g, &mut self.intent),
            None => self.intent.extend_from_slice(self.look.best_seq()),
        }
        self.scores = Some(MoveScores {
            meaning: MEANING,
            higher_is_better: true,
            score: found.score,
            chosen: m as u8,
        });
        Some(m)
    }

    fn observe(&mut self, _torus: &Torus, m: Move, _pos: u32) {
        self.last = Some(m);
        if !self.intent.is_empty() {
            self.intent.remove(0);
        }
    }

    fn intent(&self) -> &[u32] {
        &self.intent
    }

    fn scores(&self) -> Option<MoveScores> {
        self.scores
    }
}
