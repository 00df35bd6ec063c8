//! Going back over a run: snapshots taken as it moves, within a memory
//! cap, and seeking to any point it has reached by replaying from the
//! nearest snapshot before it. A run is a function of its configuration,
//! so the state reached by seeking is the state reached going forward.
//!
//! A snapshot is a copy of the run at the start of a decision (right after
//! a real move). One is taken once the work since the last (rollout steps,
//! loops and moves) reaches [`WORK_PER_BYTE`] times the snapshot's size,
//! so copying costs a small share of the search and a seek replays a
//! bounded amount of it; when the snapshots outgrow the cap, every other
//! one is dropped and the spacing doubles; a snapshot larger than the cap
//! is never taken. Before the first snapshot, and for a searcher that
//! cannot copy itself (the planners), the run is replayed from its start,
//! built again from its configuration.
//!
//! A point before a decision's first loop stands before any work on that
//! decision: slices of a plan being made (the belief MCTS's, a planner's)
//! are not points, and seeking there shows the decision before its plan.

use crate::game::named::named_enum;
use crate::param::ParamError;
use crate::run::episode::{Episode, Status, TimePoint};
use crate::searchers::phase::{PhaseKind, PhaseStep};

named_enum! {
    /// How far a step back goes.
    pub enum BackUnit {
        /// To the state before the last phase done.
        Phase = "phase",
        /// To the start of the loop in flight, or of the loop before.
        Loop = "loop",
        /// To the start of the decision under way, or of the one before.
        Move = "move",
    }
}

/// The default memory cap of one run's snapshots.
pub const DEFAULT_CAP_BYTES: usize = 64 << 20;

/// A snapshot is taken once the work since the last one reaches this many
/// times its bytes (see [`Episode::work_done`]): a step of a rollout costs
/// a few nanoseconds, a byte copied a fraction of one.
pub const WORK_PER_BYTE: u64 = 8;

/// Why a seek cannot be made.
#[derive(Clone, Debug, PartialEq)]
pub enum SeekError {
    /// Past the furthest point the run has reached.
    PastEnd {
        /// The point asked for.
        to: TimePoint,
        /// The furthest point reached.
        end: TimePoint,
    },
    /// A loop past the end of its decision.
    PastDecision {
        /// The point asked for.
        to: TimePoint,
        /// The loops the decision ran.
        loops: u32,
    },
    /// A loop or phase of a decision that ran no loops.
    NoLoops {
        /// The point asked for.
        to: TimePoint,
    },
    /// Decisions are timed: the run does not replay.
    Timed {
        /// The time budget in milliseconds.
        ms: f64,
    },
    /// The run could not be built again (it was built once, so never).
    Param(ParamError),
}

impl std::fmt::Display for SeekError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SeekError::PastEnd { to, end } => write!(
                f,
                "seek to {to} is past the end of the run so far: points from move 0, loop 0 up to {end}"
            ),
            SeekError::PastDecision { to, loops } => write!(
                f,
                "seek to {to}: loop {} is past the end of move {}'s decision, which ran loops 0..={}",
                to.loop_,
                to.mv,
                loops.saturating_sub(1)
            ),
            SeekError::NoLoops { to } => write!(
                f,
                "seek to {to}: move {}'s decision ran no loops (a move without deliberation), so only loop 0 with no phase",
                to.mv
            ),
            SeekError::Timed { ms } => write!(
                f,
                "this run decides by time (ms = {ms}): timed decisions do not replay, so it cannot seek"
            ),
            SeekError::Param(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for SeekError {}

/// How much memory the snapshots hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TimelineMemory {
    /// Bytes held by the snapshots.
    pub bytes: usize,
    /// The cap the snapshots are kept within.
    pub cap: usize,
    /// Snapshots kept.
    pub snapshots: usize,
    /// The work between snapshots, per byte of a snapshot.
    pub work_per_byte: u64,
}

