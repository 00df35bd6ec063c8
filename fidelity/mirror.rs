//! A compiled mirror of the authors' `MCTSgaussian.m` (ekozak7/Trident-2021),
//! written from reading it, that draws GNU Octave's random numbers exactly:
//! with the seeds of `code_trials.m` it gives the same step count, optimum
//! and target as the script under Octave, trial for trial
//! (`tests/suite/fidelity.rs` checks every recorded Octave trial).
//!
//! A module, not a crate: `examples/fidelity.rs` (its `mirror` command) and
//! `tests/suite/fidelity.rs` include it by path.
//!
//! [`Switches`] change one behaviour of the code at a time, to find which
//! one the crate's `paper-code` preset does differently.
//!
//! Nothing here is the authors' code: it is their algorithm, restated.

/// Octave's Mersenne twister (liboctave randmtzig), one state per
/// distribution as Octave keeps them.
pub struct Mt {
    s: [u32; 624],
    i: usize,
}

impl Mt {
    /// `rand("state", seed)` for a scalar seed below 2^32: Octave converts
    /// it to one uint32 and seeds with init_by_array on that key.
    pub fn from_state(seed: f64) -> Mt {
        let key = [(seed % 4294967296.0) as u32];
        let mut mt = Mt {
            s: [0; 624],
            i: 624,
        };
        mt.s[0] = 19650218;
        for j in 1..624 {
            let p = mt.s[j - 1];
            mt.s[j] = 1812433253u32
                .wrapping_mul(p ^ (p >> 30))
                .wrapping_add(j as u32);
        }
        let (mut i, mut j) = (1usize, 0usize);
        for _ in 0..624usize.max(key.len()) {
            let p = mt.s[i - 1];
            mt.s[i] = (mt.s[i] ^ (p ^ (p >> 30)).wrapping_mul(1664525))
                .wrapping_add(key[j])
                .wrapping_add(j as u32);
            i += 1;
            j += 1;
            if i >= 624 {
                mt.s[0] = mt.s[623];
                i = 1;
            }
            if j >= key.len() {
                j = 0;
            }
        }
        for _ in 0..623 {
            let p = mt.s[i - 1];
            mt.s[i] = (mt.s[i] ^ (p ^ (p >> 30)).wrapping_mul(1566083941)).wrapping_sub(i as u32);
            i += 1;
            if i >= 624 {
                mt.s[0] = mt.s[623];
                i = 1;
            }
        }
        mt.s[0] = 0x8000_0000;
        mt
    }

    /// The next 624 words of state.
    #[cold]
    fn twist(&mut self) {
        let mix = |a: u32, b: u32, c: u32| {
            let y = (a & 0x8000_0000) | (b & 0x7fff_ffff);
            c ^ (y >> 1) ^ (0u32.wrapping_sub(y & 1) & 0x9908_b0df)
        };
        for k in 0..227 {
            self.s[k] = mix(self.s[k], self.s[k + 1], self.s[k + 397]);
        }
        for k in 227..623 {
            self.s[k] = mix(self.s[k], self.s[k + 1], self.s[k - 227]);
        }
        self.s[623] = mix(self.s[623], self.s[0], self.s[396]);
        self.i = 0;
    }

    #[inline]
    fn next_u32(&mut self) -> u32 {
        if self.i >= 624 {
            self.twist();
        }
        let mut y = self.s[self.i];
        self.i += 1;
        y ^= y >> 11;
        y ^= (y << 7) & 0x9d2c_5680;
        y ^= (y << 15) & 0xefc6_0000;
        y ^ (y >> 18)
    }

    /// Octave's `rand`: 53 random bits in (0, 1), 0 excluded, as the two
    /// words `(a, b)` of u = (a·2^26 + b) / 2^53.
    #[inline]
    fn randu_words(&mut self) -> (u32, u32) {
        loop {
            let a = self.next_u32() >> 5;
            let b = self.next_u32() >> 6;
            if a != 0 || b != 0 {
                return (a, b);
            }
        }
    }

    /// Octave's `rand`.
    #[inline]
    pub fn randu(&mut self) -> f64 {
        let (a, b) = self.randu_words();
        (a as f64 * 67108864.0 + b as f64) / 9007199254740992.0
    }

    /// 53 bits for the mantissa and one for the sign (Octave's randi54).
    fn randi54(&mut self) -> u64 {
        let lo = self.next_u32() as u64;
        let hi = (self.next_u32() & 0x3F_FFFF) as u64;
        (hi << 32) | lo
    }
}

/// Octave's normal draws: the Marsaglia–Tsang ziggurat of randmtzig.
pub struct Ziggurat {
    ki: [u64; 256],
    wi: [f64; 256],
    fi: [f64; 256],
}

