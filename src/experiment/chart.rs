//! A result as an SVG chart, drawn with plotters (native builds only).
//!
//! * `box`: a box per series at each x value (per series when there is one
//!   x value): quartiles, median, Tukey whiskers, the rows beyond them, and
//!   the mean with its 95% CI.
//! * `line`: mean lines with 95% CI bands against a numeric x, published
//!   reference values as crosses.
//! * `heatmap`: one histogram of sampled targets per point.
//!
//! The lower bound on the mean is a dashed line wherever it is known.
//! Text is written as SVG `<text>` in a generic sans-serif family: plotters
//! only estimates its width (no font files are read), and the viewer draws it.

use super::defs::{Chart, Kind};
use super::result::ResultSet;
use super::summary::PointStats;
use crate::display::render::Palette;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
type Fallible = Result<(), Box<dyn std::error::Error>>;

/// Series colours (Okabe–Ito, readable by most colour-blind viewers).
const COLOURS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(100, 100, 100),
];
const BOUND: RGBColor = RGBColor(40, 40, 40);
const FONT: &str = "sans-serif";
/// The legend's column at the right of line and box charts.
const LEGEND_WIDTH: u32 = 270;

/// A legend entry's mark.
enum Mark {
    /// A filled swatch (a box's colour).
    Swatch(RGBColor),
    /// A solid line.
    Line(RGBColor),
    /// A dashed line (the lower bound).
    Dashed(RGBColor),
    /// A cross (a mean, a published value).
    Cross,
}

