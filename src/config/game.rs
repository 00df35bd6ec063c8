//! The game a configuration describes: the lattice, the sensor, the target
//! prior and the start cell, built once and checked.

use super::fields::Config;
use crate::game::lattice::{Sensor, Torus};
use crate::game::prior::{self, PriorKind, PriorSpec, TargetPrior};
use crate::param::{ParamError, ParamKind};

/// The lattice, sensor, target prior and start cell a configuration describes.
#[derive(Clone, Debug)]
pub struct Game {
    /// The lattice.
    pub torus: Torus,
    /// The sensor of radius r_v.
    pub sensor: Sensor,
    /// The target prior.
    pub prior: TargetPrior,
    /// The start cell.
    pub start: u32,
}

impl Config {
    /// The prior that places the target on `torus`, from `prior`, `sigma`,
    /// `paint` and `target`.
    ///
    /// # Errors
    /// A [`ParamError`] for `paint` when it does not decode for this n.
    pub fn prior_spec(&self, torus: &Torus) -> Result<PriorSpec, ParamError> {
        let n = self.n;
        Ok(match (self.target, self.prior) {
            (Some([x, y]), _) => PriorSpec::Delta {
                cell: Some(torus.cell(x as i64 - 1, y as i64 - 1)),
            },
            (None, PriorKind::Gaussian) => PriorSpec::Gaussian { sigma: self.sigma },
            (None, PriorKind::Delta) => PriorSpec::Delta { cell: None },
            (None, PriorKind::Uniform) => PriorSpec::Uniform,
            (None, PriorKind::Code) => PriorSpec::Code { sigma: self.sigma },
            (None, PriorKind::Paint) => PriorSpec::Weights {
                weights: prior::decode_paint(&self.paint, n)
                    .map_err(|e| ParamError::new("paint", e, ParamKind::Paint.allowed()))?
                    .into_iter()
                    .map(f64::from)
                    .collect(),
            },
        })
    }

    /// Builds the game this configuration describes: what an episode, the
    /// bound and an experiment's target samples all start from.
    ///
    /// # Errors
    /// A [`ParamError`] naming the first invalid field.
    pub fn game(&self) -> Result<Game, ParamError> {
        self.validate()?;
        // Past validation the lattice, the sensor and the prior build:
        // n, r_v, the cells and the paint were checked against their ranges.
        let torus = Torus::new(self.n).expect("n was validated");
        let spec = self.prior_spec(&torus)?;
        let sensor = Sensor::new(&torus, self.rv).expect("rv was validated");
        let prior = TargetPrior::new(&torus, &spec).expect("the prior was validated");
        let start = torus.cell(self.start[0] as i64 - 1, self.start[1] as i64 - 1);
        Ok(Game {
            torus,
            sensor,
            prior,
            start,
        })
    }
}
