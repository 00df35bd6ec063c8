//! A result as a chart, drawn with plotters (native builds only): SVG, and
//! PNG for papers, from the same drawing code.
//!
//! * `box`: a box per series at each x value (per series when there is one
//!   x value): quartiles, median, Tukey whiskers, the rows beyond them, and
//!   the mean with its 95% CI.
//! * `line`: mean lines with 95% CI bands against a numeric x, published
//!   reference values as crosses.
//! * `heatmap`: one histogram of sampled targets per point.
//!
//! Series differ by colour (a palette that stays apart for colour-blind
//! viewers), marker and dash ([`crate::experiment::defs::series_style`]).
//! The lower bound on the mean is a dashed line wherever it is known. The
//! legend has its own column and the chart grows to hold it. A caption
//! under every chart names the experiment, trials, seed, preset and build,
//! and, given a provenance, the date and the command.
//!
//! Text is measured, and drawn in PNGs, with the embedded DejaVu Sans, so
//! no system font is read; SVG text names it, then the viewer's sans-serif.

mod axes;
mod boxes;
mod heatmap;
mod legend;
mod lines;
mod marks;
mod scaled;
mod style;
mod text;

use super::defs::{Chart, Kind};
use super::provenance::{this_build, Provenance, CAPTION_RGB};
use super::result::ResultSet;
use super::summary::PointStats;
use legend::Mark;
use plotters::coord::Shift;
use plotters::prelude::*;
use style::{Fallible, BOUND};
use text::{wrap, FONT};

const NOTE_SIZE: f64 = 13.0;
const NOTE_LINE: u32 = 18;
/// Above the plot: the title.
const TOP: u32 = 50;

/// What a chart holds besides its plot, worked out before drawing so that
/// the chart is sized to hold all of it.
struct Frame {
    size: (u32, u32),
    stats: Vec<PointStats>,
    entries: Vec<(Mark, String)>,
    /// Notes, then the caption, each a wrapped line.
    footer: Vec<(String, RGBColor)>,
}

/// `line` cut to `max` pixels at the notes' size, with an ellipsis.
fn fit(line: &str, max: f64) -> String {
    text::cut(line, max, NOTE_SIZE, '…')
}

/// The caption, one line (two with a provenance, the command second), each
/// cut to the chart's width (the files hold it whole), so a chart's layout
/// never depends on its provenance: what was run and by which build; with
/// a provenance, when and by what command.
fn caption(result: &ResultSet, prov: Option<&Provenance>) -> Vec<String> {
    let plan = &result.plan;
    let h = &plan.header;
    let mut first = format!(
        "{} · {} {} per point · seed {} · preset {}",
        h.name,
        plan.trials(),
        if h.kind == Kind::Targets {
            "samples"
        } else {
            "trials"
        },
        plan.spec.seed,
        plan.spec.preset.map_or("none", |p| p.name())
    );
    if !result.is_complete() || result.from != 0 || result.to != plan.total_units() {
        first += &format!(
            " · partial: {} of {} units",
            result.rows.len(),
            plan.total_units()
        );
    }
    match prov {
        Some(p) => vec![
            format!("{first} · {}, made {}", p.build(), p.date),
            format!("command: {}", p.command),
        ],
        None => vec![format!("{first} · {}", this_build())],
    }
}

