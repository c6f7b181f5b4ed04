//! The options of a tracker campaign's fit, as the calibration fits every gravity model.

use super::{GravityPrior, Options, Priors, GRAVITY_DEFLECTION};

impl Options {
    /// The fit's options of a campaign read with the tracker's `noise` per coordinate (m): the
    /// characteristic length `length` of the column scaling (m), the joint errors' priors
    /// `priors` (the standard deviations of a length error, m, and of an angle error, rad), no
    /// ridge, and every gravity term held to `bound` of joint deflection at the largest torque it
    /// meets (rad, [`GravityPrior`]; 3 mrad when `None`), both weighed against `noise`.
    pub fn for_campaign(
        length: f64,
        priors: Option<(f64, f64)>,
        noise: f64,
        bound: Option<f64>,
    ) -> Self {
        Options {
            length,
            priors: priors.map(|(length, angle)| Priors {
                length,
                angle,
                noise,
            }),
            ridge: 0.0,
            gravity: Some(GravityPrior {
                deflection: bound.unwrap_or(GRAVITY_DEFLECTION),
                noise,
            }),
        }
    }
}
