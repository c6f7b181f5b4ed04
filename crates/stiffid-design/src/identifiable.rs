//! Whether a group of postures identifies every parameter of a setup's model, and which
//! combinations of parameters it cannot separate.

use super::{evaluate, Evaluation};
use nalgebra::Vector6;
use stiffid_core::math::lsq::Factor;
use stiffid_core::observation::rope_observation_matrix;
use stiffid_core::{Error, Result, Setup};

/// The combinations of the model's parameters that the group of `e` cannot separate, named.
pub fn unidentifiable(e: &Evaluation, setup: &Setup) -> Vec<String> {
    let names = setup.model().parameters();
    let combinations = e.identifiability.unidentifiable.iter();
    combinations.map(|c| c.describe(&names)).collect()
}

/// Fails when the group cannot identify every parameter of the setup's model: for the drives
/// alone, [`Error::Unidentifiable`] naming the joints; with virtual springs,
/// [`Error::Inseparable`] naming the combinations it cannot separate.
pub fn identifiable(setup: &Setup, postures: &[Vector6<f64>]) -> Result<()> {
    if setup.model().is_drives_only() {
        return Factor::try_new(rope_observation_matrix(setup, postures)).map(|_| ());
    }
    let combinations = unidentifiable(&evaluate(setup, postures), setup);
    match combinations.is_empty() {
        true => Ok(()),
        false => Err(Error::Inseparable { combinations }),
    }
}
