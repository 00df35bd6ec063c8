//! The Lévy flight: a uniform direction and a power-law length, walked as
//! unit lattice moves along the straight line to the flight's end point.

use super::{Policy, SearcherInfo, Walker};
use crate::lattice::Move;
use crate::rng::{self, Rng};

/// The Lévy flight as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "levy",
    label: "Lévy flight",
    help: "it flies a power-law distributed length (exponent mu) in a uniformly random direction, walked as unit moves",
    deliberates: false,
    uses: |_, key| key == "mu",
    build: |s| Box::new(Walker::new(Policy::Levy(Levy::new(s.cfg.mu, s.torus.n())), s.start)),
};

/// Draws a flight length from P(l) ∝ l^−μ on `[1, cap]` (inverse CDF of
/// the truncated Pareto law).
pub fn flight_length(rng: &mut Rng, mu: f64, cap: f64) -> f64 {
    let u = rng::unit_f64(rng);
    let a = mu - 1.0;
    let tail = libm::pow(cap, -a);
    libm::pow(1.0 - u * (1.0 - tail), -1.0 / a)
}

#[derive(Clone, Copy, Debug)]
struct Flight {
    sx: Move,
    sy: Move,
    ax: u32,
    ay: u32,
    done_x: u32,
    done_y: u32,
}

/// A Lévy flight walker.
///
/// Lengths are capped at N (one lattice side): a longer straight flight
/// only re-crosses the torus, and the cap keeps one flight's cost bounded.
/// Steps count unit moves; the caller checks detection after every move, so
/// a flight stops at detection.
#[derive(Clone, Debug)]
pub struct Levy {
    mu: f64,
    cap: f64,
    flight: Option<Flight>,
}

impl Levy {
    /// A walker with exponent `mu` in (1, 3] on a lattice of side `n`.
    pub fn new(mu: f64, n: u32) -> Levy {
        Levy {
            mu,
            cap: n as f64,
            flight: None,
        }
    }

    /// Drops any flight in progress.
    pub fn begin(&mut self) {
        self.flight = None;
    }

    fn new_flight(&mut self, rng: &mut Rng) -> Flight {
        let l = flight_length(rng, self.mu, self.cap);
        let theta = 2.0 * std::f64::consts::PI * rng::unit_f64(rng);
        // l ≥ 1 so the rounded end point is never (0, 0).
        let dx = libm::round(l * libm::cos(theta)) as i64;
        let dy = libm::round(l * libm::sin(theta)) as i64;
        Flight {
            sx: if dx >= 0 { Move::Right } else { Move::Left },
            sy: if dy >= 0 { Move::Down } else { Move::Up },
            ax: dx.unsigned_abs() as u32,
            ay: dy.unsigned_abs() as u32,
            done_x: 0,
            done_y: 0,
        }
    }

    /// The next unit move of the current flight (starting a new one when done).
    pub fn next_move(&mut self, rng: &mut Rng) -> Move {
        let mut f = match self.flight {
            Some(f) if f.done_x + f.done_y < f.ax + f.ay => f,
            _ => self.new_flight(rng),
        };
        // Step along the axis whose next half-step lies earlier on the line
        // (a 4-connected digital line, exact in integers).
        let x_first = f.done_y >= f.ay
            || (f.done_x < f.ax
                && (2 * f.done_x as u64 + 1) * f.ay as u64
                    <= (2 * f.done_y as u64 + 1) * f.ax as u64);
        let m = if x_first {
            f.done_x += 1;
            f.sx
        } else {
            f.done_y += 1;
            f.sy
        };
        self.flight = Some(f);
        m
    }
}
