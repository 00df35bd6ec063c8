//! Axes shared by the box and line charts: the y range and scale, the mesh
//! and its labels, tick text.

use super::style::Fallible;
use super::text::FONT;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The y range over what will be drawn, padded, and whether it is drawn on
/// a log scale: when the experiment asks for one and the positive values
/// span at least a factor of 20 (less shows too few ticks to read). On a
/// log axis the floor is below the smallest positive value; values at or
/// below 0 are drawn at the floor.
pub(super) fn y_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64, bool) {
    let vs: Vec<f64> = values.filter(|v| v.is_finite()).collect();
    let pos = vs.iter().copied().filter(|&v| v > 0.0);
    let (plo, phi) = (
        pos.clone().fold(f64::INFINITY, f64::min),
        pos.fold(0.0, f64::max),
    );
    let log = log && plo.is_finite() && phi / plo >= 20.0;
    let (lo, hi) = y_span(&vs, log);
    (lo, hi, log)
}

fn y_span(vs: &[f64], log: bool) -> (f64, f64) {
    let lo = vs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = vs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if !lo.is_finite() {
        return if log { (1.0, 10.0) } else { (0.0, 1.0) };
    }
    if log {
        let floor = vs
            .iter()
            .copied()
            .filter(|&v| v > 0.0)
            .fold(f64::INFINITY, f64::min);
        let floor = if floor.is_finite() { floor } else { 1.0 };
        (floor / 1.5, (hi.max(floor) * 1.5).max(floor * 10.0))
    } else {
        let pad = ((hi - lo) * 0.06).max(0.5);
        (lo - pad, hi + pad)
    }
}

/// The mesh, the axis descriptions and the y labels (none on a log axis:
/// [`log_ticks`] draws them); x labels by `x_format` at `x_ticks` places
/// (0: none, the caller draws its own).
pub(super) fn axis_labels<DB, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    x_label: &str,
    y_label: &str,
    x_format: &dyn Fn(&f64) -> String,
    x_ticks: usize,
    y_log: bool,
) -> Fallible
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(x_ticks)
        .x_label_formatter(x_format)
        .y_labels(if y_log { 0 } else { 8 })
        .y_label_formatter(&|v| if y_log { String::new() } else { short(*v) })
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .light_line_style(RGBColor(246, 246, 246))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()?;
    Ok(())
}

/// The values 1, 2 and 5 × 10^k within `lo..=hi`.
pub(super) fn one_two_five(lo: f64, hi: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if !(lo > 0.0 && hi > lo) {
        return out;
    }
    let mut decade = 10f64.powi(lo.log10().floor() as i32);
    while decade <= hi {
        for m in [1.0, 2.0, 5.0] {
            let v = m * decade;
            if v >= lo && v <= hi {
                out.push(v);
            }
        }
        decade *= 10.0;
    }
    out
}

/// A log y axis's grid and labels at 1, 2 and 5 × 10^k (plotters labels
/// only the powers of 10), each label skipped if it would touch the last.
pub(super) fn log_ticks<DB, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, Y>>,
    area: &DrawingArea<DB, Shift>,
    lo: f64,
    hi: f64,
) -> Fallible
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (bx, by) = area.get_base_pixel();
    let (xs, _) = chart.plotting_area().get_pixel_range();
    let style = TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Right, VPos::Center));
    let mut last = i32::MAX;
    for v in one_two_five(lo, hi) {
        let (_, py) = chart.backend_coord(&(0.0, v));
        let y = py - by;
        let major = (v.log10() - v.log10().round()).abs() < 1e-9;
        let grid = if major {
            RGBColor(215, 215, 215)
        } else {
            RGBColor(236, 236, 236)
        };
        area.draw(&PathElement::new(
            vec![(xs.start - bx, y), (xs.end - bx, y)],
            grid,
        ))?;
        area.draw(&PathElement::new(
            vec![(xs.start - bx - 5, y), (xs.start - bx, y)],
            BLACK,
        ))?;
        if last - y >= 18 {
            area.draw(&Text::new(short(v), (xs.start - bx - 8, y), style.clone()))?;
            last = y;
        }
    }
    Ok(())
}

/// A tick label: integers plainly, others with up to 3 significant digits.
pub(super) fn short(v: f64) -> String {
    if v == v.round() && v.abs() < 1e9 {
        format!("{}", v as i64)
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// A value's text for a tick: long decimals (√2) shortened to 4 significant digits.
pub(super) fn short_label(text: &str) -> String {
    match text.parse::<f64>() {
        Ok(v) if text.len() > 6 => format!("{}", (v * 1e3).round() / 1e3),
        _ => text.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_are_one_two_five_per_decade() {
        assert_eq!(one_two_five(26.0, 600.0), vec![50.0, 100.0, 200.0, 500.0]);
        assert_eq!(one_two_five(1.0, 10.0), vec![1.0, 2.0, 5.0, 10.0]);
        assert!(one_two_five(0.0, 10.0).is_empty());
    }
}
