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
