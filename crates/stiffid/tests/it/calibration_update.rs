//! Across sessions: a calibrated robot checked on another day (`calibrate --update`'s check)
//! and updated from a short check campaign (`select --for check`), on simulated robots whose
//! joint offsets and base drift by known amounts after the calibration.

use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::app::calibrate::{self, Report};
use stiffid::app::readings::Request as Readings;
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::Geometry;
use stiffid::{Robot, Setup};

/// A calibrated robot file: an odd DH table, an error map on joint 2 and the calibration's
/// held-out errors (20, up to 0.06 mm: the 95 % bound is 0.06 mm).
const CALIBRATED: &str = r#"
name = "six (calibrated)"
convention = "standard-dh"
[[joint]]
a_mm = 150.2
alpha_deg = 90.03
d_mm = 450.1
theta_offset_deg = OFF1
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = 600.3
alpha_deg = -0.02
d_mm = 0.4
theta_offset_deg = OFF2
lower_deg = -180
upper_deg = 180
error_map = { cos_deg = [0.01, -0.004], sin_deg = [0.003, 0.002] }
[[joint]]
a_mm = 119.8
alpha_deg = 90.01
d_mm = 0.2
theta_offset_deg = OFF3
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = 0.1
alpha_deg = -89.98
d_mm = 640.2
theta_offset_deg = OFF4
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = -0.1
alpha_deg = 90.02
d_mm = 0.1
theta_offset_deg = OFF5
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = 0
alpha_deg = 0
d_mm = 100
theta_offset_deg = OFF6
lower_deg = -360
upper_deg = 360

[held_out]
source = "validate"
errors_mm = [0.01, 0.012, 0.014, 0.016, 0.018, 0.02, 0.022, 0.024, 0.026, 0.028, 0.03, 0.032, 0.034, 0.036, 0.038, 0.04, 0.045, 0.05, 0.055, 0.06]
"#;

/// The calibrated robot's offsets, deg.
pub(super) const OFFSETS: [f64; 6] = [0.0, -90.0, 0.0, 0.0, 0.0, 0.0];

/// The drift of the offsets after the calibration, deg (joint 1's turns the base about its axis,
/// joint 6's the tool: the tracker and the measuring points take them).
pub(super) const DRIFT: [f64; 6] = [0.03, -0.05, 0.04, 0.02, -0.06, 0.03];

/// The robot file's text with `offsets` (deg).
pub(super) fn robot_text(offsets: &[f64; 6]) -> String {
    let mut text = CALIBRATED.to_string();
    for (i, o) in offsets.iter().enumerate() {
        text = text.replace(&format!("OFF{}", i + 1), &format!("{o:?}"));
    }
    text
}

/// The robot of [`robot_text`].
pub(super) fn robot(offsets: &[f64; 6]) -> Robot {
    stiffid::internal::robot::file::parse(&robot_text(offsets), "calibrated.toml").unwrap()
}

pub(super) fn drifted() -> Robot {
    robot(&std::array::from_fn(|i| OFFSETS[i] + DRIFT[i]))
}

/// The setup of the calibrated robot: three measuring points, a tracker noise of 0.01 mm.
pub(super) fn setup() -> Setup {
    Setup::builder("check", robot(&OFFSETS))
        .with_measuring_points(vec![
            Vector3::new(0.05, 0.0, 0.12),
            Vector3::new(-0.04, 0.05, 0.1),
            Vector3::new(0.0, -0.06, 0.15),
        ])
        .with_loading_point(Vector3::new(0.0, 0.0, 0.15))
        .with_load(stiffid::internal::setup::RopeLoad {
            load: 500.0,
            anchor: Vector3::new(2.0, 1.5, 0.0),
        })
        .with_noise(stiffid::internal::setup::Noise {
            reading_variance: 1e-10,
            levels: vec![1.0],
        })
        .build()
        .unwrap()
}

/// The tracker of the check's day in the base frame (it moved since the calibration, and with
/// it whatever moved the base).
fn tracker() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(2.5, -1.0, 0.4), Vector3::new(0.01, -0.02, 2.0))
}

/// Tracker readings of `truth` at `postures` (labels `prefix1`...), noise `sd` (m) per
/// coordinate.
fn readings(
    truth: &Robot,
    setup: &Setup,
    postures: &[Vector6<f64>],
    prefix: &str,
    sd: f64,
    seed: u64,
) -> String {
    let at = |q: &Vector6<f64>| truth.frames(q);
    readings_by(&at, setup, postures, (prefix, sd, seed))
}

