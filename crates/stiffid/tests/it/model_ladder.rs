//! `calibrate --gravity auto` (the default) on simulated campaigns of a heavy arm (the COMAU
//! preset with link masses, geometric errors in every joint, a tracker with 0.015 mm of noise):
//! the ladder of models, held out over groups of postures, fits the gravity terms where the
//! robot sags under its weight, the geometry alone where it does not, falls back to the geometry
//! on too few postures, and chooses the same with the same readings.

use crate::true_robot::{dh_case, postures, Case, Truth};
use nalgebra::Vector6;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::app::calibrate::{self, GravitySpec, Report};
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::Geometry;

/// The unloaded readings of `n` postures of the true robot of `seed`, its drives rigid with
/// `rigid` (the sag under its weight gone).
fn readings(case: &Case, seed: u64, n: usize, rigid: bool) -> String {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut truth = Truth::new(&case.setup, &mut rng);
    if rigid {
        let columns = truth.model.compliance_columns().unwrap();
        for &c in columns.iter().take(6) {
            truth.estimate.values[c] = 0.0;
        }
    }
    let qs = postures(n, &mut rng, case.angles);
    truth.readings(&qs, &[Vector6::zeros()], &mut rng)
}

fn calibrated(case: &Case, data: &str) -> Report {
    calibrated_as(case, data, GravitySpec::Auto)
}

/// The calibration of `data` with the gravity model `gravity`.
fn calibrated_as(case: &Case, data: &str, gravity: GravitySpec) -> Report {
    calibrated_with(case, data, gravity, Spec::None)
}

/// The calibration of `data` with the gravity model `gravity` and the maps `maps`.
fn calibrated_with(case: &Case, data: &str, gravity: GravitySpec, maps: Spec) -> Report {
    bounded(case, data, (gravity, None), maps)
}

/// [`calibrated_with`] with the bound on the gravity terms `bound` (rad; `None`: the default).
fn bounded(
    case: &Case,
    data: &str,
    (gravity, bound): (GravitySpec, Option<f64>),
    maps: Spec,
) -> Report {
    calibrate::run(&calibrate::Request {
        readings: stiffid::app::readings::Request {
            setup_name: "setup".into(),
            setup: &case.setup,
            name: "fit.csv".into(),
            text: data,
            force: false,
        },
        geometry: Geometry::Full,
        gravity,
        gravity_bound: bound,
        validate: None,
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps,
        error_motions: Default::default(),
        level: None,
        update: false,
        refit: Default::default(),
        weight: None,
        urdf: false,
    })
    .unwrap()
    .report
}

/// The held-out RMS of the ladder's rung of `gravity` (without maps), m.
fn held_out(report: &Report, gravity: Gravity) -> Option<f64> {
    let ladder = report.ladder.as_ref().unwrap();
    (ladder.rungs.iter())
        .find(|r| r.gravity == gravity && !r.maps)
        .and_then(|r| r.rms)
}

#[test]
fn a_robot_that_sags_gets_gravity_terms() {
    let case = dh_case();
    let report = calibrated(&case, &readings(&case, 11, 40, false));
    let ladder = report.ladder.as_ref().unwrap();
    // Five gravity models (the robot gives its link masses), each scored or skipped for a reason.
    assert_eq!(ladder.rungs.len(), 5);
    assert_eq!(ladder.folds, 5);
    assert!(ladder
        .rungs
        .iter()
        .all(|r| r.rms.is_some() != r.skipped.is_some()));
    assert_ne!(report.gravity, Gravity::None, "{ladder:#?}");
    // Postures over the joint ranges determine the gravity terms: the chosen model's predictions
    // over the joint limits spread less than the geometry's, and none is said to extrapolate.
    let spread = |g: Gravity| (ladder.rungs.iter().find(|r| r.gravity == g)).and_then(|r| r.spread);
    assert!(spread(report.gravity).unwrap() < spread(Gravity::None).unwrap());
    assert!(ladder.rungs.iter().all(|r| r.rms.is_some()), "{ladder:#?}");
    assert_eq!(report.gravity, ladder.rungs[ladder.chosen].gravity);
    // The weight's sag is millimetres: the geometry alone misses held out by far more than the
    // chosen model, which predicts to within a few times the tracker's noise.
    let geometry = held_out(&report, Gravity::None).unwrap();
    let chosen = held_out(&report, report.gravity).unwrap();
    assert!(geometry > 5.0 * chosen, "{geometry} against {chosen}");
    assert!(chosen < 1e-4, "{chosen}");
    // The document shows the ladder and the model fitted.
    let document = report.document();
    let shown = document.ladder.as_ref().unwrap();
    assert_eq!(shown.rungs.len(), 5);
    assert_eq!(document.gravity, shown.rungs[shown.chosen].gravity);
    assert!((shown.rungs[0].held_out_rms_mm.unwrap() - geometry * 1e3).abs() < 1e-9);
}