/// Draws the legend in its own column, so it never covers data.
fn draw_legend(area: &Area<'_>, entries: &[(Mark, String)]) -> Fallible {
    let mut y = 30;
    for (mark, label) in entries {
        let (x0, x1) = (10, 34);
        match mark {
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
            Mark::Line(c) => {
                area.draw(&PathElement::new(vec![(x0, y), (x1, y)], c.stroke_width(3)))?
            }
            Mark::Dashed(c) => {
                for x in (x0..x1).step_by(9) {
                    area.draw(&PathElement::new(
                        vec![(x, y), ((x + 5).min(x1), y)],
                        c.stroke_width(2),
                    ))?;
                }
            }
            Mark::Cross => area.draw(&Cross::new(((x0 + x1) / 2, y), 5, BLACK.stroke_width(2)))?,
        }
        // Long labels wrap at about 30 characters.
        let mut line = String::new();
        let mut lines = Vec::new();
        for word in label.split(' ') {
            if !line.is_empty() && line.chars().count() + word.chars().count() > 30 {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        lines.push(line);
        for (i, l) in lines.iter().enumerate() {
            area.draw(&Text::new(
                l.clone(),
                (44, y - 7 + 17 * i as i32),
                (FONT, 14).into_font(),
            ))?;
        }
        y += 17 * lines.len() as i32 + 10;
    }
    Ok(())
}

fn colour(series: usize) -> RGBColor {
    COLOURS[series % COLOURS.len()]
}

/// The chart of `result` as SVG text. A drawing error (none is expected with
/// an in-memory SVG) gives a chart that says so instead of a panic.
pub fn svg(result: &ResultSet) -> String {
    let (w, h) = size(result);
    let mut out = String::new();
    let drawn = {
        let root = SVGBackend::with_string(&mut out, (w, h)).into_drawing_area();
        draw(&root, result).and_then(|()| root.present().map_err(Into::into))
    };
    match drawn {
        Ok(()) => out,
        Err(e) => {
            let mut out = String::new();
            {
                let root = SVGBackend::with_string(&mut out, (640, 80)).into_drawing_area();
                let _ = root.fill(&WHITE);
                let _ = root.draw(&Text::new(
                    format!("chart could not be drawn: {e}"),
                    (10, 30),
                    (FONT, 14).into_font(),
                ));
                let _ = root.present();
            }
            out
        }
    }
}

fn size(result: &ResultSet) -> (u32, u32) {
    match result.plan.header.chart {
        Chart::Heatmap => {
            let k = result.plan.points.len().max(1) as u32;
            let cols = k.min(4);
            let rows = k.div_ceil(cols);
            (cols * 300 + 40, rows * 320 + 110)
        }
        _ => {
            let boxes = result.plan.points.len() as u32;
            (1000u32.max(360 + 20 * boxes) + LEGEND_WIDTH, 640)
        }
    }
}

fn draw(root: &Area<'_>, result: &ResultSet) -> Fallible {
    root.fill(&WHITE)?;
    let plan = &result.plan;
    let h = &plan.header;
    let stats = result.stats();
    let (_, height) = root.dim_in_pixel();
    root.draw(&Text::new(
        h.title.clone(),
        (20, 12),
        (FONT, 22).into_font(),
    ))?;
    let preset = plan.spec.preset.map_or("no preset", |p| p.name());
    let mut sub = format!(
        "{} {} per point · preset {preset} · seed {} · torus-search {}",
        plan.trials(),
        if h.kind == Kind::Targets {
            "samples"
        } else {
            "trials"
        },
        plan.spec.seed,
        env!("CARGO_PKG_VERSION")
    );
    if !result.is_complete() || result.from != 0 || result.to != plan.total_units() {
        sub += &format!(
            " · partial: {} of {} units",
            result.rows.len(),
            plan.total_units()
        );
    }
    root.draw(&Text::new(
        sub,
        (20, 40),
        (FONT, 14).into_font().color(&BOUND),
    ))?;
    let mut notes: Vec<String> = Vec::new();
    if stats.iter().any(|s| s.capped > 0) {
        let capped: u64 = stats.iter().map(|s| s.capped).sum();
        notes.push(if capped == 1 {
            "1 capped trial is kept at the step cap in every statistic".to_string()
        } else {
            format!("{capped} capped trials are kept at the step cap in every statistic")
        });
    }
    if let Some(n) = &h.note {
        notes.push(format!("note: {n}"));
    }
    for (i, n) in notes.iter().enumerate() {
        let y = height as i32 - 18 * (notes.len() - i) as i32;
        root.draw(&Text::new(
            n.clone(),
            (20, y),
            (FONT, 13).into_font().color(&BOUND),
        ))?;
    }
    let top = 60;
    let bottom = height - 10 - 18 * notes.len() as u32;
    let body = root.margin(top, height - bottom, 0, 0);
    if h.chart == Chart::Heatmap {
        return heatmaps(&body, result, &stats);
    }
    let (w, _) = body.dim_in_pixel();
    let (plot, side) = body.split_horizontally(w - LEGEND_WIDTH);
    let entries = match h.chart {
        Chart::Line if h.x.numeric => lines(&plot, result, &stats)?,
        _ => boxes(&plot, result, &stats)?,
    };
    draw_legend(&side, &entries)
}

/// The y range over what will be drawn, padded, and whether it is drawn on
/// a log scale: when the experiment asks for one and the positive values
/// span at least a factor of 20 (less shows too few ticks to read). On a
/// log axis the floor is below the smallest positive value; values at or
/// below 0 are drawn at the floor.
fn y_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64, bool) {
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

fn axis_labels<'a, 'b, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>,
    x_label: &str,
    y_label: &str,
    x_format: &dyn Fn(&f64) -> String,
    x_ticks: usize,
) -> Fallible
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(x_ticks)
        .x_label_formatter(x_format)
        .y_labels(8)
        .y_label_formatter(&|v| short(*v))
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .light_line_style(RGBColor(246, 246, 246))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()?;
    Ok(())
}