/// A run's snapshots and the furthest point it has reached.
pub struct Timeline {
    /// Snapshots by increasing move, with their bytes.
    snaps: Vec<(Episode, usize)>,
    bytes: usize,
    cap: usize,
    ratio: u64,
    end: TimePoint,
    /// [`Episode::work_done`] at the last snapshot.
    last_work: u64,
}

/// Where a replay from a snapshot lands: the point, or an error.
type Landed = Result<Episode, SeekError>;

impl Timeline {
    /// The timeline of `ep`, at its start, with snapshots kept within
    /// `cap` bytes.
    pub fn new(ep: &Episode, cap: usize) -> Timeline {
        Timeline::with_spacing(ep, cap, WORK_PER_BYTE)
    }

    /// As [`Timeline::new`], a snapshot taken once the work since the last
    /// reaches `work_per_byte` times its bytes (0: at every move).
    pub fn with_spacing(ep: &Episode, cap: usize, work_per_byte: u64) -> Timeline {
        Timeline {
            snaps: Vec::new(),
            bytes: 0,
            cap,
            ratio: work_per_byte,
            end: ep.point(),
            last_work: ep.work_done(),
        }
    }

    /// The furthest point the run has reached.
    pub fn end(&self) -> TimePoint {
        self.end
    }

    /// What the snapshots hold.
    pub fn memory(&self) -> TimelineMemory {
        TimelineMemory {
            bytes: self.bytes,
            cap: self.cap,
            snapshots: self.snaps.len(),
            work_per_byte: self.ratio,
        }
    }

    /// Notes where `ep` now stands (call after every step of it): the
    /// furthest point, and a snapshot when it stands at the start of a
    /// decision and enough work has been done since the last.
    pub fn note(&mut self, ep: &Episode) {
        let p = ep.point();
        let fresh = TimePoint::at(ep.steps(), ep.loops_of_decision());
        self.end = self.end.max(p).max(fresh);
        let at_move = ep.loops_of_decision() == 0
            && p.phase.is_none_or(|k| k == PhaseKind::Backup)
            && ep.status() == Status::Running;
        let latest = self.snaps.last().map_or(0, |(s, _)| s.steps());
        if !at_move || ep.steps() <= latest || ep.timed().is_some() {
            return;
        }
        let work = ep.work_done().saturating_sub(self.last_work);
        let size = ep.heap_bytes();
        if work < self.ratio.saturating_mul(size as u64) || size > self.cap {
            return;
        }
        while self.bytes + size > self.cap && !self.snaps.is_empty() {
            self.thin();
        }
        if let Some(mut s) = ep.snapshot() {
            s.forget_phase();
            self.snaps.push((s, size));
            self.bytes += size;
            self.last_work = ep.work_done();
        }
    }

    /// Drops every other snapshot (all of them when one is left) and
    /// doubles the spacing of the next.
    fn thin(&mut self) {
        if self.snaps.len() == 1 {
            self.snaps.clear();
        } else {
            let mut i = 0;
            self.snaps.retain(|_| {
                i += 1;
                i % 2 == 0
            });
        }
        self.bytes = self.snaps.iter().map(|&(_, b)| b).sum();
        self.ratio = self.ratio.saturating_mul(2).max(1);
    }

    /// Moves `ep` to point `to` of its run, which must lie within what the
    /// run has reached; the state is the one reached going forward.
    ///
    /// # Errors
    /// A [`SeekError`] naming the point and the points allowed; `ep` is
    /// then left as it was.
    pub fn seek(&self, ep: &mut Episode, to: TimePoint) -> Result<(), SeekError> {
        *ep = self.replay(ep, to)?;
        Ok(())
    }

