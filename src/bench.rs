//! Fixed workloads for benchmarks. They do no timing (the caller times them
//! with its own clock: `Instant` natively, `performance.now()` in wasm), so
//! the same work is measured on every platform.

use crate::config::{self, Config};
use crate::game::lattice::{Sensor, Torus};
use crate::game::prior::{PriorSpec, TargetPrior};
use crate::game::rng;
use crate::param::{ParamError, Value};
use crate::run::episode::{Episode, Status, TimePoint};
use crate::run::race::Race;
use crate::run::timeline::{Timeline, DEFAULT_CAP_BYTES};
use crate::searchers::mcts::search::VARIANT;
use crate::searchers::mcts::variant::Variant;
use crate::searchers::walks::policy::{Policy, PolicyKind};
use crate::searchers::walks::visit::NoVisit;

/// Runs rollouts of `kind` between uniformly random start and target cells on
/// an `n`×`n` torus with radius `rv` until at least `min_steps` lattice steps
/// are made. Returns the steps made.
///
/// # Errors
/// A [`ParamError`] for a bad `n`, `rv` or `mu`.
pub fn rollout_steps(
    kind: PolicyKind,
    n: u32,
    rv: f64,
    mu: f64,
    seed: u64,
    min_steps: u64,
) -> Result<u64, ParamError> {
    for (key, v) in [
        ("n", Value::Int(n as u64)),
        ("rv", Value::Float(rv)),
        ("mu", Value::Float(mu)),
    ] {
        let p = config::param(key).expect("a schema parameter");
        p.kind.check(p.key, &v)?;
    }
    let torus = Torus::new(n).expect("n was checked");
    let mut sensor = Sensor::new(&torus, rv).expect("rv was checked");
    let uniform =
        TargetPrior::new(&torus, &PriorSpec::Uniform).expect("uniform prior is always valid");
    let mut policy = Policy::new(kind, &torus, mu, 0.2);
    let mut r = rng::stream(seed, 0);
    let mut total = 0u64;
    while total < min_steps {
        let target = uniform.sample(&mut r);
        let start = uniform.sample(&mut r);
        sensor.arm(target);
        policy.begin(start, target);
        let out = policy.rollout(&torus, sensor.mask(), &mut r, start, 1 << 30, &mut NoVisit);
        total += out.steps as u64;
    }
    Ok(total)
}

/// Runs `loops` MCTS loops of trial 0 of `cfg` (moving on as decisions
/// complete, starting new trials when one ends). Returns (loops, real moves,
/// episodes finished).
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn mcts_loops(cfg: &Config, loops: u64) -> Result<(u64, u64, u64), ParamError> {
    let mut r = LoopRunner::new(cfg)?;
    r.run(loops)?;
    Ok((r.loops, r.moves, r.episodes))
}

/// The MCTS loops of trials 0, 1, 2, … of a config, in order: the same loops
/// the page's episode (trial 0) runs, so a stretch of them can be timed
/// natively and in the browser alike.
pub struct LoopRunner {
    cfg: Config,
    trial: u64,
    episode: Episode,
    /// Loops run so far.
    pub loops: u64,
    /// Real moves made so far.
    pub moves: u64,
    /// Episodes finished so far.
    pub episodes: u64,
}

impl LoopRunner {
    /// Starts at loop 0 of trial 0.
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field, or the searcher if
    /// it does not deliberate (it has no loops).
    pub fn new(cfg: &Config) -> Result<LoopRunner, ParamError> {
        if !cfg.searcher.info().deliberates {
            return Err(ParamError::new(
                "searcher",
                cfg.searcher,
                "a searcher that deliberates (mcts) for a loop benchmark",
            ));
        }
        Ok(LoopRunner {
            cfg: cfg.clone(),
            trial: 0,
            episode: Episode::trial(cfg, 0)?,
            loops: 0,
            moves: 0,
            episodes: 0,
        })
    }