/// A tick label: integers plainly, others with up to 3 significant digits.
fn short(v: f64) -> String {
    if v == v.round() && v.abs() < 1e9 {
        format!("{}", v as i64)
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Where each series' box sits within a category of width 1.
fn slot(series: usize, of: usize) -> (f64, f64) {
    let width = 0.8 / of as f64;
    let left = -0.4 + width * series as f64;
    (left + width * 0.12, left + width * 0.88)
}

fn boxes(
    area: &Area<'_>,
    result: &ResultSet,
    stats: &[PointStats],
) -> Result<Vec<(Mark, String)>, Box<dyn std::error::Error>> {
    let plan = &result.plan;
    let h = &plan.header;
    let single_x = h.x.values.len() == 1;
    // One x value: the series are the categories.
    let categories: Vec<String> = if single_x {
        h.series.clone()
    } else {
        h.x.values.clone()
    };
    let groups = if single_x { 1 } else { h.series.len() };
    let place = |p: &super::plan::Point| -> (f64, usize) {
        if single_x {
            (p.series as f64, 0)
        } else {
            (p.x as f64, p.series)
        }
    };
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
    let k = categories.len();
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(72);
    let x_label = if single_x {
        String::new()
    } else {
        h.x.label.clone()
    };
    let format = |v: &f64| {
        let i = v.round();
        if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < k {
            categories[i as usize].clone()
        } else {
            String::new()
        }
    };
    let x_range = -0.5..(k as f64 - 0.5);
    if log {
        let mut chart = builder.build_cartesian_2d(x_range, (lo..hi).log_scale())?;
        axis_labels(&mut chart, &x_label, &h.y.label, &format, k + 1)?;
        draw_boxes(&mut chart, result, stats, &place, groups, lo)?;
    } else {
        let mut chart = builder.build_cartesian_2d(x_range, lo..hi)?;
        axis_labels(&mut chart, &x_label, &h.y.label, &format, k + 1)?;
        draw_boxes(&mut chart, result, stats, &place, groups, f64::NEG_INFINITY)?;
    }
    let mut entries: Vec<(Mark, String)> = Vec::new();
    if groups > 1 {
        for (i, label) in h.series.iter().enumerate() {
            entries.push((Mark::Swatch(colour(i)), label.clone()));
        }
    }
    entries.push((
        Mark::Swatch(colour(0)),
        "box: quartiles and median; whiskers: Tukey (1.5 IQR); dots: trials beyond them".into(),
    ));
    entries.push((Mark::Cross, "mean and its 95% CI (t)".into()));
    if stats.iter().any(|s| s.lower_bound.is_some()) {
        entries.push((
            Mark::Dashed(BOUND),
            "lower bound on the mean (any searcher)".into(),
        ));
    }
    Ok(entries)
}

fn draw_boxes<'a, 'b: 'a, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, Y>>,
    result: &ResultSet,
    stats: &[PointStats],
    place: &dyn Fn(&super::plan::Point) -> (f64, usize),
    groups: usize,
    floor: f64,
) -> Fallible
where
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let plan = &result.plan;
    let y = |v: f64| v.max(floor);
    let by_point = result.rows_by_point();
    for ((p, s), mine) in plan.points.iter().zip(stats).zip(&by_point) {
        let (centre, group) = place(p);
        let (a, b) = slot(group, groups);
        let (x0, x1) = (centre + a, centre + b);
        let mid = (x0 + x1) / 2.0;
        let c = colour(p.series);
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
        // The mean and its 95% CI, beside the box.
        let mx = x1 - (x1 - x0) * 0.12;
        if s.mean.lo.is_finite() {
            chart.draw_series([PathElement::new(
                vec![(mx, y(s.mean.lo)), (mx, y(s.mean.hi))],
                BLACK.stroke_width(2),
            )])?;
        }
        chart.draw_series([Cross::new(
            (mx, y(s.mean.estimate)),
            4,
            BLACK.stroke_width(2),
        )])?;
    }
    Ok(())
}

fn lines(
    area: &Area<'_>,
    result: &ResultSet,
    stats: &[PointStats],
) -> Result<Vec<(Mark, String)>, Box<dyn std::error::Error>> {
    let h = &result.plan.header;
    let xs: Vec<f64> =
        h.x.values
            .iter()
            .map(|v| v.parse().unwrap_or(f64::NAN))
            .collect();
    // A log axis is drawn as a linear axis of log10(x), labelled at the x
    // values themselves (plotters labels only the powers of 10 of a log axis).
    let log_x = h.x.log && xs.iter().all(|&x| x > 0.0);
    let tx = move |x: f64| if log_x { x.log10() } else { x };
    let ts: Vec<f64> = xs.iter().map(|&x| tx(x)).collect();
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
        ($y:expr, $y_ref:expr) => {{
            let mut chart = builder.build_cartesian_2d(x_lo..x_hi, $y)?;
            axis_labels(&mut chart, &h.x.label, &h.y.label, &none, 0)?;
            chart.draw_series(ts.iter().map(|&t| {
                PathElement::new(vec![(t, $y_ref.0), (t, $y_ref.1)], RGBColor(228, 228, 228))
            }))?;
            let shared = draw_lines(&mut chart, result, stats, &ts, &tx, floor)?;
            x_ticks(&chart, area, &ts, &h.x.values, $y_ref.0)?;
            shared
        }};
    }
    let shared_bound = if y_log {
        go!((y_lo..y_hi).log_scale(), (y_lo, y_hi))
    } else {
        go!(y_lo..y_hi, (y_lo, y_hi))
    };
    let mut entries: Vec<(Mark, String)> = h
        .series
        .iter()
        .enumerate()
        .map(|(i, l)| (Mark::Line(colour(i)), l.clone()))
        .collect();
    entries.push((
        Mark::Swatch(RGBColor(160, 160, 160)),
        "band: 95% CI of the mean (t)".into(),
    ));
    if stats.iter().any(|s| s.lower_bound.is_some()) {
        let c = if shared_bound { BOUND } else { colour(0) };
        let what = if shared_bound {
            ""
        } else {
            " (per series, in its colour)"
        };
        entries.push((
            Mark::Dashed(c),
            format!("lower bound on the mean (any searcher){what}"),
        ));
    }
    for r in &h.references {
        entries.push((Mark::Cross, r.label.clone()));
    }
    Ok(entries)
}

