//! The error model and its fit: the identification Jacobian against central differences,
//! noise-free recovery of the geometry (DH, URDF) and of the gravity terms, calibrated robot files
//! that reproduce the positions, standard deviations against Monte Carlo, the fit's stop reason;
//! and the simulated campaigns (postures, points, tracker, readings) the other modules share.

use super::error_model::{MeasuredIn, Observation};
use super::fit::{self, Options};
use super::gravity::{self, LinkMass};
use super::*;
use nalgebra::{DVector, Isometry3, Point3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid_core::common::stop::Stop;
use stiffid_core::robot::{presets, urdf};
use stiffid_core::Robot;

/// `n` postures drawn in the middle 60% of the robot's joint ranges (at most +-150 deg).
pub(super) fn postures(robot: &Robot, n: usize, seed: u64) -> Vec<Vector6<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let l = robot.limits();
    (0..n)
        .map(|_| {
            Vector6::from_fn(|i, _| {
                let (lo, hi) = (l.lower[i].max(-2.6), l.upper[i].min(2.6));
                let mid = 0.5 * (lo + hi);
                mid + 0.6 * (hi - lo) * (rng.random::<f64>() - 0.5)
            })
        })
        .collect()
}

pub(super) fn points() -> Vec<Vector3<f64>> {
    vec![
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ]
}

pub(super) fn tracker() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.2, -1.1, 0.4), Vector3::new(0.1, -0.05, 2.4))
}

/// Every point read at every posture: the readings of `truth` (tracker frame), noise-free.
pub(super) fn readings(
    model: &ErrorModel,
    truth: &Estimate,
    qs: &[Vector6<f64>],
) -> Vec<Observation> {
    let at: Vec<_> = (qs.iter().enumerate())
        .flat_map(|(i, q)| (0..model.points()).map(move |k| (i, *q, k)))
        .collect();
    let pairs: Vec<_> = at.iter().map(|(_, q, k)| (*q, *k)).collect();
    let b = model.positions(&truth.values, &pairs).unwrap();
    (at.iter().zip(b))
        .map(|((i, q, k), b)| Observation {
            posture: *i,
            point: *k,
            q: *q,
            measured: (truth.frame.inverse() * Point3::from(b)).coords,
            wrench: Vector6::zeros(),
            e: stiffid_core::robot::external::ExternalValues::NONE,
            table: false,
            direction: Vector6::zeros(),
        })
        .collect()
}

/// A typical error of parameter `p` (SI): 1 mm, 1 mrad, gravity terms as given.
fn typical(model: &ErrorModel, c: usize, gravity: f64) -> f64 {
    match model.parameters()[c].target {
        Target::Frame(a) if a >= 3 => 1e-3,
        Target::Joint { component, .. } if component.is_angle() => 1e-3,
        Target::Gravity(_) => gravity,
        _ => 1e-3,
    }
}

fn perturbed(model: &ErrorModel, seed: u64, only: Option<&[usize]>, gravity: f64) -> DVector<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut x = model.nominal();
    for c in 0..x.len() {
        let draw = typical(model, c, gravity) * (2.0 * rng.random::<f64>() - 1.0);
        if only.is_none_or(|o| o.contains(&c)) {
            x[c] += draw;
        }
    }
    x
}

/// The UR10 (standard DH, Universal Robots' published table): joints 2, 3 and 4 parallel.
pub(super) fn ur10() -> Robot {
    use stiffid_core::robot::dh::{self, Convention, Row};
    let half = std::f64::consts::FRAC_PI_2;
    let rows = [
        (0.0, half, 0.1273),
        (-0.612, 0.0, 0.0),
        (-0.5723, 0.0, 0.0),
        (0.0, half, 0.163941),
        (0.0, -half, 0.1157),
        (0.0, 0.0, 0.0922),
    ];
    let joints = rows.map(|(a, alpha, d)| {
        dh::joint(
            Convention::StandardDh,
            &Row {
                a,
                alpha,
                d,
                theta_offset: 0.0,
            },
        )
    });
    let limits =
        stiffid_core::common::limits::JointBox::new(Vector6::repeat(-6.0), Vector6::repeat(6.0));
    Robot::new("UR10", "Universal Robots DH table", joints, limits).unwrap()
}

