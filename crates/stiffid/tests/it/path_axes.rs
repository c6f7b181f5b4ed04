//! Path files with external axes: `e1_mm`, `e2_deg` columns compensated as given, poses a point
//! of the part (carried by the positioner), the loaded tool landing on the target in the cell to
//! 0.1 micrometre in the forward model; values the cell cannot take refused naming the line and
//! the axis.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::compensate::{run, Input, Request};
use stiffid::internal::machining::compensate::{Compensated, Model, Options, PathPoint};
use stiffid::internal::machining::{cell, path};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{ErrorMotions, ExternalAxes, ExternalAxis};
use stiffid::internal::robot::ik::{self, tool_pose};
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Error, Setup};

/// The FANUC R-2000iC/165F on a track along x (0 to 6 m, pitching 0.2 mrad and sagging 0.3 mm
/// at its ends) beside a turntable about z through (2.5, 0, 0) m.
fn on_track() -> Setup {
    let mut track = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
    track.errors = ErrorMotions::new(vec![
        [0.0, 0.0, 0.0, 0.0, 2e-4, 0.0],
        [0.0, 0.0, -3e-4, 0.0, 0.0, 0.0],
    ])
    .unwrap();
    let turn = 360f64.to_radians();
    let table = ExternalAxis::rotary(
        "table",
        Vector3::new(2.5, 0.0, 0.0),
        Vector3::z_axis(),
        -turn,
        turn,
    );
    let cell = ExternalAxes::new(vec![track, table]).unwrap();
    let base = milling();
    let robot = base.robot().clone().with_external(Some(cell));
    base.to_builder().with_robot(robot).build().unwrap()
}

/// The FANUC milling example (its tool centre point) on a fixed base.
fn milling() -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap()
}

/// A point of the part (cell frame at `e = 0`, m) over the table, the tool pointing down.
fn part_point(i: usize) -> Isometry3<f64> {
    Isometry3::from_parts(
        Vector3::new(2.9 + 0.02 * i as f64, -0.3, 0.5).into(),
        UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0),
    )
}

/// A pose path over the part while the track and the table move: `e1_mm` and `e2_deg` per row.
fn pose_path() -> (String, Vec<[f64; 2]>) {
    let mut text = String::from("# the part on the table\nx_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,e2_deg,e1_mm\n");
    let mut e = Vec::new();
    for i in 0..4 {
        let p = part_point(i).translation.vector * 1e3;
        let (track, table) = (1200.0 + 150.0 * i as f64, 10.0 * i as f64);
        text += &format!(
            "{},{},{},180,0,0,300,-200,-400,{table},{track}\n",
            p.x, p.y, p.z
        );
        e.push([track * 1e-3, table.to_radians()]);
    }
    (text, e)
}

fn compensated(s: &Setup, text: &str) -> stiffid::Result<(Vec<PathPoint>, Vec<Compensated>)> {
    let compliance = s.model_compliance("test")?;
    let (mut points, mut results) = (Vec::new(), Vec::new());
    let request = Request {
        names: Default::default(),
        setup: s,
        compliance,
        input: Input::Path {
            name: "path.csv".into(),
            text,
            frame: Frame::Base,
        },
        options: Options::for_setup(s),
    };
    run::<Error, _>(request, |_, p, r, _| {
        points.extend_from_slice(p);
        results.extend_from_slice(r);
        Ok(())
    })?;
    Ok((points, results))
}