    /// Runs `loops` more loops.
    ///
    /// # Errors
    /// Only if a new trial's config were invalid (it was checked in `new`).
    pub fn run(&mut self, loops: u64) -> Result<(), ParamError> {
        let target = self.loops + loops;
        while self.loops < target {
            let before = self.episode.counters().rollouts;
            self.moves += self.episode.advance(target - self.loops);
            self.loops += self.episode.counters().rollouts - before;
            if self.episode.status() != crate::run::episode::Status::Running {
                self.episodes += 1;
                self.trial += 1;
                self.episode = Episode::trial(&self.cfg, self.trial)?;
            }
        }
        Ok(())
    }
}

/// The configurations whose cost per real move is benchmarked on an
/// `n`×`n` torus: every registered searcher at its defaults, and for one
/// that reads `variant`, each variant, all on a Gaussian prior with
/// σ = N/8 (5 at N = 40) so the lattice's scale, not the prior's, changes
/// with N. Labels are the page's race ids (`mcts-cells`, `rw`, …).
pub fn move_cases(n: u32) -> Vec<(String, Config)> {
    let base = Config {
        n,
        sigma: n as f64 / 8.0,
        // A benchmark measures moves, not the cap.
        step_cap: 100_000_000,
        ..Config::default()
    };
    let mut out = Vec::new();
    for info in crate::searchers::REGISTRY {
        let Some(id) = crate::searchers::SearcherId::parse(info.name) else {
            continue;
        };
        let cfg = Config {
            searcher: id,
            ..base.clone()
        };
        if info.reads(&VARIANT, &cfg.settings) {
            for &variant in Variant::ALL {
                out.push((
                    format!("{}-{variant}", info.name),
                    cfg.clone().with(&[("variant", variant.name())]),
                ));
            }
        } else {
            out.push((info.name.to_string(), cfg));
        }
    }
    out
}

/// Real moves of trials 0, 1, 2, … of a config, made one at a time with
/// whatever deliberation each takes: the workload behind a searcher's
/// cost per move.
pub struct MoveRunner {
    cfg: Config,
    trial: u64,
    episode: Episode,
    /// The episode has ended; the next decision starts the next trial.
    ended: bool,
    /// Real moves made so far.
    pub moves: u64,
    /// Episodes finished so far.
    pub episodes: u64,
}

impl MoveRunner {
    /// Starts before the first move of trial 0.
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field.
    pub fn new(cfg: &Config) -> Result<MoveRunner, ParamError> {
        cfg.validate()?;
        Ok(MoveRunner {
            cfg: cfg.clone(),
            trial: 0,
            episode: Episode::trial(cfg, 0)?,
            ended: false,
            moves: 0,
            episodes: 0,
        })
    }

    /// Starts the next trial if the last decision ended one, so that a
    /// timer can leave setting up an episode (the prior, the tables) out of
    /// the decision it times; [`MoveRunner::run`] does it itself otherwise.
    ///
    /// # Errors
    /// Only if a new trial's config were invalid (it was checked in `new`).
    pub fn ready(&mut self) -> Result<(), ParamError> {
        if self.ended {
            self.trial += 1;
            self.episode = Episode::trial(&self.cfg, self.trial)?;
            self.ended = false;
        }
        Ok(())
    }

    /// Makes `moves` more decisions, each one real move unless the trial
    /// ends first (starting the next trial whenever one has ended).
    ///
    /// # Errors
    /// As [`MoveRunner::ready`].
    pub fn run(&mut self, moves: u64) -> Result<(), ParamError> {
        // Counted in attempts, so a trial detected at its start (no move)
        // cannot keep this running for ever.
        for _ in 0..moves {
            self.ready()?;
            let before = self.episode.steps();
            let status = self.episode.step_move();
            self.moves += u64::from(self.episode.steps() - before);
            if status != crate::run::episode::Status::Running {
                self.episodes += 1;
                self.ended = true;
            }
        }
        Ok(())
    }
}

/// The teaching workloads' configuration: N = 40, L = 100, a uniform
/// prior (a long search), otherwise the defaults.
pub fn teach_config() -> Config {
    Config {
        prior: crate::game::prior::PriorKind::Uniform,
        ..Config::default()
    }
    .with(&[("loops", "100")])
}

