//! The Lévy flight: a uniform direction and a power-law length, walked as
//! unit lattice moves along the straight line to the flight's end point.
//!
//! The law is the continuous one: a length L from the truncated Pareto law
//! P(l) ∝ l^−μ on `[1, cap]`, an angle Θ uniform on the circle, and the end
//! point `(round(L cos Θ), round(L sin Θ))`. It is sampled without `pow`,
//! `sin` or `cos` on the common path (they held rollouts to 3–4 × 10⁷ unit
//! moves/s natively and a third of that in wasm):
//! - the length from a table of geometric bins, chosen by an alias table
//!   with each bin's exact probability, then within the bin by rejection
//!   from the uniform law, the density ratio bounded by its Taylor
//!   polynomials (`pow` is called only between the two bounds, about once
//!   in 10⁴ flights): an exact sampler of the same law as the inverse CDF
//!   it replaces;
//! - the angle Θ = 2π·v from 53 random bits, as before; cos Θ and sin Θ
//!   from a table of (cos, sin) at the 256 multiples of 2π/256 (built with
//!   `libm`) rotated by the remainder δ < 2π/256, whose cos and sin are
//!   Taylor polynomials with truncation error below 10⁻¹⁷: within a few
//!   units in the last place of `libm`'s values, so a rounded end point
//!   differs only when L cos Θ lies within ~10⁻¹³ of a half-integer.
//!
//! Only plain IEEE arithmetic runs per flight, so every platform draws the
//! same bits; only the random draws behind a flight differ from the
//! `pow`/`sin`/`cos` sampler.

use super::visit::{Outcome, Visit};
use crate::game::lattice::{Move, Torus};
use crate::game::rng::{self, Rng};
use crate::param::{Param, ParamKind, Value};

/// The Lévy exponent μ, for the Lévy flight and Lévy rollouts.
pub static MU: Param = Param {
    key: "mu",
    label: "Lévy exponent μ",
    kind: ParamKind::Float {
        min: 1.0,
        max: 3.0,
        min_open: true,
    },
    default: Value::Float(2.0),
    help: "Lévy exponent μ: flight lengths follow P(l) ∝ l^−μ",
    aliases: &[],
    choice_labels: &[],
    advanced: false,
};

/// Bins at most this wide relative to their start: the density ratio across
/// a bin is then at least (1 + 1/(16μ))^−μ ≈ 1 − 1/16, so a proposal is
/// rejected about once in 32 and the Taylor bounds almost always decide.
const BIN_REL_WIDTH_MU: f64 = 1.0 / 16.0;
/// At most 2¹¹ bins: the bin index and the alias coin (53 bits) share one
/// 64-bit draw.
const MAX_BIN_BITS: u32 = 11;
/// Slack on the Taylor bounds: a decision within it goes to the exact
/// `pow`, so rounding in the bounds never decides a draw.
const SLACK: f64 = 1e-12;

#[derive(Clone, Copy, Debug, Default)]
struct Bin {
    /// Start of the bin (the density's maximum in it).
    lo: f64,
    /// Width.
    width: f64,
    /// Width ÷ start: a proposal at fraction `w` is `t = w · rel` above the
    /// start, relatively.
    rel: f64,
    /// Keep this bin when the coin (53 bits) is below `keep`, else take `alias`.
    keep: u64,
    alias: u32,
}

/// The truncated Pareto law P(l) ∝ l^−μ on `[1, cap]` as a sampling table.
///
/// Built once per policy (a few hundred bins: 10 KB at μ = 2, cap = 1024;
/// at most 2048 bins, 80 KB); sampling allocates nothing.
#[derive(Clone, Debug)]
pub struct FlightLengths {
    mu: f64,
    bins: Vec<Bin>,
    /// log2 of `bins.len()` (at least 1).
    bits: u32,
}