    /// The run at point `to`, replayed from the nearest snapshot before it
    /// (or from `ep` itself when it stands between them and `to`).
    ///
    /// # Errors
    /// As [`Timeline::seek`].
    pub fn replay(&self, ep: &Episode, to: TimePoint) -> Landed {
        if let Some(ms) = ep.timed() {
            return Err(SeekError::Timed { ms });
        }
        if to > self.end {
            return Err(SeekError::PastEnd { to, end: self.end });
        }
        if !ep.searcher_info().deliberates && (to.loop_ > 0 || to.phase.is_some()) {
            return Err(SeekError::NoLoops { to });
        }
        let snap = self
            .snaps
            .iter()
            .rev()
            .map(|(s, _)| s)
            .find(|s| s.steps() <= to.mv);
        // After a back-up the state is the next loop's start (or the next
        // decision's, when it made the move): walking on starts there.
        let here = match ep.point() {
            p if p.phase == Some(PhaseKind::Backup) => {
                TimePoint::at(ep.steps(), ep.loops_of_decision())
            }
            p => p,
        };
        let from_here = here <= to && snap.is_none_or(|s| here >= s.point());
        let mut run = match (from_here, snap) {
            (true, _) => ep.snapshot(),
            (false, Some(s)) => s.snapshot(),
            (false, None) => None,
        }
        .map_or_else(|| ep.restart().map_err(SeekError::Param), Ok)?;
        run.set_clock(ep.clock());
        walk(&mut run, to)?;
        Ok(run)
    }

    /// The run at the latest point of it at or before `to` (a decision
    /// with fewer loops: its last back-up; past the end: the end).
    ///
    /// # Errors
    /// [`SeekError::Timed`] for a timed run.
    pub fn replay_at_most(&self, ep: &Episode, to: TimePoint) -> Landed {
        let to = to.min(self.end);
        match self.replay(ep, to) {
            Err(SeekError::PastDecision { loops, .. }) if loops > 0 => {
                let last = TimePoint {
                    mv: to.mv,
                    loop_: loops - 1,
                    phase: Some(PhaseKind::Backup),
                };
                self.replay(ep, last)
            }
            Err(SeekError::PastDecision { .. } | SeekError::NoLoops { .. }) => {
                self.replay(ep, TimePoint::at(to.mv, 0))
            }
            other => other,
        }
    }
}

impl Timeline {
    /// The point one `unit` before where `ep` stands (`None` at the start
    /// of the run). Crossing back into the previous decision lands on its
    /// last loop, replaying it to learn how many loops it ran.
    ///
    /// # Errors
    /// [`SeekError::Timed`] for a timed run.
    pub fn back(&self, ep: &Episode, unit: BackUnit) -> Result<Option<TimePoint>, SeekError> {
        let p = ep.point();
        let (m, l) = (p.mv, p.loop_);
        let unit = if ep.searcher_info().deliberates {
            unit
        } else {
            BackUnit::Move
        };
        let at = |mv, loop_, phase| Ok(Some(TimePoint { mv, loop_, phase }));
        match (unit, p.phase) {
            (BackUnit::Phase, Some(PhaseKind::Select)) => at(m, l, None),
            (BackUnit::Phase, Some(k)) => {
                let before = PhaseKind::ALL.iter().position(|&x| x == k).unwrap_or(1) - 1;
                at(m, l, Some(PhaseKind::ALL[before]))
            }
            (BackUnit::Phase, None) if l > 0 => at(m, l - 1, Some(PhaseKind::Rollout)),
            (BackUnit::Loop, Some(_)) => at(m, l, None),
            (BackUnit::Loop, None) if l > 0 => at(m, l - 1, None),
            (BackUnit::Move, _) if p != TimePoint::at(m, 0) => at(m, 0, None),
            (_, _) if m == 0 => Ok(None),
            (BackUnit::Move, _) => at(m - 1, 0, None),
            (_, _) => match self.loops_of(ep, m - 1)? {
                0 => at(m - 1, 0, None),
                loops if unit == BackUnit::Phase => at(m - 1, loops - 1, Some(PhaseKind::Rollout)),
                loops => at(m - 1, loops - 1, None),
            },
        }
    }

