//! What the searcher knows about the target: the prior it plans with, the
//! cells it has searched, and the practice targets MCTS draws from that.

use crate::game::lattice::Sensor;
use crate::game::named::named_enum;
use crate::game::prior::{Alias, TargetPrior};
use crate::game::rng::Rng;

named_enum! {
    /// Where practice targets come from.
    pub enum Belief {
        /// The prior, as in the paper.
        Prior = "prior",
        /// The prior with every searched cell set to zero, renormalised.
        Posterior = "posterior",
    }
}

/// The prior, the searched cells and the posterior of one trial.
#[derive(Clone, Debug)]
pub struct BeliefState {
    kind: Belief,
    /// The true target's prior.
    prior: TargetPrior,
    /// The planning prior when it differs from `prior` (a known target);
    /// sharing otherwise keeps an N = 1024 episode from holding two copies.
    plan: Option<TargetPrior>,
    /// 1 for each cell within r_v of a position occupied so far.
    searched: Vec<u8>,
    /// Planning mass not yet searched, summed with compensation: a running
    /// difference from 1 keeps rounding dust of about 10⁻¹⁶, which near
    /// the end of a search outweighs the mass truly left.
    remaining: crate::game::sum::Sum,
    /// Unsearched cells with planning mass: at 0 no mass is left, exactly.
    cells_left: u32,
    /// Counts changes to `searched`, so a drawing of it can be reused.
    generation: u64,
    /// Scratch for the posterior alias table (not a view: see `posterior_into`).
    posterior: Vec<f64>,
    alias: Option<Alias>,
}

/// Writes the planning mass with searched cells zeroed, renormalised, into
/// `out`. When the prior's support is exhausted (the planner was wrong
/// about the target) it falls back to uniform over the unsearched cells.
fn posterior_into(mass: &[f64], searched: &[u8], out: &mut Vec<f64>) {
    out.clear();
    out.extend(
        mass.iter()
            .zip(searched)
            .map(|(&m, &s)| if s == 0 { m } else { 0.0 }),
    );
    let total: f64 = out.iter().sum();
    if total > 0.0 {
        out.iter_mut().for_each(|p| *p /= total);
    } else {
        let free = searched.iter().filter(|&&s| s == 0).count().max(1) as f64;
        for (p, &s) in out.iter_mut().zip(searched) {
            *p = if s == 0 { 1.0 / free } else { 0.0 };
        }
    }
}

impl BeliefState {
    /// Heap bytes held (what a copy allocates).
    pub fn heap_bytes(&self) -> usize {
        self.prior.heap_bytes()
            + self.plan.as_ref().map_or(0, TargetPrior::heap_bytes)
            + std::mem::size_of_val(&self.searched[..])
            + std::mem::size_of_val(&self.posterior[..])
            + self.alias.as_ref().map_or(0, Alias::heap_bytes)
    }

    /// A belief of `kind` with nothing searched yet; `plan` replaces `prior`
    /// for planning when the target is known.
    pub fn new(kind: Belief, prior: TargetPrior, plan: Option<TargetPrior>) -> BeliefState {
        let cells = prior.mass().len();
        let mut remaining = crate::game::sum::Sum::default();
        let mut cells_left = 0;
        for &m in plan.as_ref().unwrap_or(&prior).mass() {
            remaining.add(m);
            cells_left += (m > 0.0) as u32;
        }
        BeliefState {
            kind,
            prior,
            plan,
            searched: vec![0; cells],
            remaining,
            cells_left,
            generation: 0,
            posterior: Vec::new(),
            alias: None,
        }
    }

    fn planning(&self) -> &TargetPrior {
        self.plan.as_ref().unwrap_or(&self.prior)
    }