// randmtzig's ZIGGURAT_NOR_R and its inverse, to the digits that name the f64.
const NOR_R: f64 = 3.654_152_885_361_009;
const NOR_INV_R: f64 = 0.273_661_237_329_758_3;
const NOR_AREA: f64 = 0.00492867323399;
const MANTISSA: f64 = 9007199254740992.0;

impl Ziggurat {
    pub fn new() -> Ziggurat {
        let mut z = Ziggurat {
            ki: [0; 256],
            wi: [0.0; 256],
            fi: [0.0; 256],
        };
        let mut x1 = NOR_R;
        z.wi[255] = x1 / MANTISSA;
        z.fi[255] = (-0.5 * x1 * x1).exp();
        z.ki[0] = (x1 * z.fi[255] / NOR_AREA * MANTISSA) as u64;
        z.wi[0] = NOR_AREA / z.fi[255] / MANTISSA;
        z.fi[0] = 1.0;
        for i in (1..255).rev() {
            let x = (-2.0 * (NOR_AREA / x1 + z.fi[i + 1]).ln()).sqrt();
            z.ki[i + 1] = (x / x1 * MANTISSA) as u64;
            z.wi[i] = x / MANTISSA;
            z.fi[i] = (-0.5 * x * x).exp();
            x1 = x;
        }
        z.ki[1] = 0;
        z
    }

    pub fn randn(&self, mt: &mut Mt) -> f64 {
        loop {
            let r = mt.randi54();
            let rabs = (r >> 1) as i64;
            let idx = (rabs & 0xFF) as usize;
            let x = (if r & 1 != 0 { -rabs } else { rabs }) as f64 * self.wi[idx];
            if rabs < self.ki[idx] as i64 {
                return x;
            } else if idx == 0 {
                let (mut xx, mut yy);
                loop {
                    xx = -NOR_INV_R * mt.randu().ln();
                    yy = -mt.randu().ln();
                    if yy + yy > xx * xx {
                        break;
                    }
                }
                return if rabs & 0x100 != 0 {
                    -NOR_R - xx
                } else {
                    NOR_R + xx
                };
            } else if (self.fi[idx - 1] - self.fi[idx]) * mt.randu() + self.fi[idx]
                < (-0.5 * x * x).exp()
            {
                return x;
            }
        }
    }
}

/// The two generators a trial draws from, seeded as `code_trials.m` does.
struct Rngs {
    uni: Mt,
    nor: Mt,
    zig: Ziggurat,
}

impl Rngs {
    /// `randi(2)` as Octave's randi.m computes it from one `rand`:
    /// 1 + floor(floor(u·2^53) / 2^52), and floor(u·2^53) = a·2^26 + b.
    #[inline]
    fn randi2(&mut self) -> i64 {
        let (a, _) = self.uni.randu_words();
        1 + (a >> 26) as i64
    }

    /// `round(normrnd(m, sigma))`: normrnd is `mu + sigma * randn`, one
    /// draw even when sigma is 0. Octave's round is half away from zero.
    fn round_normal(&mut self, m: f64, sigma: f64) -> i64 {
        let z = self.zig.randn(&mut self.nor);
        (m + sigma * z).round() as i64
    }
}

/// What the mirror plays: the code's own behaviour, or one of it changed.
#[derive(Clone, Copy)]
pub struct Switches {
    /// Period of searcher moves and playouts: the code's N+1, or N.
    pub period: i64,
    /// Detect at torus l1 <= 1 (wrapping with `period`) instead of the
    /// code's Euclidean distance without wrap.
    pub torus_detect: bool,
    /// Put the targets' centre at N/2+1 (the crate's centre) instead of N/2.
    pub centre_shift: i64,
    /// The searcher's start cell, the code's (1, 1).
    pub start: (i64, i64),
}

impl Switches {
    /// The code as it is, at side `n`.
    pub fn code(n: i64) -> Switches {
        Switches {
            period: n + 1,
            torus_detect: false,
            centre_shift: 0,
            start: (1, 1),
        }
    }
}

/// One trial as `code_trials.m` records it: the script's `MCTS(t)` =
/// `length(Px)` (moves + 1, 0 when it detects at the start, 10 001 at the
/// move cap), its `optsteps` and the target; all −1 when the script stops
/// with an index error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    pub steps: i64,
    pub mopt: i64,
    pub tx: i64,
    pub ty: i64,
}

impl Row {
    /// Reads the row of a trial from a CSV line of `code_trials.m` or the
    /// mirror: `trial,n,sigma,seed,steps,mopt,tx,ty[,seconds]`. Returns
    /// `(trial, n, sigma, seed state, row)`.
    pub fn parse(line: &str) -> Option<(u64, i64, f64, u64, Row)> {
        let f: Vec<&str> = line.split(',').collect();
        let int = |i: usize| f.get(i)?.parse::<i64>().ok();
        let row = Row {
            steps: int(4)?,
            mopt: int(5)?,
            tx: int(6)?,
            ty: int(7)?,
        };
        Some((
            f[0].parse().ok()?,
            int(1)?,
            f[2].parse().ok()?,
            f[3].parse().ok()?,
            row,
        ))
    }