    /// The loops decision `mv` ran (it must have ended).
    fn loops_of(&self, ep: &Episode, mv: u32) -> Result<u32, SeekError> {
        match self.replay(ep, TimePoint::at(mv, u32::MAX)) {
            Err(SeekError::PastDecision { loops, .. }) => Ok(loops),
            Err(SeekError::Timed { ms }) => Err(SeekError::Timed { ms }),
            _ => Ok(0),
        }
    }
}

/// Reads a point from JSON `{ "move": m, "loop": l, "phase": p }` (`loop`
/// 0 and `phase` null when left out), strictly.
///
/// # Errors
/// A [`SeekError::Param`] naming the field, the value and what is allowed.
pub fn point_from_json(v: &serde_json::Value) -> Result<TimePoint, SeekError> {
    let bad = |field, value: &dyn std::fmt::Display, allowed: &str| {
        SeekError::Param(ParamError::new(field, value, allowed))
    };
    let obj = v
        .as_object()
        .ok_or_else(|| bad("seek", v, "an object { move, loop, phase }"))?;
    if let Some(k) = obj
        .keys()
        .find(|k| !["move", "loop", "phase"].contains(&k.as_str()))
    {
        return Err(bad(
            "seek",
            &format!("key {k:?}"),
            "the keys move, loop and phase",
        ));
    }
    let int = |field: &'static str, required: bool| match obj.get(field) {
        None if !required => Ok(0),
        Some(x) => x
            .as_f64()
            .filter(|f| f.fract() == 0.0 && (0.0..=u32::MAX as f64).contains(f))
            .map(|f| f as u32)
            .ok_or_else(|| bad(field, x, "an integer in 0..=4294967295")),
        None => Err(bad(field, &"nothing", "an integer in 0..=4294967295")),
    };
    let phase = match obj.get("phase") {
        None | Some(serde_json::Value::Null) => None,
        Some(p) => Some(
            p.as_str()
                .and_then(PhaseKind::parse)
                .ok_or_else(|| bad("phase", p, "null, select, expand, rollout or backup"))?,
        ),
    };
    Ok(TimePoint {
        mv: int("move", true)?,
        loop_: int("loop", false)?,
        phase,
    })
}

/// Steps `run` forward to `to` (at or after where it stands): whole moves,
/// loops unrecorded, then the phases of the last loop recorded.
fn walk(run: &mut Episode, to: TimePoint) -> Result<(), SeekError> {
    let ended = |run: &Episode| SeekError::PastEnd {
        to,
        end: run.point(),
    };
    while run.steps() < to.mv {
        if run.status() != Status::Running {
            return Err(ended(run));
        }
        run.step_move();
    }
    // Loops, then phases; a move made on the way means the decision
    // ended before the point.
    let past = |loops: u32| {
        if loops == 0 {
            SeekError::NoLoops { to }
        } else {
            SeekError::PastDecision { to, loops }
        }
    };
    // (A loop in flight lands with its first steps here.)
    while run.loops_of_decision() < to.loop_ {
        let loops = run.loops_of_decision();
        match run.step_phase_with(false) {
            None => return Err(ended(run)),
            Some(step) if step.moved().is_some() => {
                let ran = loops + u32::from(step.phase() == Some(PhaseKind::Backup));
                return Err(past(ran));
            }
            _ => {}
        }
    }
    let Some(want) = to.phase else {
        // No loop is in flight here: only how the state was reached differs.
        run.forget_phase();
        return Ok(());
    };
    while run.point().phase != Some(want) || run.point().loop_ != to.loop_ {
        let loops = run.loops_of_decision();
        match run.step_phase() {
            None => return Err(ended(run)),
            Some(PhaseStep::Work(Some(_))) => return Err(past(loops)),
            Some(step) if step.moved().is_some() && want != PhaseKind::Backup => {
                return Err(past(loops + 1));
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "timeline_tests.rs"]
mod tests;
