//! The legend: a column at the right of the plot that names everything
//! drawn, its labels wrapped to the column, never cut off (the chart grows
//! to hold it).

use super::marks::{dashed, marker};
use super::style::Fallible;
use super::text::{wrap, FONT};
use crate::experiment::defs::SeriesStyle;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The legend column's width.
pub(super) const WIDTH: u32 = 290;
const SIZE: f64 = 14.0;
const LINE: i32 = 17;
const GAP: i32 = 10;
/// Where labels start, and how wide they may be.
const TEXT_X: i32 = 52;
const TEXT_WIDTH: f64 = (WIDTH as i32 - TEXT_X - 8) as f64;

/// A legend entry's mark.
pub(super) enum Mark {
    /// A series of a line chart: its line, dashed as drawn, and its marker.
    Line(SeriesStyle),
    /// A series of a box chart: its box colour and its marker.
    Boxed(SeriesStyle),
    /// A filled swatch (a box's colour, a band's).
    Swatch(RGBColor),
    /// A dashed line (the lower bound).
    Dashed(RGBColor),
    /// A cross (a published value).
    Cross,
}

pub(super) fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// The lines of each entry's label.
fn lines(entries: &[(Mark, String)]) -> Vec<Vec<String>> {
    entries
        .iter()
        .map(|(_, label)| wrap(label, TEXT_WIDTH, SIZE))
        .collect()
}

/// The height the legend needs.
pub(super) fn height(entries: &[(Mark, String)]) -> u32 {
    let h: i32 = lines(entries)
        .iter()
        .map(|l| LINE * l.len() as i32 + GAP)
        .sum();
    (30 + h) as u32
}

fn draw_mark<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, mark: &Mark, y: i32) -> Fallible
where
    DB::ErrorType: 'static,
{
    let (x0, x1) = (8, 44);
    match mark {
        Mark::Line(s) => {
            let c = rgb(s.colour);
            dashed(area, &[(x0, y), (x1, y)], s.dash, c.stroke_width(2))?;
            marker(area, ((x0 + x1) / 2, y), s.marker, c, 4.0)?;
        }
        Mark::Boxed(s) => {
            let c = rgb(s.colour);
            area.draw(&Rectangle::new(
                [(x0, y - 7), (x1, y + 7)],
                c.mix(0.3).filled(),
            ))?;
            area.draw(&Rectangle::new(
                [(x0, y - 7), (x1, y + 7)],
                c.stroke_width(1),
            ))?;
            marker(area, ((x0 + x1) / 2, y), s.marker, c, 4.0)?;
        }
        Mark::Swatch(c) => {
            area.draw(&Rectangle::new(
                [(x0, y - 6), (x1, y + 6)],
                c.mix(0.35).filled(),
            ))?;
            area.draw(&Rectangle::new(
                [(x0, y - 6), (x1, y + 6)],
                c.stroke_width(1),
            ))?;
        }
        Mark::Dashed(c) => dashed(area, &[(x0, y), (x1, y)], &[6, 4], c.stroke_width(2))?,
        Mark::Cross => area.draw(&Cross::new(((x0 + x1) / 2, y), 5, BLACK.stroke_width(2)))?,
    }
    Ok(())
}

/// Draws the legend in its own column, so it never covers data.
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Mark, String)],
) -> Fallible
where
    DB::ErrorType: 'static,
{
    let mut y = 30;
    for ((mark, _), lines) in entries.iter().zip(lines(entries)) {
        draw_mark(area, mark, y)?;
        for (i, l) in lines.iter().enumerate() {
            area.draw(&Text::new(
                l.clone(),
                (TEXT_X, y - 8 + LINE * i as i32),
                (FONT, SIZE).into_font(),
            ))?;
        }
        y += LINE * lines.len() as i32 + GAP;
    }
    Ok(())
}