    /// Moves (`length(Px) − 1`, a capped trial at its 10 000) and excess
    /// moves: moves less the fewest that detect the target from `start` in
    /// the code's world, its (N+1)-torus 0..N with Euclidean detection
    /// that does not wrap. `None` for a trial stopped by an index error.
    pub fn moves_excess(&self, n: i64, start: (i64, i64)) -> Option<(f64, f64)> {
        if self.steps < 0 {
            return None;
        }
        let p = n + 1;
        let d = |a: i64, b: i64| (a - b).rem_euclid(p).min((b - a).rem_euclid(p));
        let fewest = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)]
            .iter()
            .map(|&(dx, dy)| (self.tx + dx, self.ty + dy))
            .filter(|&(x, y)| (0..=n).contains(&x) && (0..=n).contains(&y))
            .map(|(x, y)| d(x, start.0) + d(y, start.1))
            .min()?;
        let moves = (self.steps - 1).max(0);
        Some((moves as f64, (moves - fewest) as f64))
    }
}

/// Trial `i` at side `n` and spread `sigma`, seeded as `code_trials.m`
/// seeds it: `rand('state', s)`, `randn('state', s)`, s = seed·10⁶ + i.
pub fn trial(n: i64, sigma: f64, seed: u64, i: u64, sw: Switches) -> Row {
    let s = (seed * 1_000_000 + i) as f64;
    let mut rngs = Rngs {
        uni: Mt::from_state(s),
        nor: Mt::from_state(s),
        zig: Ziggurat::new(),
    };
    match Trial::new(n, sigma, sw, &mut rngs).run() {
        Ok((steps, mopt, t)) => Row {
            steps: steps as i64,
            mopt,
            tx: t.0,
            ty: t.1,
        },
        Err(IndexError) => Row {
            steps: -1,
            mopt: -1,
            tx: -1,
            ty: -1,
        },
    }
}

fn md(a: i64, m: i64) -> i64 {
    a.rem_euclid(m)
}

/// `mod(a, p)` for `a` in -1..=p, without a division.
#[inline]
fn wrap1(a: i64, p: i64) -> i64 {
    if a < 0 {
        a + p
    } else if a >= p {
        a - p
    } else {
        a
    }
}

/// The code's `mod1`: mod, with 0 mapped to the modulus.
fn mod1(a: i64, m: i64) -> i64 {
    let x = md(a, m);
    if x == 0 {
        m
    } else {
        x
    }
}

struct Trial<'a> {
    n: i64,
    sigma: f64,
    sw: Switches,
    rng: &'a mut Rngs,
    /// Side of the code's statistics arrays, M = N + 1.
    m: usize,
    /// `Nx`, `K` and `Qx`, row x, column y, as the code's (x+1, y+1).
    nx: Vec<f64>,
    kk: Vec<f64>,
    qx: Vec<f64>,
}

/// The code stopped with an index error.
struct IndexError;

