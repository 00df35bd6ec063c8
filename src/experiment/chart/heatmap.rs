//! Heat maps: one histogram of sampled targets per point.

use super::style::{Fallible, BOUND};
use super::text::FONT;
use crate::display::render::Palette;
use crate::experiment::result::ResultSet;
use crate::experiment::summary::PointStats;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The panels' grid for `k` points: (columns, rows).
pub(super) fn grid(k: usize) -> (u32, u32) {
    let k = k.max(1) as u32;
    let cols = k.min(4);
    (cols, k.div_ceil(cols))
}

pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    result: &ResultSet,
    stats: &[PointStats],
) -> Fallible
where
    DB::ErrorType: 'static,
{
    let plan = &result.plan;
    let k = plan.points.len().max(1);
    let cols = k.min(4);
    let rows = k.div_ceil(cols);
    let lut = Palette::Viridis.lut();
    let panels = area.split_evenly((rows, cols));
    for ((p, s), panel) in plan.points.iter().zip(stats).zip(&panels) {
        let n = p.config.n as i32;
        let Some(h) = &s.histogram else { continue };
        let max = h.iter().copied().max().unwrap_or(0).max(1);
        let title = match &plan.header.x.key {
            Some(key) => format!("{key} = {} · max {max}/cell", plan.x_text(p)),
            None => format!("{} · max {max}/cell", plan.series_label(p)),
        };
        let mut chart = ChartBuilder::on(panel)
            .caption(title, (FONT, 15))
            .margin(8)
            .x_label_area_size(24)
            .y_label_area_size(30)
            .build_cartesian_2d(0..n, n..0)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(5)
            .y_labels(5)
            .x_label_formatter(&|v| (v + 1).to_string())
            .y_label_formatter(&|v| (v + 1).to_string())
            .label_style((FONT, 11))
            .draw()?;
        let n = n as usize;
        chart.draw_series(
            h.iter()
                .enumerate()
                .filter(|(_, &c)| c > 0)
                .map(|(cell, &c)| {
                    let (x, y) = ((cell % n) as i32, (cell / n) as i32);
                    // A square-root scale, so single samples stay visible beside the mode.
                    let t = (c as f64 / max as f64).sqrt();
                    let [r, g, b, _] = lut[(t * 255.0).round() as usize];
                    Rectangle::new([(x, y), (x + 1, y + 1)], RGBColor(r, g, b).filled())
                }),
        )?;
    }
    area.draw(&Text::new(
        "colour: samples per cell on a square-root scale (white: none); cells 1-based (x, y), y downward",
        (20, area.dim_in_pixel().1 as i32 - 16),
        (FONT, 12).into_font().color(&BOUND),
    ))?;
    Ok(())
}
