//! The N×N torus: cells, the four moves, distances and detection.
//!
//! Cells are 0-based indices `y * n + x` internally and are shown to users
//! 1-based as `(x + 1, y + 1)`, as in the paper.

use std::fmt;

/// Smallest and largest lattice side.
pub const MIN_N: u32 = 3;
/// Largest lattice side (keeps an episode at N = 1024 under 64 MiB).
pub const MAX_N: u32 = 1024;

/// One of the four unit moves. Screen convention: `Up` decreases `y`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Move {
    Up = 0,
    Right = 1,
    Down = 2,
    Left = 3,
}

impl Move {
    /// All moves, in index order.
    pub const ALL: [Move; 4] = [Move::Up, Move::Right, Move::Down, Move::Left];

    /// The move with index `i & 3`.
    #[inline]
    pub fn from_index(i: u32) -> Move {
        Move::ALL[(i & 3) as usize]
    }

    /// `(dx, dy)` of this move.
    #[inline]
    pub fn delta(self) -> (i32, i32) {
        match self {
            Move::Up => (0, -1),
            Move::Right => (1, 0),
            Move::Down => (0, 1),
            Move::Left => (-1, 0),
        }
    }

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Move::Up => "up",
            Move::Right => "right",
            Move::Down => "down",
            Move::Left => "left",
        }
    }
}

/// A lattice that cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum LatticeError {
    /// N outside `MIN_N..=MAX_N`.
    Size(i64),
    /// A detection radius that is negative or not finite.
    Radius(f64),
    /// A cell outside the lattice (1-based coordinates as given).
    Cell {
        what: &'static str,
        x: i64,
        y: i64,
        n: u32,
    },
}

impl fmt::Display for LatticeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LatticeError::Size(n) => {
                write!(f, "n must be an integer in {MIN_N}..={MAX_N}, got {n}")
            }
            LatticeError::Radius(r) => write!(f, "rv must be a finite number >= 0, got {r}"),
            LatticeError::Cell { what, x, y, n } => {
                write!(
                    f,
                    "{what} ({x},{y}) is outside the lattice: each coordinate must be in 1..={n}"
                )
            }
        }
    }
}

impl std::error::Error for LatticeError {}

/// The periodic N×N lattice with a precomputed neighbour table.
#[derive(Clone, Debug)]
pub struct Torus {
    n: u32,
    /// `nbr[4 * cell + move]` holds `4 * neighbour`: the hot loop indexes this
    /// instead of doing modular arithmetic, and the premultiplied entry keeps
    /// a shift off its dependency chain.
    nbr: Vec<u32>,
}