/// A `tree` episode of `cfg` (N and seed kept) whose first decision has
/// run `loops` loops: a tree of about `loops` nodes to export.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn big_tree(cfg: &Config, loops: u32) -> Result<Episode, ParamError> {
    let text = loops.to_string();
    let cap = (loops + 16).to_string();
    let cfg = cfg
        .clone()
        .with(&[("variant", "tree"), ("loops", &text), ("tree_nodes", &cap)]);
    let mut ep = Episode::new(&cfg)?;
    ep.step_loops(loops - 1);
    Ok(ep)
}

/// Trial 0 of `cfg` played `moves` real moves (or to its end) with its
/// timeline kept, as the page plays it: the workload behind seeking.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn played(cfg: &Config, moves: u32) -> Result<(Episode, Timeline), ParamError> {
    let mut ep = Episode::new(cfg)?;
    let mut tl = Timeline::new(&ep, DEFAULT_CAP_BYTES);
    while ep.steps() < moves && ep.status() == Status::Running {
        ep.step_move();
        tl.note(&ep);
    }
    Ok((ep, tl))
}

/// `count` points spread over what `tl` has reached of a run of
/// `loops` loops a decision (moves, loops and phases), from a fixed seed.
pub fn seek_points(tl: &Timeline, loops: u32, count: usize) -> Vec<TimePoint> {
    let end = tl.end();
    let mut r = rng::stream(0x5eec, 0);
    (0..count)
        .map(|_| {
            let mv = rng::below(&mut r, end.mv.max(1));
            let phase = match rng::below(&mut r, 5) {
                0 => None,
                k => Some(crate::searchers::phase::PhaseKind::ALL[k as usize - 1]),
            };
            TimePoint {
                mv,
                loop_: rng::below(&mut r, loops),
                phase,
            }
        })
        .collect()
}

/// `loops` loops of `cfg` through a race (the page's path, with its
/// timeline), in calls of `k` loops; returns the moves made.
///
/// # Errors
/// A [`ParamError`] naming the first invalid field.
pub fn race_loops(cfg: &Config, loops: u64, k: u64) -> Result<u64, ParamError> {
    let mut race = Race::new(std::slice::from_ref(cfg))?;
    let mut done = 0;
    while done < loops && race.running() > 0 {
        let before = race.runs()[0].counters().rollouts;
        race.advance(k.min(loops - done));
        done += race.runs()[0].counters().rollouts - before;
    }
    Ok(race.runs()[0].steps() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn move_cases_cover_every_searcher_and_variant() {
        let cases = move_cases(40);
        for info in crate::searchers::REGISTRY {
            assert!(
                cases
                    .iter()
                    .any(|(l, c)| c.searcher.name() == info.name && l.starts_with(info.name)),
                "{} missing",
                info.name
            );
        }
        for v in Variant::ALL {
            assert!(cases.iter().any(|(l, _)| *l == format!("mcts-{v}")));
        }
        assert!(cases
            .iter()
            .all(|(_, c)| c.validate().is_ok() && c.sigma == 5.0));
    }

    #[test]
    fn move_runner_makes_the_trials_moves_in_order() {
        // A small lattice so episodes end and the runner moves on to trial 1, 2, …
        let cfg = Config {
            n: 6,
            sigma: 1.0,
            searcher: crate::searchers::SearcherId::parse("rw").unwrap(),
            ..Config::default()
        };
        let mut r = MoveRunner::new(&cfg).unwrap();
        r.run(300).unwrap();
        let mut expect = 0;
        for i in 0..r.episodes {
            expect += u64::from(Episode::trial(&cfg, i).unwrap().run().steps);
        }
        // The moves of the finished trials, plus those of the one under way.
        if !r.ended {
            expect += u64::from(r.episode.steps());
        }
        assert_eq!(r.moves, expect);
        assert!(r.episodes >= 2, "trials rolled over: {}", r.episodes);
        // Starting each next trial apart, as a timer does, makes the same moves.
        let mut apart = MoveRunner::new(&cfg).unwrap();
        for _ in 0..300 {
            apart.ready().unwrap();
            apart.run(1).unwrap();
        }
        assert_eq!((apart.moves, apart.episodes), (r.moves, r.episodes));
    }
}
