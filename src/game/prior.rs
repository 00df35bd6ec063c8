//! Target priors: each samples a target and reports its exact mass over all N² cells.

use crate::game::lattice::Torus;
use crate::game::named::named_enum;
use crate::game::rng::{self, Rng};
use std::fmt;

named_enum! {
    /// The prior a configuration names (its `prior` parameter).
    pub enum PriorKind {
        /// The paper's rounded, wrapped Gaussian (`sigma`; 0 is a delta at
        /// the centre, inf is uniform).
        Gaussian = "gaussian",
        /// All mass on the paper's centre cell.
        Delta = "delta",
        /// Every cell equally likely.
        Uniform = "uniform",
        /// A painted grid of weights 0–15 (`paint`).
        Paint = "paint",
        /// The authors' `gausstarget` on the lattice their code plays on
        /// (`sigma`): run with n = N + 1 to reproduce `MCTSgaussian.m` at
        /// side N ([`PriorSpec::Code`]).
        Code = "code",
    }
}

/// Which prior, before it is built on a lattice.
#[derive(Clone, Debug, PartialEq)]
pub enum PriorSpec {
    /// All mass on one cell; `None` means the paper's centre `(N/2+1, N/2+1)`.
    Delta { cell: Option<u32> },
    /// The paper's rounded, wrapped Gaussian with standard deviation `sigma`.
    Gaussian { sigma: f64 },
    /// Every cell equally likely (σ = ∞).
    Uniform,
    /// A user-supplied non-negative weight per cell, `y * n + x`.
    Weights { weights: Vec<f64> },
    /// The authors' `gausstarget(N, σ)` with N = n − 1: x, y = round(N/2 +
    /// σZ) wrapped with period N into 1..N. Their `MCTSgaussian.m` moves on
    /// an (N+1)-torus with coordinates 0..N and starts at (1, 1); shifted by
    /// one cell, that is this n-torus with the 1-based start (1, 1) and
    /// these targets at 1-based (x, y), never in the last row or column.
    Code { sigma: f64 },
}

/// A prior that cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum PriorError {
    /// σ negative or NaN.
    Sigma(f64),
    /// A weight grid of the wrong length.
    WeightsLen { got: usize, want: usize },
    /// A negative or non-finite weight.
    Weight { index: usize, value: f64 },
    /// All weights zero.
    WeightsZero,
    /// A delta cell outside the lattice.
    Cell(u32),
}

impl fmt::Display for PriorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PriorError::Sigma(s) => write!(
                f,
                "sigma must be a number >= 0 (or inf for uniform), got {s}"
            ),
            PriorError::WeightsLen { got, want } => {
                write!(f, "prior weights must have n*n = {want} entries, got {got}")
            }
            PriorError::Weight { index, value } => {
                write!(
                    f,
                    "prior weight {index} must be a finite number >= 0, got {value}"
                )
            }
            PriorError::WeightsZero => write!(f, "prior weights must not all be zero"),
            PriorError::Cell(c) => write!(f, "delta prior cell index {c} is outside the lattice"),
        }
    }
}

impl std::error::Error for PriorError {}

/// Beyond this many lattice widths the wrapped Gaussian differs from uniform
/// by less than exp(−2π²·8²) per cell, far below f64 resolution, and drawing
/// a raw normal would lose integer precision for huge σ.
const UNIFORM_SIGMA_WIDTHS: f64 = 8.0;

#[derive(Clone, Debug)]
enum Sampler {
    Delta(u32),
    Gaussian {
        mu: f64,
        sigma: f64,
    },
    /// [`PriorSpec::Code`]: each coordinate wraps with `period` = n − 1.
    Code {
        mu: f64,
        sigma: f64,
        period: f64,
    },
    Alias(Alias),
}

/// A prior built on a lattice.
#[derive(Clone, Debug)]
pub struct TargetPrior {
    n: u32,
    mass: Vec<f64>,
    sampler: Sampler,
}

