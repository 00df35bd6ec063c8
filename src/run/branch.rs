//! A run branched from another at move m: the same trial of a (possibly
//! different) configuration whose first m real moves are the parent's.
//!
//! The branch of run R (trial i of config A) at move m with config B is
//! trial i of B in which, for each of the first m decisions, B's searcher
//! decides as it would (its own random stream, budget and loops, on the
//! belief the shared path gives), and the move made is R's; the searcher
//! observes that move, so its state after m moves is what B's searcher has
//! after searching along R's path (a planner whose plan R's path left
//! plans again from where it stands). From move m on, B decides.
//!
//! Determinism: a branch is a function of (B, i, R's first m moves) alone.
//! With B = A every decision of the prefix picks R's own move, so the
//! branch *is* R: the same path and counters from move 0 on. Only the
//! searcher's parameters may differ: the world (lattice, prior, target,
//! start, sensor, seed, step cap) must be R's, or the path would not be a
//! path of the same game.

use crate::config::fields::FIELDS;
use crate::config::Config;
use crate::game::lattice::Move;
use crate::param::ParamError;
use crate::run::episode::{Episode, Status};
use std::sync::Arc;

/// The keys of the parameters that make the world a run searches in: the
/// game's own (the config's fields) but the searcher. A branch keeps them;
/// only the searcher and its parameters may change.
pub fn world_params() -> impl Iterator<Item = &'static str> {
    FIELDS
        .iter()
        .map(|f| f.param.key)
        .filter(|&k| k != "searcher")
}

/// Why a run cannot be branched.
#[derive(Clone, Debug, PartialEq)]
pub enum BranchError {
    /// A parameter of the world differs from the parent's.
    World {
        /// The parameter's key.
        key: &'static str,
        /// Its value in the parent run, as text.
        parent: String,
        /// Its value in the branch.
        branch: String,
    },
    /// The branch move lies past the moves the parent has reached.
    PastEnd {
        /// The move asked for.
        at: u32,
        /// The moves the parent has reached.
        reached: u32,
    },
    /// A branch needs one configuration per run.
    Runs {
        /// Configurations given.
        given: usize,
        /// Runs in the race.
        runs: usize,
    },
    /// The parent could not be replayed to the branch move (a timed run).
    Seek(String),
    /// The configuration is invalid.
    Param(ParamError),
}

impl std::fmt::Display for BranchError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BranchError::World {
                key,
                parent,
                branch,
            } => write!(
                f,
                "{key} cannot change in a branch ({parent} → {branch}): it changes the world \
                 the path so far was made in; only the searcher's parameters can branch"
            ),
            BranchError::PastEnd { at, reached } => write!(
                f,
                "branch at move {at} is past the run's moves: allowed moves 0 to {reached}"
            ),
            BranchError::Runs { given, runs } => write!(
                f,
                "a branch needs one configuration per run: {given} given for {runs} runs"
            ),
            BranchError::Seek(e) => write!(f, "cannot branch: {e}"),
            BranchError::Param(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for BranchError {}

impl From<ParamError> for BranchError {
    fn from(e: ParamError) -> BranchError {
        BranchError::Param(e)
    }
}

/// Checks that `branch` may continue a run of `parent`: both valid, and
/// every world parameter ([`world_params`]) the same.
///
/// # Errors
/// A [`BranchError::World`] naming the first world parameter that differs,
/// or a [`BranchError::Param`] for an invalid configuration.
pub fn check(parent: &Config, branch: &Config) -> Result<(), BranchError> {
    parent.validate()?;
    branch.validate()?;
    for key in world_params() {
        let (a, b) = (parent.get(key)?, branch.get(key)?);
        if a != b {
            let key = crate::config::param(key).map_or(key, |p| p.key);
            return Err(BranchError::World {
                key,
                parent: a,
                branch: b,
            });
        }
    }
    Ok(())
}

/// The moves between consecutive cells of `path`.
fn moves_of(ep: &Episode, at: u32) -> Arc<[Move]> {
    let torus = ep.torus();
    ep.path()[..=at as usize]
        .windows(2)
        .map(|w| {
            torus
                .move_to(w[0], w[1])
                .expect("a path moves by unit steps")
        })
        .collect()
}

/// The branch of `parent` at move `at` with `cfg`, before its first move:
/// stepping it makes the parent's first `at` moves (see the module's
/// documentation), then its own.
///
/// # Errors
/// As [`branch`].
pub fn forced(parent: &Episode, at: u32, cfg: &Config) -> Result<Episode, BranchError> {
    check(parent.config(), cfg)?;
    if at > parent.steps() {
        return Err(BranchError::PastEnd {
            at,
            reached: parent.steps(),
        });
    }
    let mut ep = Episode::trial(cfg, parent.index())?;
    ep.set_clock(parent.clock());
    ep.force(moves_of(parent, at));
    Ok(ep)
}

/// The branch of `parent` at move `at` with `cfg`, at that move: the
/// parent's path up to it, `cfg`'s searcher with the state it has after
/// deciding along it; the loops of decision `at` have yet to run.
///
/// # Errors
/// A [`BranchError`]: a world parameter differs, `at` is past the moves
/// the parent holds, or `cfg` is invalid.
pub fn branch(parent: &Episode, at: u32, cfg: &Config) -> Result<Episode, BranchError> {
    Ok(follow(forced(parent, at, cfg)?, at, |_| {}))
}

/// A [`forced`] branch made up to move `at`, with `note` shown it after
/// each shared move and once more at `at` (a timeline records them).
pub fn follow(mut ep: Episode, at: u32, mut note: impl FnMut(&Episode)) -> Episode {
    while ep.steps() < at && ep.step_move() == Status::Running {
        note(&ep);
    }
    note(&ep);
    ep.forget_phase();
    ep
}