/// Labels the x axis at the data's x values (`ts` in axis units), skipping
/// a label that would touch the one before it.
fn x_ticks<'a, 'b: 'a, Y>(
    chart: &ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, Y>>,
    area: &Area<'_>,
    ts: &[f64],
    labels: &[String],
    y_bottom: f64,
) -> Fallible
where
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
        let half = 4 * label.chars().count() as i32;
        if x - half > last_right + 6 {
            area.draw(&Text::new(label, (x, y + 8), style.clone()))?;
            last_right = x + half;
        }
    }
    Ok(())
}

/// A value's text for a tick: long decimals (√2) shortened to 4 significant digits.
fn short_label(text: &str) -> String {
    match text.parse::<f64>() {
        Ok(v) if text.len() > 6 => format!("{}", (v * 1e3).round() / 1e3),
        _ => text.to_string(),
    }
}

fn draw_lines<'a, 'b: 'a, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, Y>>,
    result: &ResultSet,
    stats: &[PointStats],
    xs: &[f64],
    tx: &dyn Fn(f64) -> f64,
    floor: f64,
) -> Result<bool, Box<dyn std::error::Error>>
where
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let plan = &result.plan;
    let h = &plan.header;
    let y = |v: f64| v.max(floor);
    let series_points = |si: usize| {
        plan.points
            .iter()
            .zip(stats)
            .filter(move |(p, _)| p.series == si)
            .map(|(p, s)| (xs[p.x], s))
    };
    // Bounds: once when every series has the same, else per series.
    let bound_of = |si: usize| -> Vec<(f64, f64)> {
        series_points(si)
            .filter_map(|(x, s)| s.lower_bound.map(|b| (x, y(b))))
            .collect()
    };
    let first = bound_of(0);
    let shared = (1..h.series.len()).all(|si| bound_of(si) == first);
    for si in 0..h.series.len() {
        let c = colour(si);
        let pts: Vec<(f64, &PointStats)> = series_points(si).filter(|(_, s)| s.n > 0).collect();
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
            chart.draw_series([Polygon::new(band, c.mix(0.18).filled())])?;
        }
        chart.draw_series(LineSeries::new(
            pts.iter().map(|(x, s)| (*x, y(s.mean.estimate))),
            c.stroke_width(2),
        ))?;
        chart.draw_series(
            pts.iter()
                .map(|(x, s)| Circle::new((*x, y(s.mean.estimate)), 3, c.filled())),
        )?;
        let bound = bound_of(si);
        if bound.len() >= 2 && (!shared || si == 0) {
            let style = if shared { BOUND } else { c };
            chart.draw_series(DashedLineSeries::new(bound, 7, 5, style.stroke_width(2)))?;
        }
    }
    for r in &h.references {
        let pts: Vec<(f64, f64)> =
            r.x.iter()
                .zip(&r.y)
                .filter_map(|(x, v)| x.parse::<f64>().ok().map(|x| (tx(x), y(*v))))
                .collect();
        chart.draw_series(DashedLineSeries::new(
            pts.clone(),
            3,
            3,
            BLACK.stroke_width(1),
        ))?;
        chart.draw_series(pts.iter().map(|&p| Cross::new(p, 5, BLACK.stroke_width(2))))?;
    }
    Ok(shared)
}

fn heatmaps(area: &Area<'_>, result: &ResultSet, stats: &[PointStats]) -> Fallible {
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
        (20, area.dim_in_pixel().1 as i32 - 6),
        (FONT, 12).into_font().color(&BOUND),
    ))?;
    Ok(())
}