#[test]
fn a_rigid_robot_gets_the_geometry_alone() {
    let case = dh_case();
    let report = calibrated(&case, &readings(&case, 12, 40, true));
    let ladder = report.ladder.as_ref().unwrap();
    assert_eq!(report.gravity, Gravity::None, "{ladder:#?}");
    assert_eq!(ladder.chosen, 0);
    // Nothing left to explain: the geometry predicts held out to the tracker's noise.
    assert!(held_out(&report, Gravity::None).unwrap() < 5e-5);
}

#[test]
fn where_auto_keeps_no_map_the_rungs_with_maps_are_skipped_saying_so() {
    // No joint error in the truth: the choice on every posture keeps none, so no nested figure
    // is made and every rung with maps is the one without.
    let case = dh_case();
    let data = readings(&case, 12, 40, true);
    let report = calibrated_with(&case, &data, GravitySpec::Auto, Spec::Auto);
    let choice = report.maps.choice.as_ref().unwrap();
    assert!(choice.maps.is_none(), "{choice:?}");
    assert!(!choice.tried.is_empty());
    assert!(report.maps.nested.is_none() && report.maps.skipped.is_none());
    let ladder = report.ladder.as_ref().unwrap();
    for r in &ladder.rungs {
        match r.maps {
            true => assert!(r.skipped.as_ref().unwrap().contains("keeps none"), "{r:?}"),
            false => assert!(r.rms.is_some(), "{r:?}"),
        }
    }
    // The same model as without maps, to the last bit.
    let without = calibrated_with(&case, &data, GravitySpec::Auto, Spec::None);
    assert_eq!(report.gravity, without.gravity);
    assert_eq!(report.fit.estimate.values, without.fit.estimate.values);
}

#[test]
fn too_few_postures_fall_back_to_the_geometry() {
    let case = dh_case();
    let report = calibrated(&case, &readings(&case, 13, 8, false));
    let ladder = report.ladder.as_ref().unwrap();
    assert_eq!(report.gravity, Gravity::None);
    assert_eq!(ladder.folds, 0);
    assert_eq!(ladder.rungs.len(), 1);
    assert!(ladder.rungs[0].rms.is_none());
}

#[test]
fn the_same_readings_choose_the_same_model() {
    let case = dh_case();
    let data = readings(&case, 14, 40, false);
    let (a, b) = (calibrated(&case, &data), calibrated(&case, &data));
    assert_eq!(a.ladder, b.ladder);
    assert_eq!(a.gravity, b.gravity);
    assert_eq!(a.fit.estimate.values, b.fit.estimate.values);
}

/// `n` postures of a thin sweep: the axes' ranges of [`postures`], but joints 2 and 3 (those the
/// weight's sag depends on most) within 8 deg.
fn thin(
    n: usize,
    rng: &mut ChaCha8Rng,
    angles: fn(&Vector6<f64>) -> Vector6<f64>,
) -> Vec<Vector6<f64>> {
    use rand_distr::{Distribution, Uniform};
    let lo: [f64; 6] = [-60.0, -20.0, -110.0, -120.0, -80.0, 10.0];
    let hi: [f64; 6] = [60.0, -12.0, -102.0, 120.0, 80.0, 150.0];
    (0..n)
        .map(|_| {
            angles(&Vector6::from_fn(|i, _| {
                Uniform::new(lo[i], hi[i]).unwrap().sample(rng).to_radians()
            }))
        })
        .collect()
}