impl Torus {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.nbr[..])
    }

    /// Builds the torus.
    ///
    /// # Errors
    /// [`LatticeError::Size`] unless `MIN_N <= n <= MAX_N`.
    pub fn new(n: u32) -> Result<Torus, LatticeError> {
        if !(MIN_N..=MAX_N).contains(&n) {
            return Err(LatticeError::Size(n as i64));
        }
        let cells = (n * n) as usize;
        let mut nbr = Vec::with_capacity(4 * cells);
        for y in 0..n {
            for x in 0..n {
                for m in Move::ALL {
                    let (dx, dy) = m.delta();
                    let nx = (x as i64 + dx as i64).rem_euclid(n as i64) as u32;
                    let ny = (y as i64 + dy as i64).rem_euclid(n as i64) as u32;
                    nbr.push(4 * (ny * n + nx));
                }
            }
        }
        Ok(Torus { n, nbr })
    }

    /// Side length N.
    #[inline]
    pub fn n(&self) -> u32 {
        self.n
    }

    /// Number of cells N².
    #[inline]
    pub fn cells(&self) -> usize {
        (self.n * self.n) as usize
    }

    /// The neighbour table: entry `4 * cell + move` is `4 * neighbour`.
    #[inline]
    pub fn neighbours(&self) -> &[u32] {
        &self.nbr
    }

    /// The cell reached from `cell` by `m`.
    #[inline]
    pub fn step(&self, cell: u32, m: Move) -> u32 {
        self.nbr[(cell * 4 + m as u32) as usize] >> 2
    }

    /// The move from `cell` to its neighbour `to` (`None` when `to` is not a
    /// neighbour).
    #[inline]
    pub fn move_to(&self, cell: u32, to: u32) -> Option<Move> {
        Move::ALL.into_iter().find(|&m| self.step(cell, m) == to)
    }

    /// The cell at 0-based `(x, y)`, wrapping any integers onto the torus.
    #[inline]
    pub fn cell(&self, x: i64, y: i64) -> u32 {
        let n = self.n as i64;
        (y.rem_euclid(n) * n + x.rem_euclid(n)) as u32
    }

    /// 0-based `(x, y)` of `cell`.
    #[inline]
    pub fn xy(&self, cell: u32) -> (u32, u32) {
        (cell % self.n, cell / self.n)
    }

    /// The cell at 1-based user coordinates.
    ///
    /// # Errors
    /// [`LatticeError::Cell`] when a coordinate is outside `1..=n`.
    pub fn cell_1based(&self, what: &'static str, x: i64, y: i64) -> Result<u32, LatticeError> {
        let n = self.n as i64;
        if !(1..=n).contains(&x) || !(1..=n).contains(&y) {
            return Err(LatticeError::Cell {
                what,
                x,
                y,
                n: self.n,
            });
        }
        Ok(((y - 1) * n + (x - 1)) as u32)
    }

    /// Signed shortest displacement from `a` to `b` along one axis, in `(-n/2, n/2]`.
    #[inline]
    pub fn axis_delta(&self, a: u32, b: u32) -> i32 {
        let n = self.n as i32;
        let d = (b as i32 - a as i32).rem_euclid(n);
        if 2 * d > n {
            d - n
        } else {
            d
        }
    }

    /// The cell at `(x, y)` with each coordinate in `−n..2n`, and its
    /// coordinates wrapped into `0..n`: one correction each, no division
    /// (for coordinates a unit move or two from the lattice's).
    #[inline]
    pub fn near(&self, x: i32, y: i32) -> (u32, i32, i32) {
        let n = self.n as i32;
        let (x, y) = (wrap_once(n, x), wrap_once(n, y));
        ((y * n + x) as u32, x, y)
    }

    /// `|axis_delta(a, b)|` for coordinates in `0..n`, without a division:
    /// the shorter way round, `min(|a − b|, n − |a − b|)`.
    #[inline]
    pub fn axis_dist(&self, a: u32, b: u32) -> u32 {
        let d = a.abs_diff(b);
        d.min(self.n - d)
    }

    /// Torus displacement `(dx, dy)` from cell `a` to cell `b`.
    #[inline]
    pub fn delta(&self, a: u32, b: u32) -> (i32, i32) {
        let (ax, ay) = self.xy(a);
        let (bx, by) = self.xy(b);
        (self.axis_delta(ax, bx), self.axis_delta(ay, by))
    }

    /// Torus ℓ1 distance: Σ over axes of min(|d|, N − |d|).
    ///
    /// This is the fewest moves from `a` to `b`. The paper's piecewise
    /// formula uses N/2 where N belongs in its middle cases; this one is
    /// checked against breadth-first search in the tests.
    #[inline]
    pub fn l1(&self, a: u32, b: u32) -> u32 {
        let (dx, dy) = self.delta(a, b);
        dx.unsigned_abs() + dy.unsigned_abs()
    }

    /// Squared torus Euclidean distance.
    #[inline]
    pub fn dist2(&self, a: u32, b: u32) -> u64 {
        let (dx, dy) = self.delta(a, b);
        (dx as i64 * dx as i64 + dy as i64 * dy as i64) as u64
    }
}

