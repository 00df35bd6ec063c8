//! Text in charts: the embedded font, widths measured with it, and lines
//! wrapped to a width.
//!
//! Sizes are plotters' text sizes: its SVG backend writes a size-s text with
//! `font-size` s / 1.24 ([`EM_PER_SIZE`]), so a text is measured here as wide
//! as a browser draws it with DejaVu Sans, and PNGs draw it at that size.

use ab_glyph::{Font, FontRef};
use std::sync::OnceLock;

/// DejaVu Sans (assets/fonts, with its licence).
static FONT_BYTES: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

/// The family every chart text names: the embedded font, else the viewer's sans-serif.
pub(super) const FONT: &str = "DejaVu Sans, sans-serif";

fn font() -> &'static FontRef<'static> {
    static F: OnceLock<FontRef<'static>> = OnceLock::new();
    F.get_or_init(|| FontRef::try_from_slice(FONT_BYTES).expect("the embedded font parses"))
}

/// Registers the embedded font for plotters under [`FONT`] (once).
pub(super) fn register() {
    static DONE: OnceLock<()> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font(FONT, plotters::style::FontStyle::Normal, FONT_BYTES)
            .unwrap_or_else(|_| panic!("the embedded font registers"));
    });
}

/// The em size of a plotters text size (its SVG backend's `font-size`).
pub(super) const EM_PER_SIZE: f64 = 1.0 / 1.24;

/// Plotters sizes ab_glyph text by its line height (ascent − descent):
/// this is the line height of a text of size 1 drawn at the SVG's em size.
pub(super) fn line_height_per_size() -> f64 {
    let f = font();
    EM_PER_SIZE * f64::from(f.height_unscaled()) / f64::from(f.units_per_em().unwrap_or(2048.0))
}

/// The advance width of `text` at plotters size `size`, in pixels.
pub(super) fn width(text: &str, size: f64) -> f64 {
    let f = font();
    let per_unit = size * EM_PER_SIZE / f64::from(f.units_per_em().unwrap_or(2048.0));
    let mut units = 0.0f64;
    let mut prev = None;
    for c in text.chars() {
        let g = f.glyph_id(c);
        units += f64::from(f.h_advance_unscaled(g));
        if let Some(p) = prev {
            units += f64::from(f.kern_unscaled(p, g));
        }
        prev = Some(g);
    }
    units * per_unit
}

/// `text` in lines no wider than `max` pixels at `size`, broken at spaces
/// (a word wider than a line is broken between characters).
pub(super) fn wrap(text: &str, max: f64, size: f64) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let joined = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if width(&joined, size) <= max {
            line = joined;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        for c in word.chars() {
            line.push(c);
            if width(&line, size) > max && line.chars().count() > 1 {
                line.pop();
                lines.push(std::mem::take(&mut line));
                line.push(c);
            }
        }
    }
    lines.push(line);
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widths_come_from_the_font_and_lines_fit() {
        // DejaVu Sans advances: "i" 0.278 em, "W" 0.989 em, the digits 0.636
        // em; size 12.4 is em 10.
        assert!((width("0123456789", 12.4) - 63.6).abs() < 0.1);
        assert!(width("W", 14.0) > 3.0 * width("i", 14.0));
        assert!((line_height_per_size() * 1.24 - 1.164).abs() < 0.001);
        let text = "box: quartiles and median; whiskers: Tukey (1.5 IQR); dots: trials beyond them";
        let lines = wrap(text, 200.0, 14.0);
        assert!(lines.len() >= 3, "{lines:?}");
        assert!(lines.iter().all(|l| width(l, 14.0) <= 200.0), "{lines:?}");
        assert_eq!(lines.join(" "), text);
        let long = wrap("Supercalifragilisticexpialidocious", 60.0, 14.0);
        assert!(long.len() > 1 && long.iter().all(|l| width(l, 14.0) <= 60.0));
        assert_eq!(long.concat(), "Supercalifragilisticexpialidocious");
    }
}