impl Trial<'_> {
    fn new(n: i64, sigma: f64, sw: Switches, rng: &mut Rngs) -> Trial<'_> {
        let m = (n + 1) as usize;
        Trial {
            n,
            sigma,
            sw,
            rng,
            m,
            nx: vec![0.0; m * m],
            kk: vec![0.0; m * m],
            qx: vec![0.0; m * m],
        }
    }

    #[inline]
    fn at(&self, c: (i64, i64)) -> usize {
        c.0 as usize * self.m + c.1 as usize
    }

    /// The neighbour of `s` in direction `k` (up, right, down, left).
    #[inline]
    fn step(&self, s: (i64, i64), k: usize) -> (i64, i64) {
        let p = self.sw.period;
        (wrap1(s.0 + DIRS[k].0, p), wrap1(s.1 + DIRS[k].1, p))
    }

    /// `gausstarget(N, sigma)`: x then y, each rounded, wrapped with period
    /// N into 1..N.
    fn target(&mut self) -> (i64, i64) {
        let m = (self.n / 2 + self.sw.centre_shift) as f64;
        let x = mod1(self.rng.round_normal(m, self.sigma), self.n);
        let y = mod1(self.rng.round_normal(m, self.sigma), self.n);
        (x, y)
    }

    /// `dist(...) > rv` with rv = 1: sqrt(d2) > 1 exactly when d2 > 1.
    #[inline]
    fn far(&self, t: (i64, i64), s: (i64, i64)) -> bool {
        let (dx, dy) = (t.0 - s.0, t.1 - s.1);
        if self.sw.torus_detect {
            let p = self.sw.period;
            let wx = md(dx, p).min(md(-dx, p));
            let wy = md(dy, p).min(md(-dy, p));
            wx + wy > 1
        } else {
            dx * dx + dy * dy > 1
        }
    }

    /// `randmovetor`: randi(2) picks the axis (1 = y, 2 = x), then two
    /// `rand` signs are drawn, the y sign first; the move wraps with
    /// period N + 1.
    #[inline]
    fn rand_move(&mut self, s: (i64, i64)) -> (i64, i64) {
        // y = mod(randi(2), 2): 1 (a y move) when randi gives 1; then
        // x = mod(y - 1, 2): 1 exactly when y is 0. Each times its sign.
        let along_y = self.rng.randi2() == 1;
        let yp = if self.rng.uni.randu() - 0.5 > 0.0 {
            1
        } else {
            -1
        };
        let xp = if self.rng.uni.randu() - 0.5 > 0.0 {
            1
        } else {
            -1
        };
        let (x, y) = if along_y { (0, yp) } else { (xp, 0) };
        let p = self.sw.period;
        (wrap1(s.0 + x, p), wrap1(s.1 + y, p))
    }

    /// Runs one trial; returns `(length(Px), optsteps, target)`, or the
    /// index error the code stops with.
    fn run(&mut self) -> Result<(u32, i64, (i64, i64)), IndexError> {
        let limit = 10000u32;
        let t = self.target();
        let mut s = self.sw.start;
        let mut px_len = 1u32;
        let mopt = optsteps(t, s, self.n);
        let mut steps = 0u32;
        while self.far(t, s) {
            if px_len > limit {
                break;
            }
            // Expansion: each neighbour whose Nx is 0 gets one playout.
            for k in 0..4 {
                let ch = self.step(s, k);
                if self.nx[self.at(ch)] == 0.0 {
                    let r = self.at(s);
                    self.nx[r] += 1.0;
                    if k == 3 && s.0 == 0 && self.sw.period == self.n + 1 {
                        // The code's left expansion writes Nx(Sx, Sy+1)
                        // without mod1: index 0, an error in MATLAB/Octave.
                        return Err(IndexError);
                    }
                    let c = self.at(ch);
                    self.nx[c] += 1.0;
                    self.playout(ch, limit);
                }
            }
            for _ in 0..100 {
                let r = self.at(s);
                self.nx[r] += 1.0;
                let ch = self.step(s, self.best(s));
                let c = self.at(ch);
                self.nx[c] += 1.0;
                self.playout(ch, limit);
            }
            s = self.step(s, self.best(s));
            px_len += 1;
            steps = px_len;
        }
        Ok((steps, mopt, t))
    }

    /// One random-walk playout from `ch` toward a fresh practice target.
    fn playout(&mut self, ch: (i64, i64), limit: u32) {
        let pt = self.target();
        let c = self.at(ch);
        let mut s = ch;
        let mut count = 0u32;
        while self.far(pt, s) {
            count += 1;
            if count > limit {
                break;
            }
            s = self.rand_move(s);
            self.kk[c] += 1.0;
            let i = self.at(s);
            self.nx[i] += 1.0;
        }
        // Kx = K/Nx, Qx = 1/Kx (1/0 = Inf, as in MATLAB).
        self.qx[c] = 1.0 / (self.kk[c] / self.nx[c]);
    }

    /// The code's UCT over up, right, down, left (its `mod1` indices into
    /// the (N+1)-arrays name the same cells as the moves), first maximum;
    /// NaN never wins (MATLAB's max).
    fn best(&self, s: (i64, i64)) -> usize {
        let root = self.nx[self.at(s)];
        let mut best = 0usize;
        let mut best_v = f64::NAN;
        for k in 0..4 {
            let i = self.at(self.step(s, k));
            let v = self.qx[i] / self.nx[i] + 2.0 * (root.ln() / self.nx[i]).abs().sqrt();
            if !v.is_nan() && (best_v.is_nan() || v > best_v) {
                best = k;
                best_v = v;
            }
        }
        best
    }
}

/// The four neighbours in the code's order up, right, down, left: (dx, dy).
const DIRS: [(i64, i64); 4] = [(0, 1), (1, 0), (0, -1), (-1, 0)];

/// `optsteps(tx, ty, Sx, Sy, N)`.
fn optsteps(t: (i64, i64), s: (i64, i64), n: i64) -> i64 {
    let dx = (t.0 - s.0).abs();
    let dy = (t.1 - s.1).abs();
    let d = [
        dx + dy,
        (n - t.0 + s.0).abs() + dy,
        dx + (n - t.1 + s.1).abs(),
        (n - t.0 + s.0).abs() + (n - t.1 + s.1).abs(),
    ];
    *d.iter().min().unwrap()
}