impl TargetPrior {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.mass[..])
            + match &self.sampler {
                Sampler::Alias(a) => a.heap_bytes(),
                _ => 0,
            }
    }

    /// Builds `spec` on `torus`.
    ///
    /// # Errors
    /// A [`PriorError`] naming the bad value.
    pub fn new(torus: &Torus, spec: &PriorSpec) -> Result<TargetPrior, PriorError> {
        let n = torus.n();
        let cells = torus.cells();
        let centre = (n / 2) * n + n / 2;
        let (mass, sampler) = match spec {
            PriorSpec::Delta { cell } => {
                let c = cell.unwrap_or(centre);
                if c as usize >= cells {
                    return Err(PriorError::Cell(c));
                }
                (delta_mass(cells, c), Sampler::Delta(c))
            }
            PriorSpec::Gaussian { sigma } => {
                let s = *sigma;
                if s.is_nan() || s < 0.0 {
                    return Err(PriorError::Sigma(s));
                }
                if s == 0.0 {
                    (delta_mass(cells, centre), Sampler::Delta(centre))
                } else if s >= UNIFORM_SIGMA_WIDTHS * n as f64 {
                    let m = vec![1.0 / cells as f64; cells];
                    let a = Alias::new(&m);
                    (m, Sampler::Alias(a))
                } else {
                    let mu = n as f64 / 2.0;
                    let axis = wrapped_rounded_normal(n, mu, s);
                    let mut m = Vec::with_capacity(cells);
                    for y in 0..n as usize {
                        for x in 0..n as usize {
                            m.push(axis[x] * axis[y]);
                        }
                    }
                    (m, Sampler::Gaussian { mu, sigma: s })
                }
            }
            PriorSpec::Code { sigma } => code_prior(n, *sigma)?,
            PriorSpec::Uniform => {
                let m = vec![1.0 / cells as f64; cells];
                let a = Alias::new(&m);
                (m, Sampler::Alias(a))
            }
            PriorSpec::Weights { weights } => {
                if weights.len() != cells {
                    return Err(PriorError::WeightsLen {
                        got: weights.len(),
                        want: cells,
                    });
                }
                if let Some((index, &value)) = weights
                    .iter()
                    .enumerate()
                    .find(|(_, w)| !w.is_finite() || **w < 0.0)
                {
                    return Err(PriorError::Weight { index, value });
                }
                let total: f64 = weights.iter().sum();
                if total <= 0.0 {
                    return Err(PriorError::WeightsZero);
                }
                let m: Vec<f64> = weights.iter().map(|w| w / total).collect();
                let a = Alias::new(&m);
                (m, Sampler::Alias(a))
            }
        };
        Ok(TargetPrior { n, mass, sampler })
    }

    /// Probability of each cell, `y * n + x`; sums to 1.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    /// The single cell of a delta prior.
    pub fn delta_cell(&self) -> Option<u32> {
        match self.sampler {
            Sampler::Delta(c) => Some(c),
            _ => None,
        }
    }

    /// Draws a target cell.
    pub fn sample(&self, rng: &mut Rng) -> u32 {
        match &self.sampler {
            Sampler::Delta(c) => *c,
            Sampler::Gaussian { mu, sigma } => {
                // The paper: x, y ~ N(N/2, σ), rounded to the nearest lattice
                // point and wrapped; the +1 shift is the 1-based display.
                let n = self.n as f64;
                let x = libm::round(mu + sigma * rng::standard_normal(rng)).rem_euclid(n) as u32;
                let y = libm::round(mu + sigma * rng::standard_normal(rng)).rem_euclid(n) as u32;
                y * self.n + x
            }
            Sampler::Code { mu, sigma, period } => {
                // gausstarget's mod(round(.), N) with 0 taken as N gives
                // 1..N; one cell down, 0-based, that is 0..N-1. σ = ∞ is
                // its uniform limit.
                let axis = |rng: &mut Rng| {
                    if sigma.is_infinite() {
                        return rng::below(rng, *period as u32);
                    }
                    let k = libm::round(mu + sigma * rng::standard_normal(rng)).rem_euclid(*period);
                    (if k == 0.0 { *period } else { k }) as u32 - 1
                };
                let x = axis(rng);
                let y = axis(rng);
                y * self.n + x
            }
            Sampler::Alias(a) => a.sample(rng),
        }
    }
}