/// The set of displacements within a detection radius, and a byte mask
/// that marks the cells within the radius of one armed target.
#[derive(Clone, Debug)]
pub struct Sensor {
    r2: u64,
    offsets: Vec<(i32, i32)>,
    /// For each move (by index), the offsets whose cells the disc at the
    /// cell moved from does not hold: all a step can newly cover.
    fronts: [Vec<(i32, i32)>; 4],
    mask: Vec<u8>,
    armed: Option<u32>,
    n: u32,
}

impl Sensor {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.offsets[..])
            + self
                .fronts
                .iter()
                .map(|f| size_of_val(&f[..]))
                .sum::<usize>()
            + size_of_val(&self.mask[..])
    }

    /// Builds the sensor for radius `rv` (Euclidean, on the torus).
    ///
    /// # Errors
    /// [`LatticeError::Radius`] when `rv` is negative or not finite.
    pub fn new(torus: &Torus, rv: f64) -> Result<Sensor, LatticeError> {
        if !rv.is_finite() || rv < 0.0 {
            return Err(LatticeError::Radius(rv));
        }
        let n = torus.n();
        // Detection is d² ≤ rv²; the small slack keeps rv = √2 from losing
        // the diagonal to rounding.
        let r2 = (rv * rv + 1e-9).floor() as u64;
        let reach = ((r2 as f64).sqrt().floor() as i64).min(n as i64);
        let mut seen = vec![false; torus.cells()];
        let mut offsets = Vec::new();
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let c = torus.cell(dx, dy);
                if seen[c as usize] {
                    continue;
                }
                if torus.dist2(0, c) <= r2 {
                    seen[c as usize] = true;
                    offsets.push(torus.delta(0, c));
                }
            }
        }
        // Nearest offsets first makes `optimal_steps` and the arming loop
        // touch the likeliest cells first; order does not affect results.
        offsets.sort_by_key(|&(dx, dy)| (dx * dx + dy * dy, dy, dx));
        // Relative to the cell moved to, the cell moved from is at −(mx, my):
        // an offset is in its disc when o + (mx, my) is within the radius.
        let fronts = Move::ALL.map(|m| {
            let (mx, my) = m.delta();
            offsets
                .iter()
                .copied()
                .filter(|&(dx, dy)| {
                    torus.dist2(0, torus.cell(dx as i64 + mx as i64, dy as i64 + my as i64)) > r2
                })
                .collect()
        });
        Ok(Sensor {
            r2,
            offsets,
            fronts,
            mask: vec![0; torus.cells()],
            armed: None,
            n,
        })
    }

    /// The squared radius as detection compares it (a target at squared
    /// distance d² is detected when d² ≤ this): two sensors with the same
    /// value on one torus are the same sensor.
    pub fn radius2(&self) -> u64 {
        self.r2
    }

    /// Displacements `(dx, dy)` within the radius (each cell once).
    pub fn offsets(&self) -> &[(i32, i32)] {
        &self.offsets
    }

    /// True when `a` detects a target at `b`.
    #[inline]
    pub fn detects(&self, torus: &Torus, a: u32, b: u32) -> bool {
        torus.dist2(a, b) <= self.r2
    }

    /// The most cells one step can newly cover (the largest front).
    pub fn front_len(&self) -> usize {
        self.fronts.iter().map(Vec::len).max().unwrap_or(0)
    }

    /// The largest coordinate offset within the radius (0 when the disc is
    /// the cell alone).
    pub fn reach(&self) -> u32 {
        self.offsets
            .iter()
            .map(|&(dx, dy)| dx.unsigned_abs().max(dy.unsigned_abs()))
            .max()
            .unwrap_or(0)
    }

    /// The largest ℓ1 length of an offset within the radius (0 when the
    /// disc is the cell alone): a cell the disc at `c` holds lies within
    /// this many moves of `c`.
    pub fn reach_l1(&self) -> u32 {
        self.offsets
            .iter()
            .map(|&(dx, dy)| dx.unsigned_abs() + dy.unsigned_abs())
            .max()
            .unwrap_or(0)
    }

    /// The cells within the radius of `cell`, each once.
    pub fn around(&self, cell: u32) -> impl Iterator<Item = u32> + '_ {
        disc(self.n, &self.offsets, cell)
    }

    /// [`Sensor::around`] the cell at `(x, y)`, both in `0..n`: the same
    /// cells in the same order, without dividing to find the coordinates.
    pub fn around_xy(&self, x: i32, y: i32) -> impl Iterator<Item = u32> + '_ {
        disc_xy(self.n, &self.offsets, x, y)
    }

    /// The cells within the radius of `cell` that are not within it of the
    /// cell a move `m` came from: [`Sensor::around`]'s cells in its order,
    /// less those (3 of 5 remain at r_v = 1, moving straight or not).
    pub fn front(&self, m: Move, cell: u32) -> impl Iterator<Item = u32> + '_ {
        disc(self.n, &self.fronts[m as usize], cell)
    }

    /// Marks the cells that detect a target at `target` (disarming the previous one).
    pub fn arm(&mut self, target: u32) {
        if self.armed == Some(target) {
            return;
        }
        self.disarm();
        for c in disc(self.n, &self.offsets, target) {
            self.mask[c as usize] = 1;
        }
        self.armed = Some(target);
    }

    /// Clears the mask.
    pub fn disarm(&mut self) {
        if let Some(t) = self.armed.take() {
            for c in disc(self.n, &self.offsets, t) {
                self.mask[c as usize] = 0;
            }
        }
    }

    /// The detection mask of the armed target (1 = detects).
    #[inline]
    pub fn mask(&self) -> &[u8] {
        &self.mask
    }

    /// True when `cell` detects the armed target.
    #[inline]
    pub fn hit(&self, cell: u32) -> bool {
        self.mask[cell as usize] != 0
    }

    /// Fewest moves from `start` until a target at `target` is detected.
    pub fn optimal_steps(&self, torus: &Torus, start: u32, target: u32) -> u32 {
        self.around(target)
            .map(|c| torus.l1(start, c))
            .min()
            .unwrap_or(0)
    }
}

