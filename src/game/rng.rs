//! Portable random streams: a seed replays identically on every platform.
//!
//! `rand::rngs::SmallRng` is a different generator on 32-bit targets, so the
//! crate names Xoshiro256++ explicitly and draws integers and floats with
//! its own width-independent helpers (never `usize` ranges).

use rand::{Rng as _, SeedableRng};
pub use rand_xoshiro::Xoshiro256PlusPlus as Rng;

/// SplitMix64 finaliser: a bijective mix that decorrelates nearby inputs.
#[inline]
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The generator for stream `stream` of run `seed`.
///
/// Trial `i` of a batch uses streams `2i` (the world: its target) and
/// `2i + 1` (the searcher), so results do not depend on how
/// trials are spread over threads.
pub fn stream(seed: u64, stream: u64) -> Rng {
    let s = splitmix64(seed ^ splitmix64(stream.wrapping_mul(0xD1B5_4A32_D192_ED03)));
    Rng::seed_from_u64(s)
}

/// A uniform integer in `0..n` (Lemire's method with rejection; exact).
///
/// # Panics
/// Never for `n >= 1`; `n == 0` is a caller bug and returns 0.
#[inline]
pub fn below(rng: &mut Rng, n: u32) -> u32 {
    if n <= 1 {
        return 0;
    }
    let mut m = (rng.next_u32() as u64) * (n as u64);
    let mut low = m as u32;
    if low < n {
        let threshold = n.wrapping_neg() % n;
        while low < threshold {
            m = (rng.next_u32() as u64) * (n as u64);
            low = m as u32;
        }
    }
    (m >> 32) as u32
}

/// A uniform float in `[0, 1)` with 53 random bits.
#[inline]
pub fn unit_f64(rng: &mut Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// True with probability `p` (clamped to `[0, 1]`).
#[inline]
pub fn chance(rng: &mut Rng, p: f64) -> bool {
    unit_f64(rng) < p
}

/// A standard normal deviate (Marsaglia's polar method with `libm`, so the
/// bits are the same on every platform).
pub fn standard_normal(rng: &mut Rng) -> f64 {
    loop {
        let u = 2.0 * unit_f64(rng) - 1.0;
        let v = 2.0 * unit_f64(rng) - 1.0;
        let s = u * u + v * v;
        if s > 0.0 && s < 1.0 {
            return u * libm::sqrt(-2.0 * libm::log(s) / s);
        }
    }
}

/// 64 raw random bits.
#[inline]
pub fn bits(rng: &mut Rng) -> u64 {
    rng.next_u64()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_differ_and_replay() {
        let a: Vec<u64> = (0..4).map(|_| bits(&mut stream(1, 0))).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        assert_ne!(bits(&mut stream(1, 0)), bits(&mut stream(1, 1)));
        assert_ne!(bits(&mut stream(1, 0)), bits(&mut stream(2, 0)));
    }

    #[test]
    fn below_is_in_range_and_roughly_uniform() {
        let mut r = stream(7, 0);
        let mut counts = [0u32; 6];
        for _ in 0..60_000 {
            counts[below(&mut r, 6) as usize] += 1;
        }
        // Each count is Binomial(60000, 1/6): sd ≈ 91; allow 5 sd.
        for c in counts {
            assert!((c as i64 - 10_000).abs() < 460, "{counts:?}");
        }
    }
}
