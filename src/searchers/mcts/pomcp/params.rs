//! The belief MCTS's parameters, and how it scales returns for UCT.

use crate::game::named::named_enum;
use crate::param::{Param, ParamKind, Value};
use crate::searchers::planning::lookahead::MAX_HORIZON;
use std::borrow::Cow;

named_enum! {
    /// How the belief MCTS scales returns for UCT.
    pub enum ReturnScale {
        /// By the range of returns seen this decision (c scaled to it).
        Range = "range",
        /// As a fraction of the expected steps left (the root's mean return).
        Left = "left",
        /// The best (lowest) return seen through the child, by the range.
        Best = "best",
    }
}

/// The default `pomcp_depth`: rollout steps counted before the reference
/// tail stands in. Chosen so that a decision of 100 loops at N = 40 stays
/// within a few milliseconds (`EXPERIMENTS.md`, "The belief MCTS").
pub const DEFAULT_POMCP_DEPTH: u32 = 25;

/// The default `pomcp_plan`: the horizon depth of the first plan, made once
/// a trial (`EXPERIMENTS.md`, "The belief MCTS", has its cost).
pub const DEFAULT_POMCP_PLAN: u32 = 5;

/// How returns are scaled for UCT.
pub static POMCP_SCALE: Param = Param {
    key: "pomcp_scale",
    label: "Return scale",
    kind: ParamKind::Choice(|| ReturnScale::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("best")),
    help: "pomcp: a child's value for UCT and for the real move: best (the best return found through it, scaled by the spread of returns this decision), range (its mean return, scaled the same way) or left (its mean return as a fraction of the expected steps left)",
    aliases: &[],
    choice_labels: &["mean, by range", "mean, of steps left", "best return, by range"],
    advanced: true,
};

/// The posterior share below which returns sample the practice target's time.
pub static POMCP_EXACT: Param = Param {
    key: "pomcp_exact",
    label: "Exact returns until",
    kind: ParamKind::Float {
        min: 0.0,
        max: 1.0,
        min_open: false,
    },
    default: Value::Float(0.0),
    help: "pomcp: a return counts the expected steps exactly until this share of the posterior is left, then adds the practice target's sampled remaining steps (1 = the sampled return of plain POMCP, 0 = expected steps only)",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// Rollout steps counted before the reference tail stands in.
pub static POMCP_DEPTH: Param = Param {
    key: "pomcp_depth",
    label: "Exact rollout depth",
    kind: ParamKind::Int { min: 1, max: 100_000 },
    default: Value::Int(DEFAULT_POMCP_DEPTH as u64),
    help: "pomcp: rollout steps counted exactly; the rest of a return is then estimated from one coverage walk to the end, made at the start of the decision",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};

/// The horizon depth of the plan the belief MCTS starts from.
pub static POMCP_PLAN: Param = Param {
    key: "pomcp_plan",
    label: "Plan horizon",
    kind: ParamKind::Int {
        min: 0,
        max: MAX_HORIZON as u64,
    },
    default: Value::Int(DEFAULT_POMCP_PLAN as u64),
    help: "pomcp: the horizon depth of the plan it starts from (rollouts rejoin the plan, and a move leaves it only for a line checked exactly to be cheaper); 0 = no plan, coverage-walk rollouts",
    aliases: &[],
    choice_labels: &[],
    advanced: true,
};
