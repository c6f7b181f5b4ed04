//! Whether to believe an identification: the chi-square model check, non-negative least squares
//! against an enumeration of active sets, cross-validation against leave-one-out by hand, the
//! measurement frames, the unit check and the share of the deflection explained.

use crate::common;
use stiffid::internal::identify::Identify;
use stiffid::internal::model::Compliance;

use common::{deg, paper_measurements, synthetic, with_noise, PAPER_POSTURES_DEG};
use nalgebra::{DMatrix, DVector, Isometry3, Matrix6, Translation3, UnitQuaternion, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::identify::cross_validation::Method;
use stiffid::internal::identify::validate;
use stiffid::internal::identify::{cross_validate, least_squares, nonnegative};
use stiffid::internal::io::measurements;
use stiffid::internal::observation::{Measurement, Observations};
use stiffid::{internal::setup, Error, Setup};

const FANUC_CSV: &str =
    include_str!("../../../../examples/data/fanuc-r2000ic-165f/measurements.csv");

fn paper() -> Setup {
    setup::builtin("zhang2021-comau-nj165").unwrap()
}

/// The paper postures, each measured `repeats` times (same label), with the setup's noise.
fn noisy_paper_data(setup: &Setup, repeats: usize, seed: u64) -> Vec<Measurement> {
    let clean = paper_measurements(setup);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..repeats)
        .flat_map(|_| with_noise(&clean, setup.noise().displacement_sd(), &mut rng))
        .collect()
}

#[test]
fn chi_square_ratio_is_near_one_with_the_setups_noise() {
    let setup = paper();
    let id = least_squares(setup.arm(), &noisy_paper_data(&setup, 10, 7)).unwrap();
    let a = id.adequacy(setup.noise().displacement_variance()).unwrap();
    assert_eq!(a.dof, 720 - 6);
    // s / sigma has a standard deviation of about 1 / sqrt(2 dof) = 0.026.
    assert!((a.noise_ratio - 1.0).abs() < 0.1, "ratio {}", a.noise_ratio);
    assert!(
        a.p_value > 0.001 && !a.model_error_dominates(),
        "p {}",
        a.p_value
    );
    assert!((a.chi2 - a.dof as f64 * a.noise_ratio.powi(2)).abs() < 1e-9 * a.chi2);
    // Ten times the noise: the model check fails.
    let loud = with_noise(
        &paper_measurements(&setup),
        10.0 * setup.noise().displacement_sd(),
        &mut ChaCha8Rng::seed_from_u64(1),
    );
    let a = least_squares(setup.arm(), &loud)
        .unwrap()
        .adequacy(setup.noise().displacement_variance())
        .unwrap();
    assert!(a.noise_ratio > 5.0 && a.model_error_dominates(), "{a:?}");
    // The noise intervals: normal quantile, sigma^2 instead of s^2.
    let u = id.uncertainty.as_ref().unwrap();
    let scale = (setup.noise().displacement_variance() / u.residual_variance).sqrt();
    let a = id.adequacy(setup.noise().displacement_variance()).unwrap();
    for j in 0..6 {
        let se = a.from_noise.compliance_std_error[j];
        assert!((se - u.compliance_std_error[j] * scale).abs() < 1e-12 * se);
    }
}

/// `min |a x - b|, x >= 0` by trying every set of free variables (64 for 6 unknowns): the
/// feasible unconstrained solution on each set, the best of them.
fn nnls_by_enumeration(a: &Matrix6<f64>, b: &Vector6<f64>) -> Vector6<f64> {
    let mut best = (f64::INFINITY, Vector6::zeros());
    for mask in 0u32..64 {
        let free: Vec<usize> = (0..6).filter(|j| mask & (1 << j) != 0).collect();
        let mut x = Vector6::zeros();
        if !free.is_empty() {
            let sub = DMatrix::from_fn(6, free.len(), |i, k| a[(i, free[k])]);
            let z = sub
                .svd(true, true)
                .solve(&DVector::from_column_slice(b.as_slice()), 1e-14)
                .unwrap();
            if z.iter().any(|v| *v < 0.0) {
                continue;
            }
            for (k, &j) in free.iter().enumerate() {
                x[j] = z[k];
            }
        }
        let objective = (a * x - b).norm();
        if objective < best.0 {
            best = (objective, x);
        }
    }
    best.1
}

