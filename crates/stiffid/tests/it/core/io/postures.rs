//! Posture files: written and read back, errors naming the line and column, the separator hint,
//! a cell's external axes, and the limit on the number of postures.

use approx::assert_relative_eq;
use nalgebra::Vector6;
use stiffid_core::common::error::ColumnProblem;
use stiffid_core::common::limits::MAX_GROUP_POSTURES;
use stiffid_core::io::postures::*;
use stiffid_core::{Error, Result};

fn parse_in_bounds(text: &str) -> Result<Vec<Vector6<f64>>> {
    let s = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    parse(text, s.robot(), Some(s.bounds()))
}

#[test]
fn written_postures_read_back() {
    let q = vec![
        Vector6::new(0.1, -0.2, -1.5, 0.4, 0.5, -0.6),
        Vector6::new(-0.3, 0.2, -2.0, -1.0, 0.0, 3.0),
    ];
    let back = parse_in_bounds(&to_csv(&q)).unwrap();
    assert_eq!(back.len(), 2);
    for (a, b) in q.iter().zip(&back) {
        assert_relative_eq!(a, b, epsilon = 1e-7);
    }
}

#[test]
fn errors_name_the_line_and_column() {
    let head = HEADER.join(",");
    let bad = format!("{head}\n1,0,0,-90,0,0,0\n2,0,x,-90,0,0,0\n");
    let e = parse_in_bounds(&bad).unwrap_err();
    assert!(
        matches!(&e, Error::Column { line: 3, column: Some(3), name, problem: ColumnProblem::NotANumber { value } } if name == "q2_deg" && value == "x"),
        "{e:?}"
    );
    let e = parse_in_bounds("posture,a\n").unwrap_err().to_string();
    assert!(
        e.starts_with("line 1: expected the header 'posture,q1_deg"),
        "{e}"
    );
    let e = parse_in_bounds(&format!("{head}\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least one posture row"), "{e}");
    let e = parse_in_bounds(&format!("{head}\n1,0,0,-90\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2: expected 7 fields"), "{e}");
    let e = parse_in_bounds(&format!("{head}\n1,0,0,-90,0,0,9000\n"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("column 7 (q6_deg): q6_deg = 9000 is outside the setup's bounds"),
        "{e}"
    );
}

#[test]
fn a_semicolon_separated_file_gets_the_separator_hint() {
    let text = HEADER.join(";") + "\n1;0;0;-90;0;0;0\n";
    let e = parse_in_bounds(&text).unwrap_err().to_string();
    assert!(
        e.contains("' (this header separates its columns with ';'"),
        "{e}"
    );
    // A header merely wrong gets none.
    let e = parse_in_bounds("posture,a\n").unwrap_err().to_string();
    assert!(!e.contains("';'"), "{e}");
    // A measurement file (whose columns are named, in any order) gets it too.
    let measurements = "posture;point;q1_deg;q2_deg;q3_deg;q4_deg;q5_deg;q6_deg;fx_n;fy_n;fz_n;dx_mm;dy_mm;dz_mm\n";
    let e = stiffid_core::io::measurements::parse(measurements)
        .unwrap_err()
        .to_string();
    assert!(e.contains("columns with ';'"), "{e}");
}

#[test]
fn a_cells_postures_carry_its_external_axes() {
    let text = stiffid_core::robot::presets::text("comau-smart5-nj165-3.0").unwrap().to_string()
        + "\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_mm = [0, 6000]\n"
        + "[[external_axis]]\nname = \"turn\"\nrole = \"positioner\"\ndirection = [0, 0, 1]\nlimits_deg = [-180, 180]\n";
    let cell = stiffid_core::robot::file::parse(&text, "cell.toml").unwrap();
    let q = vec![Vector6::new(0.1, -0.2, -1.5, 0.4, 0.5, -0.6); 2];
    let e = vec![vec![1.25, 0.5], vec![5.5, -3.0]];
    let written = to_csv_cell(&q, &e, cell.external());
    assert!(
        written.starts_with(&(HEADER.join(",") + ",e1_mm,e2_deg\n")),
        "{written}"
    );
    assert!(written.contains(",1250.000000,28.647890\n"), "{written}");
    let back = parse_cell(&written, &cell, None).unwrap();
    assert_eq!(back.q.len(), 2);
    for (a, b) in e.iter().zip(&back.e) {
        assert_relative_eq!(a[0], b[0], epsilon = 1e-9);
        assert_relative_eq!(a[1], b[1], epsilon = 1e-8);
    }
    // Without its columns, with an axis it lacks, outside the travel: refused, named.
    let e = parse(&to_csv(&q), &cell, None).unwrap_err().to_string();
    assert!(e.contains("e1_mm,e2_deg"), "{e}");
    let plain = stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
    let e = parse(&written, &plain, None).unwrap_err().to_string();
    assert!(e.contains("the robot has no external axes: e1_mm"), "{e}");
    let far = written.replace(",1250.000000,", ",7000.000000,");
    let e = parse_cell(&far, &cell, None).unwrap_err().to_string();
    assert!(
        e.contains("line 2 e1_mm (track)") && e.contains("0 to 6000 mm"),
        "{e}"
    );
    let nan = written.replace(",28.647890\n", ",x\n");
    let e = parse_cell(&nan, &cell, None).unwrap_err().to_string();
    assert!(e.contains("e2_deg"), "{e}");
    // The arm's postures alone: at the cell's zero, another station refused naming it.
    let e = parse(&written, &cell, None).unwrap_err().to_string();
    assert!(e.starts_with("posture 1: e1_mm: not 0"), "{e}");
    let zero = to_csv_cell(&q, &[vec![0.0, 0.0], vec![0.0, 0.0]], cell.external());
    let back = parse(&zero, &cell, None).unwrap();
    assert!((back[1] - q[1]).amax() < 1e-8, "{:?}", back[1]);
}

#[test]
fn more_postures_than_the_limit_are_refused() {
    let mut text = HEADER.join(",") + "\n";
    for i in 0..=MAX_GROUP_POSTURES {
        text += &format!("{},0,0,-90,0,30,0\n", i + 1);
    }
    let e = parse_in_bounds(&text).unwrap_err().to_string();
    let last = MAX_GROUP_POSTURES + 2;
    assert!(
        e.starts_with(&format!(
            "line {last}: more than {MAX_GROUP_POSTURES} postures"
        )),
        "{e}"
    );
}