/// The mass and sampler of [`PriorSpec::Code`] on the n-torus.
fn code_prior(n: u32, sigma: f64) -> Result<(Vec<f64>, Sampler), PriorError> {
    if sigma.is_nan() || sigma < 0.0 {
        return Err(PriorError::Sigma(sigma));
    }
    let period = n - 1;
    let mu = period as f64 / 2.0;
    // Mass of 0-based coordinate k: the code's coordinate k + 1, i.e. the
    // class (k + 1) mod N of round(N/2 + σZ); the last one (n − 1) is never
    // drawn.
    let mut axis = vec![0.0; n as usize];
    let uniform = sigma >= UNIFORM_SIGMA_WIDTHS * period as f64;
    let mut centre = 0;
    if sigma == 0.0 {
        let k = libm::round(mu).rem_euclid(period as f64) as u32;
        centre = (if k == 0 { period } else { k }) - 1;
        axis[centre as usize] = 1.0;
    } else if uniform {
        axis[..period as usize].fill(1.0 / period as f64);
    } else {
        let w = wrapped_rounded_normal(period, mu, sigma);
        for (k, a) in axis[..period as usize].iter_mut().enumerate() {
            *a = w[(k + 1) % period as usize];
        }
    }
    let mut m = Vec::with_capacity((n * n) as usize);
    for y in 0..n as usize {
        for x in 0..n as usize {
            m.push(axis[x] * axis[y]);
        }
    }
    let sampler = if sigma == 0.0 {
        Sampler::Delta(centre * n + centre)
    } else {
        Sampler::Code {
            mu,
            sigma: if uniform { f64::INFINITY } else { sigma },
            period: period as f64,
        }
    };
    Ok((m, sampler))
}

fn delta_mass(cells: usize, c: u32) -> Vec<f64> {
    let mut m = vec![0.0; cells];
    m[c as usize] = 1.0;
    m
}

/// Standard normal upper tail Q(z) = P(Z > z), accurate in both tails.
fn upper_tail(z: f64) -> f64 {
    0.5 * libm::erfc(z / std::f64::consts::SQRT_2)
}

/// P(round(X) ≡ k mod n) for X ~ N(mu, sigma), each k in 0..n.
fn wrapped_rounded_normal(n: u32, mu: f64, sigma: f64) -> Vec<f64> {
    let nf = n as f64;
    // Mass beyond 40σ is below 1e-300.
    let span = 40.0 * sigma;
    let lo_m = libm::floor((mu - span) / nf) as i64 - 1;
    let hi_m = libm::ceil((mu + span) / nf) as i64 + 1;
    let mut p = vec![0.0; n as usize];
    for (k, pk) in p.iter_mut().enumerate() {
        let mut s = 0.0;
        for m in lo_m..=hi_m {
            let a = (k as f64 + m as f64 * nf - 0.5 - mu) / sigma;
            let b = (k as f64 + m as f64 * nf + 0.5 - mu) / sigma;
            // P(a < Z ≤ b), computed on the side where it does not cancel.
            s += if a >= 0.0 {
                upper_tail(a) - upper_tail(b)
            } else if b <= 0.0 {
                upper_tail(-b) - upper_tail(-a)
            } else {
                1.0 - upper_tail(b) - upper_tail(-a)
            };
        }
        *pk = s;
    }
    let total: f64 = p.iter().sum();
    for v in &mut p {
        *v /= total;
    }
    p
}

/// The largest weight level of a painted prior.
pub const PAINT_MAX_LEVEL: u8 = 15;

const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";

/// Encodes painted levels (0–15 per cell) as URL-safe text: runs of equal
/// levels, each as three base64url digits holding 4 bits of level and 12
/// bits of (run length − 1), so a run covers at most 4096 cells.
///
/// Levels above 15 are clamped to 15.
pub fn encode_paint(levels: &[u8]) -> String {
    let mut out = String::with_capacity(3 * (levels.len() / 64 + 1));
    let mut i = 0;
    while i < levels.len() {
        let lv = levels[i].min(PAINT_MAX_LEVEL);
        let mut run = 1;
        while i + run < levels.len() && levels[i + run].min(PAINT_MAX_LEVEL) == lv && run < 4096 {
            run += 1;
        }
        let word = (lv as usize) << 12 | (run - 1);
        for shift in [12, 6, 0] {
            out.push(B64[(word >> shift) & 63] as char);
        }
        i += run;
    }
    out
}

