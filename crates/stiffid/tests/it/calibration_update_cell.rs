//! `calibrate --update` on a cell: the calibrated arm of [`crate::calibration_update`] on a
//! 4 m track (its direction off by 1 mrad, error motions of two orders) beside a turntable, the
//! track's and the turntable's calibration held, and the arm's offsets, the tracker, the tool and
//! the track's zero offset refitted from a short check campaign read at several stations and
//! angles.

use crate::calibration_update::{request, robot_text, setup, DRIFT, OFFSETS};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use stiffid::app::calibrate::{self, Refits, Report};
use stiffid::{Robot, Setup};

/// The cell's external axes as the calibration found them; `TRACK` and `TABLE` the zero
/// offsets (mm, deg).
const CELL: &str = r#"
[[external_axis]]
name = "track"
role = "carrier"
direction = [1.0, 0.001, 0.0]
limits_mm = [0.0, 4000.0]
offset_mm = TRACK
error_motions = [[0.01, 0.05, -0.03, 0.02, 0.1, -0.05], [-0.02, 0.03, 0.04, -0.01, 0.05, 0.03]]

[[external_axis]]
name = "table"
role = "positioner"
direction = [0.0, 0.002, 1.0]
point_mm = [2000.0, 1800.0, 0.0]
limits_deg = [-180.0, 180.0]
offset_deg = TABLE
"#;

/// The track's drift along its direction, mm.
const TRACK_DRIFT: f64 = 0.4;

/// The calibrated cell with the arm's `offsets` (deg) and the axes' zero offsets.
fn cell_robot(offsets: &[f64; 6], track: f64, table: f64) -> Robot {
    let text = robot_text(offsets)
        + &CELL
            .replace("TRACK", &format!("{track:?}"))
            .replace("TABLE", &format!("{table:?}"));
    stiffid::internal::robot::file::parse(&text, "calibrated.toml").unwrap()
}

/// The cell's setup: the setup of [`crate::calibration_update`] on the calibrated cell.
fn cell_setup() -> Setup {
    let setup = setup();
    let robot = cell_robot(&OFFSETS, 0.0, 0.0);
    setup.to_builder().with_robot(robot).build().unwrap()
}

/// The cell on the check's day: the arm's offsets drifted, the track's zero by
/// [`TRACK_DRIFT`], the turntable's by 0.05 deg.
fn drifted() -> Robot {
    let offsets = std::array::from_fn(|i| OFFSETS[i] + DRIFT[i]);
    cell_robot(&offsets, TRACK_DRIFT, 0.05)
}

/// The tracker of the check's day in the cell's frame.
fn tracker() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(2.0, -2.5, 0.6), Vector3::new(0.01, -0.02, 1.2))
}

/// Reflectors on the turntable (part frame at `e = 0`, m).
fn reflectors() -> [Vector3<f64>; 2] {
    [Vector3::new(2.3, 1.8, 0.4), Vector3::new(1.8, 2.1, 0.5)]
}

/// Noise-free tracker readings of `truth` at `postures`, posture `i` at station `i mod 3` and
/// turntable angle `37 i` deg; with `tables`, the turntable's reflectors read at each posture.
fn readings(truth: &Robot, setup: &Setup, postures: &[Vector6<f64>], tables: bool) -> String {
    let mut text = String::from(
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,e1_mm,e2_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm\n",
    );
    let axes = truth.external().unwrap();
    for (i, q) in postures.iter().enumerate() {
        let e = [
            0.5 + 1.5 * (i % 3) as f64,
            (37.0 * i as f64 % 360.0 - 180.0).to_radians(),
        ];
        let frames = truth.frames_at(q, &e);
        let deg: Vec<String> = q.iter().map(|a| format!("{:?}", a.to_degrees())).collect();
        let mut row = |point: String, at: Vector3<f64>| {
            let t = (tracker().inverse() * Point3::from(at)).coords * 1e3;
            text += &format!(
                "C{},{point},{},{:?},{:?},{:?},{:?},{:?}\n",
                i + 1,
                deg.join(","),
                e[0] * 1e3,
                e[1].to_degrees(),
                t.x,
                t.y,
                t.z
            );
        };
        for (k, p) in setup.tool().measuring_points.iter().enumerate() {
            row(format!("{}", k + 1), frames.point(p));
        }
        if tables {
            for (k, x) in reflectors().iter().enumerate() {
                let at = axes.positioner_pose(&e) * Point3::from(*x);
                row(format!("T{}", k + 1), at.coords);
            }
        }
    }
    text
}

/// `calibrate --update LIST` of the cell on `data` (held-out `held`).
fn update(setup: &Setup, data: &str, held: Option<&str>, list: &str) -> stiffid::Result<Report> {
    calibrate::run(&calibrate::Request {
        refit: Refits::parse(list).unwrap(),
        ..request(setup, data, held, true)
    })
    .map(|o| o.report)
}

/// The value of parameter `name` in `report`, SI.
fn value(report: &Report, name: &str) -> f64 {
    let params = report.model.parameters();
    let c = params.iter().position(|p| p.name == name).unwrap();
    report.fit.estimate.values[c]
}

