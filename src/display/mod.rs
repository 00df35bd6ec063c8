//! Display: frames for the page and heatmap colours.

pub mod render;
pub mod view;
