//! The scenes of a calibration, an identification and a compensation in a cell with a track and
//! a tilt-rotate positioner (examples/track/track-cell.toml): each posture drawn at the external
//! values its readings, measurements or path points carry, every joint position equal to the
//! kinematics job's with those values to 1e-9 mm, and the scene drawn again from the document
//! alone (as Python draws it) equal to the command's. A box the positioner carries is drawn
//! where each posture's values put it.

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::document::scene::Scene;
use stiffid::app::measurements::Data;
use stiffid::app::{calibrate, compensate, identify, kinematics};
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::Geometry;
use stiffid::internal::observation::Measurement;
use stiffid::internal::robot::external::ExternalValues;
use stiffid::internal::robot::kinematics::Coordinates;
use stiffid::Setup;

use crate::carried_obstacles::{track_cell as track_cell_with, turn, PLATE};

fn track_cell() -> Setup {
    let text = include_str!("../../../../examples/track/track-cell.toml");
    stiffid::internal::setup::parse(text, "track-cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

/// `n` postures of the cell's arm (seeded) and a station per posture along the rail with the
/// table tilted and turned (SI).
fn postures(setup: &Setup, n: usize) -> (Vec<Vector6<f64>>, Vec<Vec<f64>>) {
    let q = stiffid::internal::design::random_group(&setup.without_cell(), n, 17);
    let e = (0..n)
        .map(|i| {
            let k = i as f64;
            vec![
                0.4 + 0.45 * k,
                (-40.0 + 7.0 * k).to_radians(),
                (25.0 * k - 120.0).to_radians(),
            ]
        })
        .collect();
    (q, e)
}

/// Every posture of `scene` stands at `q` and `e`: its external values, joint positions and
/// TCP those of the kinematics job at the same values (1e-9 mm).
fn assert_at_kinematics(setup: &Setup, scene: &Scene, q: &[Vector6<f64>], e: &[Vec<f64>]) {
    assert_eq!(scene.postures.len(), q.len());
    for ((p, q), e) in scene.postures.iter().zip(q).zip(e) {
        for (got, want) in p.external.iter().zip(e) {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
        assert_eq!(p.external.len(), e.len());
        let report = kinematics::run(&kinematics::Request {
            robot: setup.robot(),
            q: *q,
            point: setup.tool().tcp,
            characteristic_length: Some(1.2),
            coordinates: Coordinates::Axis,
            stiffness: None,
            external: e.clone(),
            workpiece: None,
        })
        .unwrap();
        let doc = report.document();
        for j in 0..6 {
            let got = Vector3::from(p.joint_positions_m[j]) * 1e3;
            let want = Vector3::from(doc.joint_positions_mm[j]);
            assert!((got - want).norm() < 1e-9, "joint {j}: {got} vs {want}");
        }
        let tcp = Vector3::from(p.tcp_m) * 1e3;
        assert!((tcp - Vector3::from(doc.point_position_mm)).norm() < 1e-9);
    }
}

/// The readings of the cell's measuring points (cell frame, as the tracker's at the identity)
/// at each posture and station, noise-free.
fn readings(setup: &Setup, q: &[Vector6<f64>], e: &[Vec<f64>]) -> String {
    let header = stiffid::internal::io::readings::header();
    let mut text = header.replace("q6_deg,", "q6_deg,e1_mm,e2_deg,e3_deg,") + "\n";
    for (i, (q, e)) in q.iter().zip(e).enumerate() {
        let frames = setup.robot().frames_at(q, e);
        for (k, m) in setup.tool().measuring_points.iter().enumerate() {
            let p = frames.point(m) * 1e3;
            let q: Vec<String> = q.iter().map(|v| format!("{:?}", v.to_degrees())).collect();
            text += &format!(
                "P{},{},{},{:?},{:?},{:?},{:?},{:?},{:?}\n",
                i + 1,
                k + 1,
                q.join(","),
                e[0] * 1e3,
                e[1].to_degrees(),
                e[2].to_degrees(),
                p.x,
                p.y,
                p.z
            );
        }
    }
    text
}

#[test]
fn a_calibrations_scene_stands_each_posture_at_its_readings_station() {
    let setup = track_cell();
    let (q, e) = postures(&setup, 12);
    let text = readings(&setup, &q, &e);
    let report = calibrate::run(&calibrate::Request {
        readings: stiffid::app::readings::Request {
            setup_name: "setup".into(),
            setup: &setup,
            name: "readings.csv".into(),
            text: &text,
            force: false,
        },
        geometry: Geometry::Offsets,
        gravity: stiffid::app::calibrate::GravitySpec::Fixed(Gravity::None),
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
    let doc = report.document();
    let json = serde_json::to_string(&doc).unwrap();
    let mut value: serde_json::Value = serde_json::from_str(&json).unwrap();
    let e1 = value["postures"][1]["e1_mm"].as_f64().unwrap();
    assert!((e1 - 850.0).abs() < 1e-9, "{e1}");
    let scene = calibrate::scene::scene(&setup, &json).unwrap();
    assert_at_kinematics(&setup, &scene, &q, &e);
    // The carriage at C(e) base.
    let axes = setup.robot().external().unwrap();
    for (p, e) in scene.postures.iter().zip(&e) {
        let carriage = axes.carrier_pose(e) * setup.robot().base();
        let got = Vector3::from(p.link_frames[9].translation_m);
        assert!((got - carriage.translation.vector).norm() < 1e-12);
    }
    // A posture without the cell's values is refused naming them.
    value["postures"][1]
        .as_object_mut()
        .unwrap()
        .remove("e1_mm");
    let err = calibrate::scene::scene(&setup, &value.to_string())
        .unwrap_err()
        .to_string();
    assert!(err.contains("postures") && err.contains("e1_mm"), "{err}");
}

#[test]
fn an_identifications_scene_stands_each_posture_at_its_measurements_station() {
    let setup = track_cell();
    let (q, e) = postures(&setup, 8);
    let h = setup.model_nominal_compliance().unwrap();
    let points = setup.tool().measuring_points.len();
    let mut data = Vec::new();
    for (i, (q, e)) in q.iter().zip(&e).enumerate() {
        let frames = setup.robot().frames_at(q, e);
        let lp = frames.point(&setup.tool().loading_point);
        let f = (setup.load().anchor - lp).normalize() * setup.load().load;
        let wrench = Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0);
        for point in 0..points {
            data.push(Measurement {
                posture: i,
                point,
                q: *q,
                e: ExternalValues::new(e).unwrap(),
                wrench,
                displacement: Vector3::new(1e-4, -2e-4, 3e-4) * (1.0 + point as f64),
            });
        }
    }
    let report = identify::run(identify::Request {
        progress: &(),
        setup_name: "setup".into(),
        setup: &setup,
        data: Data::<&[u8]>::Measurements(data),
        options: identify::Options::default(),
    })
    .unwrap();
    assert!(h.len() >= 6);
    let text = serde_json::to_string(&report.document()).unwrap();
    let external = report.external().unwrap();
    assert_eq!(external, e);
    let scene =
        identify::document::scene::scene(&setup, report.postures().unwrap(), &external, &text)
            .unwrap();
    assert_at_kinematics(&setup, &scene, &q, &e);
}

#[test]
fn a_compensations_scene_stands_at_the_path_points_stations() {
    let setup = track_cell();
    let (q, e) = postures(&setup, 5);
    let mut text = String::from(
        "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,e1_mm,e2_deg,e3_deg\n",
    );
    for (i, (q, e)) in q.iter().zip(&e).enumerate() {
        let d = q.map(f64::to_degrees);
        text += &format!(
            "{},{},{},{},{},{},0,0,{},{},{},{}\n",
            d[0],
            d[1],
            d[2],
            d[3],
            d[4],
            d[5],
            -200.0 * (1.0 + i as f64),
            e[0] * 1e3,
            e[1].to_degrees(),
            e[2].to_degrees()
        );
    }
    let request = compensate::Request {
        names: Default::default(),
        setup: &setup,
        compliance: setup.model_compliance("test").unwrap(),
        input: compensate::Input::Path {
            name: "path.csv".into(),
            text: &text,
            frame: stiffid::internal::observation::deflection::Frame::Base,
        },
        options: stiffid::internal::machining::compensate::Options::for_setup(&setup),
    };
    let mut results = Vec::new();
    let mut report = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    report.report.names = compensate::document::Names {
        setup: "track-cell.toml".into(),
        stiffness: "nominal".into(),
        out: "out.csv".into(),
        program_out: String::new(),
    };
    let json = serde_json::to_string(&report.report).unwrap();
    let scene = compensate::scene::of_document(&setup, &json)
        .unwrap()
        .unwrap();
    // The first point and the largest deflection.
    let largest = (0..results.len())
        .max_by(|&a, &b| {
            let n = |i: usize| results[i].deflection.fixed_rows::<3>(0).norm();
            n(a).total_cmp(&n(b))
        })
        .unwrap();
    let drawn = [0, largest];
    let qs: Vec<Vector6<f64>> = drawn.iter().map(|&i| results[i].q).collect();
    let es: Vec<Vec<f64>> = drawn.iter().map(|&i| e[i].clone()).collect();
    assert_at_kinematics(&setup, &scene, &qs, &es);
    for (i, p) in scene.path.iter().enumerate() {
        let want = results[i].pose.translation.vector;
        assert!((Vector3::from(p.at_m) - want).norm() < 1e-12, "{i}");
        let tcp = setup
            .robot()
            .frames_at(&q[i], &e[i])
            .point(&setup.tool().tcp);
        assert!(
            (Point3::from(want) - Point3::from(tcp)).norm() < 1e-9,
            "{i}"
        );
    }
    assert_eq!(scene.path.len(), 5);
}

/// A box the positioner carries, in a compensation's scene: its frame in each drawn posture
/// applied to its corners equals the table's tilt and turn at that posture's values (about
/// their lines, [`turn`]) applied to the box at rest, to 1e-9 m.
#[test]
fn a_carried_box_is_drawn_where_each_postures_values_put_it() {
    let setup = track_cell_with(&PLATE.replace("AXIS", "rotate")).unwrap();
    let (q, e) = postures(&setup, 3);
    let axes = setup.robot().external();
    let values: Vec<ExternalValues> = e.iter().map(|e| ExternalValues::new(e).unwrap()).collect();
    let drawn = (q.iter().zip(&values).enumerate())
        .map(|(i, (q, e))| (format!("point {}", i + 1), q, e))
        .collect();
    let part = compensate::scene::ScenePart::new(&[], false, drawn, axes);
    let scene = compensate::scene::scene(&setup, &part).unwrap().unwrap();
    let plate = &scene.obstacles[0];
    assert_eq!(plate.carried_by.as_deref(), Some("rotate"));
    assert_eq!(plate.frames.len(), q.len());
    let (min, max) = (Vector3::from(plate.min_m), Vector3::from(plate.max_m));
    for (f, e) in plate.frames.iter().zip(&e) {
        let [x, y, z, w] = f.rotation_xyzw;
        let frame = Isometry3::from_parts(
            Translation3::from(Vector3::from(f.translation_m)),
            UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)),
        );
        let table = turn([3000.0, 1800.0, 700.0], Vector3::x(), e[1])
            * turn([3000.0, 1800.0, 900.0], Vector3::z(), e[2]);
        for k in 0..8 {
            let corner = Point3::from(Vector3::from_fn(|a, _| match (k >> a) & 1 {
                0 => min[a],
                _ => max[a],
            }));
            let error = (frame * corner - table * corner).norm();
            assert!(error < 1e-9, "corner {k} at {e:?}: {error} m");
        }
    }
}
