//! Line charts: each series' means against a numeric x, in its colour,
//! dash and marker, with its 95% CI band; the lower bound dashed; published
//! reference values as crosses.

use super::axes::{axis_labels, log_ticks, short_label, y_range};
use super::legend::{rgb, Mark};
use super::marks::{dashed, marker};
use super::style::{Fallible, BOUND};
use super::text::FONT;
use crate::experiment::defs::series_style;
use crate::experiment::result::ResultSet;
use crate::experiment::summary::PointStats;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Each series' (x in axis units, stats) at its points, in x order.
fn series_points<'a>(
    result: &'a ResultSet,
    stats: &'a [PointStats],
    ts: &'a [f64],
    si: usize,
) -> impl Iterator<Item = (f64, &'a PointStats)> + 'a {
    result
        .plan
        .points
        .iter()
        .zip(stats)
        .filter(move |(p, _)| p.series == si)
        .map(move |(p, s)| (ts[p.x], s))
}

/// Each series' bound points; the bound is drawn once when all agree.
fn bounds(result: &ResultSet, stats: &[PointStats], ts: &[f64]) -> (Vec<Vec<(f64, f64)>>, bool) {
    let all: Vec<Vec<(f64, f64)>> = (0..result.plan.header.series.len())
        .map(|si| {
            series_points(result, stats, ts, si)
                .filter_map(|(x, s)| s.lower_bound.map(|b| (x, b)))
                .collect()
        })
        .collect();
    let shared = all.iter().all(|b| *b == all[0]);
    (all, shared)
}

/// The x values in axis units: log10 on a log axis.
fn axis_x(result: &ResultSet) -> (Vec<f64>, bool) {
    let h = &result.plan.header;
    let xs: Vec<f64> =
        h.x.values
            .iter()
            .map(|v| v.parse().unwrap_or(f64::NAN))
            .collect();
    // A log axis is drawn as a linear axis of log10(x), labelled at the x
    // values themselves (plotters labels only the powers of 10 of a log axis).
    let log_x = h.x.log && xs.iter().all(|&x| x > 0.0);
    (
        xs.iter()
            .map(|&x| if log_x { x.log10() } else { x })
            .collect(),
        log_x,
    )
}

/// What the legend of a line chart says.
pub(super) fn entries(result: &ResultSet, stats: &[PointStats]) -> Vec<(Mark, String)> {
    let h = &result.plan.header;
    let mut entries: Vec<(Mark, String)> = h
        .series
        .iter()
        .enumerate()
        .map(|(i, l)| (Mark::Line(series_style(i)), l.clone()))
        .collect();
    entries.push((
        Mark::Swatch(RGBColor(160, 160, 160)),
        "band: 95% CI of the mean (t)".into(),
    ));
    if stats.iter().any(|s| s.lower_bound.is_some()) {
        let (_, shared) = bounds(result, stats, &axis_x(result).0);
        let (c, what) = if shared {
            (BOUND, "")
        } else {
            (rgb(series_style(0).colour), " (per series, in its colour)")
        };
        entries.push((
            Mark::Dashed(c),
            format!("lower bound on the mean (any searcher){what}"),
        ));
    }
    for r in &h.references {
        entries.push((Mark::Cross, r.label.clone()));
    }
    entries
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
    let (ts, _) = axis_x(result);
    let t_lo = ts.iter().copied().fold(f64::INFINITY, f64::min);
    let t_hi = ts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let span = t_hi - t_lo;
    let pad = if span > 0.0 { span * 0.05 } else { 0.5 };
    let (x_lo, x_hi) = (t_lo - pad, t_hi + pad);
    let refs = h.references.iter().flat_map(|r| r.y.iter().copied());
    let values = stats
        .iter()
        .flat_map(|s| {
            [
                s.mean.estimate,
                s.mean.lo,
                s.mean.hi,
                s.lower_bound.unwrap_or(f64::NAN),
            ]
        })
        .chain(refs);
    let (y_lo, y_hi, y_log) = y_range(values, h.y.log);
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(72);
    let floor = if y_log { y_lo } else { f64::NEG_INFINITY };
    let none = |_: &f64| String::new();
    macro_rules! go {
        ($y:expr) => {{
            let mut chart = builder.build_cartesian_2d(x_lo..x_hi, $y)?;
            axis_labels(&mut chart, &h.x.label, &h.y.label, &none, 0, y_log)?;
            if y_log {
                log_ticks(&chart, area, y_lo, y_hi)?;
            }
            chart.draw_series(
                ts.iter().map(|&t| {
                    PathElement::new(vec![(t, y_lo), (t, y_hi)], RGBColor(228, 228, 228))
                }),
            )?;
            draw_lines(&mut chart, area, result, stats, &ts, floor)?;
            x_ticks(&chart, area, &ts, &h.x.values, y_lo)
        }};
    }
    if y_log {
        go!((y_lo..y_hi).log_scale())
    } else {
        go!(y_lo..y_hi)
    }
}

/// Labels the x axis at the data's x values (`ts` in axis units), skipping
/// a label that would touch the one before it.
fn x_ticks<DB, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, Y>>,
    area: &DrawingArea<DB, Shift>,
    ts: &[f64],
    labels: &[String],
    y_bottom: f64,
) -> Fallible
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (bx, by) = area.get_base_pixel();
    let style = TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    let mut last_right = i32::MIN;
    let mut order: Vec<usize> = (0..ts.len()).collect();
    order.sort_by(|&a, &b| ts[a].total_cmp(&ts[b]));
    for i in order {
        let (px, py) = chart.backend_coord(&(ts[i], y_bottom));
        let (x, y) = (px - bx, py - by);
        area.draw(&PathElement::new(
            vec![(x, y), (x, y + 5)],
            BLACK.stroke_width(1),
        ))?;
        let label = short_label(&labels[i]);
        let half = (super::text::width(&label, 13.0) / 2.0).ceil() as i32;
        if x - half > last_right + 6 {
            area.draw(&Text::new(label, (x, y + 8), style.clone()))?;
            last_right = x + half;
        }
    }
    Ok(())
}