fn fanuc() -> Robot {
    presets::get("fanuc-r2000ic-165f").unwrap()
}

pub(super) fn masses() -> [LinkMass; 6] {
    let m = |mass: f64, x: f64, y: f64, z: f64| LinkMass {
        mass,
        centre: Vector3::new(x, y, z),
        ..LinkMass::default()
    };
    [
        m(300.0, 0.1, 0.0, -0.2),
        m(120.0, 0.5, 0.0, 0.1),
        m(90.0, 0.1, 0.05, 0.3),
        m(40.0, 0.0, 0.02, -0.4),
        m(15.0, 0.0, 0.0, 0.05),
        m(60.0, 0.02, 0.01, 0.15),
    ]
}

#[test]
fn identification_jacobian_matches_central_differences() {
    let robot = fanuc();
    for g in [
        gravity::Terms::lumped(&robot, stiffid_core::Coordinates::Axis),
        gravity::Terms::masses(
            &robot,
            masses(),
            stiffid_core::Coordinates::Kinematic,
            Vector6::zeros(),
        )
        .unwrap(),
    ] {
        let model =
            ErrorModel::new(&robot, &points(), MeasuredIn::Tracker, Geometry::Full, g).unwrap();
        let mut x = perturbed(&model, 3, None, 2e-6);
        x.rows_mut(0, 6).fill(0.0);
        let at: Vec<_> = postures(&robot, 4, 9)
            .into_iter()
            .enumerate()
            .map(|(i, q)| (q, i % 3))
            .collect();
        let j = model.jacobian(&x, &at).unwrap();
        matches_central_differences(&model, &x, &j, |v| model.positions(v, &at).unwrap());
    }
}

/// Every column of `j` against the central differences of the positions `b` at `x`, to 1e-7
/// relative.
pub(super) fn matches_central_differences(
    model: &ErrorModel,
    x: &DVector<f64>,
    j: &nalgebra::DMatrix<f64>,
    b: impl Fn(&DVector<f64>) -> Vec<Vector3<f64>>,
) {
    for c in 0..x.len() {
        let h = 1e-6 / j.column(c).amax().max(1e-3);
        let (mut plus, mut minus) = (x.clone(), x.clone());
        plus[c] += h;
        minus[c] -= h;
        for (r, (p, m)) in b(&plus).iter().zip(&b(&minus)).enumerate() {
            let fd = (p - m) / (2.0 * h);
            let analytic = j.fixed_view::<3, 1>(3 * r, c).into_owned();
            let scale = analytic.norm().max(fd.norm()).max(1e-3);
            assert!(
                (fd - analytic).norm() < 1e-7 * scale,
                "{} row {r}: {fd:?} vs {analytic:?}",
                model.parameters()[c].name
            );
        }
    }
}

/// Fits noise-free readings of errors in every identifiable parameter and checks each against
/// its true value; returns the model's identifiability for the caller's checks of the merged.
fn recovers(
    model: &ErrorModel,
    qs: &[Vector6<f64>],
    gravity: f64,
) -> identifiability::Identifiability {
    let nominal = Estimate {
        frame: Isometry3::identity(),
        values: model.nominal(),
    };
    let probe = readings(model, &nominal, qs);
    let start0 = fit::start(model, &probe).unwrap();
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let found = fit::fit(model, &probe, &start0, &options).unwrap();
    let identified = found.identifiability.identified.clone();
    let truth = Estimate {
        frame: tracker(),
        values: {
            let mut x = perturbed(model, 5, Some(&identified), gravity);
            x.rows_mut(0, 6).fill(0.0);
            x
        },
    };
    let data = readings(model, &truth, qs);
    let start = fit::start(model, &data).unwrap();
    let result = fit::fit(model, &data, &start, &options).unwrap();
    assert!(result.rms < 1e-11, "rms {}", result.rms);
    for &c in &identified {
        let p = &model.parameters()[c];
        if matches!(p.target, Target::Frame(_)) {
            continue;
        }
        let (got, want) = (result.estimate.values[c], truth.values[c]);
        let size = (want - p.nominal)
            .abs()
            .max(typical(model, c, gravity) * 1e-3);
        assert!(
            (got - want).abs() <= 1e-9 * size.max(want.abs()),
            "{}: {got:e} vs {want:e}",
            p.name
        );
    }
    let frame = result.estimate.frame;
    assert!((frame.translation.vector - tracker().translation.vector).norm() < 1e-12);
    assert!(frame.rotation.angle_to(&tracker().rotation) < 1e-12);
    result.identifiability
}

