//! The ladder of gravity models and maps (`stiffid::app::calibrate::ladder`).

use stiffid::app::calibrate::ladder::*;
use stiffid_metrology::calibration::gravity::Gravity;

fn rung(errors: Vec<f64>) -> Rung {
    Rung {
        gravity: Gravity::None,
        maps: false,
        rms: None,
        skipped: None,
        spread: None,
        errors,
    }
}

#[test]
fn the_simplest_within_one_standard_error_of_the_best() {
    // The second rung is better by far more than a standard error: chosen; the third
    // improves on it by less than one: not.
    let a = rung(vec![4.0, 5.0, 6.0, 5.0]);
    let b = rung(vec![1.0, 1.2, 0.8, 1.0]);
    let c = rung(vec![0.9, 1.3, 0.6, 1.0]);
    assert_eq!(choose(&[a.clone(), b.clone(), c.clone()]), 1);
    // Without the second, the third is chosen over the first.
    assert_eq!(choose(&[a.clone(), c]), 1);
    // A skipped rung is never chosen, whatever its errors.
    let mut skipped = rung(vec![0.0; 4]);
    skipped.skipped = Some("not converged".into());
    assert_eq!(choose(&[a, skipped, b]), 2);
}

#[test]
fn a_rung_that_loses_to_a_simpler_one_is_not_chosen() {
    let a = rung(vec![1.0, 1.0, 1.0, 1.0]);
    let b = rung(vec![1.5, 1.4, 1.6, 1.5]);
    assert_eq!(choose(&[a, b]), 0);
    assert_eq!(choose(&[]), 0);
}

#[test]
fn auto_tries_masses_only_where_the_robot_has_them() {
    assert_eq!(
        GravitySpec::Auto.rungs(false),
        [
            Gravity::None,
            Gravity::Arm,
            Gravity::Lumped,
            Gravity::LumpedLinks
        ]
    );
    assert_eq!(GravitySpec::Auto.rungs(true)[4], Gravity::Masses);
    assert_eq!(
        "arm".parse::<GravitySpec>().unwrap().rungs(true),
        [Gravity::Arm]
    );
    let lumped: GravitySpec = "lumped".parse().unwrap();
    assert_eq!(lumped.rungs(true), vec![Gravity::Lumped]);
    assert_eq!("auto".parse::<GravitySpec>().unwrap(), GravitySpec::Auto);
    assert!("sag".parse::<GravitySpec>().is_err());
}