impl FlightLengths {
    /// The table for exponent `mu` (> 1; the config checks (1, 3]) and
    /// `cap` ≥ 1.
    ///
    /// # Panics
    /// If `mu` ≤ 1 or `cap` < 1 or either is not finite (a caller bug: the
    /// configuration validates both).
    pub fn new(mu: f64, cap: f64) -> FlightLengths {
        assert!(
            mu > 1.0 && mu.is_finite() && cap >= 1.0 && cap.is_finite(),
            "Lévy law needs mu > 1 and cap >= 1, got mu {mu}, cap {cap}"
        );
        let a = mu - 1.0;
        let span = libm::log(cap);
        // Geometric bins from 1 to cap, each at most (1 + 1/(16μ)) × its start.
        let want = libm::ceil(span / libm::log1p(BIN_REL_WIDTH_MU / mu)).max(1.0);
        let used = (want as usize).min(1 << MAX_BIN_BITS);
        let bits = (used.next_power_of_two().trailing_zeros()).max(1);
        let size = 1usize << bits;
        let edge = |i: usize| {
            if i >= used {
                cap
            } else {
                libm::exp(span * i as f64 / used as f64)
            }
        };
        let mut bins = vec![Bin::default(); size];
        // Exact bin masses: ∫ l^−μ over the bin, up to the common factor 1/a.
        let mut mass = vec![0.0f64; size];
        for (i, bin) in bins.iter_mut().enumerate().take(used) {
            let (lo, hi) = (edge(i), edge(i + 1));
            bin.lo = lo;
            bin.width = hi - lo;
            bin.rel = bin.width / lo;
            mass[i] = libm::pow(lo, -a) - libm::pow(hi, -a);
        }
        if cap == 1.0 {
            mass[0] = 1.0;
            bins[0].lo = 1.0;
        }
        for b in &mut bins[used..] {
            // Padding (never chosen): a valid bin so no path reads garbage.
            b.lo = 1.0;
        }
        let (keep, alias) = alias_table(&mass);
        for (b, (k, al)) in bins.iter_mut().zip(keep.into_iter().zip(alias)) {
            b.keep = k;
            b.alias = al;
        }
        FlightLengths { mu, bins, bits }
    }

    /// The exponent μ.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// Bytes of the table.
    pub fn table_bytes(&self) -> usize {
        self.bins.len() * std::mem::size_of::<Bin>()
    }

    /// One length from the law.
    #[inline(always)]
    pub fn sample(&self, rng: &mut Rng) -> f64 {
        let r = rng::bits(rng);
        // `bins.len()` is 2^bits: the masks keep both indices in range
        // without a bounds check.
        let mask = self.bins.len() - 1;
        let slot = &self.bins[(r >> (64 - self.bits)) as usize & mask];
        let coin = (r << self.bits) >> 11;
        let i = if coin < slot.keep {
            (r >> (64 - self.bits)) as usize
        } else {
            slot.alias as usize
        };
        let b = &self.bins[i & mask];
        let (lo, width, rel) = (b.lo, b.width, b.rel);
        loop {
            let w = rng::unit_f64(rng);
            let u = rng::unit_f64(rng);
            // Accept l = lo (1 + t) with probability (1 + t)^−μ, the density
            // relative to its maximum in the bin. For t ≥ 0,
            // 1 − μt ≤ (1 + t)^−μ ≤ 1 − μt + μ(μ+1)t²/2 (convexity; the
            // third derivative is negative).
            let t = w * rel;
            let lower = 1.0 - self.mu * t;
            if u < lower - SLACK {
                return lo + w * width;
            }
            if self.slow_accept(u, t, lower) {
                return lo + w * width;
            }
        }
    }

    /// The rare decisions the lower bound leaves open: reject above the
    /// upper bound, else compare with the exact ratio.
    #[cold]
    #[inline(never)]
    fn slow_accept(&self, u: f64, t: f64, lower: f64) -> bool {
        let upper = lower + 0.5 * self.mu * (self.mu + 1.0) * t * t;
        u < upper + SLACK && u < libm::pow(1.0 + t, -self.mu)
    }
}

/// Vose's alias table for weights `w` (not all zero): for slot `i`, keep it
/// when a 53-bit coin is below `keep[i]`, else take `alias[i]`. Plain f64
/// arithmetic in a fixed order, so every platform builds the same table.
fn alias_table(w: &[f64]) -> (Vec<u64>, Vec<u32>) {
    let k = w.len();
    let total: f64 = w.iter().sum();
    let mut scaled: Vec<f64> = w.iter().map(|&x| x * k as f64 / total).collect();
    let mut keep = vec![1u64 << 53; k];
    let mut alias: Vec<u32> = (0..k as u32).collect();
    let (mut small, mut large): (Vec<usize>, Vec<usize>) = (0..k).partition(|&i| scaled[i] < 1.0);
    while let (Some(s), Some(&l)) = (small.pop(), large.last()) {
        keep[s] = libm::round(scaled[s] * (1u64 << 53) as f64) as u64;
        alias[s] = l as u32;
        scaled[l] -= 1.0 - scaled[s];
        if scaled[l] < 1.0 {
            large.pop();
            small.push(l);
        }
    }
    // What is left has weight 1 up to rounding: it keeps itself.
    (keep, alias)
}

