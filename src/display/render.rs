//! Heatmap rendering: values on the N×N lattice to one RGBA buffer.
//!
//! Pure Rust (no browser types), so it is tested natively; the frame
//! builder ([`crate::display::view`]) fills the buffers the page puts on a canvas.
//!
//! The palettes are built here from first principles rather than copied from a
//! table: each is a path through the OKLab colour space whose lightness rises
//! linearly, so equal steps in value are equal steps in perceived lightness
//! (perceptually uniform) and the order survives any colour-vision deficiency
//! or greyscale printing (lightness alone carries it). The hues run along the
//! blue–yellow axis, which red–green colour-blind viewers see fully.
//!
//! * [`Palette::Viridis`] — purple-blue → teal → yellow, after matplotlib's viridis.
//! * [`Palette::Ember`] — near-black → purple → orange → pale yellow, after inferno.
//! * [`Palette::Cividis`] — navy → grey → yellow, no red–green component at all.

use crate::game::named::named_enum;

named_enum! {
    /// A named colour ramp, sampled into a 256-entry lookup table.
    pub enum Palette {
        /// Purple-blue → teal → yellow.
        Viridis = "viridis",
        /// Near-black → purple → orange → pale yellow.
        Ember = "ember",
        /// Navy → grey → yellow.
        Cividis = "cividis",
    }
}

impl Palette {
    /// (lightness start, lightness end, hue start°, hue end°, chroma at 0, ½, 1).
    fn path(self) -> ([f64; 2], [f64; 2], [f64; 3]) {
        match self {
            Palette::Viridis => ([0.30, 0.93], [300.0, 100.0], [0.14, 0.10, 0.19]),
            Palette::Ember => ([0.16, 0.97], [290.0, 460.0], [0.08, 0.21, 0.16]),
            Palette::Cividis => ([0.26, 0.92], [262.0, 96.0], [0.10, 0.005, 0.16]),
        }
    }

    /// The 256-entry RGBA lookup table (alpha 255).
    pub fn lut(self) -> [[u8; 4]; 256] {
        let ([l0, l1], [h0, h1], [c0, cm, c1]) = self.path();
        let mut lut = [[0u8; 4]; 256];
        for (i, slot) in lut.iter_mut().enumerate() {
            let t = i as f64 / 255.0;
            let l = l0 + (l1 - l0) * t;
            let h = (h0 + (h1 - h0) * t).to_radians();
            // Quadratic through the three chroma control points.
            let c = c0 * (1.0 - t) * (1.0 - 2.0 * t)
                + cm * 4.0 * t * (1.0 - t)
                + c1 * t * (2.0 * t - 1.0);
            let c = c.max(0.0);
            let rgb = oklch_to_srgb_in_gamut(l, c, h);
            *slot = [rgb[0], rgb[1], rgb[2], 255];
        }
        lut
    }
}

/// How values map onto the palette.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// `t = v / max`.
    Linear,
    /// `t = (v - min) / (max - min)` over the nonzero values: contrast for
    /// nearly flat fields such as the visit counts of long rollouts.
    Stretch,
    /// `t = ln(1 + v/floor) / ln(1 + max/floor)`. For counts use `floor = 1`;
    /// for probability masses a floor a few decades below the maximum.
    Log { floor: f64 },
}

named_enum! {
    /// How values map onto a palette, by name (see [`Scale`]).
    pub enum ScaleKind {
        /// Zero to the maximum.
        Linear = "linear",
        /// The smallest nonzero value to the maximum.
        Stretch = "stretch",
        /// Logarithmic.
        Log = "log",
    }
}

impl Scale {
    /// The scale `kind` for values whose maximum is `max`. A log scale's
    /// floor is 1 for counts, and four decades below the maximum for masses.
    pub fn of(kind: ScaleKind, max: f64, counts: bool) -> Scale {
        match kind {
            ScaleKind::Linear => Scale::Linear,
            ScaleKind::Stretch => Scale::Stretch,
            ScaleKind::Log => Scale::Log {
                floor: if counts { 1.0 } else { max * 1e-4 },
            },
        }
    }
}

