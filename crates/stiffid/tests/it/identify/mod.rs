//! Identification from synthetic measurements made with the forward model: exact recovery without
//! noise, confidence intervals that cover the truth at their nominal rate, robust mode, validation
//! (Eq. 22) and the errors.

use crate::common;
use stiffid::internal::identify::Identify;
use stiffid::internal::model::Compliance;

use common::{deg, on_robot, paper_measurements, synthetic, with_noise, PAPER_POSTURES_DEG};
use nalgebra::{Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::identify::validate;
use stiffid::internal::identify::{least_squares, Loss};
use stiffid::internal::observation::{Measurement, Observations};
use stiffid::internal::robot::kinematics::Coordinates;
use stiffid::MeasurementField;
use stiffid::{
    internal::{robot::presets, setup},
    Error,
};

fn max_relative_error(a: &Vector6<f64>, truth: &Vector6<f64>) -> f64 {
    (a - truth).component_div(truth).amax()
}

#[test]
fn noise_free_data_recover_the_stiffness_of_every_preset_and_spring_placement() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for name in presets::names() {
        for springs in [Coordinates::Axis, Coordinates::Kinematic] {
            let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
            let setup = on_robot(&paper, presets::get(name).unwrap(), springs);
            let (lo, hi) = (setup.robot().limits().lower, setup.robot().limits().upper);
            let postures: Vec<Vector6<f64>> = (0..8)
                .map(|_| {
                    Vector6::from_fn(|i, _| lo[i] + rng.random_range(0.1..0.9) * (hi[i] - lo[i]))
                })
                .collect();
            let wrenches: Vec<Vector6<f64>> = (0..8)
                .map(|_| {
                    Vector6::from_fn(|i, _| rng.random_range(-1.0..1.0) * [500.0, 100.0][i / 3])
                })
                .collect();
            let data = synthetic(&setup, &postures, |i, _| wrenches[i]);
            let id = least_squares(setup.arm(), &data).unwrap();
            let err = max_relative_error(&id.stiffness, setup.nominal_stiffness().unwrap());
            assert!(err < 1e-9, "{name}, {springs:?}: relative error {err:e}");
            assert_eq!((id.rows, id.postures), (96, 8));
            assert!(id.residual_rms < 1e-12 * data[0].displacement.norm().max(1e-6));
        }
    }
}

#[test]
fn the_t_quantile_and_the_delta_method_are_the_documented_ones() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let data = paper_measurements(&setup);
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let noisy = with_noise(&data, setup.noise().displacement_sd(), &mut rng);
    let id = least_squares(setup.arm(), &noisy).unwrap();
    let u = id.uncertainty.unwrap();
    assert_eq!(u.dof, 66);
    // t_{0.975, 66} from R: qt(0.975, 66) = 1.996564418952332.
    assert!((u.t_quantile - 1.996564418952332).abs() < 1e-9);
    let rss = id.residuals.norm_squared();
    assert!((u.residual_variance - rss / 66.0).abs() < 1e-12 * u.residual_variance);
    for j in 0..6 {
        let (h, se) = (id.compliance[j], u.compliance_std_error[j]);
        assert!((u.stiffness_std_error[j] - se / (h * h)).abs() < 1e-9 * u.stiffness_std_error[j]);
        assert!((u.compliance_ci95[j][1] - h - u.t_quantile * se).abs() < 1e-12 * h);
        let [lo, hi] = u.stiffness_ci95_from_compliance[j];
        assert!((lo - 1.0 / u.compliance_ci95[j][1]).abs() < 1e-9 * lo);
        assert!((hi - 1.0 / u.compliance_ci95[j][0]).abs() < 1e-9 * hi);
    }
}

#[test]
fn confidence_intervals_cover_the_truth_at_about_95_percent() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let clean = paper_measurements(&setup);
    let truth_h = setup.nominal_compliance().unwrap();
    let truth_k = setup.nominal_stiffness().unwrap();
    // Ten times the paper's noise, so that the intervals are wide enough to matter.
    let sigma = 10.0 * setup.noise().displacement_sd();
    let sets = 300;
    let (mut covered_h, mut covered_k) = (0, 0);
    for set in 0..sets {
        let mut rng =
            ChaCha8Rng::seed_from_u64(0x5eed ^ (set as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let noisy = with_noise(&clean, sigma, &mut rng);
        let u = least_squares(setup.arm(), &noisy)
            .unwrap()
            .uncertainty
            .unwrap();
        for j in 0..6 {
            let [lo, hi] = u.compliance_ci95[j];
            covered_h += usize::from(lo <= truth_h[j] && truth_h[j] <= hi);
            let [lo, hi] = u.stiffness_ci95[j];
            covered_k += usize::from(lo <= truth_k[j] && truth_k[j] <= hi);
        }
    }
    let total = (6 * sets) as f64;
    let (rate_h, rate_k) = (covered_h as f64 / total, covered_k as f64 / total);
    assert!(
        (0.90..=0.99).contains(&rate_h),
        "compliance coverage {rate_h}"
    );
    assert!(
        (0.90..=0.99).contains(&rate_k),
        "stiffness (delta method) coverage {rate_k}"
    );
}

#[test]
fn robust_modes_down_weight_an_injected_outlier() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut data = with_noise(
        &paper_measurements(&setup),
        setup.noise().displacement_sd(),
        &mut rng,
    );
    // Measurement 10 (posture 3, point 2), y: 0.3 mm off, about 30 sigma.
    data[9].displacement.y += 0.3e-3;
    let outlier_row = 3 * 9 + 1;
    let plain = least_squares(setup.arm(), &data).unwrap();
    let plain_err = max_relative_error(&plain.stiffness, setup.nominal_stiffness().unwrap());
    for loss in [Loss::Huber, Loss::Tukey] {
        let id = Observations::from_measurements(setup.arm(), &data)
            .unwrap()
            .robust(loss)
            .unwrap();
        let fit = id.robust.as_ref().unwrap();
        assert!(fit.converged(), "{loss:?}");
        assert_eq!(fit.down_weighted()[0], outlier_row, "{loss:?}");
        assert!(
            fit.weights[outlier_row] < 0.1,
            "{loss:?}: {}",
            fit.weights[outlier_row]
        );
        // The MAD scale estimates the noise, not the outlier.
        let ratio = fit.scale / setup.noise().displacement_sd();
        assert!((0.6..1.6).contains(&ratio), "{loss:?}: scale/sigma {ratio}");
        let err = max_relative_error(&id.stiffness, setup.nominal_stiffness().unwrap());
        assert!(
            err < plain_err / 2.0,
            "{loss:?}: {err} vs least squares {plain_err}"
        );
    }
    let tukey = Observations::from_measurements(setup.arm(), &data)
        .unwrap()
        .robust(Loss::Tukey)
        .unwrap();
    assert_eq!(tukey.robust.unwrap().weights[outlier_row], 0.0);
}