/// [`readings`] of the true robot's frames `frames` at each commanded posture.
pub(super) fn readings_by(
    frames: &dyn Fn(&Vector6<f64>) -> stiffid::Frames,
    setup: &Setup,
    postures: &[Vector6<f64>],
    (prefix, sd, seed): (&str, f64, u64),
) -> String {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, sd.max(1e-300)).unwrap();
    let mut text = String::from(
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm\n",
    );
    for (i, q) in postures.iter().enumerate() {
        let frames = frames(q);
        for (k, p) in setup.tool().measuring_points.iter().enumerate() {
            let b = Point3::from(frames.point(p));
            let mut t = (tracker().inverse() * b).coords;
            if sd > 0.0 {
                t += Vector3::from_fn(|_, _| noise.sample(&mut rng));
            }
            let t = t * 1e3;
            let deg: Vec<String> = q.iter().map(|a| format!("{:?}", a.to_degrees())).collect();
            text += &format!(
                "{prefix}{},{},{},{:?},{:?},{:?}\n",
                i + 1,
                k + 1,
                deg.join(","),
                t.x,
                t.y,
                t.z
            );
        }
    }
    text
}

/// `calibrate --update` of `setup` on `data` (held-out `held`).
fn update(setup: &Setup, data: &str, held: Option<&str>) -> stiffid::Result<Report> {
    calibrate::run(&request(setup, data, held, true)).map(|o| o.report)
}

pub(super) fn request<'a>(
    setup: &'a Setup,
    data: &'a str,
    held: Option<&'a str>,
    update: bool,
) -> calibrate::Request<'a> {
    calibrate::Request {
        readings: Readings {
            setup_name: "setup".into(),
            setup,
            name: "check.csv".into(),
            text: data,
            force: false,
        },
        geometry: Geometry::Full,
        gravity: stiffid::app::calibrate::GravitySpec::Fixed(Gravity::None),
        gravity_bound: None,
        validate: held.map(|h| ("held.csv".to_string(), h)),
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps: Spec::Auto,
        error_motions: Default::default(),
        level: None,
        update,
        refit: Default::default(),
        weight: None,
        urdf: false,
    }
}

/// The check postures `select --for check` designs (10, D-optimal for the update's parameters).
pub(super) fn check_postures(setup: &Setup) -> Vec<Vector6<f64>> {
    use stiffid::app::select;
    let request = select::Request {
        setup,
        criterion: stiffid::internal::design::Criterion::RelativeA,
        purpose: stiffid::app::purpose::Purpose::Check,
        calibration: Default::default(),
        method: select::Method::Global,
        start: None,
        pool: None,
        postures: stiffid::app::purpose::Purpose::Check.default_postures(),
        target_pct: None,
        options: stiffid::internal::design::SearchOptions {
            starts: 4,
            ..Default::default()
        },
        restarts: None,
        distinct: None,
        for_candidates: false,
        candidates: None,
        stations: Vec::new(),
        progress: &(),
        out: None,
        report_dir: None,
    };
    let report = select::run(&request).unwrap();
    let calibration = report.calibration.as_ref().unwrap();
    assert_eq!(calibration.options.geometry, Some(Geometry::Offsets));
    report.report.postures
}