fn merged_names(model: &ErrorModel, id: &identifiability::Identifiability) -> Vec<String> {
    (id.merged.iter())
        .map(|m| model.parameters()[m.parameter].name.clone())
        .collect()
}

#[test]
fn fanuc_geometry_recovered_and_merged_named() {
    let robot = fanuc();
    let model = ErrorModel::new(
        &robot,
        &points(),
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )
    .unwrap();
    let id = recovers(&model, &postures(&robot, 30, 1), 0.0);
    // A complete minimal model of a 6R arm read at 3 points: 4 * 6 + 3 * 3 (tracker 6, joints
    // 2-5 four each, joint 6 two, the points).
    assert_eq!(id.rank, 33);
    let merged = merged_names(&model, &id);
    for name in [
        "joint1.theta",
        "joint1.d",
        "joint1.a",
        "joint1.alpha",
        "joint1.beta",
        "joint1.b",
        "joint6.theta",
        "joint6.d",
    ] {
        assert!(merged.contains(&name.to_string()), "{name} in {merged:?}");
    }
    // Joints 2 and 3 are parallel: one of their d errors merges, joint 3's beta is kept.
    assert!(merged.contains(&"joint2.d".into()) != merged.contains(&"joint3.d".into()));
    let beta3 = model
        .parameters()
        .iter()
        .position(|p| p.name == "joint3.beta");
    assert!(id.identified.contains(&beta3.unwrap()));
    // joint1.theta merges into the tracker's rotation about z.
    let theta1 = id
        .merged
        .iter()
        .find(|m| model.parameters()[m.parameter].name == "joint1.theta");
    let into = &theta1.unwrap().into;
    assert_eq!(model.parameters()[into[0].0].name, "tracker.rz");
}

#[test]
fn urdf_geometry_recovered() {
    let text = include_str!("../../../data/comau-nj165.urdf");
    let robot = urdf::parse(text, "comau-nj165.urdf", None).unwrap();
    let model = ErrorModel::new(
        &robot,
        &points()[..2],
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )
    .unwrap();
    let id = recovers(&model, &postures(&robot, 30, 2), 0.0);
    assert_eq!(id.rank, 24 + 6);
    let merged = merged_names(&model, &id);
    assert!(merged.contains(&"joint1.theta".to_string()));
}

