//! The path CSV format: both kinds of rows, roll-pitch-yaw as URDF, and errors naming line and
//! column.

use approx::assert_relative_eq;
use nalgebra::{UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::Target;
use stiffid::internal::machining::path::parse;
use stiffid::internal::observation::deflection::Frame;
use stiffid::Error;

#[test]
fn postures_and_poses_parse_in_si_units() {
    let text = "# a comment\nq1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,frame\n\
                10,20,-30,0,45,90,1,2,3,tool\n0,0,0,0,0,0,4,5,6,\n";
    let points = parse(text, Frame::Base).unwrap();
    assert_eq!(points.len(), 2);
    assert_eq!(points[0].line, 3);
    assert_eq!(points[0].frame, Frame::Tool);
    assert_eq!(points[1].frame, Frame::Base);
    assert_eq!(points[1].wrench, Vector6::new(4.0, 5.0, 6.0, 0.0, 0.0, 0.0));
    let Target::Posture(q) = &points[0].target else {
        panic!("expected a posture")
    };
    assert_relative_eq!(q[2], -30f64.to_radians());

    let text = "fz_n,fy_n,fx_n,mx_nm,my_nm,mz_nm,x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg\n\
                -200,0,0,1,2,3,1500,-200,800,10,20,30\n";
    let points = parse(text, Frame::Tool).unwrap();
    assert_eq!(points[0].frame, Frame::Tool);
    assert_eq!(
        points[0].wrench,
        Vector6::new(0.0, 0.0, -200.0, 1.0, 2.0, 3.0)
    );
    let Target::Pose(t) = &points[0].target else {
        panic!("expected a pose")
    };
    assert_relative_eq!(t.translation.vector, Vector3::new(1.5, -0.2, 0.8));
    // URDF's rpy: fixed axes, R = Rz(yaw) Ry(pitch) Rx(roll).
    let axis = |v: Vector3<f64>, deg: f64| {
        UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(v), deg.to_radians())
    };
    let expected = axis(Vector3::z(), 30.0) * axis(Vector3::y(), 20.0) * axis(Vector3::x(), 10.0);
    assert_relative_eq!(t.rotation, expected, epsilon = 1e-12);
}

fn row_error(text: &str) -> (u64, String, String) {
    match parse(text, Frame::Base) {
        Err(Error::Column {
            line,
            name,
            problem,
            ..
        }) => (line, name, problem.to_string()),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_files_name_the_line_and_column() {
    let q = "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg";
    let cases = [
        (format!("{q},fx_n,fy_n\n"), 1, "fz_n", "missing"),
        (
            "fx_n,fy_n,fz_n\n1,2,3\n".to_string(),
            1,
            "",
            "missing columns: expected q1_deg",
        ),
        (
            format!("{q},fx_n,fy_n,fz_n,speed\n"),
            1,
            "",
            "unknown column 'speed'",
        ),
        (
            format!("{q},fx_n,fy_n,fz_n\n0,0,0,0,0,0,1,2,3\n0,0,NaN,0,0,0,1,2,3\n"),
            3,
            "q3_deg",
            "'NaN' is not a finite number",
        ),
        (
            format!("{q},fx_n,fy_n,fz_n\n0,0,0,0,0,0,1,2,abc\n"),
            2,
            "fz_n",
            "'abc' is not a finite number",
        ),
        (
            format!("{q},fx_n,fy_n,fz_n,frame\n0,0,0,0,0,0,1,2,3,world\n"),
            2,
            "frame",
            "expected base or tool",
        ),
        (
            format!("{q},fx_n,fy_n,fz_n\n0,0,0,0,0,0,1,2\n"),
            2,
            "",
            "expected 9 fields",
        ),
        (format!("{q},fx_n,fy_n,fz_n\n"), 1, "", "at least one"),
        (
            format!("{q},x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n\n"),
            1,
            "",
            "not both",
        ),
        (format!("{q},fx_n,fy_n,fz_n,mx_nm\n"), 1, "my_nm", "missing"),
    ];
    for (text, line, column, message) in cases {
        let (l, c, m) = row_error(&text);
        assert_eq!((l, c.as_str()), (line, column), "{text}: {m}");
        assert!(m.contains(message), "{text}: {m}");
    }
}

/// Lines are counted from the text, whatever the line ends: the csv crate's own count is one too
/// low after a `\r\n` (it counts the `\n` when it reads the next record).
#[test]
fn lines_are_right_after_crlf_blank_and_comment_lines() {
    let header = "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n";
    let good = "0,0,-90,0,30,0,0,0,-500";
    let bad = "0,0,-90,0,30,0,0,0,x";
    for end in ["\n", "\r\n"] {
        let text = ["# c", header, good, "", "# d", good, bad].join(end) + end;
        let points = parse(&text.replace(bad, good), Frame::Base).unwrap();
        let lines: Vec<u64> = points.iter().map(|p| p.line).collect();
        assert_eq!(lines, [3, 6, 7], "{end:?}");
        assert_eq!(row_error(&text).0, 7, "{end:?}");
    }
}

#[test]
fn a_posture_file_names_the_line_of_a_crlf_row() {
    let robot = stiffid::internal::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
    let text = "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\r\n1,0,0,-90,0,30,0\r\n\r\n2,0,0,-90,0,30,x\r\n";
    match stiffid::internal::io::postures::parse(text, &robot, None) {
        Err(Error::Column { line, name, .. }) => assert_eq!((line, name.as_str()), (4, "q6_deg")),
        other => panic!("{other:?}"),
    }
}