/// How transparent low values are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Alpha {
    /// Every cell opaque; zero gets the palette's first colour.
    Opaque,
    /// Zero is fully transparent, other cells fade in: alpha = `lo + (hi - lo)·t`.
    Ramp {
        /// Alpha of the lowest level.
        lo: u8,
        /// Alpha of the highest level.
        hi: u8,
    },
}

impl Alpha {
    /// `[255, 255]` is opaque; anything else ramps from `lo` to `hi`.
    pub fn of([lo, hi]: [u8; 2]) -> Alpha {
        if lo == 255 && hi == 255 {
            Alpha::Opaque
        } else {
            Alpha::Ramp { lo, hi }
        }
    }
}

/// The extent of a layer's values, for the legend.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Extent {
    /// The smallest value.
    pub min: f64,
    /// The smallest value above zero (0 when there is none).
    pub min_nonzero: f64,
    /// The largest value.
    pub max: f64,
    /// The sum.
    pub sum: f64,
    /// How many values are above zero.
    pub nonzero: usize,
}

/// Values that can be drawn: masses (f64), counts (u32) and flags (u8).
pub trait Drawable: Copy {
    /// The value as a float.
    fn to_f64(self) -> f64;
}
impl Drawable for f64 {
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
}
impl Drawable for u32 {
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
}
impl Drawable for u8 {
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
}

/// Minimum, maximum, sum and count of nonzero values (NaN and negatives count as 0).
pub fn summarize<T: Drawable>(values: &[T]) -> Extent {
    let mut s = Extent {
        min: f64::INFINITY,
        min_nonzero: f64::INFINITY,
        max: 0.0,
        sum: 0.0,
        nonzero: 0,
    };
    // Plain comparisons, not f64::min/max: `clean` leaves no NaN, and wasm's
    // min/max instructions propagate NaN, so f64::min costs extra selects.
    for &v in values {
        let v = clean(v.to_f64());
        let positive = v > 0.0;
        let nz = if positive { v } else { f64::INFINITY };
        s.min = if v < s.min { v } else { s.min };
        s.min_nonzero = if nz < s.min_nonzero {
            nz
        } else {
            s.min_nonzero
        };
        s.max = if v > s.max { v } else { s.max };
        s.sum += v;
        s.nonzero += positive as usize;
    }
    if values.is_empty() {
        s.min = 0.0;
    }
    if s.nonzero == 0 {
        s.min_nonzero = 0.0;
    }
    s
}

#[inline]
fn clean(v: f64) -> f64 {
    // NaN fails the comparison and maps to 0, as do negatives.
    if v > 0.0 {
        v
    } else {
        0.0
    }
}

/// Added before truncating to a level, so that `max · (255 / max)`, which
/// can round to 254.99999, still reaches the top level.
const LEVEL_EPS: f64 = 1e-6;

/// A reusable renderer: the palette table is computed once.
#[derive(Clone)]
pub struct Colorizer {
    lut: [[u8; 4]; 256],
}

impl Colorizer {
    /// A renderer for `palette`.
    pub fn new(palette: Palette) -> Self {
        Colorizer { lut: palette.lut() }
    }

    /// The palette's 256-entry RGBA table.
    pub fn lut(&self) -> &[[u8; 4]; 256] {
        &self.lut
    }

    /// Colours `values` on the scale `kind` (its log floor set by whether
    /// they are `counts`), summarising them once; returns the extent.
    ///
    /// # Panics
    /// If `out` does not hold `4 * values.len()` bytes.
    pub fn colorize_kind<T: Drawable>(
        &self,
        values: &[T],
        out: &mut [u8],
        kind: ScaleKind,
        counts: bool,
        alpha: Alpha,
    ) -> Extent {
        let summary = summarize(values);
        self.colorize_summarized(
            values,
            out,
            summary,
            Scale::of(kind, summary.max, counts),
            alpha,
        )
    }

    /// Writes one RGBA pixel per value into `out` (which must hold
    /// `4 * values.len()` bytes) and returns the value summary.
    ///
    /// # Panics
    /// If `out` has the wrong length.
    pub fn colorize<T: Drawable>(
        &self,
        values: &[T],
        out: &mut [u8],
        scale: Scale,
        alpha: Alpha,
    ) -> Extent {
        self.colorize_summarized(values, out, summarize(values), scale, alpha)
    }