    /// Marks every cell within the sensor's radius of `cell` as searched.
    pub fn search_around(&mut self, sensor: &Sensor, cell: u32) {
        let mass = self.plan.as_ref().unwrap_or(&self.prior).mass();
        let mut changed = false;
        for c in sensor.around(cell) {
            let c = c as usize;
            if self.searched[c] == 0 {
                self.searched[c] = 1;
                self.remaining.add(-mass[c]);
                self.cells_left -= (mass[c] > 0.0) as u32;
                changed = true;
            }
        }
        if changed {
            self.alias = None;
            self.generation += 1;
        }
    }

    /// A practice target from the belief.
    pub fn practice_target(&mut self, rng: &mut Rng) -> u32 {
        if self.kind == Belief::Prior {
            return self.planning().sample(rng);
        }
        self.posterior_target(rng)
    }

    /// A practice target from the posterior, whatever this belief's kind
    /// (the belief MCTS plans on the posterior by construction).
    pub fn posterior_target(&mut self, rng: &mut Rng) -> u32 {
        // Rejection from the prior is exact for the posterior and cheap while
        // much mass remains; past a few misses fall back to an alias table.
        for _ in 0..8 {
            let c = self.planning().sample(rng);
            if self.searched[c as usize] == 0 {
                return c;
            }
        }
        if self.alias.is_none() {
            let mass = self.plan.as_ref().unwrap_or(&self.prior).mass();
            posterior_into(mass, &self.searched, &mut self.posterior);
            self.alias = Some(Alias::new(&self.posterior));
        }
        self.alias.as_ref().expect("built above").sample(rng)
    }

    /// The true target's prior mass per cell.
    pub fn prior_mass(&self) -> &[f64] {
        self.prior.mass()
    }

    /// The planning prior's mass (differs from the prior with `known`).
    pub fn plan_mass(&self) -> &[f64] {
        self.planning().mass()
    }

    /// Writes the posterior (the planning prior with searched cells zeroed,
    /// renormalised) into `out`.
    pub fn posterior_into(&self, out: &mut Vec<f64>) {
        posterior_into(self.planning().mass(), &self.searched, out);
    }

    /// 1 for each cell within r_v of any position occupied so far.
    pub fn searched(&self) -> &[u8] {
        &self.searched
    }

    /// Planning mass not yet searched.
    pub fn remaining(&self) -> f64 {
        if self.cells_left == 0 {
            0.0
        } else {
            self.remaining.value().max(0.0)
        }
    }

    /// The unsearched cells with positive planning mass.
    pub fn cells_left(&self) -> u32 {
        self.cells_left
    }