#[test]
fn nonnegative_least_squares_matches_the_enumeration_of_active_sets() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut some_active = 0;
    for _ in 0..100 {
        let a = Matrix6::from_fn(|i, j| match i <= j {
            true => rng.random_range(-1.0..1.0) + if i == j { 2.0 } else { 0.0 },
            false => 0.0,
        });
        let b = Vector6::from_fn(|_, _| rng.random_range(-1.0..1.0));
        let fit = nonnegative::solve(&a, &b);
        assert_eq!(fit.stop, stiffid::internal::common::stop::Stop::Converged);
        let truth = nnls_by_enumeration(&a, &b);
        assert!((fit.h - truth).amax() < 1e-10, "{} vs {}", fit.h, truth);
        assert!(fit.h.iter().all(|v| *v >= 0.0));
        for j in 0..6 {
            assert_eq!(fit.active[j], fit.h[j] == 0.0);
        }
        some_active += usize::from(fit.active.iter().any(|a| *a));
    }
    assert!(
        some_active > 33,
        "the cases exercise the bounds: {some_active}"
    );
}

#[test]
fn nonnegative_fit_equals_least_squares_when_that_is_non_negative() {
    let setup = paper();
    let data = noisy_paper_data(&setup, 1, 3);
    let obs = Observations::from_measurements(setup.arm(), &data).unwrap();
    let (plain, bounded) = (obs.least_squares().unwrap(), obs.nonnegative().unwrap());
    assert!(plain.compliance.iter().all(|h| *h > 0.0));
    assert_eq!(bounded.active_bounds, Some([false; 6]));
    assert!((plain.compliance - bounded.compliance).amax() < 1e-12 * plain.compliance.amax());
    let (u, v) = (
        plain.uncertainty.as_ref().unwrap(),
        bounded.uncertainty.as_ref().unwrap(),
    );
    assert!(
        (u.compliance_std_error - v.compliance_std_error).amax()
            < 1e-9 * u.compliance_std_error.amax()
    );
    assert_eq!(plain.physical(), [true; 6]);
}

#[test]
fn nonnegative_fit_of_a_negative_least_squares_solution_holds_it_at_zero() {
    // Displacements with the wrong sign: every least-squares compliance is negative.
    let setup = paper();
    let flipped: Vec<Measurement> = paper_measurements(&setup)
        .into_iter()
        .map(|m| Measurement {
            displacement: -m.displacement,
            ..m
        })
        .collect();
    let obs = Observations::from_measurements(setup.arm(), &flipped).unwrap();
    let plain = obs.least_squares().unwrap();
    assert_eq!(plain.physical(), [false; 6]);
    let bounded = obs.nonnegative().unwrap();
    assert_eq!(bounded.active_bounds, Some([true; 6]));
    assert_eq!(
        (plain.nonnegative_stop, bounded.nonnegative_stop),
        (None, Some(stiffid::internal::common::stop::Stop::Converged))
    );
    assert_eq!(bounded.compliance, Vector6::zeros());
    assert_eq!(bounded.physical(), [false; 6]);
}