/// Noise-free, the update from the 10 designed postures recovers the drifted robot: the
/// held-out readings of the drifted robot are predicted to 1e-9 mm, joints 2 to 5's offsets
/// move by their drift to 1e-9 deg (joint 1's goes into the tracker, joint 6's into the
/// measuring points), the error map of joint 2 and the DH table stay as the file has them.
#[test]
fn noise_free_drift_is_recovered_by_the_update() {
    let setup = setup();
    let postures = check_postures(&setup);
    assert_eq!(postures.len(), 10);
    let truth = drifted();
    let data = readings(&truth, &setup, &postures, "C", 0.0, 1);
    let held_postures = stiffid::internal::design::random_group(&setup, 20, 7);
    let held = readings(&truth, &setup, &held_postures, "H", 0.0, 2);
    let report = update(&setup, &data, Some(&held)).unwrap();
    let validation = report.validation.as_ref().unwrap();
    assert!(
        validation.calibrated.rms < 1e-12,
        "{:e}",
        validation.calibrated.rms
    );
    // Before the update the drift shows: the calibrated robot misses by more than 0.1 mm.
    assert!(
        validation.nominal.rms > 1e-4,
        "{:e}",
        validation.nominal.rms
    );
    let params = report.model.parameters();
    for (j, drift) in DRIFT.iter().enumerate().take(5).skip(1) {
        let c = params
            .iter()
            .position(|p| p.name == format!("joint{}.theta", j + 1))
            .unwrap();
        let got = report.fit.estimate.values[c].to_degrees();
        assert!((got - drift).abs() < 1e-9, "joint {}: {got}", j + 1);
    }
    assert!(params
        .iter()
        .all(|p| !p.name.contains(".d") && !p.name.contains("map")));
    let file = report.robot_toml.as_ref().unwrap();
    assert!(
        file.contains("error_map = { cos_deg = [0.01, -0.004]"),
        "{file}"
    );
    assert!(file.contains("[held_out]"), "{file}");
    let updated = stiffid::internal::robot::file::parse(file, "updated.toml").unwrap();
    assert!(updated
        .name()
        .ends_with(stiffid::internal::robot::CALIBRATED));
    // The drift verdict on the drifted robot.
    let check = report.check.as_ref().unwrap();
    assert!(check.drifted);
    assert_eq!(check.bound, 0.06e-3);
}

/// With 0.01 mm of tracker noise, the check says the undrifted robot did not drift beyond its
/// intervals and the drifted one did, and the document states the verdict with the share outside.
#[test]
fn the_check_tells_a_drifted_robot_from_an_undrifted_one() {
    let setup = setup();
    let postures = stiffid::internal::design::random_group(&setup, 10, 3);
    for (truth, drifted) in [(robot(&OFFSETS), false), (self::drifted(), true)] {
        let data = readings(&truth, &setup, &postures, "C", 1e-5, 4);
        let report = update(&setup, &data, None).unwrap();
        let check = report.check.as_ref().unwrap();
        assert_eq!(check.drifted, drifted);
        let document = report.document();
        let c = document.check.as_ref().unwrap();
        assert_eq!(c.readings, 30);
        assert_eq!(c.drifted, drifted);
        match drifted {
            true => assert!(c.share_outside > 0.5, "{}", c.share_outside),
            false => assert!(c.outside <= c.allowed, "{} > {}", c.outside, c.allowed),
        }
    }
}

/// An update without a calibrated robot file or from too few postures is refused naming
/// `update`; a level without held-out readings or update is refused; `select --for check`
/// refuses a geometry of its own.
#[test]
fn an_update_refuses_what_it_cannot_do() {
    let setup = setup();
    let postures = stiffid::internal::design::random_group(&setup, 10, 3);
    let data = readings(&drifted(), &setup, &postures, "C", 0.0, 1);
    let plain = robot_text(&OFFSETS).replace(" (calibrated)", "");
    let plain = stiffid::internal::robot::file::parse(&plain, "nominal.toml").unwrap();
    let nominal = setup.to_builder().with_robot(plain).build().unwrap();
    let e = update(&nominal, &data, None).unwrap_err().to_string();
    assert!(
        e.starts_with("update") && e.contains("not a calibrated robot file"),
        "{e}"
    );
    let few = readings(&drifted(), &setup, &postures[..4], "C", 0.0, 1);
    let e = update(&setup, &few, None).unwrap_err().to_string();
    assert!(
        e.starts_with("update") && e.contains("at least 5 check postures"),
        "{e}"
    );
    // Without update, a level needs held-out readings.
    let level = calibrate::Request {
        level: Some(0.9),
        ..request(&setup, &data, None, false)
    };
    assert!(calibrate::run(&level)
        .unwrap_err()
        .to_string()
        .starts_with("level"));
    let options = stiffid::app::purpose::CalibrationOptions {
        geometry: Some(Geometry::Full),
        ..Default::default()
    };
    let e = stiffid::app::purpose::check(stiffid::app::purpose::Purpose::Check, &options)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("geometry") && e.contains("check"), "{e}");
}

