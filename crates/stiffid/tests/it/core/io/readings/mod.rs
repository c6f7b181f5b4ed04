use nalgebra::Vector3;
use stiffid_core::Robot;
mod direction;

use stiffid_core::io::readings::*;

fn robot() -> Robot {
    stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap()
}

fn error(body: &str) -> String {
    let text = format!("{}\n{body}", header());
    parse(&text, &robot(), 4).unwrap_err().to_string()
}

#[test]
fn rows_read_in_any_column_order() {
    let text = "# registration\nx_tracker_mm,posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,y_tracker_mm,z_tracker_mm\n\
                1500,a,2,10,0,-90,0,0,0,-20,300\n1600,a,1,10,0,-90,0,0,0,-20,300\n1700,b,1,0,0,-90,0,0,0,-20,300\n";
    let r = parse(text, &robot(), 4).unwrap();
    assert_eq!(r.labels, ["a", "b"]);
    assert_eq!(r.lines, [3, 4, 5]);
    let first = &r.readings[0];
    assert_eq!((first.posture, first.point), (0, 1));
    assert!((first.q[0] - 10f64.to_radians()).abs() < 1e-15);
    assert_eq!(first.position, Vector3::new(1.5, -0.02, 0.3));
    assert_eq!(r.readings[2].posture, 1);
}

/// The Comau on a 6 m track along x, with a turntable when `positioner`.
fn cell(positioner: bool) -> Robot {
    use stiffid_core::robot::external::{ExternalAxes, ExternalAxis};
    let mut axes = vec![ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0)];
    if positioner {
        let p = Vector3::new(3.0, 2.0, 0.8);
        let pi = std::f64::consts::PI;
        axes.push(ExternalAxis::rotary("turn", p, Vector3::z_axis(), -pi, pi));
    }
    robot().with_external(Some(ExternalAxes::new(axes).unwrap()))
}

#[test]
fn external_axes_and_table_reflectors() {
    let head = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,e1_mm,e2_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm";
    let row = "0,0,-90,0,0,0";
    let text = format!(
        "{head}\na,1,{row},2500,0,1,2,3\nt,T1,{row},2500,45,4,5,6\nt,t2,{row},2500,45,4,5,6\n"
    );
    let r = parse(&text, &cell(true), 4).unwrap();
    assert_eq!(r.readings[0].e.as_slice(), [2.5, 0.0]);
    assert!((r.readings[1].e.as_slice()[1] - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    let t = &r.readings[2];
    assert!(t.table && t.point == 1 && !r.readings[0].table);
    assert_eq!((r.tables, r.labels.len()), (2, 2));
    let error = |text: String, robot: &Robot| parse(&text, robot, 4).unwrap_err().to_string();
    let e = error(format!("{head}\na,1,{row},6500,0,1,2,3\n"), &cell(true));
    assert_eq!(
        e,
        "line 2, column 9 (e1_mm): e1_mm = 6500 is outside the axis's travel [0.0, 6000.0]"
    );
    let e = error(format!("{head}\na,T0,{row},2500,0,1,2,3\n"), &cell(true));
    assert!(
        e.contains("column 2 (point): 'T0' is not a reflector fixed in the cell (T1 to T100)"),
        "{e}"
    );
    let e = error(
        format!("{head}\na,1,{row},2500,0,1,2,3\na,2,{row},2400,0,1,2,3\n"),
        &cell(true),
    );
    assert!(
        e.contains("posture 'a' has other external axis values on line 2"),
        "{e}"
    );
    let e = error(
        format!("{head}\nt,T1,{row},2500,0,1,2,3\nt,T1,{row},2500,0,1,2,3\n"),
        &cell(true),
    );
    assert!(
        e.contains("table reflector T1 of posture 't' is read on line 2 already"),
        "{e}"
    );
    // Missing the positioner's column; a column of an axis the cell lacks.
    let short_head = head.replace(",e2_deg", "");
    let e = error(format!("{short_head}\na,1,{row},2500,1,2,3\n"), &cell(true));
    assert!(e.contains("missing column 'e2_deg'"), "{e}");
    let e = error(format!("{head}\na,1,{row},2500,0,1,2,3\n"), &cell(false));
    assert_eq!(
        e,
        "line 1, column 10 (e2_deg): no external axis has this column: the cell's external axes are e1_mm (track)"
    );
    // A reflector fixed in a cell without a positioner: a fixed point of the cell.
    let fixed = parse(
        &format!("{short_head}\na,T3,{row},2500,1,2,3\n"),
        &cell(false),
        4,
    );
    let fixed = fixed.unwrap();
    assert!(fixed.readings[0].table && fixed.readings[0].point == 2);
    assert_eq!(fixed.tables, 3);
    let e = error(format!("{head}\na,1,{row},2500,0,1,2,3\n"), &robot());
    assert!(
        e.contains(
            "column 9 (e1_mm): no external axis has this column: the cell has no external axes"
        ),
        "{e}"
    );
}

#[test]
fn errors_name_the_line_and_column() {
    let e = error("a,1,0,0,-90,0,0,0,1,2,x\n");
    assert_eq!(
        e,
        "line 2, column 11 (z_tracker_mm): 'x' is not a finite number"
    );
    let e = error("a,5,0,0,-90,0,0,0,1,2,3\n");
    assert!(
        e.contains(
            "column 2 (point): point = 5 is outside the setup's measuring points [1.0, 4.0]"
        ),
        "{e}"
    );
    let e = error("a,1,0,0,-90,0,0,0,1,2,3\na,1,0,0,-90,0,0,0,1,2,3\n");
    assert!(
        e.contains("line 3, column 1 (posture): point 1 of posture 'a' is read on line 2 already"),
        "{e}"
    );
    let e = error("a,1,0,0,-90,0,0,0,1,2,3\na,2,1,0,-90,0,0,0,1,2,3\n");
    assert!(
        e.contains("posture 'a' has other axis angles on line 2"),
        "{e}"
    );
    let e = error("a,1,0,0,-90,0,0,0,1,2,1e9\n");
    assert!(
        e.contains("column 11 (z_tracker_mm): z_tracker_mm = 1e9 is outside the accepted range"),
        "{e}"
    );
    let e = error("a,1,0,999,-90,0,0,0,1,2,3\n");
    assert!(e.contains("column 4 (q2_deg): q2_deg = 999"), "{e}");
    let e = error("");
    assert!(e.contains("at least one reading row"), "{e}");
    let e = parse("posture,point,q1,q2_deg\n", &robot(), 4)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown column 'q1' (did you mean 'q1_deg'?)"),
        "{e}"
    );
    let e = parse("posture,point\n", &robot(), 4)
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing column 'q1_deg'"), "{e}");
}