/// A painted prior that cannot be decoded.
#[derive(Clone, Debug, PartialEq)]
pub enum PaintError {
    /// A character outside base64url, or a length that is not a multiple of 3.
    Syntax,
    /// The runs do not cover exactly `n * n` cells.
    Size { got: usize, want: usize },
    /// Every level is 0: no cell could hold the target.
    Empty,
}

impl fmt::Display for PaintError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PaintError::Syntax => write!(
                f,
                "paint is not run-length encoded levels (base64url, 3 characters a run)"
            ),
            PaintError::Size { got, want } => {
                write!(f, "paint covers {got} cells, not n*n = {want}")
            }
            PaintError::Empty => write!(f, "paint has no cell above level 0"),
        }
    }
}

impl std::error::Error for PaintError {}

/// Decodes [`encode_paint`] text into `n * n` levels.
///
/// # Errors
/// A [`PaintError`] when the text is malformed, covers another number of
/// cells, or paints nothing.
pub fn decode_paint(text: &str, n: u32) -> Result<Vec<u8>, PaintError> {
    let want = n as usize * n as usize;
    let bytes = text.as_bytes();
    if bytes.len() % 3 != 0 {
        return Err(PaintError::Syntax);
    }
    let digit = |b: u8| B64.iter().position(|&d| d == b).ok_or(PaintError::Syntax);
    let mut levels = Vec::with_capacity(want);
    for run in bytes.chunks_exact(3) {
        let word = digit(run[0])? << 12 | digit(run[1])? << 6 | digit(run[2])?;
        let lv = (word >> 12) as u8;
        let len = (word & 4095) + 1;
        if lv > PAINT_MAX_LEVEL {
            return Err(PaintError::Syntax);
        }
        if levels.len() + len > want {
            return Err(PaintError::Size {
                got: levels.len() + len,
                want,
            });
        }
        levels.resize(levels.len() + len, lv);
    }
    if levels.len() != want {
        return Err(PaintError::Size {
            got: levels.len(),
            want,
        });
    }
    if levels.iter().all(|&l| l == 0) {
        return Err(PaintError::Empty);
    }
    Ok(levels)
}

/// Rescales painted levels from an `from`×`from` grid to `to`×`to`
/// (nearest cell), for when the lattice side changes under a painting.
pub fn resize_paint(levels: &[u8], from: u32, to: u32) -> Vec<u8> {
    let (from, to) = (from as usize, to as usize);
    let mut out = Vec::with_capacity(to * to);
    for y in 0..to {
        for x in 0..to {
            out.push(levels[(y * from / to) * from + x * from / to]);
        }
    }
    out
}

/// Walker/Vose alias table: O(1) sampling from a fixed discrete distribution.
#[derive(Clone, Debug)]
pub struct Alias {
    prob: Vec<f64>,
    alias: Vec<u32>,
}

impl Alias {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.prob[..]) + std::mem::size_of_val(&self.alias[..])
    }

    /// Builds the table for weights `w` (non-negative, positive sum).
    pub fn new(w: &[f64]) -> Alias {
        let len = w.len();
        let total: f64 = w.iter().sum();
        let mut prob: Vec<f64> = w.iter().map(|x| x * len as f64 / total).collect();
        let mut alias: Vec<u32> = (0..len as u32).collect();
        let mut small = Vec::new();
        let mut large = Vec::new();
        for (i, &p) in prob.iter().enumerate() {
            if p < 1.0 {
                small.push(i as u32);
            } else {
                large.push(i as u32);
            }
        }
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            alias[s as usize] = l;
            prob[l as usize] = (prob[l as usize] + prob[s as usize]) - 1.0;
            if prob[l as usize] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // Leftovers are 1 up to rounding.
        for i in small.into_iter().chain(large) {
            prob[i as usize] = 1.0;
        }
        Alias { prob, alias }
    }

    /// Draws an index.
    #[inline]
    pub fn sample(&self, rng: &mut Rng) -> u32 {
        let i = rng::below(rng, self.prob.len() as u32);
        if rng::unit_f64(rng) < self.prob[i as usize] {
            i
        } else {
            self.alias[i as usize]
        }
    }
}