/// log2 of the number of table angles.
const ANGLE_BITS: u32 = 8;

/// cos and sin of Θ = 2π·v for a 53-bit uniform `v`, from a table of the
/// 2⁸ angles 2πj/2⁸ and the Taylor polynomials of the remainder.
#[derive(Clone, Debug)]
pub struct Directions {
    /// (cos, sin) of 2πj/2⁸.
    table: Vec<(f64, f64)>,
}

impl Default for Directions {
    fn default() -> Directions {
        Directions::new()
    }
}

impl Directions {
    /// Builds the table (with `libm`, so every platform has the same bits).
    pub fn new() -> Directions {
        let step = 2.0 * core::f64::consts::PI / (1u32 << ANGLE_BITS) as f64;
        Directions {
            table: (0..1u32 << ANGLE_BITS)
                .map(|j| (libm::cos(step * j as f64), libm::sin(step * j as f64)))
                .collect(),
        }
    }

    /// (cos Θ, sin Θ) for Θ = 2π·v / 2⁵³, `v` < 2⁵³.
    #[inline(always)]
    pub fn cos_sin(&self, v: u64) -> (f64, f64) {
        let (c0, s0) = self.table[(v >> (53 - ANGLE_BITS)) as usize & ((1 << ANGLE_BITS) - 1)];
        let rem = v & ((1u64 << (53 - ANGLE_BITS)) - 1);
        // δ < 2π/2⁸ ≈ 0.0245: the next terms, δ⁸/8! and δ⁹/9!, are below
        // 4 × 10⁻¹⁸ and 1 × 10⁻²⁰.
        let d = rem as f64 * (2.0 * core::f64::consts::PI / (1u64 << 53) as f64);
        let d2 = d * d;
        let cd = 1.0 - d2 * (1.0 / 2.0 - d2 * (1.0 / 24.0 - d2 * (1.0 / 720.0)));
        let sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0 - d2 * (1.0 / 5040.0))));
        (c0 * cd - s0 * sd, s0 * cd + c0 * sd)
    }

    /// Bytes of the table.
    pub fn table_bytes(&self) -> usize {
        self.table.len() * std::mem::size_of::<(f64, f64)>()
    }
}

/// Draws the end point of a flight: length from `lengths`, angle uniform,
/// both coordinates rounded half away from zero.
#[inline(always)]
pub fn flight_end(lengths: &FlightLengths, dirs: &Directions, rng: &mut Rng) -> (i64, i64) {
    let (c, s) = dirs.cos_sin(rng::bits(rng) >> 11);
    let l = lengths.sample(rng);
    (round_half_away(l * c), round_half_away(l * s))
}

/// `libm::round(v) as i64` for |v| < 2⁶², without the call or the
/// saturating conversion: the same sum and truncation `libm::round` does.
#[inline(always)]
fn round_half_away(v: f64) -> i64 {
    debug_assert!(v.abs() < (1u64 << 62) as f64);
    // SAFETY: |v| + 0.5 < 2⁶³, so the truncation is in range.
    unsafe { (v + (0.5 - 0.25 * f64::EPSILON).copysign(v)).to_int_unchecked::<i64>() }
}

/// A flight in progress, walked as a 4-connected digital line.
///
/// The next move is along x when `err ≤ 0`, where
/// `err = (2·done_x + 1)·|dy| − (2·done_y + 1)·|dx|`: the axis whose next
/// half-step lies earlier on the line, exact in integers. At the ends of
/// either axis the sign of `err` already forces the other one.
#[derive(Clone, Copy, Debug, Default)]
struct Flight {
    /// Move index along x and along y.
    mx: u32,
    my: u32,
    err: i64,
    /// 2|dy| (added after an x move) and 2|dx| (subtracted after a y move).
    inc_x: i64,
    dec_y: i64,
    /// Unit moves left.
    left: u32,
}

impl Flight {
    fn to(dx: i64, dy: i64) -> Flight {
        let (ax, ay) = (dx.abs(), dy.abs());
        Flight {
            mx: if dx >= 0 { Move::Right } else { Move::Left } as u32,
            my: if dy >= 0 { Move::Down } else { Move::Up } as u32,
            err: ay - ax,
            inc_x: 2 * ay,
            dec_y: 2 * ax,
            left: (ax + ay) as u32,
        }
    }

    /// The next move's index, advancing the line.
    #[inline(always)]
    fn step(&mut self) -> u32 {
        let x = self.err <= 0;
        self.err += if x { self.inc_x } else { -self.dec_y };
        self.left -= 1;
        if x {
            self.mx
        } else {
            self.my
        }
    }
}

