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

/// A line's advance width in font units, measured as it grows: the same
/// sums, in the same order, as measuring each prefix whole, without going
/// over the prefix again (a provenance line of 200 shard paths is 12 000
/// characters long).
#[derive(Clone, Copy, Default)]
struct Run {
    units: f64,
    prev: Option<ab_glyph::GlyphId>,
}

impl Run {
    fn push(&mut self, c: char) {
        let f = font();
        let g = f.glyph_id(c);
        self.units += f64::from(f.h_advance_unscaled(g));
        if let Some(p) = self.prev {
            self.units += f64::from(f.kern_unscaled(p, g));
        }
        self.prev = Some(g);
    }

    fn with(mut self, c: char) -> Run {
        self.push(c);
        self
    }

    fn pixels(&self, size: f64) -> f64 {
        self.units * size * EM_PER_SIZE / f64::from(font().units_per_em().unwrap_or(2048.0))
    }
}

/// The advance width of `text` at plotters size `size`, in pixels.
pub(super) fn width(text: &str, size: f64) -> f64 {
    let mut run = Run::default();
    text.chars().for_each(|c| run.push(c));
    run.pixels(size)
}

/// `line` cut to `max` pixels at `size`, ending in `tail` when cut.
pub(super) fn cut(line: &str, max: f64, size: f64, tail: char) -> String {
    if width(line, size) <= max {
        return line.to_string();
    }
    let mut run = Run::default();
    let mut keep = 0;
    for (i, c) in line.char_indices() {
        run.push(c);
        if run.with(tail).pixels(size) > max {
            break;
        }
        keep = i + c.len_utf8();
    }
    format!("{}{tail}", &line[..keep])
}

/// `text` in lines no wider than `max` pixels at `size`, broken at spaces
/// (a word wider than a line is broken between characters).
pub(super) fn wrap(text: &str, max: f64, size: f64) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    let mut run = Run::default();
    for word in text.split(' ') {
        let mut joined = if line.is_empty() {
            Run::default()
        } else {
            run.with(' ')
        };
        word.chars().for_each(|c| joined.push(c));
        if joined.pixels(size) <= max {
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
            run = joined;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
            run = Run::default();
        }
        for c in word.chars() {
            run.push(c);
            line.push(c);
            if run.pixels(size) > max && line.chars().count() > 1 {
                line.pop();
                lines.push(std::mem::take(&mut line));
                line.push(c);
                run = Run::default().with(c);
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

    /// The old measure: each prefix whole, popped a character at a time.
    fn cut_by_popping(line: &str, max: f64, size: f64) -> String {
        if width(line, size) <= max {
            return line.to_string();
        }
        let mut s = line.to_string();
        while !s.is_empty() && width(&format!("{s}…"), size) > max {
            s.pop();
        }
        format!("{s}…")
    }

    /// The old wrap: every candidate line measured whole.
    fn wrap_by_remeasuring(text: &str, max: f64, size: f64) -> Vec<String> {
        let (mut lines, mut line) = (Vec::new(), String::new());
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

    #[test]
    fn wrapping_as_it_grows_breaks_where_measuring_whole_lines_does() {
        let texts = [
            "box: quartiles and median; whiskers: Tukey (1.5 IQR); dots: trials beyond them",
            "Supercalifragilisticexpialidocious and  two  spaces, AV Wa To yo",
            "",
        ];
        for t in texts {
            for max in [10.0, 60.0, 200.0, 1e4] {
                assert_eq!(
                    wrap(t, max, 14.0),
                    wrap_by_remeasuring(t, max, 14.0),
                    "{t:?} at {max}"
                );
            }
        }
    }

    #[test]
    fn a_cut_line_is_the_longest_prefix_that_fits_with_its_ellipsis() {
        let line = "command: torus-search merge shards/sigma-sweep.shard-1-of-200.json Wave AV To";
        for max in [0.0, 5.0, 40.0, 123.4, 300.0, 1e4] {
            let got = cut(line, max, 14.0, '…');
            assert_eq!(got, cut_by_popping(line, max, 14.0), "max {max}");
            assert!(
                got == line || width(&got, 14.0) <= max || got == "…",
                "{got}"
            );
        }
    }
}
