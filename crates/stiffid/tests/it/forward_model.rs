//! The forward model and the observation matrix agree: `Psi h = delta` (Eq. 10) for the nominal
//! compliance, and noise-free identification recovers it.

use crate::common;

use nalgebra::{DVector, Vector6};
use stiffid::internal::{
    math::lsq::Factor, observation::rope_observation_matrix, observation::stiffness, setup,
};

fn postures() -> Vec<Vector6<f64>> {
    common::PAPER_POSTURES_DEG.iter().map(common::deg).collect()
}

#[test]
fn observation_matrix_times_compliance_is_the_forward_displacement() {
    for name in stiffid::internal::setup::builtin_names() {
        let setup = setup::builtin(name).unwrap();
        let qs: Vec<_> = postures()
            .iter()
            .map(|q| {
                q.zip_zip_map(&setup.bounds().lower, &setup.bounds().upper, |v, l, u| {
                    v.clamp(l, u)
                })
            })
            .collect();
        let psi = rope_observation_matrix(&setup, &qs);
        let delta: Vec<f64> = qs
            .iter()
            .flat_map(|q| {
                let frames = setup.robot().frames(q);
                stiffness::rope_displacements(&setup, &frames, setup.nominal_stiffness().unwrap())
                    .into_iter()
                    .flat_map(|d| [d.x, d.y, d.z])
            })
            .collect();
        let delta = DVector::from_vec(delta);
        let h = setup.nominal_compliance().unwrap();
        assert!((&psi * h - &delta).amax() < 1e-12 * delta.amax(), "{name}");
        let recovered = Factor::try_new(psi.clone()).unwrap().solve(&delta);
        let rel = (recovered - h).component_div(&h).amax();
        assert!(rel < 1e-9, "{name}: relative error {rel:e}");
    }
}