#[test]
fn validation_compares_measured_and_predicted_displacements() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let data = paper_measurements(&setup);
    let exact =
        validate::compare(setup.arm(), &setup.model_compliance("test").unwrap(), &data).unwrap();
    assert_eq!(exact.checks.len(), 24);
    assert!(exact.max < 1e-15, "{}", exact.max);
    // Twice as stiff: every prediction is half the measurement, so delta_b = |delta_m| / 2.
    let stiffer = validate::compare(
        setup.arm(),
        &Compliance::drives(setup.nominal_compliance().unwrap() / 2.0, None),
        &data,
    )
    .unwrap();
    for (c, m) in stiffer.checks.iter().zip(&data) {
        assert!((c.predicted - m.displacement / 2.0).norm() < 1e-15);
        assert!((c.delta_b - m.displacement.norm() / 2.0).abs() < 1e-15);
    }
    let halves: Vec<f64> = data.iter().map(|m| m.displacement.norm() / 2.0).collect();
    let mean = halves.iter().sum::<f64>() / 24.0;
    assert!((stiffer.mean - mean).abs() < 1e-15);
    assert!((stiffer.max - halves.iter().cloned().fold(0.0, f64::max)).abs() < 1e-15);
    assert!(validate::compare(
        setup.arm(),
        &Compliance::drives(Vector6::repeat(-1.0), None),
        &data
    )
    .is_err());
}

#[test]
fn data_that_cannot_be_used_are_errors_naming_the_measurement() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let data = paper_measurements(&setup);
    let field = |e: Error| match e {
        Error::Measurement { number, field, .. } => (number, field),
        other => panic!("unexpected {other}"),
    };
    let mut bad = data.clone();
    bad[4].point = 4;
    assert_eq!(
        field(least_squares(setup.arm(), &bad).unwrap_err()),
        (5, MeasurementField::Point)
    );
    let mut bad = data.clone();
    bad[6].q[2] = setup.robot().limits().upper[2] + 0.1;
    assert_eq!(
        field(least_squares(setup.arm(), &bad).unwrap_err()),
        (7, MeasurementField::Axis(2))
    );
    let mut bad = data.clone();
    bad[2].wrench[1] = f64::NAN;
    assert_eq!(
        field(least_squares(setup.arm(), &bad).unwrap_err()),
        (3, MeasurementField::Force)
    );
    let mut bad = data.clone();
    bad[5].posture = 0;
    assert_eq!(
        field(least_squares(setup.arm(), &bad).unwrap_err()),
        (6, MeasurementField::Posture)
    );
    assert_eq!(
        least_squares(setup.arm(), &data[..1]).unwrap_err(),
        Error::TooFewRows { rows: 3 }
    );
}

#[test]
fn a_joint_no_measurement_loads_is_named() {
    // The loading point on the joint-6 axis and no moment: tau_6 = 0 in every posture.
    let setup = setup::builtin("zhang2021-comau-nj165")
        .unwrap()
        .to_builder()
        .with_loading_point(Vector3::new(0.0, 0.0, 0.2))
        .build()
        .unwrap();
    let data = paper_measurements(&setup);
    match least_squares(setup.arm(), &data).unwrap_err() {
        Error::Unidentifiable { joints, .. } => assert_eq!(joints, vec![6]),
        other => panic!("unexpected {other}"),
    }
}

#[test]
fn one_posture_may_carry_several_wrenches() {
    // Each posture loaded twice (rope load, then a wrench with moments), rows interleaved so that
    // the torques change within a posture while its frames are reused.
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let qs: Vec<_> = PAPER_POSTURES_DEG.iter().map(deg).collect();
    let rope = synthetic(&setup, &qs, |_, q| {
        setup.rope_wrench(&setup.robot().frames(q))
    });
    let twist = synthetic(&setup, &qs, |i, _| {
        Vector6::new(100.0, -50.0 * i as f64, 200.0, 20.0, -30.0, 40.0)
    });
    let data: Vec<Measurement> = rope
        .into_iter()
        .zip(twist)
        .flat_map(|(a, b)| [a, b])
        .collect();
    let id = least_squares(setup.arm(), &data).unwrap();
    assert_eq!((id.rows, id.postures), (144, 6));
    let err = max_relative_error(&id.stiffness, setup.nominal_stiffness().unwrap());
    assert!(err < 1e-9, "relative error {err:e}");
}