/// Mirrored readings (the tracker's x negated) are refused as a mirror image before any model
/// is fitted: the job begins no fit, for a calibration and an update alike (it used to climb
/// the models' ladder first, about half a minute, and could stop on a joint map's coefficients
/// the readings had never asked for).
#[test]
fn mirrored_readings_are_refused_before_any_fit() {
    struct Stages(std::sync::Mutex<Vec<String>>);
    impl stiffid::Progress for Stages {
        fn begin(&self, what: &str, _total: usize) {
            self.0.lock().unwrap().push(what.to_string());
        }
    }
    let setup = setup();
    let postures = stiffid::internal::design::random_group(&setup, 30, 3);
    let data = readings(&drifted(), &setup, &postures, "C", 1e-5, 1);
    let mirror = |(i, line): (usize, &str)| {
        let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
        let n = fields.len();
        if i > 0 {
            fields[n - 3] = format!("{:?}", -fields[n - 3].parse::<f64>().unwrap());
        }
        fields.join(",") + "\n"
    };
    let mirrored: String = data.lines().enumerate().map(mirror).collect();
    for update in [false, true] {
        let stages = Stages(Default::default());
        let request = calibrate::Request {
            progress: &stages,
            ..request(&setup, &mirrored, None, update)
        };
        let e = calibrate::run(&request).unwrap_err().to_string();
        assert!(
            e.starts_with("check.csv: readings: the tracker's readings are a mirror image"),
            "{e}"
        );
        assert!(stages.0.lock().unwrap().is_empty(), "update {update}");
    }
}

/// The figure of the guide: on the drifted robot, with 0.01 mm of tracker noise, over five
/// seeded draws, the held-out RMS error on 200 random postures of the calibrated robot as it
/// is (no update, the tracker registered on the held-out readings), updated from the 10
/// designed check postures, and recalibrated in full (`--geometry full`) from 50 random
/// postures: the update recovers at least 95 % of the full recalibration's gain in every draw,
/// and the check finds the robot drifted in every draw.
#[test]
fn the_update_recovers_the_gain_of_a_full_recalibration() {
    let setup = setup();
    let truth = drifted();
    let check = check_postures(&setup);
    let full_postures = stiffid::internal::design::random_group(&setup, 50, 11);
    let held_postures = stiffid::internal::design::random_group(&setup, 200, 12);
    let mut figures = Vec::new();
    for draw in 0..5 {
        let seed = 100 + 10 * draw;
        let held = readings(&truth, &setup, &held_postures, "H", 1e-5, seed);
        let data = readings(&truth, &setup, &check, "C", 1e-5, seed + 1);
        let updated = update(&setup, &data, Some(&held)).unwrap();
        assert!(updated.check.as_ref().unwrap().drifted);
        let full_data = readings(&truth, &setup, &full_postures, "F", 1e-5, seed + 2);
        let full = calibrate::Request {
            maps: Spec::None,
            ..request(&setup, &full_data, Some(&held), false)
        };
        let full = calibrate::run(&full).unwrap();
        let (u, f) = (
            updated.validation.as_ref().unwrap(),
            full.validation.as_ref().unwrap(),
        );
        let (none, update, full) = (u.nominal.rms, u.calibrated.rms, f.calibrated.rms);
        let recovered = (none - update) / (none - full);
        figures.push((none * 1e3, update * 1e3, full * 1e3, recovered));
        assert!(recovered > 0.95, "draw {draw}: {figures:?}");
    }
    eprintln!("held-out RMS mm (none, update, full, share of the gain): {figures:?}");
}

/// An update whose check campaign reads no reflectors keeps the part its calibrated robot file
/// located (`[part]`), with a warning that says how to locate it again; it never drops it.
#[test]
fn an_update_without_reflectors_keeps_the_located_part() {
    let part = "\n[part]\nxyz_mm = [1200.0, -300.0, 400.0]\nrpy_deg = [0.0, 0.0, 30.0]\n";
    let robot =
        stiffid::internal::robot::file::parse(&(robot_text(&OFFSETS) + part), "calibrated.toml")
            .unwrap();
    let located = *robot.part().unwrap();
    let setup = setup().to_builder().with_robot(robot).build().unwrap();
    let postures = stiffid::internal::design::random_group(&setup, 10, 3);
    let data = readings(&drifted(), &setup, &postures, "C", 0.0, 4);
    let report = update(&setup, &data, None).unwrap();
    let file = report.robot_toml.as_ref().unwrap();
    let updated = stiffid::internal::robot::file::parse(file, "updated.toml").unwrap();
    let kept = updated.part().expect("the updated file keeps [part]");
    assert!((kept.translation.vector - located.translation.vector).norm() < 1e-12);
    assert!(kept.rotation.angle_to(&located.rotation) < 1e-12);
    assert!(report
        .warnings
        .iter()
        .any(|w| w.message.contains("keeps the part")));
}
