//! A program written back (`crate::program::JointProgram::write_pair`): a KRL program's targets
//! into its `.dat`, every other byte as read.

use crate::program::{parse_with_data, Dialect};
use stiffid_core::Error;

#[test]
fn targets_in_the_dat_are_written_back_into_it_and_nothing_else() {
    let src = "DEF pick( )\r\nPTP XHOME1\r\nPTP XP1\r\nEND\r\n";
    let dat = "DEFDAT  pick\r\nDECL E6AXIS XHOME1={A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0,E1 0.0}\r\nDECL E6AXIS XP1={A1 10.5,A2 -80.0,A3 85.0,A4 1.0,A5 20.0,A6 3.0,E1 0.0}\r\nENDDAT\r\n";
    let p = parse_with_data(src, Some(dat), Dialect::Krl).unwrap();
    assert_eq!(p.targets[1].q_deg, [10.5, -80.0, 85.0, 1.0, 20.0, 3.0]);
    let q = [p.targets[0].q_deg, [10.5, -80.25, 85.0, 1.0, 20.0, 3.125]];
    let e: Vec<Vec<Option<f64>>> = p.targets.iter().map(|t| t.external.clone()).collect();
    let (s, d) = p.write_pair(&q, &e).unwrap();
    assert_eq!(s, src);
    let want = dat
        .replace("A2 -80.0,", "A2 -80.250000000,")
        .replace("A6 3.0,", "A6 3.125000000,");
    assert_eq!(d.as_deref(), Some(want.as_str()));
    // The program alone cannot carry them.
    assert!(matches!(p.write(&q), Err(Error::InvalidField { field, .. }) if field == "data"));
    assert_eq!(p.write(&[q[0], p.targets[1].q_deg]).unwrap(), src);
}

/// A point visited twice with different compensations becomes two points: the first visit's
/// value in its declaration, the second's in a copy declared beside it under a free name, which
/// the second motion names; every other byte as read. Visits alike share one point.
#[test]
fn a_point_visited_with_different_values_is_written_as_two_points() {
    let src = "DEF pick( )\nPTP XP1\nPTP XP2\nPTP XP1\nPTP XP1\nEND\n";
    let dat = "DEFDAT pick\nDECL E6AXIS XP1={A1 1.0,A2 2.0,A3 3.0,A4 4.0,A5 5.0,A6 6.0}\nDECL E6AXIS XP1_2={A1 0.0,A2 0.0,A3 0.0,A4 0.0,A5 0.0,A6 0.0}\nDECL E6AXIS XP2={A1 0.0,A2 0.0,A3 0.0,A4 0.0,A5 0.0,A6 0.0}\nENDDAT\n";
    let p = parse_with_data(src, Some(dat), Dialect::Krl).unwrap();
    let a = [1.0, 2.5, 3.0, 4.0, 5.0, 6.0];
    let b = [1.0, 2.0, 3.0, 4.0, 5.0, 6.25];
    let q = [a, p.targets[1].q_deg, b, b];
    let e = vec![Vec::new(); 4];
    let (s, d) = p.write_pair(&q, &e).unwrap();
    // XP1_2 is taken: the copy is XP1_3, named by the two later visits.
    assert_eq!(
        s,
        "DEF pick( )\nPTP XP1\nPTP XP2\nPTP XP1_3\nPTP XP1_3\nEND\n"
    );
    let d = d.unwrap();
    let want = "DECL E6AXIS XP1={A1 1.0,A2 2.500000000,A3 3.0,A4 4.0,A5 5.0,A6 6.0}\nDECL E6AXIS XP1_3={A1 1.000000000,A2 2.000000000,A3 3.000000000,A4 4.000000000,A5 5.000000000,A6 6.250000000}\nDECL E6AXIS XP1_2=";
    assert!(d.contains(want), "{d}");
    // Read back, each motion goes to its own value.
    let back = parse_with_data(&s, Some(&d), Dialect::Krl).unwrap();
    let got: Vec<[f64; 6]> = back.targets.iter().map(|t| t.q_deg).collect();
    assert_eq!(got, vec![a, p.targets[1].q_deg, b, b]);
}