/// Noise-free, 12 check postures over three stations and twelve turntable angles (its two
/// reflectors read at each) recover the drifted cell: held-out readings at other stations and
/// angles predicted to 1e-9 mm, joints 2 to 5's offsets to 1e-9 deg and the track's zero
/// offset to 1e-9 mm; the track's direction, error motions and the turntable's line held (in
/// `held`), and the updated robot file carries the track's new zero.
#[test]
fn noise_free_drift_of_a_cell_is_recovered_by_the_update() {
    let setup = cell_setup();
    let truth = drifted();
    let postures = stiffid::internal::design::random_group(&setup, 12, 5);
    let data = readings(&truth, &setup, &postures, true);
    let held = readings(
        &truth,
        &setup,
        &stiffid::internal::design::random_group(&setup, 20, 9),
        false,
    );
    let report = update(&setup, &data, Some(&held), "offsets,base,tool,external").unwrap();
    let validation = report.validation.as_ref().unwrap();
    assert!(
        validation.calibrated.rms < 1e-12,
        "{:e}",
        validation.calibrated.rms
    );
    assert!(
        validation.nominal.rms > 1e-4,
        "{:e}",
        validation.nominal.rms
    );
    for (j, drift) in DRIFT.iter().enumerate().take(5).skip(1) {
        let got = value(&report, &format!("joint{}.theta", j + 1)).to_degrees();
        assert!((got - drift).abs() < 1e-9, "joint {}: {got}", j + 1);
    }
    let track = value(&report, "track.offset") * 1e3;
    assert!(
        (track - TRACK_DRIFT).abs() < 1e-9,
        "track offset {track} mm"
    );
    let held: Vec<&str> = (report.model.held().iter())
        .map(|&c| report.model.parameters()[c].name.as_str())
        .collect();
    for name in [
        "track.direction.ry",
        "table.location.y",
        "table.direction.rz",
    ] {
        assert!(held.contains(&name), "{held:?}");
    }
    let file = report.robot_toml.as_ref().unwrap();
    let updated = stiffid::internal::robot::file::parse(file, "updated.toml").unwrap();
    let axis = &updated.external().unwrap().axes()[0];
    assert!((axis.offset * 1e3 - TRACK_DRIFT).abs() < 1e-6, "{file}");
    let motions = &axis.errors.coefficients()[1];
    assert!((motions[4] - 0.05e-3).abs() < 1e-12, "{motions:?}");
}

/// Without reflectors on the turntable, the track's zero offset is a shift of the tracker's
/// registration: `external` is refused naming `track.offset` and what it merges with; the same
/// readings update the rest (`offsets,base,tool`).
#[test]
fn a_track_offset_without_table_reflectors_is_refused() {
    let setup = cell_setup();
    let truth = drifted();
    let postures = stiffid::internal::design::random_group(&setup, 12, 5);
    let data = readings(&truth, &setup, &postures, false);
    let e = update(&setup, &data, None, "offsets,base,tool,external")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("update")
            && e.contains("track.offset merges with tracker.")
            && e.contains("as a shift of the tracker's registration"),
        "{e}"
    );
    update(&setup, &data, None, "offsets,base,tool").unwrap();
}

/// `select --for check` on the cell, given three stations of the track, designs the check at the
/// best of them (the arm there, the track's calibration held); the 10 postures it designs, read
/// over the three stations and the table's angles with its reflectors, update the cell as the
/// random ones do (noise-free: held out to 1e-9 mm, the track's zero to 1e-9 mm).
#[test]
fn the_check_designed_on_the_cell_updates_it() {
    use stiffid::app::select;
    use stiffid::internal::robot::external::ExternalValues;
    let setup = cell_setup();
    let stations: Vec<ExternalValues> = [0.5, 2.0, 3.5]
        .iter()
        .map(|s| ExternalValues::new(&[*s, 0.0]).unwrap())
        .collect();
    let report = select::run(&select::Request {
        setup: &setup,
        criterion: stiffid::internal::design::Criterion::RelativeA,
        purpose: stiffid::app::purpose::Purpose::Check,
        calibration: Default::default(),
        method: select::Method::Global,
        start: None,
        pool: None,
        postures: stiffid::app::purpose::Purpose::Check.default_postures(),
        target_pct: None,
        options: stiffid::internal::design::SearchOptions {
            starts: 2,
            ..Default::default()
        },
        restarts: None,
        distinct: None,
        for_candidates: false,
        candidates: None,
        stations,
        progress: &(),
        out: None,
        report_dir: None,
    })
    .unwrap();
    assert_eq!((report.postures.len(), report.stations.len()), (10, 3));
    assert!(report.station.is_some());
    let truth = drifted();
    let data = readings(&truth, &setup, &report.postures, true);
    let held = readings(
        &truth,
        &setup,
        &stiffid::internal::design::random_group(&setup, 20, 9),
        false,
    );
    let updated = update(&setup, &data, Some(&held), "offsets,base,tool,external").unwrap();
    let validation = updated.validation.as_ref().unwrap();
    assert!(
        validation.calibrated.rms < 1e-12,
        "{:e}",
        validation.calibrated.rms
    );
    let track = value(&updated, "track.offset") * 1e3;
    assert!(
        (track - TRACK_DRIFT).abs() < 1e-9,
        "track offset {track} mm"
    );
}
