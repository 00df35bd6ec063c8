//! What every part of a chart shares: its result type and the colour of
//! the lower bound and secondary text.

use plotters::style::RGBColor;

/// A drawing step: plotters' errors boxed.
pub(super) type Fallible = Result<(), Box<dyn std::error::Error>>;

/// The colour of the lower bound and of secondary text.
pub(super) const BOUND: RGBColor = RGBColor(40, 40, 40);
