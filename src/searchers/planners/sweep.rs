//! The fixed sweep: a lawnmower (boustrophedon) or helix over the whole
//! torus from the start cell, ignoring the prior: the deterministic anchor
//! the belief planners are measured against.
//!
//! # Rule
//! With a sensor reaching `r` cells along an axis (r = 1 at r_v = 1) a
//! straight pass covers a stripe `s = 2r + 1` rows high and newly covers
//! `s` cells per move (3 at r_v = 1, the most any move can). Stripes are
//! centred `s` rows apart below the start (the last one moved up so that it
//! ends at the torus' last row instead of wrapping onto the first stripe).
//! Each pass makes `N − 1` moves along its row, visiting every column (off
//! its centre row a disc reaches other columns only partly); then the sweep
//! steps down to the next stripe.
//! `lawnmower` passes alternately right and left, `helix` always right
//! (drifting around the torus). Once the sweep is done the pattern starts
//! again from where it stands (only reached when the prior put mass
//! nowhere the sweep looked, which a full sweep rules out).

use crate::game::lattice::{Move, Sensor, Torus};
use crate::game::named::named_enum;
use crate::param::{Param, ParamKind, Value};
use crate::searchers::info::{Reads, SearcherInfo};
use crate::searchers::searcher::{Searcher, World};
use std::borrow::Cow;

named_enum! {
    /// The sweep's pattern.
    pub enum SweepPattern {
        /// Boustrophedon: passes alternately right and left.
        Lawnmower = "lawnmower",
        /// Every pass to the right, around the torus.
        Helix = "helix",
    }
}

/// The sweep's pattern.
pub static SWEEP_PATTERN: Param = Param {
    key: "sweep_pattern",
    label: "Sweep pattern",
    kind: ParamKind::Choice(|| SweepPattern::NAMES.to_vec()),
    default: Value::Name(Cow::Borrowed("lawnmower")),
    help:
        "the sweep's pattern: lawnmower (passes alternately right and left) or helix (always right)",
    aliases: &[],
    choice_labels: &["lawnmower", "helix"],
    advanced: false,
};

/// The sweep as a searcher.
pub static INFO: SearcherInfo = SearcherInfo {
    name: "sweep",
    label: "Sweep",
    help: "a fixed lawnmower or helix over the whole torus from the start, ignoring the prior",
    deterministic: true,
    deliberates: false,
    params: &[Reads::always(&SWEEP_PATTERN)],
    build: |s| {
        Box::new(Sweep::new(
            s.torus,
            s.sensor,
            s.start,
            s.settings.choice(&SWEEP_PATTERN),
        ))
    },
};

/// How far the sensor reaches along an axis.
pub fn axis_reach(sensor: &Sensor) -> i64 {
    sensor
        .offsets()
        .iter()
        .filter(|&&(dx, _)| dx == 0)
        .map(|&(_, dy)| dy.unsigned_abs() as i64)
        .max()
        .unwrap_or(0)
}

/// Writes the sweep's cells from `start` (excluded) into `out`.
pub fn sweep_path(
    torus: &Torus,
    sensor: &Sensor,
    start: u32,
    pattern: SweepPattern,
    out: &mut Vec<u32>,
) {
    let n = torus.n() as i64;
    let r = axis_reach(sensor).min(n);
    let s = 2 * r + 1;
    let stripes = ((n + s - 1) / s).max(1);
    let last_centre = (n - 1 - 2 * r).max(0);
    let centre = |k: i64| (k * s).min(last_centre);
    // Every column is visited: off the centre row a disc reaches a row
    // only in the columns near its centre (at r_v = 1 only its own).
    let moves = n - 1;
    let (x0, y0) = torus.xy(start);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (mut x, mut y) = (0i64, 0i64);
    for k in 0..stripes {
        let dir = match pattern {
            SweepPattern::Helix => 1,
            SweepPattern::Lawnmower if k % 2 == 0 => 1,
            SweepPattern::Lawnmower => -1,
        };
        for _ in 0..moves {
            x += dir;
            out.push(torus.cell(x0 + x, y0 + y));
        }
        if k + 1 < stripes {
            while y < centre(k + 1) {
                y += 1;
                out.push(torus.cell(x0 + x, y0 + y));
            }
        }
    }
}

/// The sweep searcher: follows its precomputed path.
pub struct Sweep {
    pattern: SweepPattern,
    path: Vec<u32>,
    next: usize,
    intent_len: usize,
}

impl Sweep {
    /// The sweep of `pattern` from `start`.
    pub fn new(torus: &Torus, sensor: &Sensor, start: u32, pattern: SweepPattern) -> Sweep {
        let mut path = Vec::new();
        sweep_path(torus, sensor, start, pattern, &mut path);
        Sweep {
            pattern,
            path,
            next: 0,
            intent_len: 2 * torus.n() as usize,
        }
    }
}

impl Searcher for Sweep {
    fn think(&mut self, w: &mut World<'_>, _max_loops: u32) -> Option<Move> {
        if self.next >= self.path.len() {
            // Done: sweep again from here (allocation only here, once per
            // full sweep).
            self.path.clear();
            self.next = 0;
            sweep_path(w.torus, w.sensor, w.pos, self.pattern, &mut self.path);
        }
        let to = self.path.get(self.next).copied().unwrap_or(w.pos);
        Some(w.torus.move_to(w.pos, to).unwrap_or(Move::Right))
    }

    fn observe(&mut self, _torus: &Torus, _m: Move, pos: u32) {
        // Off the sweep (a branch's shared prefix made another move):
        // sweep again from here.
        self.next = match self.path.get(self.next) {
            Some(&c) if c == pos => self.next + 1,
            _ => self.path.len(),
        };
    }

    fn intent(&self) -> &[u32] {
        let from = self.next.min(self.path.len());
        let to = (from + self.intent_len).min(self.path.len());
        &self.path[from..to]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sweep_covers_the_torus_with_unit_moves_and_ends_when_it_has() {
        for n in [3, 4, 5, 7, 10, 40] {
            for rv in [0.0, 1.0, 1.5, 2.0] {
                for pattern in SweepPattern::ALL {
                    let torus = Torus::new(n).unwrap();
                    let sensor = Sensor::new(&torus, rv).unwrap();
                    let start = torus.cell(2, 1);
                    let mut path = Vec::new();
                    sweep_path(&torus, &sensor, start, *pattern, &mut path);
                    let mut seen = vec![false; torus.cells()];
                    let mut p = start;
                    for c in sensor.around(start) {
                        seen[c as usize] = true;
                    }
                    let mut full_at = None;
                    for (i, &q) in path.iter().enumerate() {
                        assert_eq!(torus.l1(p, q), 1, "n={n} rv={rv} {pattern}");
                        p = q;
                        for c in sensor.around(q) {
                            seen[c as usize] = true;
                        }
                        if full_at.is_none() && seen.iter().all(|&s| s) {
                            full_at = Some(i);
                        }
                    }
                    assert!(seen.iter().all(|&s| s), "n={n} rv={rv} {pattern}");
                    // It ends once the torus is covered: at its last cell,
                    // or at r_v = 1.5, whose disc reaches one cell
                    // diagonally, two cells before (N = 3's discs cover
                    // most of the torus from the start).
                    if n > 3 {
                        let (at, len) = (full_at.unwrap(), path.len());
                        let spare = if rv == 1.5 { 2 } else { 0 };
                        assert_eq!(at + 1 + spare, len, "n={n} rv={rv} {pattern}");
                    }
                }
            }
        }
    }
}
