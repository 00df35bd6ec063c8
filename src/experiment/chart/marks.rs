//! A series' marks, drawn in pixels: its marker shape and its dashed line.

use super::style::Fallible;
use crate::experiment::defs::Marker;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The corners of a regular shape of `n` points at radius `r`, the first
/// up, alternating with radius `inner` when given (a star).
fn ring(n: usize, r: f64, inner: Option<f64>) -> Vec<(f64, f64)> {
    let k = if inner.is_some() { 2 * n } else { n };
    (0..k)
        .map(|i| {
            let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::TAU * i as f64 / k as f64;
            let rr = if i % 2 == 1 { inner.unwrap_or(r) } else { r };
            (rr * a.cos(), rr * a.sin())
        })
        .collect()
}

/// Draws marker `m` of radius `r` centred at pixel `at`.
pub(super) fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    at: (i32, i32),
    m: Marker,
    colour: RGBColor,
    r: f64,
) -> Fallible
where
    DB::ErrorType: 'static,
{
    let px = |(x, y): (f64, f64)| (at.0 + x.round() as i32, at.1 + y.round() as i32);
    let edge = RGBColor(30, 30, 30).mix(0.75).stroke_width(1);
    let filled = |pts: Vec<(f64, f64)>| -> Fallible {
        let pts: Vec<(i32, i32)> = pts.into_iter().map(px).collect();
        area.draw(&Polygon::new(pts.clone(), colour.filled()))?;
        let mut closed = pts.clone();
        closed.push(pts[0]);
        area.draw(&PathElement::new(closed, edge))?;
        Ok(())
    };
    let strokes = |arms: &[(f64, f64, f64, f64)]| -> Fallible {
        for &(x0, y0, x1, y1) in arms {
            area.draw(&PathElement::new(
                vec![px((x0, y0)), px((x1, y1))],
                colour.stroke_width(2),
            ))?;
        }
        Ok(())
    };
    match m {
        Marker::Circle => {
            area.draw(&Circle::new(at, r.round() as i32, colour.filled()))?;
            area.draw(&Circle::new(at, r.round() as i32, edge))?;
            Ok(())
        }
        Marker::Square => {
            let s = r * 0.9;
            filled(vec![(-s, -s), (s, -s), (s, s), (-s, s)])
        }
        Marker::Triangle => filled(ring(3, r * 1.25, None)),
        Marker::Diamond => filled(vec![
            (0.0, -1.3 * r),
            (1.3 * r, 0.0),
            (0.0, 1.3 * r),
            (-1.3 * r, 0.0),
        ]),
        Marker::Star => filled(ring(5, r * 1.35, Some(r * 0.6))),
        Marker::Hexagon => filled(ring(6, r * 1.1, None)),
        Marker::Times => {
            let s = r;
            strokes(&[(-s, -s, s, s), (-s, s, s, -s)])
        }
        Marker::Plus => {
            let s = r * 1.25;
            strokes(&[(-s, 0.0, s, 0.0), (0.0, -s, 0.0, s)])
        }
        Marker::Wye => {
            let arms: Vec<(f64, f64, f64, f64)> = ring(3, r * 1.3, None)
                .into_iter()
                .map(|(x, y)| (0.0, 0.0, x, -y))
                .collect();
            strokes(&arms)
        }
        Marker::Asterisk => {
            let arms: Vec<(f64, f64, f64, f64)> = ring(6, r * 1.25, None)
                .into_iter()
                .take(3)
                .map(|(x, y)| (-x, -y, x, y))
                .collect();
            strokes(&arms)
        }
    }
}

/// The dashes of the polyline `pts` (pixels) under `pattern` (on, off, …;
/// empty: one solid run), as runs of points: a dash that turns a corner
/// stays one run.
pub(super) fn dash_runs(pts: &[(i32, i32)], pattern: &[u32]) -> Vec<Vec<(i32, i32)>> {
    if pattern.is_empty() || pattern.iter().all(|&p| p == 0) {
        return vec![pts.to_vec()];
    }
    let mut runs = Vec::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    let (mut idx, mut left) = (0usize, f64::from(pattern[0]));
    let round = |run: &[(f64, f64)]| -> Vec<(i32, i32)> {
        run.iter()
            .map(|&(x, y)| (x.round() as i32, y.round() as i32))
            .collect()
    };
    for w in pts.windows(2) {
        let (a, b) = (
            (f64::from(w[0].0), f64::from(w[0].1)),
            (f64::from(w[1].0), f64::from(w[1].1)),
        );
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let at = |t: f64| (a.0 + (b.0 - a.0) * t / len, a.1 + (b.1 - a.1) * t / len);
        let mut t = 0.0;
        while t < len {
            let step = left.min(len - t);
            if idx % 2 == 0 {
                if run.is_empty() {
                    run.push(at(t));
                }
                run.push(at(t + step));
            }
            t += step;
            left -= step;
            if left <= 1e-9 {
                if idx % 2 == 0 && run.len() > 1 {
                    runs.push(round(&run));
                }
                run.clear();
                idx = (idx + 1) % pattern.len();
                left = f64::from(pattern[idx]);
            }
        }
    }
    if run.len() > 1 {
        runs.push(round(&run));
    }
    runs
}

/// Draws the polyline `pts` (pixels) dashed by `pattern`.
pub(super) fn dashed<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    pts: &[(i32, i32)],
    pattern: &[u32],
    style: ShapeStyle,
) -> Fallible
where
    DB::ErrorType: 'static,
{
    for run in dash_runs(pts, pattern) {
        area.draw(&PathElement::new(run, style))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dashes_follow_the_pattern_around_corners() {
        let solid = dash_runs(&[(0, 0), (10, 0)], &[]);
        assert_eq!(solid, vec![vec![(0, 0), (10, 0)]]);
        // 30 px along x under (9 on, 4 off): dashes at 0–9, 13–22, 26–30.
        let runs = dash_runs(&[(0, 0), (30, 0)], &[9, 4]);
        assert_eq!(
            runs,
            vec![
                vec![(0, 0), (9, 0)],
                vec![(13, 0), (22, 0)],
                vec![(26, 0), (30, 0)]
            ]
        );
        // A dash turning a corner is one run through the corner.
        let runs = dash_runs(&[(0, 0), (5, 0), (5, 10)], &[9, 4]);
        assert_eq!(runs[0], vec![(0, 0), (5, 0), (5, 4)]);
        assert_eq!(runs[1], vec![(5, 8), (5, 10)]);
    }
}