/// Asserts that `counts` of draws follow the probabilities `p`: a cell of
/// probability 0 is never drawn, and every other count lies within `z`
/// binomial standard errors of its expectation.
#[cfg(test)]
pub(crate) fn assert_draws_follow(counts: &[u32], p: &[f64], z: f64) {
    assert_eq!(counts.len(), p.len());
    let draws = counts.iter().map(|&c| c as f64).sum::<f64>();
    for (i, (&c, &p)) in counts.iter().zip(p).enumerate() {
        if p == 0.0 {
            assert_eq!(c, 0, "index {i} has probability 0 but was drawn");
        } else {
            let (want, se) = (draws * p, (draws * p * (1.0 - p)).sqrt());
            let got = c as f64;
            assert!(
                (got - want).abs() <= z * se,
                "index {i}: {got} draws against {want} ± {se}"
            );
        }
    }
}

#[cfg(test)]
#[path = "prior_code_tests.rs"]
mod code_tests;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delta_centre_matches_paper_for_even_n() {
        let t = Torus::new(40).unwrap();
        let p = TargetPrior::new(&t, &PriorSpec::Gaussian { sigma: 0.0 }).unwrap();
        // (N/2+1, N/2+1) 1-based is (20, 20) 0-based.
        assert_eq!(p.delta_cell(), Some(20 * 40 + 20));
        // All the mass is on that cell, and every draw lands there.
        for spec in [
            PriorSpec::Gaussian { sigma: 0.0 },
            PriorSpec::Delta { cell: None },
            PriorSpec::Delta { cell: Some(7) },
        ] {
            let p = TargetPrior::new(&t, &spec).unwrap();
            let c = p.delta_cell().unwrap();
            assert_eq!(p.mass().len(), 1600, "{spec:?}");
            for (i, &m) in p.mass().iter().enumerate() {
                assert_eq!(m, if i == c as usize { 1.0 } else { 0.0 }, "{spec:?}");
            }
            let mut r = rng::stream(3, 0);
            assert!((0..100).all(|_| p.sample(&mut r) == c), "{spec:?}");
        }
    }

    #[test]
    fn gaussian_tails_keep_their_relative_accuracy() {
        // Each axis cell's mass is a difference of two normal tails, taken
        // on the side where it does not cancel. So the mass is symmetric
        // about the mode to rounding even 19 cells (7.6σ) out, where it is
        // below 1e-13 and a difference of the near-1 complements would be
        // off by 1e-3 of itself; and it keeps falling there.
        let (n, sigma) = (40, 2.5);
        let axis = wrapped_rounded_normal(n, n as f64 / 2.0, sigma);
        let mode = (n / 2) as usize;
        for d in 1..mode {
            let (hi, lo) = (axis[mode + d], axis[mode - d]);
            assert!(
                (hi / lo - 1.0).abs() < 1e-9,
                "cells {} and {}: {hi:e} against {lo:e}",
                mode + d,
                mode - d
            );
            assert!(hi < axis[mode + d - 1], "not falling at {}", mode + d);
        }
        // Against the tail itself: P(18.5 < X − μ ≤ 19.5) plus the wrapped
        // P(−21.5 < X − μ ≤ −20.5).
        let want = upper_tail(18.5 / sigma) - upper_tail(19.5 / sigma) + upper_tail(20.5 / sigma)
            - upper_tail(21.5 / sigma);
        let far = axis[mode + 19];
        assert!((far / want - 1.0).abs() < 1e-9, "{far:e} against {want:e}");
    }

    #[test]
    fn gaussian_mass_sums_to_one_and_converges_to_uniform() {
        let t = Torus::new(20).unwrap();
        for s in [0.3, 2.0, 5.0, 20.0, 100.0, 1e9, f64::INFINITY] {
            let p = TargetPrior::new(&t, &PriorSpec::Gaussian { sigma: s }).unwrap();
            let total: f64 = p.mass().iter().sum();
            assert!((total - 1.0).abs() < 1e-12, "sigma {s}: {total}");
            if s >= 40.0 {
                let u = 1.0 / 400.0;
                assert!(p.mass().iter().all(|m| (m - u).abs() < 1e-12), "sigma {s}");
            }
        }
    }

    #[test]
    fn paint_round_trips_and_rejects_bad_text() {
        let n = 37;
        let levels: Vec<u8> = (0..n * n)
            .map(|i| {
                if (i * 7919) % 97 < 20 {
                    (i % 15) as u8 + 1
                } else {
                    0
                }
            })
            .collect();
        let s = encode_paint(&levels);
        assert!(s
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_'));
        assert_eq!(decode_paint(&s, n).unwrap(), levels);
        assert!(matches!(
            decode_paint(&s, n + 1),
            Err(PaintError::Size { .. })
        ));
        assert_eq!(decode_paint(&format!("{s}A"), n), Err(PaintError::Syntax));
        assert_eq!(decode_paint("A*A", 3), Err(PaintError::Syntax));
        assert_eq!(
            decode_paint(&encode_paint(&[0; 9]), 3),
            Err(PaintError::Empty)
        );
        // Runs longer than 4096 cells split.
        let mut big = vec![0u8; 1024 * 1024];
        big[5] = 3;
        assert_eq!(decode_paint(&encode_paint(&big), 1024).unwrap(), big);
        // The exact text: a run is one 16-bit word, level << 12 | (length
        // − 1), as three base64url digits, and equal neighbours share a run.
        assert_eq!(encode_paint(&[0; 9]), "AAI");
        assert_eq!(encode_paint(&[0, 0, 1, 1, 17, 0]), "AABBABPAAAAA");
        assert_eq!(encode_paint(&vec![2; 4097]), "C__CAA");
        assert_eq!(
            decode_paint("AABBABPAAAAA", 3).unwrap_err(),
            PaintError::Size { got: 6, want: 9 }
        );
        // The run that overshoots is counted in the error.
        assert_eq!(
            decode_paint("AABBABAAB", 2).unwrap_err(),
            PaintError::Size { got: 6, want: 4 }
        );
        assert_eq!(
            PaintError::Size { got: 6, want: 4 }.to_string(),
            "paint covers 6 cells, not n*n = 4"
        );
        assert_eq!(
            PaintError::Syntax.to_string(),
            "paint is not run-length encoded levels (base64url, 3 characters a run)"
        );
        assert_eq!(
            PaintError::Empty.to_string(),
            "paint has no cell above level 0"
        );
        // Halving a grid keeps its corners.
        let mut g = vec![0u8; 16];
        g[0] = 9;
        assert_eq!(resize_paint(&g, 4, 2), vec![9, 0, 0, 0]);
        assert_eq!(resize_paint(&[1, 2, 3, 4], 2, 4)[15], 4);
    }

    #[test]
    fn alias_table_draws_unnormalised_weights_in_proportion() {
        // Weights need not sum to 1, and zero weights are never drawn. A
        // table built as if they summed to 1 draws weights 1 and 3 equally
        // often.
        let w = [0.0, 1.0, 3.0, 0.0, 4.0];
        let table = Alias::new(&w);
        let mut counts = [0u32; 5];
        let mut r = rng::stream(11, 0);
        for _ in 0..80_000 {
            counts[table.sample(&mut r) as usize] += 1;
        }
        let p = w.map(|wi| wi / 8.0);
        assert_draws_follow(&counts, &p, 4.5);
    }

    #[test]
    fn rejects_bad_specs() {
        // Each error names the bad value, as the library's users see it.
        let t = Torus::new(4).unwrap();
        let message = |spec: PriorSpec| TargetPrior::new(&t, &spec).unwrap_err().to_string();
        assert_eq!(
            message(PriorSpec::Gaussian { sigma: -1.0 }),
            "sigma must be a number >= 0 (or inf for uniform), got -1"
        );
        assert!(message(PriorSpec::Gaussian { sigma: f64::NAN }).ends_with("got NaN"));
        assert_eq!(
            message(PriorSpec::Weights {
                weights: vec![1.0; 3]
            }),
            "prior weights must have n*n = 16 entries, got 3"
        );
        assert_eq!(
            message(PriorSpec::Weights {
                weights: vec![0.0; 16]
            }),
            "prior weights must not all be zero"
        );
        let mut w = vec![1.0; 16];
        w[3] = f64::INFINITY;
        assert_eq!(
            message(PriorSpec::Weights { weights: w }),
            "prior weight 3 must be a finite number >= 0, got inf"
        );
        assert_eq!(
            message(PriorSpec::Delta { cell: Some(16) }),
            "delta prior cell index 16 is outside the lattice"
        );
        // The last valid delta cell is accepted.
        assert!(TargetPrior::new(&t, &PriorSpec::Delta { cell: Some(15) }).is_ok());
    }
}
