//! The part's frame after a calibration on a fixed cell (the arm on a fixed base, or on a
//! track, no positioner), end to end on the simulated true robot of [`crate::true_robot`]: four reflectors
//! on the part (`[workpiece] reflectors_mm`) are read by the tracker in the calibration's
//! session as fixed points of the cell (`T1`..`T4`, three times each), the calibration fits each
//! as a free point of the cell and locates the part from them as it does from a positioner's
//! table, the calibrated robot file records it (`[part]`), and a setup pointing at that file
//! takes it. The calibration's registration takes the base's errors, so the cell frame moves:
//! the nominal setup's part frame, kept, misses the part by as much.

use crate::true_cell;
use crate::true_part::pointing;
use crate::true_robot::{self, Case, Row, Truth};
use crate::true_table::{on_table, readings, reflectors_mm};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::machining::program::generate::Targets;
use stiffid::internal::machining::Language;
use stiffid::internal::metrology::calibration::error_model::Observation;
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::robot::external::ExternalValues;
use stiffid::Setup;

/// The fixed cell: the COMAU of [`true_robot::dh_case`] with the part where its tool is at
/// [`true_robot::q0`] ([`true_robot::with_part`]) and the reflectors of [`on_table`] on it;
/// the part's frame (base frame, m).
fn fixed_case() -> (Case, Isometry3<f64>) {
    let arm = true_robot::dh_case();
    let (placed, part) = true_robot::with_part(&arm.setup, &true_robot::q0(&arm));
    let setup = placed
        .to_builder()
        .with_table_reflectors(on_table())
        .build()
        .unwrap();
    (Case { setup, ..arm }, part)
}

/// The TCP error on the true robot (the part truly at `part`, true base frame) of the
/// rectangle compensated on `setup` with the part at its `[workpiece]`, joint targets.
fn landing(
    truth: &Truth,
    (setup, compliance): (&Setup, &stiffid::internal::model::Compliance),
    q0: &Vector6<f64>,
    part: &Isometry3<f64>,
) -> Row {
    let given = *setup.workpiece().unwrap();
    let (_, results) = true_robot::written_from(
        setup,
        compliance,
        (q0, &true_robot::rectangle()),
        (Language::GCode, Targets::Joint),
    );
    let errors: Vec<f64> = (results.iter())
        .map(|r| {
            let on_part = given.inverse() * Point3::from(r.pose.translation.vector);
            let truly = truth.estimate.frame.inverse() * (part * on_part);
            (truth.tcp_at(&r.q_compensated, &r.wrench) - truly.coords).norm()
        })
        .collect();
    true_robot::row(&errors)
}

/// The fixed cell calibrated from 30 postures and the 4 reflectors on the part read three
/// times each (0.015 mm of noise): the part located by the calibration lies within the noise of
/// where the true part is in the calibrated cell, a setup pointing at the calibrated robot file
/// takes it, and the rectangle compensated with it lands on the true part within 3 times the
/// held-out error, where the nominal setup's part frame, kept, misses it by what the
/// calibration moved the cell frame; repeated in the setup pointing at the file it is refused
/// naming both places.
#[test]
fn the_part_on_a_fixed_cell_located_by_the_calibration_lands_on_the_true_part() {
    let (case, part) = fixed_case();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let truth = Truth::new(&true_robot::dh_case().setup, &mut rng);
    // The part truly where the nominal setup says, the reflectors on it as the setup says.
    let reflectors: Vec<Vector3<f64>> = (on_table().iter())
        .map(|r| (part * Point3::from(*r)).coords)
        .collect();
    let fit = true_robot::postures(30, &mut rng, case.angles);
    let data = readings(&truth, None, (&fit, &[0.0; 3]), &reflectors, &mut rng);
    assert!(data.contains("\nE3,T4,"), "{data}");
    let held_q = true_robot::postures(12, &mut rng, case.angles);
    let held = readings(&truth, None, (&held_q, &[0.0]), &reflectors, &mut rng);
    let (kept, weight, frame, held_rms, _) =
        true_robot::calibrated(&case, Gravity::Masses, &data, &held);
    let robot = kept.robot();
    let located = *robot
        .part()
        .expect("the calibrated robot file records [part]");
    // Where the part truly is in the calibrated cell: the tracker's registration of the true
    // base frame's part.
    let truly = frame * truth.estimate.frame.inverse() * part;
    let off = truly.inverse() * located;
    let moved = part.inverse() * truly;
    eprintln!(
        "fixed part: located {:.4} mm and {:.5} deg from the true part; the cell frame moved it {:.4} mm and {:.5} deg; held out {:.4} mm",
        off.translation.vector.norm() * 1e3,
        off.rotation.angle().to_degrees(),
        moved.translation.vector.norm() * 1e3,
        moved.rotation.angle().to_degrees(),
        held_rms * 1e3
    );
    assert!(off.translation.vector.norm() < 0.03e-3, "{off}");
    assert!(off.rotation.angle() < 0.03e-3 / 0.25, "{off}");
    assert!(moved.translation.vector.norm() > 20.0 * off.translation.vector.norm());
    // A setup pointing at the calibrated file takes its part, with a note.
    let taken = pointing(robot, &reflectors_mm()).unwrap();
    assert_eq!(taken.workpiece(), Some(&located));
    assert!(taken.robot().external().is_none());
    assert!(taken.notes().iter().any(|n| n.message.contains("[part]")));
    // The nominal setup's part frame, repeated there, is refused naming both places.
    let (c, [r, p, y]) = (
        part.translation.vector * 1e3,
        stiffid::internal::robot::file::rpy(&part.rotation).map(f64::to_degrees),
    );
    let repeated = format!(
        "base_from_part = {{ xyz_mm = [{:?}, {:?}, {:?}], rpy_deg = [{r:?}, {p:?}, {y:?}] }}",
        c.x, c.y, c.z
    );
    let refused = pointing(robot, &repeated).unwrap_err().to_string();
    for words in [
        "workpiece.base_from_part",
        "calibrated.toml",
        "[part]",
        "mm away",
    ] {
        assert!(refused.contains(words), "{refused}");
    }
    // The compliance: the true drives', the sag the calibrated file's.
    let mut compliance = kept.model_compliance("the test").unwrap();
    let h = case.setup.nominal_compliance().unwrap() * 1.3;
    compliance.h = nalgebra::DVector::from_column_slice(h.as_slice());
    compliance.own_weight = weight.and_then(|w| w.own_weight);
    let placed = kept.to_builder().with_workpiece(located).build().unwrap();
    let q0 = true_robot::q0(&case);
    let new = landing(&truth, (&placed, &compliance), &q0, &part);
    let old = landing(&truth, (&kept, &compliance), &q0, &part);
    for (what, r) in [("located part", new), ("nominal part frame kept", old)] {
        eprintln!(
            "fixed part: {what}: TCP error mean {:.4} mm, max {:.4} mm",
            r.mean * 1e3,
            r.max * 1e3
        );
    }
    assert!(new.mean <= 3.0 * held_rms, "{new:?} vs {held_rms}");
    assert!(old.mean > 10.0 * new.mean, "{old:?} vs {new:?}");
}

