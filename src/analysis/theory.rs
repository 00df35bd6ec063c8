//! Exact random-walk hitting times on the torus, to check simulations against.

use crate::game::lattice::{Sensor, Torus};

/// Kemeny's constant of the simple random walk on the N×N torus:
/// Σ over nonzero modes (a, b) of 1 / (1 − (cos 2πa/N + cos 2πb/N)/2).
///
/// On a vertex-transitive graph it is the mean hitting time of a uniformly
/// placed target (exact hit, r_v = 0) from any start, counting 0 steps when
/// the target is the start.
pub fn kemeny(n: u32) -> f64 {
    let mut s = 0.0;
    let w = 2.0 * std::f64::consts::PI / n as f64;
    for a in 0..n {
        for b in 0..n {
            if a == 0 && b == 0 {
                continue;
            }
            s += 1.0 / (1.0 - (libm::cos(w * a as f64) + libm::cos(w * b as f64)) / 2.0);
        }
    }
    s
}

/// Mean random-walk steps from every cell until a cell within `sensor`'s
/// radius of `target` is entered, by solving the linear system
/// h = 0 on the detection set, h = 1 + mean of neighbours elsewhere.
///
/// Dense Gaussian elimination: meant for small lattices (N ≤ 16).
pub fn rw_hitting_times(torus: &Torus, sensor: &Sensor, target: u32) -> Vec<f64> {
    let cells = torus.cells();
    let det: Vec<bool> = (0..cells as u32)
        .map(|c| sensor.detects(torus, c, target))
        .collect();
    let idx: Vec<Option<usize>> = {
        let mut k = 0;
        det.iter()
            .map(|&d| {
                if d {
                    None
                } else {
                    k += 1;
                    Some(k - 1)
                }
            })
            .collect()
    };
    let m = det.iter().filter(|&&d| !d).count();
    let mut a = vec![0.0f64; m * (m + 1)];
    let w = m + 1;
    for c in 0..cells {
        let Some(i) = idx[c] else { continue };
        a[i * w + i] += 1.0;
        a[i * w + m] = 1.0;
        for mv in crate::game::lattice::Move::ALL {
            let nb = torus.step(c as u32, mv) as usize;
            if let Some(j) = idx[nb] {
                a[i * w + j] -= 0.25;
            }
        }
    }
    // Partial pivoting; the matrix is diagonally dominant, so this is stable.
    for col in 0..m {
        let piv = (col..m)
            .max_by(|&x, &y| a[x * w + col].abs().total_cmp(&a[y * w + col].abs()))
            .unwrap_or(col);
        if piv != col {
            for k in 0..w {
                a.swap(col * w + k, piv * w + k);
            }
        }
        let p = a[col * w + col];
        for row in 0..m {
            if row != col {
                let f = a[row * w + col] / p;
                if f != 0.0 {
                    for k in col..w {
                        a[row * w + k] -= f * a[col * w + k];
                    }
                }
            }
        }
    }
    (0..cells)
        .map(|c| idx[c].map_or(0.0, |i| a[i * w + m] / a[i * w + i]))
        .collect()
}

/// The law of `min(T, cap)` for the simple random walk from `start`, `T`
/// the first step at which a cell within `sensor`'s radius of `target` is
/// entered (0 when the start detects it): entry `t` is `P(min(T, cap) = t)`
/// for `t` in `0..=cap`, so the last entry is `P(T ≥ cap)`, the capped mass.
/// Exact up to rounding, by pushing the walk's undetected mass one step at
/// a time (O(cap · N²)).
pub fn rw_hitting_law(
    torus: &Torus,
    sensor: &Sensor,
    start: u32,
    target: u32,
    cap: u32,
) -> Vec<f64> {
    let cells = torus.cells();
    let det: Vec<bool> = (0..cells as u32)
        .map(|c| sensor.detects(torus, c, target))
        .collect();
    let mut law = vec![0.0; cap as usize + 1];
    if det[start as usize] {
        law[0] = 1.0;
        return law;
    }
    let mut mass = vec![0.0f64; cells];
    mass[start as usize] = 1.0;
    let mut next = vec![0.0f64; cells];
    for p in law.iter_mut().take(cap as usize).skip(1) {
        next.iter_mut().for_each(|m| *m = 0.0);
        let mut hit = 0.0;
        for (c, &m) in mass.iter().enumerate() {
            if m == 0.0 {
                continue;
            }
            for mv in crate::game::lattice::Move::ALL {
                let nb = torus.step(c as u32, mv) as usize;
                if det[nb] {
                    hit += m / 4.0;
                } else {
                    next[nb] += m / 4.0;
                }
            }
        }
        std::mem::swap(&mut mass, &mut next);
        *p = hit;
    }
    // Undetected after cap − 1 steps: the trial reaches the cap.
    law[cap as usize] = mass.iter().sum();
    law
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_system_agrees_with_kemeny_on_average() {
        // Averaging the hitting time from a fixed start over all targets is Kemeny's constant.
        let t = Torus::new(6).unwrap();
        let s = Sensor::new(&t, 0.0).unwrap();
        let mean: f64 = (0..36)
            .map(|tg| rw_hitting_times(&t, &s, tg)[0])
            .sum::<f64>()
            / 36.0;
        assert!((mean - kemeny(6)).abs() < 1e-9, "{mean} vs {}", kemeny(6));
    }
}