/// The cells at `offsets` from `cell` on an `n`×`n` torus. A free function
/// so that `arm` can write the mask while it borrows only the offsets.
fn disc(n: u32, offsets: &[(i32, i32)], cell: u32) -> impl Iterator<Item = u32> + '_ {
    disc_xy(n, offsets, (cell % n) as i32, (cell / n) as i32)
}

/// [`disc`] around the cell at `(x, y)`, both in `0..n`.
fn disc_xy(n: u32, offsets: &[(i32, i32)], x: i32, y: i32) -> impl Iterator<Item = u32> + '_ {
    let n = n as i32;
    // Offsets are torus displacements, |d| ≤ n/2, so one correction wraps
    // a coordinate (the belief planners and the belief MCTS sweep discs in
    // their inner loops).
    offsets
        .iter()
        .map(move |&(dx, dy)| (wrap_once(n, y + dy) * n + wrap_once(n, x + dx)) as u32)
}

/// The coordinate `v`, within `n` of `0..n`, wrapped onto `0..n` by one
/// correction: no division, which the scans and disc sweeps that wrap
/// every cell they touch would otherwise pay for.
#[inline]
pub fn wrap_once(n: i32, v: i32) -> i32 {
    debug_assert!((-n..2 * n).contains(&v), "{v} is not within n of 0..{n}");
    if v < 0 {
        v + n
    } else if v >= n {
        v - n
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_is_cell_within_n_of_the_lattice() {
        for n in [3u32, 4, 7] {
            let t = Torus::new(n).unwrap();
            let n = n as i32;
            for y in -n..2 * n {
                for x in -n..2 * n {
                    let (c, wx, wy) = t.near(x, y);
                    assert_eq!(c, t.cell(x as i64, y as i64), "n {n}: ({x},{y})");
                    assert_eq!(t.xy(c), (wx as u32, wy as u32));
                }
            }
        }
    }

    #[test]
    fn axis_dist_is_the_length_of_axis_delta() {
        for n in [1u32, 2, 3, 4, 7, 8, 40] {
            let t = Torus::new(n.max(3)).unwrap();
            let n = t.n();
            for a in 0..n {
                for b in 0..n {
                    assert_eq!(
                        t.axis_dist(a, b),
                        t.axis_delta(a, b).unsigned_abs(),
                        "n {n}: {a} {b}"
                    );
                    // The displacement lies in (−n/2, n/2]: half-way round
                    // an even lattice is +n/2 either way.
                    let d = t.axis_delta(a, b);
                    assert!(-(n as i32) < 2 * d && 2 * d <= n as i32, "n {n}: {a} {b}");
                    assert_eq!((a as i32 + d).rem_euclid(n as i32), b as i32);
                }
            }
        }
    }

    #[test]
    fn rejects_bad_sizes_and_radii() {
        assert_eq!(Torus::new(2).unwrap_err(), LatticeError::Size(2));
        assert!(Torus::new(1025).is_err());
        let t = Torus::new(5).unwrap();
        assert!(Sensor::new(&t, -1.0).is_err());
        assert!(Sensor::new(&t, f64::NAN).is_err());
        assert!(t.cell_1based("start", 0, 1).is_err());
        assert_eq!(t.cell_1based("start", 5, 5).unwrap(), 24);
        // Each error names the value and the allowed range.
        assert_eq!(
            Torus::new(1025).unwrap_err().to_string(),
            "n must be an integer in 3..=1024, got 1025"
        );
        assert_eq!(
            Sensor::new(&t, -1.5).unwrap_err().to_string(),
            "rv must be a finite number >= 0, got -1.5"
        );
        assert_eq!(
            t.cell_1based("start", 0, 1).unwrap_err().to_string(),
            "start (0,1) is outside the lattice: each coordinate must be in 1..=5"
        );
        assert_eq!(
            t.cell_1based("target", 3, 6).unwrap_err(),
            LatticeError::Cell {
                what: "target",
                x: 3,
                y: 6,
                n: 5
            }
        );
    }

    #[test]
    fn moves_have_indices_and_names() {
        // Indices wrap: the planners take index + 2 as the reverse move,
        // which `every_move_wraps_at_every_edge` checks for `Move::ALL`.
        for i in 0..8u32 {
            assert_eq!(
                Move::from_index(i),
                Move::ALL[(i % 4) as usize],
                "index {i}"
            );
        }
        let names = Move::ALL.map(Move::name);
        assert_eq!(names, ["up", "right", "down", "left"]);
    }

    #[test]
    fn moves_wrap() {
        let t = Torus::new(4).unwrap();
        assert_eq!(t.step(0, Move::Left), 3);
        assert_eq!(t.step(0, Move::Up), 12);
        assert_eq!(t.step(15, Move::Right), 12);
        assert_eq!(t.step(15, Move::Down), 3);
    }

    #[test]
    fn radius_one_is_five_cells() {
        let t = Torus::new(10).unwrap();
        assert_eq!(Sensor::new(&t, 0.0).unwrap().offsets().len(), 1);
        assert_eq!(Sensor::new(&t, 1.0).unwrap().offsets().len(), 5);
        assert_eq!(Sensor::new(&t, 2f64.sqrt()).unwrap().offsets().len(), 9);
        // The squared radius detection compares with, √2 not lost to rounding.
        for (rv, r2) in [
            (0.0, 0),
            (1.0, 1),
            (1.5, 2),
            (2f64.sqrt(), 2),
            (2.0, 4),
            (3.7, 13),
        ] {
            assert_eq!(Sensor::new(&t, rv).unwrap().radius2(), r2, "rv {rv}");
        }
        // A radius larger than the torus covers every cell once.
        assert_eq!(
            Sensor::new(&Torus::new(3).unwrap(), 50.0)
                .unwrap()
                .offsets()
                .len(),
            9
        );
    }
}