/// Readings of the tool's measuring points at `qs` (rad) on the true carriage at `s` (m), and
/// of the `reflectors` fixed in the cell (true cell frame, m) three times each, with the
/// tracker's noise; no load columns (a reflector's row is refused beside load steps).
fn track_readings(
    truth: &Truth,
    (qs, s): (&[Vector6<f64>], &[f64]),
    reflectors: &[Vector3<f64>],
    rng: &mut ChaCha8Rng,
) -> String {
    let noise = Normal::new(0.0, true_cell::NOISE).unwrap();
    let mut text =
        stiffid::internal::io::readings::header().replace("q6_deg,", "q6_deg,e1_mm,") + "\n";
    let mut row = |label: String, point: String, i: usize, cell: Point3<f64>| {
        let t = (truth.estimate.frame.inverse() * cell).coords;
        let t = t + Vector3::from_fn(|_, _| noise.sample(rng));
        let q: Vec<String> = qs[i]
            .iter()
            .map(|v| format!("{:?}", v.to_degrees()))
            .collect();
        text += &format!(
            "{label},{point},{},{:?},{:?},{:?},{:?}\n",
            q.join(","),
            s[i] * 1e3,
            t.x * 1e3,
            t.y * 1e3,
            t.z * 1e3
        );
    };
    for i in 0..qs.len() {
        for k in 0..truth.model.points() {
            let o = Observation {
                posture: i,
                point: k,
                q: qs[i],
                measured: Vector3::zeros(),
                wrench: Vector6::zeros(),
                e: ExternalValues::NONE,
                table: false,
                direction: Vector6::zeros(),
            };
            let b = truth.model.predict(&truth.estimate.values, &[o]).unwrap()[0];
            let cell = true_cell::true_track(s[i]) * Point3::from(b);
            row(format!("P{}", i + 1), format!("{}", k + 1), i, cell);
        }
    }
    for i in [0, qs.len() / 2, qs.len() - 1] {
        for (k, r) in reflectors.iter().enumerate() {
            row(
                format!("P{}", i + 1),
                format!("T{}", k + 1),
                i,
                Point3::from(*r),
            );
        }
    }
    text
}