/// Each pose row is a point of the part, which the table turns and the track leaves behind: the
/// nominal pose in the cell is `P(e) x`, the wrench is the cell's turned onto the pitching
/// carriage, and the loaded tool at the compensated angles, carried by the track, lands on the
/// target to 0.1 micrometre.
#[test]
fn a_path_that_moves_the_track_and_the_table_lands_on_the_part_to_0_1_um() {
    let s = on_track();
    let cell_axes = s.robot().external().unwrap().clone();
    let (text, e) = pose_path();
    let (points, results) = compensated(&s, &text).unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let mut moved = 0.0f64;
    for (i, ((p, r), e)) in points.iter().zip(&results).zip(&e).enumerate() {
        assert_eq!(p.external.as_slice(), e, "{i}");
        let target = cell_axes.positioner_pose(e) * part_point(i);
        assert!(
            (r.pose.translation.vector - target.translation.vector).norm() < 1e-9,
            "{i}: nominal pose in the cell"
        );
        let carrier = cell_axes.carrier_pose(e);
        let cell_wrench = Vector6::new(300.0, -200.0, -400.0, 0.0, 0.0, 0.0);
        assert!((r.wrench - cell_wrench).amax() < 1e-9, "{i}: {}", r.wrench);
        assert!(
            (p.wrench - cell_wrench).amax() > 1e-3,
            "turned onto the carriage"
        );
        let loaded = carrier * model.loaded_pose(&r.q_compensated, &p.wrench);
        let error = (loaded.translation.vector - target.translation.vector).norm();
        assert!(error < 1e-7, "{i}: {error} m");
        let rotation = loaded.rotation.angle_to(&target.rotation);
        assert!(rotation < 1e-6, "{i}: {rotation} rad");
        let uncompensated = carrier * model.loaded_pose(&r.q, &p.wrench);
        moved = moved.max((uncompensated.translation.vector - target.translation.vector).norm());
    }
    assert!(moved > 1e-5, "the load deflects the tool: {moved} m");
}

/// Axis angles with the track: the nominal pose is the arm's at `q` on the carriage at `e`.
#[test]
fn a_posture_path_on_the_track_is_placed_on_the_carriage() {
    let s = on_track();
    let q = ik::solve(
        s.robot(),
        &s.tool().tcp,
        &(Isometry3::translation(-1.2, 0.0, 0.0) * part_point(0)),
        &Options::for_setup(&s).q0,
        &ik::Options::default(),
    )
    .unwrap()
    .q;
    let d = q.map(f64::to_degrees);
    let text = format!(
        "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,e1_mm,e2_deg\n{},{},{},{},{},{},0,0,-500,4200,0\n",
        d[0], d[1], d[2], d[3], d[4], d[5]
    );
    let (_, results) = compensated(&s, &text).unwrap();
    let expected = tool_pose(&s.robot().frames_at(&q, &[4.2, 0.0]), &s.tool().tcp);
    assert!((results[0].pose.translation.vector - expected.translation.vector).norm() < 1e-9);
    // The same row without the track's values is not compensated on a carriage somewhere.
    let bare = text.replace(",e1_mm,e2_deg", "").replace(",4200,0", "");
    let e = compensated(&s, &bare).unwrap_err().to_string();
    assert!(
        e.contains("path.csv") && e.contains("line 1") && e.contains("missing column 'e1_mm'"),
        "{e}"
    );
}

/// Values the cell cannot take are refused naming the file, the line and the axis.
#[test]
fn external_values_the_cell_cannot_take_are_refused_naming_line_and_axis() {
    let s = on_track();
    let (text, _) = pose_path();
    let beyond = text.replace(",1650\n", ",6500\n");
    let e = compensated(&s, &beyond).unwrap_err().to_string();
    assert!(
        e.contains("line 6") && e.contains("e1_mm (track)") && e.contains("6500"),
        "{e}"
    );
    let other = text.replace("e1_mm", "e3_mm");
    let e = compensated(&s, &other).unwrap_err().to_string();
    assert!(
        e.contains("line 2, column 11 (e3_mm): no external axis has this column")
            && e.contains("e1_mm (track), e2_deg (table)"),
        "{e}"
    );
    let unit = text.replace("e2_deg", "e2_mm");
    let e = compensated(&s, &unit).unwrap_err().to_string();
    assert!(e.contains("column 10 (e2_mm)"), "{e}");
    let fixed = milling();
    let e = compensated(&fixed, &text).unwrap_err().to_string();
    assert!(
        e.contains("line 2") && e.contains("the cell has no external axes"),
        "{e}"
    );
    // Points read for the cell meet a robot without its axes: refused naming the line.
    let cell_axes = s.robot().external();
    let points: Vec<PathPoint> = path::points(&text, Frame::Base, cell_axes)
        .unwrap()
        .collect::<stiffid::Result<_>>()
        .unwrap();
    assert_eq!(points[1].line, 4);
    let e = cell::on_carriage(fixed.robot(), points[1].clone()).unwrap_err();
    assert!(e.to_string().contains("line 4"), "{e}");
}
