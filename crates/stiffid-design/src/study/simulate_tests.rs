//! Monte Carlo simulation with the first-order predictions given ([`super::simulate`]).

use super::simulate::{monte_carlo, monte_carlo_with_predictions, Options};
use nalgebra::Vector6;
use stiffid_core::setup;

/// Six spread postures within the paper's Table 1 bounds, deg.
fn group() -> Vec<Vector6<f64>> {
    [
        [10.0, -20.0, -100.0, 30.0, 40.0, -60.0],
        [-45.0, 10.0, -70.0, -90.0, -30.0, 120.0],
        [60.0, -40.0, -130.0, 150.0, 60.0, 10.0],
        [-80.0, 30.0, -50.0, -20.0, -70.0, -150.0],
        [30.0, 0.0, -160.0, 100.0, 20.0, 80.0],
        [-10.0, -55.0, -90.0, -160.0, 80.0, -30.0],
    ]
    .iter()
    .map(|q| Vector6::from_iterator(q.iter().map(|d: &f64| d.to_radians())))
    .collect()
}

#[test]
fn predictions_given_are_kept_and_must_match_the_groups() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let options = Options { runs: 20, seed: 4 };
    let own = &monte_carlo(&setup, &[group()], &options).unwrap()[0];
    let given = vec![[1.0; 6]; setup.noise().levels.len()];
    let with = &monte_carlo_with_predictions(
        &setup,
        &[group()],
        std::slice::from_ref(&given),
        &options,
        &(),
    )
    .unwrap()[0];
    // The runs are the same; only the prediction is the one given.
    assert_eq!(with.mean_deviation_pct, own.mean_deviation_pct);
    assert_eq!(with.predicted_deviation_pct, given);
    let e = monte_carlo_with_predictions(&setup, &[group(), group()], &[given], &options, &())
        .unwrap_err();
    assert!(
        e.to_string()
            .contains("one prediction per group (2), got 1"),
        "{e}"
    );
}