/// The arm on the track of [`true_cell::track_case`] (a bowed, pitching true carriage), the part
/// fixed in the cell beside the rail with four reflectors on it read three times each, 30
/// postures over 6 stations: the calibration locates the part within the noise of where it truly
/// is in the calibrated cell, and the calibrated robot file records it.
#[test]
fn the_part_beside_a_track_is_located_by_the_calibration() {
    let case = true_cell::track_case();
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let truth = Truth::new(&true_robot::dh_case().setup, &mut rng);
    let part = Isometry3::new(Vector3::new(3.2, 1.4, 0.3), Vector3::z() * 0.4);
    let reflectors: Vec<Vector3<f64>> = (on_table().iter())
        .map(|r| (part * Point3::from(*r)).coords)
        .collect();
    let setup = (case.setup.to_builder())
        .with_workpiece(part)
        .with_table_reflectors(on_table())
        .build()
        .unwrap();
    let case = Case { setup, ..case };
    let fit = true_robot::postures(30, &mut rng, case.angles);
    let data = track_readings(
        &truth,
        (&fit, &true_cell::stations(30, 5)),
        &reflectors,
        &mut rng,
    );
    let held_q = true_robot::postures(12, &mut rng, case.angles);
    let held_s: Vec<f64> = (0..12).map(|i| 0.25 + 0.5 * i as f64).collect();
    let held = track_readings(&truth, (&held_q, &held_s), &reflectors, &mut rng);
    let (kept, _, frame, held_rms, _) =
        true_robot::calibrated(&case, Gravity::Masses, &data, &held);
    let located = *kept.robot().part().expect("[part]");
    let truly = frame * truth.estimate.frame.inverse() * part;
    let off = truly.inverse() * located;
    let moved = part.inverse() * truly;
    eprintln!(
        "track part: located {:.4} mm and {:.5} deg from the true part; the cell frame moved it {:.4} mm and {:.5} deg; held out {:.4} mm",
        off.translation.vector.norm() * 1e3,
        off.rotation.angle().to_degrees(),
        moved.translation.vector.norm() * 1e3,
        moved.rotation.angle().to_degrees(),
        held_rms * 1e3
    );
    assert!(off.translation.vector.norm() < 0.03e-3, "{off}");
    assert!(off.rotation.angle() < 0.03e-3 / 0.25, "{off}");
    assert!(moved.translation.vector.norm() > 20.0 * off.translation.vector.norm());
}

/// Reflectors that no rigid transform explains (the setup's `T1` and `T2` swapped, or `T3` placed
/// 50 m away) are refused naming `workpiece.reflectors_mm` and the reflector, never written
/// into `[part]` with a distance warning only.
#[test]
fn reflectors_no_rigid_transform_explains_are_refused() {
    let (case, part) = fixed_case();
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let truth = Truth::new(&true_robot::dh_case().setup, &mut rng);
    let reflectors: Vec<Vector3<f64>> = (on_table().iter())
        .map(|r| (part * Point3::from(*r)).coords)
        .collect();
    let fit = true_robot::postures(30, &mut rng, case.angles);
    let data = readings(&truth, None, (&fit, &[0.0; 3]), &reflectors, &mut rng);
    let mut swapped = on_table();
    swapped.swap(0, 1);
    let mut far = on_table();
    far[2].x = 50.0;
    // T2 placed 3 mm off: a rigid transform explains it within the 10 mm limit after the fit
    // spreads it, so the part is located, with the fit's residuals warned of (never silently).
    let mut off = on_table();
    off[1].y += 3e-3;
    let cases = [
        (swapped, "lies"),
        (far, "T3 lies"),
        (off, "misfit"),
        (on_table(), "placed"),
    ];
    for (placed, named) in cases {
        let setup = (case.setup.to_builder())
            .with_table_reflectors(placed)
            .build()
            .unwrap();
        let request = stiffid::app::calibrate::Request {
            readings: stiffid::app::readings::Request {
                setup_name: "setup".into(),
                setup: &setup,
                name: "fit.csv".into(),
                text: &data,
                force: false,
            },
            geometry: stiffid::internal::metrology::calibration::Geometry::Full,
            gravity: stiffid::app::calibrate::GravitySpec::Fixed(Gravity::None),
            gravity_bound: None,
            validate: None,
            reregister: false,
            cross_validate: false,
            priors: None,
            progress: &(),
            maps: stiffid::internal::metrology::calibration::maps::Spec::None,
            error_motions: Default::default(),
            level: None,
            update: false,
            refit: Default::default(),
            weight: None,
            urdf: false,
        };
        match stiffid::app::calibrate::run(&request) {
            Err(stiffid::Error::InvalidField { field, message }) => {
                assert_eq!(field, "workpiece.reflectors_mm", "{message}");
                assert!(
                    message.contains(named) && message.contains("mm from its place"),
                    "{message}"
                );
            }
            Err(other) => panic!("{other}"),
            Ok(outcome) if named == "placed" => {
                let reflectors = |w: &&stiffid::internal::common::warning::Warning| {
                    w.message.contains("the part located from the reflectors")
                        && w.kind == stiffid::internal::common::warning::WarningKind::Misfit
                };
                assert!(
                    !outcome.warnings.iter().any(|w| reflectors(&w)),
                    "{:?}",
                    outcome.warnings
                );
            }
            Ok(outcome) if named == "misfit" => {
                let w = (outcome.warnings.iter())
                    .find(|w| {
                        w.kind == stiffid::internal::common::warning::WarningKind::Misfit
                            && w.message.contains("the part located from the reflectors")
                    })
                    .unwrap_or_else(|| panic!("{:?}", outcome.warnings));
                assert!(
                    w.message.contains("mm RMS, the longest")
                        && w.message.contains("times what the tracker noise leaves"),
                    "{}",
                    w.message
                );
            }
            Ok(_) => panic!("{named}: accepted"),
        }
    }
}