impl Frame {
    fn of(result: &ResultSet, prov: Option<&Provenance>) -> Frame {
        let h = &result.plan.header;
        let stats = result.stats();
        let entries = match h.chart {
            Chart::Heatmap => Vec::new(),
            Chart::Line if h.x.numeric => lines::entries(result, &stats),
            _ => boxes::entries(result, &stats),
        };
        let (width, body) = if h.chart == Chart::Heatmap {
            let (cols, rows) = heatmap::grid(result.plan.points.len());
            (cols * 300 + 40, rows * 320 + 60)
        } else {
            let boxes = result.plan.points.len() as u32;
            let width = 1000u32.max(360 + 20 * boxes) + legend::WIDTH;
            (width, 570u32.max(legend::height(&entries)))
        };
        let mut notes: Vec<String> = Vec::new();
        let capped: u64 = stats.iter().map(|s| s.capped).sum();
        if capped == 1 {
            notes.push("1 capped trial is kept at the step cap in every statistic".into());
        } else if capped > 1 {
            notes.push(format!(
                "{capped} capped trials are kept at the step cap in every statistic"
            ));
        }
        if let Some(n) = &h.note {
            notes.push(format!("note: {n}"));
        }
        let max = f64::from(width - 40);
        let [r, g, b] = CAPTION_RGB;
        let grey = RGBColor(r, g, b);
        let footer: Vec<(String, RGBColor)> = notes
            .iter()
            .flat_map(|n| wrap(n, max, NOTE_SIZE).into_iter().map(|l| (l, BOUND)))
            .chain(caption(result, prov).iter().map(|c| (fit(c, max), grey)))
            .collect();
        let height = TOP + body + 10 + NOTE_LINE * footer.len() as u32;
        Frame {
            size: (width, height),
            stats,
            entries,
            footer,
        }
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    result: &ResultSet,
    frame: &Frame,
) -> Fallible
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let h = &result.plan.header;
    root.draw(&Text::new(
        h.title.clone(),
        (20, 14),
        (FONT, 22).into_font(),
    ))?;
    let (_, height) = frame.size;
    let footer_h = 10 + NOTE_LINE * frame.footer.len() as u32;
    for (i, (line, colour)) in frame.footer.iter().enumerate() {
        let y = (height - footer_h + 4 + NOTE_LINE * i as u32) as i32;
        root.draw(&Text::new(
            line.clone(),
            (20, y),
            (FONT, NOTE_SIZE).into_font().color(colour),
        ))?;
    }
    let body = root.margin(TOP, footer_h, 0, 0);
    if h.chart == Chart::Heatmap {
        return heatmap::draw(&body, result, &frame.stats);
    }
    let (w, _) = body.dim_in_pixel();
    let (plot, side) = body.split_horizontally(w - legend::WIDTH);
    match h.chart {
        Chart::Line if h.x.numeric => lines::draw(&plot, result, &frame.stats)?,
        _ => boxes::draw(&plot, result, &frame.stats)?,
    }
    legend::draw(&side, &frame.entries)
}

/// The chart of `result` as SVG text, its caption naming this build. A
/// drawing error (none is expected) gives a chart that says so instead of
/// a panic.
pub fn svg(result: &ResultSet) -> String {
    svg_of(result, None)
}

/// The chart of `result` as SVG text, with `prov` in its caption.
pub fn svg_stamped(result: &ResultSet, prov: &Provenance) -> String {
    svg_of(result, Some(prov))
}

fn svg_of(result: &ResultSet, prov: Option<&Provenance>) -> String {
    text::register();
    let frame = Frame::of(result, prov);
    let mut out = String::new();
    let drawn = {
        let root = SVGBackend::with_string(&mut out, frame.size).into_drawing_area();
        draw(&root, result, &frame).and_then(|()| root.present().map_err(Into::into))
    };
    match drawn {
        Ok(()) => out,
        Err(e) => {
            let mut out = String::new();
            {
                let root = SVGBackend::with_string(&mut out, (640, 80)).into_drawing_area();
                let _ = failed(&root, &e.to_string());
            }
            out
        }
    }
}

fn failed<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, e: &str) -> Fallible
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    root.draw(&Text::new(
        format!("chart could not be drawn: {e}"),
        (10, 30),
        (FONT, 14).into_font(),
    ))?;
    root.present()?;
    Ok(())
}

/// The chart of `result` as PNG bytes at twice the SVG's size (192 pixels
/// per inch), with `prov` in its caption and in the PNG's text chunks
/// (Title, Software, Creation Time, Source, Description).
pub fn png_stamped(result: &ResultSet, prov: &Provenance) -> Vec<u8> {
    text::register();
    let frame = Frame::of(result, Some(prov));
    let k = scaled::SCALE;
    let (w, h) = (frame.size.0 * k, frame.size.1 * k);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    let drawn = {
        let backend = scaled::Scaled::new(BitMapBackend::with_buffer(&mut buf, (w, h)), k);
        let root = backend.into_drawing_area();
        draw(&root, result, &frame)
            .and_then(|()| root.present().map_err(Into::into))
            .map_err(|e| {
                let _ = failed(&root, &e.to_string());
            })
    };
    let _ = drawn;
    let chunks = [
        ("Title", result.plan.header.title.clone()),
        ("Software", prov.build()),
        ("Creation Time", prov.date.clone()),
        ("Source", prov.command.clone()),
        (
            "Description",
            format!("spec: {}", result.plan.spec.to_text()),
        ),
    ];
    scaled::encode_png(&buf, (w, h), &chunks).expect("a PNG encodes into memory")
}