fn draw_lines<DB, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, Y>>,
    area: &DrawingArea<DB, Shift>,
    result: &ResultSet,
    stats: &[PointStats],
    ts: &[f64],
    floor: f64,
) -> Fallible
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let h = &result.plan.header;
    let y = |v: f64| v.max(floor);
    let (bx, by) = area.get_base_pixel();
    let pixel = |chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, Y>>, x: f64, v: f64| {
        let (px, py) = chart.backend_coord(&(x, y(v)));
        (px - bx, py - by)
    };
    let (all_bounds, shared) = bounds(result, stats, ts);
    for (si, series_bound) in all_bounds.iter().enumerate() {
        let style = series_style(si);
        let c = rgb(style.colour);
        let pts: Vec<(f64, &PointStats)> = series_points(result, stats, ts, si)
            .filter(|(_, s)| s.n > 0)
            .collect();
        let band: Vec<(f64, f64)> = pts
            .iter()
            .filter(|(_, s)| s.mean.lo.is_finite())
            .map(|(x, s)| (*x, y(s.mean.lo)))
            .chain(
                pts.iter()
                    .rev()
                    .filter(|(_, s)| s.mean.hi.is_finite())
                    .map(|(x, s)| (*x, y(s.mean.hi))),
            )
            .collect();
        if band.len() >= 4 {
            chart.draw_series([Polygon::new(band, c.mix(0.15).filled())])?;
        }
        let line: Vec<(i32, i32)> = pts
            .iter()
            .map(|(x, s)| pixel(chart, *x, s.mean.estimate))
            .collect();
        dashed(area, &line, style.dash, c.stroke_width(2))?;
        let bound: Vec<(i32, i32)> = series_bound
            .iter()
            .map(|&(x, b)| pixel(chart, x, b))
            .collect();
        if bound.len() >= 2 && (!shared || si == 0) {
            let bc = if shared { BOUND } else { c };
            dashed(area, &bound, &[7, 5], bc.stroke_width(2))?;
        }
    }
    // Markers last, so no band or line covers them.
    for si in 0..h.series.len() {
        let style = series_style(si);
        for (x, s) in series_points(result, stats, ts, si).filter(|(_, s)| s.n > 0) {
            marker(
                area,
                pixel(chart, x, s.mean.estimate),
                style.marker,
                rgb(style.colour),
                4.0,
            )?;
        }
    }
    for r in &h.references {
        let (_, log_x) = axis_x(result);
        let pts: Vec<(i32, i32)> =
            r.x.iter()
                .zip(&r.y)
                .filter_map(|(x, v)| {
                    x.parse::<f64>()
                        .ok()
                        .map(|x| (if log_x { x.log10() } else { x }, *v))
                })
                .map(|(x, v)| pixel(chart, x, v))
                .collect();
        dashed(area, &pts, &[3, 3], BLACK.stroke_width(1))?;
        for p in pts {
            area.draw(&Cross::new(p, 5, BLACK.stroke_width(2)))?;
        }
    }
    Ok(())
}
