//! What the belief planners share.
//!
//! Every quantity here is a planning quantity: mass is the belief's
//! planning mass, "covered" means searched for real or by a simulation
//! ([`crate::game::coverage::Coverage`]). For a path `p_0, p_1, …` from the
//! current cell the expected number of further moves until detection,
//! given no detection so far, is proportional to `Σ_{t≥1} R_t` (`R_t`:
//! planning mass left after `t` simulated moves): see
//! `crate::analysis::bound`. Planners compare paths by that sum.

pub mod completion;
pub mod coverage_walk;
pub mod far_goal;
pub mod lookahead;
pub mod plan_cache;
pub mod planned_path;
pub mod refine;