#[test]
fn gravity_compliances_recovered_with_known_masses() {
    let robot = fanuc();
    let g = gravity::Terms::masses(
        &robot,
        masses(),
        stiffid_core::Coordinates::Axis,
        Vector6::zeros(),
    )
    .unwrap();
    let model = ErrorModel::new(&robot, &points(), MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    let id = recovers(&model, &postures(&robot, 40, 3), 5e-6);
    let merged = merged_names(&model, &id);
    // Joint 1 is vertical: gravity exerts no torque about it.
    assert!(merged.contains(&"gravity.c1".to_string()), "{merged:?}");
    for c in 2..=5 {
        assert!(!merged.contains(&format!("gravity.c{c}")), "{merged:?}");
    }
}

#[test]
fn gravity_lumped_recovered() {
    let robot = fanuc();
    let g = gravity::Terms::lumped(&robot, stiffid_core::Coordinates::Axis);
    let model =
        ErrorModel::new(&robot, &points(), MeasuredIn::Tracker, Geometry::Offsets, g).unwrap();
    let id = recovers(&model, &postures(&robot, 60, 4), 5e-5);
    assert!(id.rank > 6 + 9 + 6);
}

/// The three bodies' lumped terms with full geometry on the FANUC preset (kinematic springs):
/// recovered, and 17 products kept (model.md, section 7): joint 1 (vertical) and the moments
/// along the axes merge; the arm's six (`c2` times the upper arm's and the forearm's two moments
/// in their plane, `c3` times the forearm's two) are among them.
#[test]
fn gravity_lumped_bodies_recovered() {
    let robot = fanuc();
    let g = gravity::Terms::of(
        &robot,
        gravity::Gravity::Lumped,
        stiffid_core::Coordinates::Kinematic,
        Vector6::zeros(),
    )
    .unwrap();
    let model = ErrorModel::new(&robot, &points(), MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    let id = recovers(&model, &postures(&robot, 40, 4), 5e-5);
    let kept: Vec<&str> = (id.identified.iter())
        .map(|&c| model.parameters()[c].name.as_str())
        .filter(|n| n.starts_with("gravity."))
        .collect();
    assert_eq!(kept.len(), 17, "{kept:?}");
    assert!(
        !kept.iter().any(|n| n.starts_with("gravity.c1.")),
        "{kept:?}"
    );
    assert_eq!(id.rank, 33 + 17);
}

/// The written robot files reproduce the model's positions at the fitted values (every joint
/// error, the lateral `b` too) at the same axis angles, the robot TOML and the URDF agree to
/// 1e-9 mm, a robot whose axis map couples axes has no URDF (and says why), and a calibrated
/// robot file calibrates again: its own calibration's files reproduce it.
#[test]
fn calibrated_robot_files_reproduce_positions() {
    // A controller's world away from the base frame (a FANUC's at the height of axis 2, turned):
    // the calibrated files carry it; a URDF's as ROS-Industrial's `base` link.
    let world = Isometry3::new(
        Vector3::new(0.01, -0.02, 0.675),
        Vector3::new(0.0, 0.0, 1.0),
    );
    let base = format!(
        "<link name=\"base\"/><joint name=\"base_link-base\" type=\"fixed\"><parent link=\"world\"/><child link=\"base\"/>{}</joint></robot>",
        stiffid_core::robot::urdf_write::origin_xml(&world)
    );
    let text = include_str!("../../../data/comau-nj165.urdf").replace("</robot>", &base);
    let urdf_robot = urdf::parse(&text, "comau-nj165.urdf", None).unwrap();
    let robots = [
        fanuc(),
        presets::get("comau-smart5-nj165-3.0").unwrap(),
        presets::get("kuka-kr210-robond").unwrap(),
        ur10(),
        urdf_robot,
    ];
    let robots = robots.map(|r| r.with_controller_world(world).unwrap());
    for (n, robot) in robots.iter().enumerate() {
        for measured_in in [MeasuredIn::Tracker, MeasuredIn::Base] {
            let mut robot = robot.clone();
            for round in 0..2 {
                let toml = calibrated_files_agree(&robot, measured_in, 11 + round, n);
                robot = stiffid_core::robot::file::parse(&toml, "calibrated.toml").unwrap();
            }
        }
    }
}

/// Calibrates `robot` (errors of seed `seed`), checks its files (the test above) and returns
/// the robot TOML.
fn calibrated_files_agree(robot: &Robot, measured_in: MeasuredIn, seed: u64, n: usize) -> String {
    let model = ErrorModel::new(
        robot,
        &points(),
        measured_in,
        Geometry::Full,
        gravity::Terms::none(robot),
    )
    .unwrap();
    let estimate = Estimate {
        frame: tracker(),
        values: perturbed(&model, seed, None, 0.0),
    }
    .recentre();
    let qs = postures(robot, 5, 12);
    let at: Vec<_> = qs.iter().map(|q| (*q, 1)).collect();
    let want: Vec<Vector3<f64>> = match measured_in {
        MeasuredIn::Tracker => model.positions(&estimate.values, &at).unwrap(),
        // Base-frame readings: the calibrated robot predicts the readings `T^-1 b`.
        MeasuredIn::Base => (model.positions(&estimate.values, &at).unwrap().iter())
            .map(|b| (estimate.frame.inverse() * Point3::from(*b)).coords)
            .collect(),
    };
    let c = model.point(&estimate.values, 1);
    let toml = robot_file::robot_toml(&model, &estimate).unwrap();
    let from_toml = stiffid_core::robot::file::parse(&toml, "out.toml").unwrap();
    let same_limits = |written: &Robot| {
        let (a, b) = (written.limits(), robot.limits());
        let close = |x: f64, y: f64| x == y || (x - y).abs() < 1e-12;
        assert!(
            (0..6).all(|i| close(a.lower[i], b.lower[i]) && close(a.upper[i], b.upper[i])),
            "robot {n}: {a:?} vs {b:?}"
        );
    };
    same_limits(&from_toml);
    let urdf_text = robot_file::urdf(&model, &estimate, &Isometry3::identity());
    let coupled = robot.axis_map().matrix.map(|v| (v != 0.0) as u8).sum() > 6;
    match &urdf_text {
        Err(e) => assert!(
            coupled && e.to_string().contains("axis map") && e.to_string().contains("--out"),
            "robot {n}: {e}"
        ),
        Ok(_) => assert!(!coupled, "robot {n}: a URDF of a coupled axis map"),
    }
    let from_urdf = urdf_text
        .ok()
        .map(|t| urdf::parse(&t, "out.urdf", None).unwrap());
    for ((q, _), w) in at.iter().zip(&want) {
        let got = from_toml.frames(q).point(&c);
        assert!((got - w).norm() < 1e-11, "robot {n} toml: {got:?} vs {w:?}");
        if let Some(u) = &from_urdf {
            let other = u.frames(q).point(&c);
            assert!(
                (other - got).norm() < 1e-12,
                "robot {n} urdf: {other:?} vs {got:?}"
            );
        }
    }
    from_urdf.iter().for_each(same_limits);
    for written in [Some(&from_toml), from_urdf.as_ref()].into_iter().flatten() {
        let (a, b) = (written.controller_world(), robot.controller_world());
        assert!(
            (a.translation.vector - b.translation.vector).norm() < 1e-12
                && a.rotation.angle_to(&b.rotation) < 1e-12,
            "robot {n}: controller world {a} vs {b}"
        );
    }
    toml
}

/// The standard deviations of the fit agree with a 500-run Monte Carlo of noisy readings
/// (within 10%), for every identified joint offset and point coordinate.
#[test]
fn standard_deviations_match_monte_carlo() {
    use rand_distr::{Distribution, Normal};
    let robot = fanuc();
    let model = ErrorModel::new(
        &robot,
        &points()[..2],
        MeasuredIn::Tracker,
        Geometry::Offsets,
        gravity::Terms::none(&robot),
    )
    .unwrap();
    let truth = Estimate {
        frame: tracker(),
        values: model.nominal(),
    };
    let clean = readings(&model, &truth, &postures(&robot, 15, 21));
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let noise = Normal::new(0.0, 5e-5).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let runs = 500;
    let n = model.parameters().len();
    let (mut sum, mut sum2, mut sd_sum) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut fitted = Vec::new();
    for _ in 0..runs {
        let noisy: Vec<Observation> = (clean.iter())
            .map(|o| Observation {
                measured: o.measured + Vector3::from_fn(|_, _| noise.sample(&mut rng)),
                ..o.clone()
            })
            .collect();
        let start = fit::start(&model, &noisy).unwrap();
        let f = fit::fit(&model, &noisy, &start, &options).unwrap();
        fitted = f.fitted.clone();
        for &c in &f.fitted {
            let v = f.estimate.values[c];
            sum[c] += v;
            sum2[c] += v * v;
            sd_sum[c] += f.sd[c].unwrap();
        }
    }
    let mut checked = 0;
    for &c in &fitted {
        if matches!(model.parameters()[c].target, Target::Frame(_)) {
            continue;
        }
        let mean = sum[c] / runs as f64;
        let empirical =
            ((sum2[c] / runs as f64 - mean * mean) * runs as f64 / (runs - 1) as f64).sqrt();
        let predicted = sd_sum[c] / runs as f64;
        assert!(
            (empirical / predicted - 1.0).abs() < 0.1,
            "{}: Monte Carlo {empirical:e}, fit {predicted:e}",
            model.parameters()[c].name
        );
        checked += 1;
    }
    assert!(checked >= 6 + 4, "{checked}");
}

#[test]
fn the_fit_says_why_it_stopped_and_warns_at_its_iteration_limit() {
    let robot = ur10();
    let model = ErrorModel::new(
        &robot,
        &points()[..2],
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )
    .unwrap();
    let truth = Estimate {
        frame: tracker(),
        values: perturbed(&model, 3, None, 0.0),
    };
    let data = readings(&model, &truth, &postures(&robot, 20, 4));
    let start = fit::start(&model, &data).unwrap();
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    // One step from the registered nominal leaves the 1 mm errors partly unfitted.
    let cut = fit::fit_within(&model, &data, &start, &options, 1).unwrap();
    assert_eq!(cut.stop, Stop::IterationLimit);
    assert_eq!(cut.iterations, 1);
    let warning = fit::stop_warning(cut.stop, cut.iterations).unwrap();
    assert_eq!(
        warning.kind,
        stiffid_core::common::warning::WarningKind::NotConverged
    );
    assert!(
        warning.message.contains("limit of 1 iterations"),
        "{}",
        warning.message
    );
    // Left to its limit, the noise-free fit reaches the readings and stops at a minimum.
    let done = fit::fit(&model, &data, &start, &options).unwrap();
    assert!(
        done.rms < 1e-11 && cut.rms > 1e3 * done.rms.max(1e-15),
        "{} {}",
        cut.rms,
        done.rms
    );
    assert_eq!(done.stop, Stop::Converged);
    assert!(done.iterations < fit::MAX_ITERATIONS);
    assert_eq!(fit::stop_warning(done.stop, done.iterations), None);
}

/// A robot calibrated on a mount (the setup's `[robot_base]`: 500 mm up, turned), read from a
/// URDF or not: a URDF cannot record the mount apart from the robot (a URDF robot's own document
/// keeps its root link and meshes at the foot; a generated one would carry the mount in its first
/// joint but not in the controller's world), and a setup reading a calibrated robot does not
/// mount it again: refused, saying to use the robot file, which records it. Without a mount it
/// is written.
#[test]
fn a_robot_calibrated_on_a_mount_has_no_urdf() {
    let text = include_str!("../../../data/comau-nj165.urdf");
    let foot = urdf::parse(text, "comau-nj165.urdf", None).unwrap();
    let preset = presets::get("kuka-kr210-robond").unwrap();
    let mount = Isometry3::new(Vector3::new(0.1, -0.05, 0.5), Vector3::new(0.0, 0.0, 0.5));
    for nominal in [foot, preset] {
        for on_mount in [false, true] {
            let base = match on_mount {
                true => mount * nominal.base(),
                false => *nominal.base(),
            };
            let robot = nominal.clone().with_base(base).unwrap();
            let terms = gravity::Terms::none(&robot);
            let model = ErrorModel::new(
                &robot,
                &points(),
                MeasuredIn::Tracker,
                Geometry::Full,
                terms,
            )
            .unwrap();
            let estimate = Estimate {
                frame: tracker(),
                values: perturbed(&model, 3, None, 0.0),
            }
            .recentre();
            let given = if on_mount {
                mount
            } else {
                Isometry3::identity()
            };
            match (robot_file::urdf(&model, &estimate, &given), on_mount) {
                (Ok(_), false) => {}
                (Err(e), true) => assert!(
                    e.to_string()
                        .contains("calibrated on a mount (xyz_mm = [100, -50, 500]")
                        && e.to_string().contains("--out"),
                    "{e}"
                ),
                (other, _) => panic!("{} on a mount {on_mount}: {other:?}", nominal.name()),
            }
            // The robot file holds the mount: its flange is the mounted robot's.
            let toml = robot_file::robot_toml(&model, &estimate).unwrap();
            let from_toml = stiffid_core::robot::file::parse(&toml, "out.toml").unwrap();
            let q = Vector6::new(0.1, 0.2, -0.3, 0.4, 0.5, 0.6);
            let at = from_toml.frames(&q).flange.translation.vector;
            let want = model.robot().frames(&q).flange.translation.vector;
            assert!((at - want).norm() < 0.05, "{at} vs {want}");
        }
    }
}