/// The RMS and largest error (m) of `gravity` fitted to `data` on the held-out readings `held`.
fn validated(case: &Case, data: &str, held: &str, gravity: GravitySpec) -> (f64, f64, Gravity) {
    validated_ladder(case, data, held, gravity).0
}

/// [`validated`] and the ladder climbed.
fn validated_ladder(
    case: &Case,
    data: &str,
    held: &str,
    gravity: GravitySpec,
) -> ((f64, f64, Gravity), Option<calibrate::ladder::Ladder>) {
    let report = calibrate::run(&calibrate::Request {
        readings: stiffid::app::readings::Request {
            setup_name: "setup".into(),
            setup: &case.setup,
            name: "fit.csv".into(),
            text: data,
            force: false,
        },
        geometry: Geometry::Full,
        gravity,
        gravity_bound: None,
        validate: Some(("held.csv".into(), held)),
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps: Spec::None,
        error_motions: Default::default(),
        level: None,
        update: false,
        refit: Default::default(),
        weight: None,
        urdf: false,
    })
    .unwrap();
    let v = &report.validation.as_ref().unwrap().calibrated;
    ((v.rms, v.max, report.gravity), report.report.ladder)
}

/// A campaign whose postures leave the sag's joints a thin sweep (joints 2 and 3 within 8 deg,
/// 30 postures) and held-out postures over the whole range: the three bodies' lumped terms,
/// which the sweep does not determine, spread the predictions over the hull of those postures
/// by more than the geometry's (their bound holds them), and the ladder skips them as
/// extrapolating; the lumped
/// terms fitted when asked for stay within 1.5 times the geometry's held-out error; the
/// default's choice (the robot's masses) stays within twice the geometry's
/// held-out error.
#[test]
fn a_thin_sweep_does_not_blow_up_the_default() {
    let case = dh_case();
    for seed in [21, 22, 23] {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let truth = Truth::new(&case.setup, &mut rng);
        let fit = thin(30, &mut rng, case.angles);
        let wide = postures(40, &mut rng, case.angles);
        let data = truth.readings(&fit, &[Vector6::zeros()], &mut rng);
        let held = truth.readings(&wide, &[Vector6::zeros()], &mut rng);
        let geometry = validated(&case, &data, &held, GravitySpec::Fixed(Gravity::None));
        let (auto, ladder) = validated_ladder(&case, &data, &held, GravitySpec::Auto);
        let lumped = validated(&case, &data, &held, GravitySpec::Fixed(Gravity::Lumped));
        let ladder = ladder.unwrap();
        let rung = |g: Gravity| ladder.rungs.iter().find(|r| r.gravity == g).unwrap();
        let (none, three) = (rung(Gravity::None), rung(Gravity::Lumped));
        println!(
            "seed {seed}: geometry {geometry:.6?} auto {auto:.6?} lumped {lumped:.6?}; spread {:.6?} against {:.6?}, held out {:.6?} against {:.6}",
            three.spread, none.spread, three.rms, none_held(&ladder)
        );
        let why = three.skipped.as_deref().unwrap_or_default();
        assert!(why.starts_with("it extrapolates"), "{ladder:#?}");
        // Within the sweep it beats the geometry held out: only the spread shows it.
        assert!(three.rms.unwrap() < none_held(&ladder), "{ladder:#?}");
        // Over the hull of the thin sweep and the held-out postures its spread and held-out
        // error in quadrature exceed the geometry's, whose spread there is smaller.
        let base = none.spread.unwrap().hypot(none_held(&ladder));
        assert!(three.spread.unwrap() > none.spread.unwrap(), "{ladder:#?}");
        assert!(
            three.spread.unwrap().hypot(three.rms.unwrap()) > base,
            "{ladder:#?}"
        );
        assert!(auto.0 <= 2.0 * geometry.0, "{auto:?} against {geometry:?}");
        // Asked for, the lumped terms (their bound weighed against the residuals' noise) stay
        // within 1.5 times the geometry's held-out error.
        assert!(
            lumped.0 <= 1.5 * geometry.0,
            "{lumped:?} against {geometry:?}"
        );
    }
}

