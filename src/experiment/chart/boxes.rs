//! Box charts: a box per series at each x value (per series when there is
//! one x value): quartiles, median, Tukey whiskers, the rows beyond them,
//! and the mean (the series' marker) with its 95% CI. Category labels are
//! wrapped to their category's width, so neighbours never overlap.

use super::axes::{axis_labels, log_ticks, y_range};
use super::legend::{rgb, Mark};
use super::marks::marker;
use super::style::{Fallible, BOUND};
use super::text::{width, wrap, FONT};
use crate::experiment::defs::series_style;
use crate::experiment::plan::Point;
use crate::experiment::result::ResultSet;
use crate::experiment::summary::PointStats;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const MARGIN: u32 = 16;
const Y_LABELS: u32 = 72;
const TICK_LINE: i32 = 16;

/// What the legend of a box chart says.
pub(super) fn entries(result: &ResultSet, stats: &[PointStats]) -> Vec<(Mark, String)> {
    let h = &result.plan.header;
    let mut entries: Vec<(Mark, String)> = Vec::new();
    if h.series.len() > 1 {
        for (i, label) in h.series.iter().enumerate() {
            entries.push((Mark::Boxed(series_style(i)), label.clone()));
        }
    }
    entries.push((
        Mark::Boxed(series_style(0)),
        "box: quartiles and median; whiskers: Tukey (1.5 IQR); circles: trials beyond them; marker: the mean, its black bar the 95% CI (t)".into(),
    ));
    if stats.iter().any(|s| s.lower_bound.is_some()) {
        entries.push((
            Mark::Dashed(BOUND),
            "lower bound on the mean (any searcher)".into(),
        ));
    }
    entries
}

/// The categories along x: the x values, or the series with one x value.
fn categories(result: &ResultSet) -> (Vec<String>, bool) {
    let h = &result.plan.header;
    let single_x = h.x.values.len() == 1;
    if single_x {
        (h.series.clone(), true)
    } else {
        (h.x.values.clone(), false)
    }
}

/// Where each series' box sits within a category of width 1.
fn slot(series: usize, of: usize) -> (f64, f64) {
    let width = 0.8 / of as f64;
    let left = -0.4 + width * series as f64;
    (left + width * 0.12, left + width * 0.88)
}

pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    result: &ResultSet,
    stats: &[PointStats],
) -> Fallible
where
    DB::ErrorType: 'static,
{
    let h = &result.plan.header;
    let (cats, single_x) = categories(result);
    let groups = if single_x { 1 } else { h.series.len() };
    let values = stats.iter().flat_map(|s| {
        [
            s.spread.whisker_low,
            s.spread.whisker_high,
            s.mean.lo,
            s.mean.hi,
            s.lower_bound.unwrap_or(f64::NAN),
            s.spread.min,
            s.spread.max,
        ]
    });
    let (lo, hi, log) = y_range(values, h.y.log);
    let k = cats.len();
    let (w, _) = area.dim_in_pixel();
    let cat_px = f64::from(w.saturating_sub(2 * MARGIN + Y_LABELS)) / k as f64;
    let room = (cat_px - 8.0).max(24.0);
    // The largest size at which every word fits its category, then wrapped.
    let size = [13.0, 12.0, 11.0, 10.0]
        .into_iter()
        .find(|&z| {
            cats.iter()
                .flat_map(|c| c.split(' '))
                .all(|w| width(w, z) <= room)
        })
        .unwrap_or(10.0);
    let labels: Vec<Vec<String>> = cats.iter().map(|c| wrap(c, room, size)).collect();
    let rows = labels.iter().map(Vec::len).max().unwrap_or(1) as u32;
    let x_label = if single_x { "" } else { h.x.label.as_str() };
    let desc = if x_label.is_empty() { 0 } else { 24 };
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(MARGIN)
        .x_label_area_size(16 + TICK_LINE as u32 * rows + desc)
        .y_label_area_size(Y_LABELS);
    let none = |_: &f64| String::new();
    let x_range = -0.5..(k as f64 - 0.5);
    if log {
        let mut chart = builder.build_cartesian_2d(x_range, (lo..hi).log_scale())?;
        axis_labels(&mut chart, x_label, &h.y.label, &none, 0, true)?;
        log_ticks(&chart, area, lo, hi)?;
        draw_boxes(&mut chart, area, result, stats, groups, lo)?;
        category_labels(&chart, area, &labels, size, lo)
    } else {
        let mut chart = builder.build_cartesian_2d(x_range, lo..hi)?;
        axis_labels(&mut chart, x_label, &h.y.label, &none, 0, false)?;
        draw_boxes(&mut chart, area, result, stats, groups, f64::NEG_INFINITY)?;
        category_labels(&chart, area, &labels, size, lo)
    }
}

