//! PNG output: the chart drawn at `SCALE` times its size on plotters'
//! bitmap backend, through a backend that scales every coordinate, stroke
//! and text, then encoded by the `png` crate with the provenance as text
//! chunks.

use super::text::line_height_per_size;
use plotters::prelude::*;
use plotters::style::{FontDesc, TextStyle};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

/// Pixels per chart unit in PNG output (a 1270-unit chart is 2540 pixels wide).
pub(super) const SCALE: u32 = 2;

/// A backend drawing on `inner` at `k` times the size it reports.
pub(super) struct Scaled<DB> {
    inner: DB,
    k: i32,
    /// Plotters sizes bitmap text by line height; this turns em sizes into it.
    text: f64,
}

impl<DB: DrawingBackend> Scaled<DB> {
    pub(super) fn new(inner: DB, k: u32) -> Scaled<DB> {
        Scaled {
            inner,
            k: k as i32,
            text: line_height_per_size(),
        }
    }

    fn at(&self, (x, y): BackendCoord) -> BackendCoord {
        (x * self.k, y * self.k)
    }
}

/// A style with its stroke `k` times wider.
struct Wide {
    colour: BackendColor,
    width: u32,
}

impl BackendStyle for Wide {
    fn color(&self) -> BackendColor {
        self.colour
    }
    fn stroke_width(&self) -> u32 {
        self.width
    }
}

impl<DB: DrawingBackend> Scaled<DB> {
    fn wide<S: BackendStyle>(&self, s: &S) -> Wide {
        Wide {
            colour: s.color(),
            width: s.stroke_width() * self.k as u32,
        }
    }

    fn text_style<'a, T: BackendTextStyle>(&self, s: &'a T) -> TextStyle<'a> {
        TextStyle {
            font: FontDesc::new(
                s.family(),
                s.size() * f64::from(self.k) * self.text,
                s.style(),
            )
            .transform(s.transform()),
            color: s.color(),
            pos: s.anchor(),
        }
    }
}

type Drawn<E> = Result<(), DrawingErrorKind<E>>;

impl<DB: DrawingBackend> DrawingBackend for Scaled<DB> {
    type ErrorType = DB::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        let (w, h) = self.inner.get_size();
        (w / self.k as u32, h / self.k as u32)
    }
    fn ensure_prepared(&mut self) -> Drawn<DB::ErrorType> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Drawn<DB::ErrorType> {
        self.inner.present()
    }
    fn draw_pixel(&mut self, p: BackendCoord, c: BackendColor) -> Drawn<DB::ErrorType> {
        let (x, y) = self.at(p);
        self.inner
            .draw_rect((x, y), (x + self.k - 1, y + self.k - 1), &c, true)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
    ) -> Drawn<DB::ErrorType> {
        let w = self.wide(s);
        let (a, b) = (self.at(a), self.at(b));
        if w.width <= 1 {
            self.inner.draw_line(a, b, &w)
        } else {
            self.inner.draw_path([a, b], &w)
        }
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
        fill: bool,
    ) -> Drawn<DB::ErrorType> {
        let (a, b) = (self.at(a), self.at(b));
        if fill {
            return self.inner.draw_rect(a, b, &s.color(), true);
        }
        let w = self.wide(s);
        self.inner.draw_path([a, (b.0, a.1), b, (a.0, b.1), a], &w)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Drawn<DB::ErrorType> {
        let pts: Vec<BackendCoord> = path.into_iter().map(|p| self.at(p)).collect();
        let w = self.wide(s);
        self.inner.draw_path(pts, &w)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        c: BackendCoord,
        r: u32,
        s: &S,
        fill: bool,
    ) -> Drawn<DB::ErrorType> {
        let w = self.wide(s);
        self.inner
            .draw_circle(self.at(c), r * self.k as u32, &w, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        s: &S,
    ) -> Drawn<DB::ErrorType> {
        let pts: Vec<BackendCoord> = vert.into_iter().map(|p| self.at(p)).collect();
        self.inner.fill_polygon(pts, &s.color())
    }
    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        s: &T,
        pos: BackendCoord,
    ) -> Drawn<DB::ErrorType> {
        let style = self.text_style(s);
        self.inner.draw_text(text, &style, self.at(pos))
    }
    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        s: &T,
    ) -> Result<(u32, u32), DrawingErrorKind<DB::ErrorType>> {
        let (w, h) = self.inner.estimate_text_size(text, &self.text_style(s))?;
        Ok((w / self.k as u32, h / self.k as u32))
    }
}

/// PNG bytes of an RGB image `w`×`h`, with text chunks `(keyword, text)`.
///
/// # Errors
/// The encoder's message (none is expected writing to memory).
pub(super) fn encode_png(
    rgb: &[u8],
    (w, h): (u32, u32),
    text: &[(&str, String)],
) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        // 2 chart units per pixel at 96 units per inch: 192 pixels per inch.
        enc.set_pixel_dims(Some(png::PixelDimensions {
            xppu: 7559,
            yppu: 7559,
            unit: png::Unit::Meter,
        }));
        for (k, v) in text {
            enc.add_itxt_chunk(k.to_string(), v.clone())
                .map_err(|e| e.to_string())?;
        }
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(rgb).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())?;
    }
    Ok(out)
}