/// The geometry's held-out RMS without maps in `ladder`, m.
fn none_held(ladder: &calibrate::ladder::Ladder) -> f64 {
    (ladder.rungs.iter())
        .find(|r| r.gravity == Gravity::None && !r.maps)
        .and_then(|r| r.rms)
        .unwrap()
}

/// Mirrored readings (the tracker's x negated) fitted anyway (`force`), the maps `auto`: the
/// maps it chose do not survive the final fit (their coefficients leave their range) and are
/// dropped with the reason, the geometry fitted and its misfit said, never an error about a map
/// the user did not ask for.
#[test]
fn forced_mirrored_readings_drop_the_maps_that_fail() {
    let case = dh_case();
    let data = readings(&case, 15, 30, false);
    let mirror = |(i, line): (usize, &str)| {
        let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
        let n = fields.len();
        if i > 0 {
            fields[n - 3] = format!("{:?}", -fields[n - 3].parse::<f64>().unwrap());
        }
        fields.join(",") + "\n"
    };
    let mirrored: String = data.lines().enumerate().map(mirror).collect();
    let report = calibrate::run(&calibrate::Request {
        readings: stiffid::app::readings::Request {
            setup_name: "setup".into(),
            setup: &case.setup,
            name: "fit.csv".into(),
            text: &mirrored,
            force: true,
        },
        geometry: Geometry::Full,
        gravity: GravitySpec::Fixed(Gravity::None),
        gravity_bound: None,
        validate: None,
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps: Spec::Auto,
        error_motions: Default::default(),
        level: None,
        update: false,
        refit: Default::default(),
        weight: None,
        urdf: false,
    })
    .unwrap();
    let why = report.maps.skipped.as_deref().unwrap_or_default();
    assert!(
        why.starts_with("the fit with the maps chosen failed"),
        "{why}"
    );
    assert!(report.model.map_start().is_none());
}

/// A gravity model given is fitted exactly as the ladder fits its rung, with the same bound on
/// its terms: on a robot that sags, the model the default chose (`--maps none`) given by name
/// gives the same fit to 1e-12, at the default bound and at a tenth of it, and the document
/// states the bound used; a tighter bound holds the terms nearer their nominal values. On a
/// robot that does not sag, the readings no longer choose a given model's bound: it is the
/// stated one.
#[test]
fn a_given_gravity_model_is_fitted_as_its_rung() {
    let case = dh_case();
    let data = readings(&case, 15, 40, false);
    let mut sizes = Vec::new();
    for bound in [None, Some(3e-4)] {
        let auto = bounded(&case, &data, (GravitySpec::Auto, bound), Spec::None);
        assert_ne!(auto.gravity, Gravity::None);
        let given = bounded(
            &case,
            &data,
            (GravitySpec::Fixed(auto.gravity), bound),
            Spec::None,
        );
        let apart = (&auto.fit.estimate.values - &given.fit.estimate.values).amax();
        println!("bound {bound:?}: {:?}, apart {apart:e}", auto.gravity);
        assert!(apart <= 1e-12, "{apart:e}");
        assert_eq!(auto.fit.rms, given.fit.rms);
        for report in [&auto, &given] {
            let document = serde_json::to_value(report.document()).unwrap();
            let stated = document["gravity_prior_mrad"].as_f64().unwrap();
            assert!(
                (stated - bound.unwrap_or(3e-3) * 1e3).abs() < 1e-12,
                "{stated}"
            );
        }
        let start = given.model.gravity_start();
        let terms = given.model.gravity().len();
        let moved = &given.fit.estimate.values - given.model.nominal();
        sizes.push(moved.rows(start, terms).norm());
    }
    assert!(sizes[1] < sizes[0], "{sizes:?}");
    let rigid = readings(&case, 15, 40, true);
    let given = calibrated_as(&case, &rigid, GravitySpec::Fixed(Gravity::Lumped));
    assert_eq!(given.gravity_bound, 3e-3);
    assert_eq!(given.fit.gravity_deflection, None);
}