#[test]
fn k_folds_equal_to_the_postures_is_leave_one_out_by_hand() {
    let setup = paper();
    let data = noisy_paper_data(&setup, 1, 5);
    let obs = Observations::from_measurements(setup.arm(), &data).unwrap();
    let full = obs.least_squares().unwrap();
    let cv = cross_validate(&obs, &full, 6, Method::LeastSquares).unwrap();
    assert_eq!(cv.folds.len(), 6);
    let se = full.uncertainty.as_ref().unwrap().stiffness_std_error;
    for (p, fold) in cv.folds.iter().enumerate() {
        assert_eq!(fold.postures, vec![p]);
        let (held, rest): (Vec<Measurement>, Vec<Measurement>) =
            data.iter().cloned().partition(|m| m.posture == p);
        let by_hand = least_squares(setup.arm(), &rest).unwrap();
        let rel = (0..6)
            .map(|j| (fold.stiffness[j] / by_hand.stiffness[j] - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(rel < 1e-9, "fold {p}: {rel:e}");
        let check = validate::compare(
            setup.arm(),
            &Compliance::drives(by_hand.compliance, None),
            &held,
        )
        .unwrap();
        for (a, c) in fold.delta_b.iter().zip(&check.checks) {
            assert!((a - c.delta_b).abs() < 1e-12, "{a} vs {}", c.delta_b);
        }
        for j in 0..6 {
            let moved = (by_hand.stiffness[j] - full.stiffness[j]).abs() > se[j];
            assert_eq!(fold.influential[j], moved);
        }
    }
    let ks: Vec<f64> = cv.folds.iter().map(|f| f.stiffness[3]).collect();
    let mean = ks.iter().sum::<f64>() / 6.0;
    let std = (ks.iter().map(|k| (k - mean).powi(2)).sum::<f64>() / 5.0).sqrt();
    assert!((cv.stiffness_mean[3] - mean).abs() < 1e-9 * mean);
    assert!((cv.stiffness_std[3] - std).abs() < 1e-9 * std);
    // Large posture numbers (a hash map instead of a table) tell the postures apart the same way.
    let sparse: Vec<Measurement> = data
        .iter()
        .map(|m| Measurement {
            posture: m.posture * 1_000_003 + 7,
            ..m.clone()
        })
        .collect();
    let again = Observations::from_measurements(setup.arm(), &sparse).unwrap();
    assert_eq!(
        (again.postures, &again.posture_index),
        (6, &obs.posture_index)
    );
    // Two folds: postures 0, 2, 4 and 1, 3, 5, every measurement held out once.
    let two = cross_validate(&obs, &full, 2, Method::LeastSquares).unwrap();
    assert_eq!(two.folds[0].postures, vec![0, 2, 4]);
    assert_eq!(two.folds[1].postures, vec![1, 3, 5]);
    assert_eq!(
        two.folds[0].measurements.len() + two.folds[1].measurements.len(),
        24
    );
    assert!(cross_validate(&obs, &full, 7, Method::LeastSquares).is_err());
    assert!(cross_validate(&obs, &full, 1, Method::LeastSquares).is_err());
}

/// The FANUC file with forces in the tool frame and displacements in a tracker frame.
fn fanuc_in_other_frames(setup: &Setup, tracker: &Isometry3<f64>) -> String {
    let file = measurements::parse(FANUC_CSV).unwrap();
    let mut text = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_tool_n,fy_tool_n,fz_tool_n,mx_tool_nm,my_tool_nm,mz_tool_nm,dx_tracker_mm,dy_tracker_mm,dz_tracker_mm\n".to_string();
    for m in &file.measurements {
        let r = setup.robot().frames(&m.q).flange.rotation;
        let f = r.inverse() * m.wrench.fixed_rows::<3>(0);
        let moment = r.inverse() * m.wrench.fixed_rows::<3>(3);
        let d = tracker.rotation.inverse() * m.displacement * 1e3;
        let q = m.q.map(f64::to_degrees);
        let row: Vec<String> = [q.as_slice(), f.as_slice(), moment.as_slice(), d.as_slice()]
            .concat()
            .iter()
            .map(|v| format!("{v:e}"))
            .collect();
        text += &format!(
            "{},{},{}\n",
            file.labels[m.posture],
            m.point + 1,
            row.join(",")
        );
    }
    text
}

#[test]
fn tool_frame_forces_and_tracker_frame_displacements_give_the_base_frame_stiffness() {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let base = {
        let mut f = measurements::parse(FANUC_CSV).unwrap();
        f.to_base_frame(&setup).unwrap();
        least_squares(setup.arm(), &f.measurements).unwrap()
    };
    let tracker = Isometry3::from_parts(
        Translation3::new(3.2, -1.1, 0.4),
        UnitQuaternion::from_euler_angles(0.3, -0.7, 2.5),
    );
    let text = fanuc_in_other_frames(&setup, &tracker);
    let mut file = measurements::parse(&text).unwrap();
    assert!(matches!(
        file.clone().to_base_frame(&setup),
        Err(Error::InvalidField { field, .. }) if field == "tracker.base_from_tracker"
    ));
    let setup = setup
        .to_builder()
        .with_tracker(stiffid::internal::setup::Tracker {
            position: tracker.translation.vector,
            max_incidence: None,
            measuring_normals: vec![nalgebra::Vector3::z()],
            base_from_tracker: Some(tracker),
            registration_uncertainty: None,
        })
        .build()
        .unwrap();
    file.to_base_frame(&setup).unwrap();
    let other = least_squares(setup.arm(), &file.measurements).unwrap();
    let rel = (other.stiffness - base.stiffness)
        .component_div(&base.stiffness)
        .amax();
    assert!(rel < 1e-9, "relative difference {rel:e}");
}

#[test]
fn the_setup_reads_the_tracker_transform() {
    let text = setup::builtin_text("fanuc-r2000ic-165f")
        .unwrap()
        .to_string()
        + "\n[tracker]\nbase_from_tracker = { xyz_mm = [3000, 0, 500], rpy_deg = [0, 0, 90] }\n";
    let s = setup::parse(&text, "t.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap();
    let tracker = s.tracker().unwrap();
    let t = tracker.base_from_tracker.unwrap();
    assert!((t.translation.vector - nalgebra::Vector3::new(3.0, 0.0, 0.5)).norm() < 1e-12);
    assert_eq!(
        tracker.position, t.translation.vector,
        "the position is the transform's"
    );
    let x = t.rotation * nalgebra::Vector3::x();
    assert!(
        (x - nalgebra::Vector3::y()).norm() < 1e-12,
        "yaw 90 deg turns x into y: {x}"
    );
    let parse = |text: &str| {
        setup::parse(text, "t.toml", |r, _| {
            stiffid::internal::robot::presets::get(r)
        })
    };
    let bad = text.replace("rpy_deg = [0, 0, 90]", "rpy_deg = [0, nan, 90]");
    let e = parse(&bad).unwrap_err();
    assert!(
        e.to_string().contains("tracker.base_from_tracker.rpy_deg"),
        "{e}"
    );
    let apart = text.replace("[tracker]\n", "[tracker]\nposition_mm = [3000, 0, 600]\n");
    let e = parse(&apart).unwrap_err();
    assert!(
        e.to_string().contains("tracker.position_mm")
            && e.to_string().contains("translation of base_from_tracker"),
        "{e}"
    );
    let agree = text.replace("[tracker]\n", "[tracker]\nposition_mm = [3000, 0, 500]\n");
    assert!(parse(&agree).is_ok());
}

#[test]
fn the_unit_check_fires_on_displacements_in_metres_and_forces_in_kilonewtons() {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let data = measurements::parse(FANUC_CSV).unwrap().measurements;
    let fit = |scale_d: f64, scale_f: f64| {
        let scaled: Vec<Measurement> = data
            .iter()
            .map(|m| Measurement {
                displacement: m.displacement * scale_d,
                wrench: m.wrench * scale_f,
                ..m.clone()
            })
            .collect();
        least_squares(setup.arm(), &scaled)
            .unwrap()
            .unit_check(setup.nominal_stiffness().unwrap())
    };
    assert_eq!(fit(1.0, 1.0), None);
    let metres = fit(1e-3, 1.0).unwrap();
    assert!(metres.stiffer && metres.joints.len() >= 4, "{metres:?}");
    assert!((metres.typical_ratio / 1000.0).ln().abs() < 1.5);
    let kilo = fit(1.0, 1e-3).unwrap();
    assert!(!kilo.stiffer && kilo.joints.len() >= 4, "{kilo:?}");
}

#[test]
fn absurd_magnitudes_and_no_deflection_are_errors() {
    let setup = paper();
    let data = paper_measurements(&setup);
    let mut bad = data.clone();
    bad[3].displacement.x = 1.5;
    let e = least_squares(setup.arm(), &bad).unwrap_err();
    assert!(
        e.to_string().contains("measurement 4, displacement") && e.to_string().contains("limit"),
        "{e}"
    );
    let mut bad = data.clone();
    bad[2].wrench[2] = -2e6;
    assert!(least_squares(setup.arm(), &bad)
        .unwrap_err()
        .to_string()
        .contains("measurement 3, force"));
    let zero: Vec<Measurement> = data
        .iter()
        .map(|m| Measurement {
            displacement: nalgebra::Vector3::zeros(),
            ..m.clone()
        })
        .collect();
    let e = least_squares(setup.arm(), &zero).unwrap_err();
    assert!(
        e.to_string()
            .contains("every measured displacement is zero"),
        "{e}"
    );
}

#[test]
fn validation_reports_the_share_of_the_deflection_explained() {
    let setup = paper();
    let qs: Vec<_> = PAPER_POSTURES_DEG.iter().map(deg).collect();
    let data = synthetic(&setup, &qs, |_, q| {
        setup.rope_wrench(&setup.robot().frames(q))
    });
    let exact =
        validate::compare(setup.arm(), &setup.model_compliance("test").unwrap(), &data).unwrap();
    assert!((exact.explained - 1.0).abs() < 1e-12);
    let stiffer = validate::compare(
        setup.arm(),
        &Compliance::drives(setup.nominal_compliance().unwrap() / 2.0, None),
        &data,
    )
    .unwrap();
    assert!(
        (stiffer.explained - 0.5).abs() < 1e-12,
        "{}",
        stiffer.explained
    );
    let norms: Vec<f64> = data.iter().map(|m| m.displacement.norm()).collect();
    let rms = (norms.iter().map(|v| v * v).sum::<f64>() / norms.len() as f64).sqrt();
    assert!((stiffer.measured[2] - rms).abs() < 1e-15);
}

/// Every fold is fitted as the full fit: a bounded or robust cross-validation's folds equal the
/// same method refitted by hand without the fold's measurements.
#[test]
fn bounded_and_robust_folds_are_refits_with_the_full_fits_method() {
    use stiffid::internal::identify::Loss;
    let setup = paper();
    let data = noisy_paper_data(&setup, 1, 5);
    let obs = Observations::from_measurements(setup.arm(), &data).unwrap();
    for method in [
        Method::Nonnegative,
        Method::Robust(Loss::Tukey),
        Method::Robust(Loss::Huber),
    ] {
        let full = method.fit(&obs).unwrap();
        let cv = cross_validate(&obs, &full, 3, method).unwrap();
        for fold in &cv.folds {
            let rest: Vec<Measurement> = (0..data.len())
                .filter(|i| !fold.measurements.contains(i))
                .map(|i| data[i].clone())
                .collect();
            let by_hand = method
                .fit(&Observations::from_measurements(setup.arm(), &rest).unwrap())
                .unwrap();
            for j in 0..6 {
                let (a, b) = (fold.stiffness[j], by_hand.stiffness[j]);
                assert!(
                    a == b || ((a - b) / b).abs() < 1e-9,
                    "{method:?} joint {j}: {a} vs {b}"
                );
            }
        }
    }
}

/// Data exact to their rounding (the model's displacements written to 1e-9 mm): the folds move
/// the stiffness by as much as its standard error, both the rounding's, so a threshold of one
/// standard error alone calls postures influential; none is.
#[test]
fn data_exact_to_rounding_have_no_influential_posture() {
    let setup = paper();
    let rounded: Vec<Measurement> = paper_measurements(&setup)
        .into_iter()
        .map(|m| Measurement {
            displacement: m.displacement.map(|d| (d * 1e12).round() / 1e12),
            ..m
        })
        .collect();
    let obs = Observations::from_measurements(setup.arm(), &rounded).unwrap();
    let full = obs.least_squares().unwrap();
    let cv = cross_validate(&obs, &full, 6, Method::LeastSquares).unwrap();
    let se = full.uncertainty.as_ref().unwrap().stiffness_std_error;
    let by_one_se = cv
        .folds
        .iter()
        .any(|f| (0..6).any(|j| (f.stiffness[j] - full.stiffness[j]).abs() > se[j]));
    assert!(
        by_one_se,
        "the rounding moves some stiffness by a standard error"
    );
    assert!(cv.folds.iter().all(|f| f.influential.iter().all(|i| !i)));
    // With the tracker's noise, a threshold of one standard error stands.
    let noisy =
        Observations::from_measurements(setup.arm(), &noisy_paper_data(&setup, 1, 5)).unwrap();
    let full = noisy.least_squares().unwrap();
    let cv = cross_validate(&noisy, &full, 6, Method::LeastSquares).unwrap();
    let se = full.uncertainty.as_ref().unwrap().stiffness_std_error;
    for f in &cv.folds {
        for j in 0..6 {
            let moved = (f.stiffness[j] - full.stiffness[j]).abs() > se[j];
            assert_eq!(f.influential[j], moved);
        }
    }
}