/// A Lévy flight walker.
///
/// Lengths are capped at N (one lattice side): a longer straight flight
/// only re-crosses the torus, and the cap keeps one flight's cost bounded.
/// Steps count unit moves; the caller checks detection after every move, so
/// a flight stops at detection.
#[derive(Clone, Debug)]
pub struct Levy {
    lengths: FlightLengths,
    dirs: Directions,
    flight: Flight,
    /// The flight after this one, drawn when this one starts (none while
    /// `next.left == 0`). Flights are independent of the walk, so drawing
    /// one early changes no law; it lets the processor compute it while the
    /// current flight is walked, instead of after a mispredicted loop exit.
    next: Flight,
}

impl Levy {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.lengths.bins[..]) + std::mem::size_of_val(&self.dirs.table[..])
    }

    /// A walker with exponent `mu` in (1, 3] on a lattice of side `n`.
    ///
    /// # Panics
    /// If `mu` ≤ 1 or is not finite (the configuration checks (1, 3]).
    pub fn new(mu: f64, n: u32) -> Levy {
        Levy {
            lengths: FlightLengths::new(mu, n as f64),
            dirs: Directions::new(),
            flight: Flight::default(),
            next: Flight::default(),
        }
    }

    /// The length law's table.
    pub fn lengths(&self) -> &FlightLengths {
        &self.lengths
    }

    /// Bytes of the walker's tables (lengths and directions).
    pub fn table_bytes(&self) -> usize {
        self.lengths.table_bytes() + self.dirs.table_bytes()
    }

    /// Drops any flight in progress (the next walk starts with a new
    /// flight: the one drawn ahead, which no walk has used).
    pub fn begin(&mut self) {
        self.flight.left = 0;
    }

    #[inline(always)]
    fn new_flight(&self, rng: &mut Rng) -> Flight {
        // l ≥ 1, so the end point is never (0, 0) and a flight has a move.
        let (dx, dy) = flight_end(&self.lengths, &self.dirs, rng);
        Flight::to(dx, dy)
    }

    /// Starts the next flight and draws the one after it.
    #[inline(always)]
    fn start_flight(&mut self, rng: &mut Rng) -> Flight {
        let f = if self.next.left > 0 {
            self.next
        } else {
            self.new_flight(rng)
        };
        self.next = self.new_flight(rng);
        f
    }

    /// The next unit move of the current flight (starting a new one when done).
    pub fn next_move(&mut self, rng: &mut Rng) -> Move {
        if self.flight.left == 0 {
            self.flight = self.start_flight(rng);
        }
        Move::from_index(self.flight.step())
    }

    /// Walks from `start` until `mask` marks the cell or `cap` moves,
    /// continuing the flight in progress: the same moves as [`Levy::next_move`]
    /// called `cap` times.
    ///
    /// The hot loop: the neighbour table (entries 4 × a cell), the digital
    /// line's error term, one byte load for detection, no allocation.
    ///
    /// # Panics
    /// If `mask` is shorter than the lattice.
    #[inline]
    pub fn rollout<V: Visit>(
        &mut self,
        torus: &Torus,
        mask: &[u8],
        rng: &mut Rng,
        start: u32,
        cap: u32,
        visit: &mut V,
    ) -> Outcome {
        let nbr = torus.neighbours();
        assert!(mask.len() >= torus.cells() && (start as usize) < torus.cells());
        if mask[start as usize] != 0 {
            return Outcome {
                steps: 0,
                detected: true,
            };
        }
        let mut p = 4 * start as usize;
        let mut steps = 0u32;
        let mut f = self.flight;
        while steps < cap {
            if f.left == 0 {
                f = self.start_flight(rng);
            }
            let first = steps;
            let end = steps + f.left.min(cap - steps);
            let (mut err, inc_x, dec_y, mx, my) = (f.err, f.inc_x, f.dec_y, f.mx, f.my);
            while steps != end {
                // `Flight::step` without the count of moves left, which
                // is settled once the loop ends.
                let x = err <= 0;
                err += if x { inc_x } else { -dec_y };
                let m = (if x { mx } else { my }) as usize;
                // SAFETY: `p / 4` starts in range and every table entry is
                // 4 × a cell index < cells() ≤ mask.len() (asserted above), so
                // `p + m < 4 * cells() = nbr.len()` (m < 4) and `p >> 2 < mask.len()`.
                unsafe {
                    p = *nbr.get_unchecked(p + (m & 3)) as usize;
                    core::hint::assert_unchecked(p % 4 == 0);
                    steps += 1;
                    visit.visit((p >> 2) as u32, steps);
                    if *mask.get_unchecked(p >> 2) != 0 {
                        f.err = err;
                        f.left -= steps - first;
                        self.flight = f;
                        return Outcome {
                            steps,
                            detected: true,
                        };
                    }
                }
            }
            f.err = err;
            f.left -= steps - first;
        }
        self.flight = f;
        Outcome {
            steps: cap,
            detected: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_half_away_from_zero_like_libm() {
        for v in [
            0.0,
            0.4999999999999999,
            0.5,
            1.5,
            2.5,
            -0.5,
            -2.5,
            -2.4999999999999996,
            7.3,
            -7.7,
            1023.5,
            -1024.49,
        ] {
            assert_eq!(round_half_away(v), libm::round(v) as i64, "{v}");
        }
    }

    #[test]
    fn table_directions_match_libm() {
        // Within a few ulps of libm's cos and sin everywhere, including
        // next to the table's angles; a sign error in the rotation, a wrong
        // table index or a missing term of cos δ would be off by
        // 3 × 10⁻¹³ or more.
        let d = Directions::new();
        let mut r = rng::stream(9, 0);
        let mut worst = 0.0f64;
        for k in 0..200_000u64 {
            let v = if k < 1024 {
                (k << 43).wrapping_sub(k & 1) & ((1 << 53) - 1)
            } else {
                rng::bits(&mut r) >> 11
            };
            let th = 2.0 * core::f64::consts::PI * (v as f64 / (1u64 << 53) as f64);
            let (c, s) = d.cos_sin(v);
            worst = worst
                .max((c - libm::cos(th)).abs())
                .max((s - libm::sin(th)).abs());
        }
        assert!(worst < 1.5e-15, "worst error {worst:e}");
    }

    #[test]
    fn alias_table_reproduces_its_weights() {
        // The mass each slot receives (kept share plus aliased shares) equals
        // its weight to f64 precision; a table that dropped the last
        // redistribution step would be off by whole percents.
        let w = [0.5, 0.1, 0.0, 0.25, 0.15, 0.0, 0.0, 0.0];
        let (keep, alias) = alias_table(&w);
        let mut got = [0.0f64; 8];
        for i in 0..8 {
            let k = keep[i] as f64 / (1u64 << 53) as f64;
            got[i] += k / 8.0;
            got[alias[i] as usize] += (1.0 - k) / 8.0;
        }
        for i in 0..8 {
            assert!((got[i] - w[i]).abs() < 1e-12, "{got:?}");
        }
    }

    #[test]
    fn the_rollout_makes_the_moves_next_move_makes() {
        let t = Torus::new(9).unwrap();
        let mask = vec![0u8; t.cells()];
        let mut a = Levy::new(1.6, 9);
        let mut b = a.clone();
        let (mut ra, mut rb) = (rng::stream(3, 0), rng::stream(3, 0));
        let mut path = Vec::new();
        a.rollout(&t, &mask, &mut ra, 10, 500, &mut path);
        let mut cell = 10;
        for (i, &c) in path.iter().enumerate() {
            cell = t.step(cell, b.next_move(&mut rb));
            assert_eq!(c, cell, "move {i}");
        }
        assert_eq!(rng::bits(&mut ra), rng::bits(&mut rb));
    }

    #[test]
    fn flights_walk_a_digital_line_to_their_end() {
        // Every flight reaches (dx, dy) in |dx| + |dy| moves, each along the
        // axis whose next half-step comes first (checked against the
        // rational comparison the error term replaces).
        for (dx, dy) in [(5i64, 2i64), (-3, 7), (0, -4), (6, 0), (-2, -2), (1, -9)] {
            let mut f = Flight::to(dx, dy);
            let (ax, ay) = (dx.abs(), dy.abs());
            let (mut done_x, mut done_y) = (0i64, 0i64);
            while f.left > 0 {
                let want_x =
                    done_y >= ay || (done_x < ax && (2 * done_x + 1) * ay <= (2 * done_y + 1) * ax);
                let m = f.step();
                if want_x {
                    done_x += 1;
                    assert_eq!(m, if dx >= 0 { 1 } else { 3 });
                } else {
                    done_y += 1;
                    assert_eq!(m, if dy >= 0 { 2 } else { 0 });
                }
            }
            assert_eq!((done_x, done_y), (ax, ay));
        }
    }
}
