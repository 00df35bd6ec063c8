//! The heat layers a run can show: the prior, the belief, what was searched and a searcher's own counts.

use crate::game::named::named_enum;

named_enum! {
    /// A heat layer of the lattice.
    pub enum Layer {
        /// The true target's prior mass.
        Prior = "prior",
        /// The planning prior's mass (a delta on the target when it is known).
        Plan = "plan",
        /// The planning prior with searched cells removed, renormalised.
        Posterior = "posterior",
        /// MCTS visit counts (a tree projected onto cells; NSARW's own counts).
        Visits = "visits",
        /// Cells within r_v of any position occupied so far.
        Searched = "searched",
        /// A NSARW walker's own visit counts.
        Walker = "walker",
    }
}

impl Layer {
    /// A name for people.
    pub fn label(self) -> &'static str {
        match self {
            Layer::Prior => "Prior mass",
            Layer::Plan => "Planning prior",
            Layer::Posterior => "Posterior mass",
            Layer::Visits => "MCTS visits",
            Layer::Searched => "Searched",
            Layer::Walker => "NSARW counts",
        }
    }

    /// True for counts (a log scale's floor is 1), false for masses and flags.
    pub fn counts(self) -> bool {
        matches!(self, Layer::Visits | Layer::Walker)
    }

    /// True for a yes/no layer, drawn on a linear scale whatever is asked.
    pub fn binary(self) -> bool {
        self == Layer::Searched
    }

    /// True when the layer changes as the search runs.
    pub fn dynamic(self) -> bool {
        !matches!(self, Layer::Prior | Layer::Plan)
    }
}