    fn colorize_summarized<T: Drawable>(
        &self,
        values: &[T],
        out: &mut [u8],
        summary: Extent,
        scale: Scale,
        alpha: Alpha,
    ) -> Extent {
        assert_eq!(out.len(), 4 * values.len(), "RGBA buffer length");
        let max = summary.max;
        let (lo, hi) = match alpha {
            Alpha::Opaque => (255.0, 255.0),
            Alpha::Ramp { lo, hi } => (lo as f64, hi as f64),
        };
        let transparent_zero = matches!(alpha, Alpha::Ramp { .. });
        // Precompute the map level -> pixel for all 256 levels, each pixel
        // as the u32 whose bytes in memory are R, G, B, A.
        let mut px = [0u32; 256];
        for (i, p) in px.iter_mut().enumerate() {
            let t = i as f64 / 255.0;
            let a = (lo + (hi - lo) * t).round().clamp(0.0, 255.0) as u8;
            let c = self.lut[i];
            *p = u32::from_ne_bytes([c[0], c[1], c[2], a]);
        }
        let zero = if transparent_zero { 0 } else { px[0] };
        if max <= 0.0 {
            fill(values, out, &px, zero, |_| 0);
            return summary;
        }
        match scale {
            Scale::Linear => {
                let k = 255.0 / max;
                // At least level 1, so a tiny nonzero value stays visible.
                fill(values, out, &px, zero, |v| {
                    ((v * k + LEVEL_EPS) as usize).clamp(1, 255)
                });
            }
            Scale::Stretch => {
                let lo = summary.min_nonzero;
                let span = max - lo;
                let k = if span > 0.0 { 255.0 / span } else { 0.0 };
                // Level 0 is the minimum: transparent in ramp mode.
                fill(values, out, &px, zero, |v| {
                    (((v - lo) * k + LEVEL_EPS) as usize).min(255)
                });
            }
            Scale::Log { floor } => {
                let floor = if floor > 0.0 && floor.is_finite() {
                    floor
                } else {
                    max * 1e-6
                };
                let inv_floor = 1.0 / floor;
                let k = 255.0 / fast_log2(1.0 + max * inv_floor) as f64;
                fill(values, out, &px, zero, |v| {
                    ((fast_log2(1.0 + v * inv_floor) as f64 * k) as usize).clamp(1, 255)
                });
            }
        }
        summary
    }
}

/// Writes `px[level(v)]` for each positive value and `zero` for the rest,
/// one u32 store a pixel (byte by byte only if `out` is not 4-aligned): the
/// recolouring of big layers is most of what a frame costs.
#[inline(always)]
fn fill<T: Drawable>(
    values: &[T],
    out: &mut [u8],
    px: &[u32; 256],
    zero: u32,
    level: impl Fn(f64) -> usize,
) {
    let pixel = |v: T| {
        let v = clean(v.to_f64());
        if v > 0.0 {
            px[level(v).min(255)]
        } else {
            zero
        }
    };
    // SAFETY: every 4 bytes are a valid u32, and align_to_mut splits off
    // any unaligned ends.
    let (head, words, tail) = unsafe { out.align_to_mut::<u32>() };
    if head.is_empty() && tail.is_empty() {
        for (&v, w) in values.iter().zip(words.iter_mut()) {
            *w = pixel(v);
        }
    } else {
        for (&v, chunk) in values.iter().zip(out.chunks_exact_mut(4)) {
            chunk.copy_from_slice(&pixel(v).to_ne_bytes());
        }
    }
}

/// log2 with ~0.005 absolute error, from the float's exponent plus a cubic in
/// the mantissa; about ten times cheaper than `f64::log2` in wasm, which
/// matters at N = 1024 (a million cells per layer per frame).
#[inline]
pub fn fast_log2(x: f64) -> f32 {
    let x = x as f32;
    if x <= 0.0 || x.is_nan() {
        return f32::NEG_INFINITY;
    }
    if x.is_infinite() {
        return f32::INFINITY;
    }
    let bits = x.to_bits();
    let exp = ((bits >> 23) & 0xff) as i32 - 127;
    let m = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000); // in [1, 2)
    let y = m - 1.0;
    // Minimax-style cubic for log2(1 + y), y in [0, 1).
    let p =
        y * (std::f32::consts::LOG2_E + y * (-0.721_347_5 + y * (0.478_537_5 - 0.199_885_6 * y)));
    exp as f32 + p
}

