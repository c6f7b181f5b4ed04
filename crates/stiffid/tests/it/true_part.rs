//! The part's frame after a calibration, end to end on the simulated true cell of
//! [`crate::true_table`] (the true arm on a turntable whose true axis is off its nominal line):
//! the calibration locates the part from the four reflectors on the table, the calibrated robot
//! file records it (`[part]`), and a setup pointing at that file takes it; the part frame of the
//! nominal setup kept instead misses the part by what the calibration moved the cell frame.

use crate::true_cell::compensated;
use crate::true_robot::{self, Row, Truth};
use crate::true_table::{on_table, readings, reflectors_mm, table_case, Table, OVER_TABLE_DEG};
use nalgebra::{Isometry3, Point3, Translation3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::{Robot, Setup};

/// The milled points (the part's frame, m): a circle of 150 mm about its origin with the tool
/// as at `over` (cell frame), each with its table angle (rad).
fn points(over: &Isometry3<f64>) -> Vec<(Isometry3<f64>, f64)> {
    let part = Translation3::from(-over.translation.vector);
    (0..8)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_4 * i as f64;
            let at = Translation3::from(0.15 * Vector3::new(a.cos(), a.sin(), 0.0));
            (part * at * over, (15.0 * i as f64 - 50.0).to_radians())
        })
        .collect()
}

/// The path file of `points` with the part at `part` (cell frame), each with a milling force.
fn path(points: &[(Isometry3<f64>, f64)], part: &Isometry3<f64>) -> String {
    let mut text = String::from("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,e1_deg\n");
    for (pose, e) in points {
        let pose = part * pose;
        let (r, p, y) = pose.rotation.euler_angles();
        let at = pose.translation.vector * 1e3;
        text += &format!(
            "{:?},{:?},{:?},{:?},{:?},{:?},300,-200,-400,{:?}\n",
            at.x,
            at.y,
            at.z,
            r.to_degrees(),
            p.to_degrees(),
            y.to_degrees(),
            e.to_degrees()
        );
    }
    text
}

/// The setup pointing at the calibrated robot `robot` (`calibrated.toml`) with `workpiece`
/// (the `[workpiece]` table's lines).
pub(crate) fn pointing(robot: &Robot, workpiece: &str) -> stiffid::Result<Setup> {
    let text = true_robot::setup_text(
        "calibrated.toml",
        "[bounds]\nlower_deg = [-90.0, -60.0, -180.0, -180.0, -90.0, -180.0]\nupper_deg = [90.0, 40.0, -40.0, 180.0, 90.0, 180.0]",
    ) + "\n[workpiece]\n"
        + workpiece
        + "\n";
    stiffid::internal::setup::parse(&text, "setup.toml", |_, _| Ok(robot.clone()))
}

/// The TCP error on the true cell (the true `table`, the part truly at `part`, true base frame)
/// of `points` compensated on `setup` with the part at its `[workpiece]`.
fn landing(
    (truth, table): (&Truth, &Table),
    (setup, compliance): (&Setup, &stiffid::internal::model::Compliance),
    points: &[(Isometry3<f64>, f64)],
    part: &Isometry3<f64>,
) -> Row {
    let mut options = Options::for_setup(setup);
    options.q0 = Vector6::from_fn(|i, _| OVER_TABLE_DEG[i].to_radians());
    let text = path(points, setup.workpiece().unwrap());
    let (_, results) = compensated(setup, compliance, &options, &text);
    assert_eq!(results.len(), points.len());
    let errors: Vec<f64> = (points.iter().zip(&results))
        .map(|((pose, e), r)| {
            assert!((r.external.as_slice()[0] - e).abs() < 1e-12);
            let truly = table.at(*e) * part * Point3::from(pose.translation.vector);
            let want = truth.estimate.frame.inverse() * truly;
            (truth.tcp_at(&r.q_compensated, &r.wrench) - want.coords).norm()
        })
        .collect();
    true_robot::row(&errors)
}

/// The true cell calibrated from 30 postures and the 4 table reflectors at 12 angles (0.015 mm
/// of noise): the part located by the calibration and taken by a setup pointing at the
/// calibrated robot file lands the path on the true part within 3 times the held-out error,
/// where the nominal setup's part frame, kept, misses it by what the calibration moved the cell
/// frame; repeating it in the setup pointing at the file is refused naming both places.
#[test]
fn the_part_located_by_the_calibration_lands_on_the_true_part() {
    let (case, table, over) = table_case();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let truth = Truth::new(&true_robot::dh_case().setup, &mut rng);
    let true_table = table.truth();
    // The part truly where the nominal setup says, the reflectors on it as the setup says.
    let part = *case.setup.workpiece().unwrap();
    let reflectors: Vec<Vector3<f64>> = (on_table().iter())
        .map(|r| (part * Point3::from(*r)).coords)
        .collect();
    let angles: Vec<f64> = (0..12)
        .map(|i| (-165.0 + 30.0 * i as f64).to_radians())
        .collect();
    let fit = true_robot::postures(30, &mut rng, case.angles);
    let data = readings(
        &truth,
        Some(&true_table),
        (&fit, &angles),
        &reflectors,
        &mut rng,
    );
    let held_q = true_robot::postures(12, &mut rng, case.angles);
    let held_e: Vec<f64> = angles.iter().map(|e| e + 0.2).collect();
    let held = (held_q.as_slice(), held_e.as_slice());
    let held = readings(&truth, Some(&true_table), held, &reflectors, &mut rng);
    let (kept, weight, _, held_rms, _) =
        true_robot::calibrated(&case, Gravity::Masses, &data, &held);
    let robot = kept.robot();
    let located = *robot
        .part()
        .expect("the calibrated robot file records [part]");
    // A setup pointing at the calibrated file takes its part, with a note.
    let taken = pointing(robot, &reflectors_mm()).unwrap();
    assert_eq!(taken.workpiece(), Some(&located));
    assert!(taken.notes().iter().any(|n| n.message.contains("[part]")));
    // The nominal setup's part frame, repeated there, is refused naming both places.
    let c = part.translation.vector * 1e3;
    let repeated = format!(
        "base_from_part = {{ xyz_mm = [{:?}, {:?}, {:?}], rpy_deg = [0.0, 0.0, 0.0] }}",
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
    let points = points(&over);
    let cell = (&truth, &true_table);
    let new = landing(cell, (&placed, &compliance), &points, &part);
    let old = landing(cell, (&kept, &compliance), &points, &part);
    let apart = part.inverse() * located;
    eprintln!(
        "part: located {:.4} mm and {:.5} deg from the nominal setup's; held out {:.4} mm",
        apart.translation.vector.norm() * 1e3,
        apart.rotation.angle().to_degrees(),
        held_rms * 1e3
    );
    for (what, r) in [("located part", new), ("nominal part frame kept", old)] {
        eprintln!(
            "part: {what}: TCP error mean {:.4} mm, max {:.4} mm",
            r.mean * 1e3,
            r.max * 1e3
        );
    }
    assert!(new.mean <= 3.0 * held_rms, "{new:?} vs {held_rms}");
    assert!(old.mean > 10.0 * new.mean, "{old:?} vs {new:?}");
}