/// Each category's label lines, centred under it.
fn category_labels<DB, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, Y>>,
    area: &DrawingArea<DB, Shift>,
    labels: &[Vec<String>],
    size: f64,
    y_bottom: f64,
) -> Fallible
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (bx, by) = area.get_base_pixel();
    let style = TextStyle::from((FONT, size).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    for (i, lines) in labels.iter().enumerate() {
        let (px, py) = chart.backend_coord(&(i as f64, y_bottom));
        let (x, y) = (px - bx, py - by);
        area.draw(&PathElement::new(
            vec![(x, y), (x, y + 5)],
            BLACK.stroke_width(1),
        ))?;
        for (j, l) in lines.iter().enumerate() {
            area.draw(&Text::new(
                l.clone(),
                (x, y + 8 + TICK_LINE * j as i32),
                style.clone(),
            ))?;
        }
    }
    Ok(())
}

fn draw_boxes<DB, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, Y>>,
    area: &DrawingArea<DB, Shift>,
    result: &ResultSet,
    stats: &[PointStats],
    groups: usize,
    floor: f64,
) -> Fallible
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let plan = &result.plan;
    let single_x = groups == 1;
    let place = |p: &Point| -> (f64, usize) {
        if single_x {
            (p.series as f64, 0)
        } else {
            (p.x as f64, p.series)
        }
    };
    let y = |v: f64| v.max(floor);
    let by_point = result.rows_by_point();
    let (bx, by) = area.get_base_pixel();
    for ((p, s), mine) in plan.points.iter().zip(stats).zip(&by_point) {
        let (centre, group) = place(p);
        let (a, b) = slot(group, groups);
        let (x0, x1) = (centre + a, centre + b);
        let mid = (x0 + x1) / 2.0;
        let style = series_style(p.series);
        let c = rgb(style.colour);
        if let Some(lb) = s.lower_bound {
            let span = if groups == 1 {
                (x0 - 0.05, x1 + 0.05)
            } else {
                (centre - 0.45, centre + 0.45)
            };
            chart.draw_series(DashedLineSeries::new(
                [(span.0, y(lb)), (span.1, y(lb))],
                6,
                4,
                BOUND.stroke_width(2),
            ))?;
        }
        if s.n == 0 {
            continue;
        }
        chart.draw_series([
            Rectangle::new(
                [(x0, y(s.spread.q1)), (x1, y(s.spread.q3))],
                c.mix(0.22).filled(),
            ),
            Rectangle::new(
                [(x0, y(s.spread.q1)), (x1, y(s.spread.q3))],
                c.stroke_width(1),
            ),
        ])?;
        let cap = (x1 - x0) * 0.25;
        chart.draw_series(
            [
                vec![(x0, y(s.spread.median)), (x1, y(s.spread.median))],
                vec![(mid, y(s.spread.q3)), (mid, y(s.spread.whisker_high))],
                vec![(mid, y(s.spread.q1)), (mid, y(s.spread.whisker_low))],
                vec![
                    (mid - cap, y(s.spread.whisker_high)),
                    (mid + cap, y(s.spread.whisker_high)),
                ],
                vec![
                    (mid - cap, y(s.spread.whisker_low)),
                    (mid + cap, y(s.spread.whisker_low)),
                ],
            ]
            .into_iter()
            .map(|pts| PathElement::new(pts, c.stroke_width(2))),
        )?;
        // Rows beyond the whiskers, drawn one by one (capped trials among them).
        chart.draw_series(
            mine.iter()
                .map(|r| r.value as f64)
                .filter(|&v| v < s.spread.whisker_low || v > s.spread.whisker_high)
                .map(|v| Circle::new((mid, y(v)), 2, c.stroke_width(1))),
        )?;
        // The mean (the series' marker) and its 95% CI, beside the box.
        let mx = x1 - (x1 - x0) * 0.12;
        if s.mean.lo.is_finite() {
            chart.draw_series([PathElement::new(
                vec![(mx, y(s.mean.lo)), (mx, y(s.mean.hi))],
                BLACK.stroke_width(2),
            )])?;
        }
        let (px, py) = chart.backend_coord(&(mx, y(s.mean.estimate)));
        marker(area, (px - bx, py - by), style.marker, c, 4.5)?;
    }
    Ok(())
}