fn oklab_to_linear_srgb(l: f64, a: f64, b: f64) -> [f64; 3] {
    let l_ = l + 0.396_337_777_4 * a + 0.215_803_757_3 * b;
    let m_ = l - 0.105_561_345_8 * a - 0.063_854_172_8 * b;
    let s_ = l - 0.089_484_177_5 * a - 1.291_485_548 * b;
    let (l3, m3, s3) = (l_ * l_ * l_, m_ * m_ * m_, s_ * s_ * s_);
    [
        4.076_741_662_1 * l3 - 3.307_711_591_3 * m3 + 0.230_969_929_2 * s3,
        -1.268_438_004_6 * l3 + 2.609_757_401_1 * m3 - 0.341_319_396_5 * s3,
        -0.004_196_086_3 * l3 - 0.703_418_614_7 * m3 + 1.707_614_701 * s3,
    ]
}

fn srgb_encode(c: f64) -> u8 {
    let c = c.clamp(0.0, 1.0);
    let v = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (v * 255.0).round() as u8
}

/// OKLCh to 8-bit sRGB, reducing chroma (keeping lightness and hue) until the
/// colour is inside the sRGB gamut, so lightness stays exactly on its ramp.
fn oklch_to_srgb_in_gamut(l: f64, c: f64, h: f64) -> [u8; 3] {
    let inside = |c: f64| {
        let rgb = oklab_to_linear_srgb(l, c * h.cos(), c * h.sin());
        rgb.iter().all(|&v| (-1e-6..=1.0 + 1e-6).contains(&v))
    };
    let mut c_ok = c;
    if !inside(c) {
        let (mut lo, mut hi) = (0.0, c);
        for _ in 0..30 {
            let mid = 0.5 * (lo + hi);
            if inside(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        c_ok = lo;
    }
    let rgb = oklab_to_linear_srgb(l, c_ok * h.cos(), c_ok * h.sin());
    [
        srgb_encode(rgb[0]),
        srgb_encode(rgb[1]),
        srgb_encode(rgb[2]),
    ]
}

/// OKLab lightness of an sRGB colour (for tests and the legend).
pub fn oklab_lightness(rgb: [u8; 3]) -> f64 {
    let lin = |v: u8| {
        let c = v as f64 / 255.0;
        if c <= 0.040_45 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let (r, g, b) = (lin(rgb[0]), lin(rgb[1]), lin(rgb[2]));
    let l = 0.412_221_470_8 * r + 0.536_332_536_3 * g + 0.051_445_992_9 * b;
    let m = 0.211_903_498_2 * r + 0.680_699_545_1 * g + 0.107_396_956_6 * b;
    let s = 0.088_302_461_9 * r + 0.281_718_837_6 * g + 0.629_978_700_5 * b;
    0.210_454_255_3 * l.cbrt() + 0.793_617_785 * m.cbrt() - 0.004_072_046_8 * s.cbrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palettes_have_monotone_linear_lightness() {
        for &p in Palette::ALL {
            let lut = p.lut();
            let ls: Vec<f64> = lut
                .iter()
                .map(|c| oklab_lightness([c[0], c[1], c[2]]))
                .collect();
            let ([l0, l1], _, _) = p.path();
            for (i, &l) in ls.iter().enumerate() {
                let want = l0 + (l1 - l0) * i as f64 / 255.0;
                // 8-bit quantisation moves lightness by well under 0.01.
                assert!(
                    (l - want).abs() < 0.01,
                    "{p:?} level {i}: L={l} want {want}"
                );
            }
            for w in ls.windows(8).step_by(8) {
                assert!(w[7] > w[0], "{p:?} lightness not increasing");
            }
        }
    }

    #[test]
    fn palette_names_round_trip() {
        for &p in Palette::ALL {
            assert_eq!(Palette::parse(p.name()), Some(p));
        }
        assert_eq!(Palette::parse("jet"), None);
    }

    #[test]
    fn fast_log2_is_accurate() {
        let mut x = 1e-9;
        while x < 1e12 {
            let err = (fast_log2(x) as f64 - x.log2()).abs();
            assert!(err < 0.01, "x={x} err={err}");
            x *= 1.37;
        }
        assert_eq!(fast_log2(0.0), f32::NEG_INFINITY);
    }

    #[test]
    fn linear_scale_maps_zero_and_max() {
        let c = Colorizer::new(Palette::Viridis);
        let vals = [0u32, 5, 10];
        let mut out = vec![0u8; 12];
        let s = c.colorize(
            &vals,
            &mut out,
            Scale::Linear,
            Alpha::Ramp { lo: 40, hi: 220 },
        );
        assert_eq!(s.max, 10.0);
        assert_eq!(s.sum, 15.0);
        assert_eq!(s.nonzero, 2);
        assert_eq!(&out[0..4], &[0, 0, 0, 0], "zero is transparent");
        let top = c.lut()[255];
        assert_eq!(&out[8..11], &top[..3]);
        assert_eq!(out[11], 220);
        assert_eq!(&out[4..7], &c.lut()[127][..3]);
    }

    #[test]
    fn opaque_zero_gets_first_colour() {
        let c = Colorizer::new(Palette::Cividis);
        let mut out = vec![0u8; 8];
        c.colorize(&[0.0f64, 1.0], &mut out, Scale::Linear, Alpha::Opaque);
        assert_eq!(&out[0..4], &c.lut()[0]);
        assert_eq!(&out[4..8], &c.lut()[255]);
    }

    #[test]
    fn log_scale_spreads_small_counts() {
        let c = Colorizer::new(Palette::Ember);
        let vals = [1u32, 10, 100, 1000];
        let mut lin = vec![0u8; 16];
        let mut log = vec![0u8; 16];
        c.colorize(&vals, &mut lin, Scale::Linear, Alpha::Opaque);
        c.colorize(&vals, &mut log, Scale::Log { floor: 1.0 }, Alpha::Opaque);
        let level = |buf: &[u8], i: usize| {
            let px = &buf[4 * i..4 * i + 3];
            c.lut().iter().position(|l| &l[..3] == px).unwrap()
        };
        assert_eq!(level(&lin, 1), 2);
        // ln(11)/ln(1001) ≈ 0.347 → level 88.
        assert!(
            (level(&log, 1) as i32 - 88).abs() <= 2,
            "{}",
            level(&log, 1)
        );
        assert_eq!(level(&log, 3), 255);
    }

    #[test]
    fn stretch_spans_min_to_max() {
        let c = Colorizer::new(Palette::Viridis);
        let mut out = vec![0u8; 16];
        let s = c.colorize(
            &[0u32, 100, 150, 200],
            &mut out,
            Scale::Stretch,
            Alpha::Ramp { lo: 0, hi: 200 },
        );
        assert_eq!(s.min_nonzero, 100.0);
        assert_eq!(&out[0..4], &[0, 0, 0, 0]);
        assert_eq!(out[7], 0, "the minimum is transparent");
        assert_eq!(&out[12..15], &c.lut()[255][..3]);
        assert_eq!(&out[8..11], &c.lut()[127][..3]);
        // A flat field is all level 0 rather than a division by zero.
        let s = c.colorize(&[0u32, 7, 7, 7], &mut out, Scale::Stretch, Alpha::Opaque);
        assert_eq!(s.max, 7.0);
        assert_eq!(&out[4..8], &c.lut()[0]);
    }

    #[test]
    fn all_zero_and_nan_are_safe() {
        let c = Colorizer::new(Palette::Viridis);
        let mut out = vec![7u8; 8];
        let s = c.colorize(
            &[0.0f64, f64::NAN],
            &mut out,
            Scale::Log { floor: 0.0 },
            Alpha::Ramp { lo: 0, hi: 255 },
        );
        assert_eq!(s.max, 0.0);
        assert_eq!(out, vec![0u8; 8]);
        let mut out = vec![0u8; 8];
        c.colorize(
            &[f64::NAN, 2.0],
            &mut out,
            Scale::Log { floor: 0.0 },
            Alpha::Opaque,
        );
        assert_eq!(&out[0..4], &c.lut()[0]);
    }
}