    /// Changes whenever the searched set (and so the posterior) changes.
    pub fn generation(&self) -> u64 {
        self.generation
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::game::lattice::Torus;
    use crate::game::prior::PriorSpec;

    /// A 10 × 10 lattice, r_v = 1, and a prior from `weights`.
    fn small(weights: Vec<f64>) -> (Sensor, BeliefState) {
        let torus = Torus::new(10).unwrap();
        let sensor = Sensor::new(&torus, 1.0).unwrap();
        let prior = TargetPrior::new(&torus, &PriorSpec::Weights { weights }).unwrap();
        (sensor, BeliefState::new(Belief::Posterior, prior, None))
    }

    /// The posterior written out from its definition, independently of
    /// `posterior_into`: the prior on unsearched cells over their total.
    fn reference_posterior(b: &BeliefState) -> Vec<f64> {
        let open = |c: usize| b.searched()[c] == 0;
        let prior = b.prior_mass();
        let left: f64 = (0..prior.len())
            .filter(|&c| open(c))
            .map(|c| prior[c])
            .sum();
        (0..prior.len())
            .map(|c| if open(c) { prior[c] / left } else { 0.0 })
            .collect()
    }

    #[test]
    fn the_posterior_is_the_prior_on_unsearched_cells_renormalised() {
        let (sensor, mut b) = small((0..100).map(|c| (c % 7 + 1) as f64).collect());
        for cell in [0, 37, 55] {
            b.search_around(&sensor, cell);
        }
        assert!(b.remaining() < 0.9, "{}", b.remaining());
        let mut out = Vec::new();
        b.posterior_into(&mut out);
        let want = reference_posterior(&b);
        assert_eq!(out.len(), want.len());
        for (c, (&got, &want)) in out.iter().zip(&want).enumerate() {
            assert!((got - want).abs() <= 1e-15, "cell {c}: {got} vs {want}");
        }
        assert!((out.iter().sum::<f64>() - 1.0).abs() <= 1e-14);
    }

    #[test]
    fn an_exhausted_posterior_is_uniform_over_the_unsearched_cells() {
        // The planner was wrong: all of the prior's mass is searched.
        let mut w = vec![0.0; 100];
        w[44] = 1.0;
        let (sensor, mut b) = small(w);
        b.search_around(&sensor, 44);
        let mut out = Vec::new();
        b.posterior_into(&mut out);
        for (c, (&p, &s)) in out.iter().zip(b.searched()).enumerate() {
            let want = if s == 0 { 1.0 / 95.0 } else { 0.0 };
            assert_eq!(p, want, "cell {c}");
        }
        assert_eq!(out.len(), 100);
    }

    /// Practice targets from a posterior whose prior mass is mostly
    /// searched (so the rejection sampler gives way to the alias table):
    /// never a searched cell, and each cell's count within 4.5 standard
    /// errors of its posterior share. Keeping the searched cells' mass in
    /// the table draws them; a uniform table draws a cell of weight 1
    /// (against a mean of 4) 31 standard errors too often.
    #[test]
    fn posterior_targets_follow_the_posterior() {
        let mut w: Vec<f64> = (0..100).map(|c| (c % 7 + 1) as f64).collect();
        w[0] = 1e6;
        let (sensor, mut b) = small(w);
        b.search_around(&sensor, 0);
        let post = reference_posterior(&b);
        let mut rng = crate::game::rng::stream(5, 0);
        let mut counts = [0u32; 100];
        for _ in 0..40_000 {
            counts[b.posterior_target(&mut rng) as usize] += 1;
        }
        crate::game::prior::assert_draws_follow(&counts, &post, 4.5);
    }

    #[test]
    fn the_unsearched_mass_is_exact_to_the_last_cell() {
        // N = 40, σ = 2.5: far from the mode cells hold 10⁻²⁸ of the mass.
        // Searching all but the far corner's disc must leave the corner's
        // mass, not the rounding dust (about 10⁻¹⁶) of a running
        // difference from 1; searching it too leaves exactly 0.
        let mut c = Config::default();
        c.set("sigma", "2.5").unwrap();
        let g = c.game().unwrap();
        let mut b = BeliefState::new(Belief::Posterior, g.prior.clone(), None);
        let corner = g.torus.cell(39, 39);
        let last: Vec<u32> = g.sensor.around(corner).collect();
        for cell in 0..g.torus.cells() as u32 {
            if !g.sensor.around(cell).any(|c| last.contains(&c)) {
                b.search_around(&g.sensor, cell);
            }
        }
        let left: f64 = (0..g.torus.cells())
            .filter(|&c| b.searched()[c] == 0)
            .map(|c| g.prior.mass()[c])
            .sum();
        assert!(left > 0.0 && left < 1e-20, "the corner holds {left}");
        let unsearched = (0..g.torus.cells())
            .filter(|&c| b.searched()[c] == 0 && g.prior.mass()[c] > 0.0)
            .count();
        assert_eq!(b.cells_left() as usize, unsearched);
        let got = b.remaining();
        // Compensated, the error is of order cells × ε² ≈ 10⁻²⁹.
        assert!(
            (got - left).abs() <= 1e-28,
            "remaining {got} against {left}"
        );
        b.search_around(&g.sensor, corner);
        for cell in 0..g.torus.cells() as u32 {
            b.search_around(&g.sensor, cell);
        }
        assert_eq!(b.remaining(), 0.0);
        assert_eq!(b.cells_left(), 0);
    }
}
