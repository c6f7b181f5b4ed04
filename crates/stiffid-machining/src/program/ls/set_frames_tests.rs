//! The frames an LS program sets at its start ([`super`]).

use crate::program::cartesian::Frame;
use crate::program::Context;
use nalgebra::Vector3;

/// A program as RoboDK's post writes it: register 9's elements, user frame 9 set from it, then a
/// linear motion in user frame 9; `start` the instructions before the motion.
fn program(start: &[&str]) -> String {
    let mut mn = String::new();
    for (i, t) in start.iter().enumerate() {
        mn += &format!("{:>4}:  {t} ;\n", i + 1);
    }
    let n = start.len() + 1;
    format!("/PROG  A\n/MN\n{mn}{n:>4}:L P[1] 100mm/sec FINE ;\n/POS\nP[1]{{\n   GP1:\n\tUF : 9, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n\tX = 10.000 mm,\tY = 0.000 mm,\tZ = 0.000 mm,\n\tW = 0.000 deg,\tP = 0.000 deg,\tR = 0.000 deg\n}};\n/END\n")
}

/// `POSREG.VA` with register 9 in Cartesian (`true`) or joint representation.
fn posreg(cartesian: bool) -> String {
    let value = match cartesian {
        true => "  Group: 1   Config: N U T, 0, 0, 0\n  X:     0.000   Y:     0.000   Z:     0.000\n  W:     0.000   P:     0.000   R:     0.000\n",
        false => "  Group: 1\n  J1 =     0.000 deg   J2 =     0.000 deg   J3 =     0.000 deg\n  J4 =     0.000 deg   J5 =     0.000 deg   J6 =     0.000 deg\n",
    };
    format!("[*POSREG*]$POSREG  Storage: SHADOW  Access: RW  : ARRAY[1,10] OF Position Reg\n    [1,9] =   ''\n{value}")
}

/// The frame of the program's one Cartesian target, read with `backup`; or the refusal's line.
fn frame(text: &str, backup: &[(String, String)]) -> Result<Frame, u64> {
    let context = Context {
        backup,
        ..Default::default()
    };
    match super::super::read::targets(text, &context) {
        Ok(p) => Ok(p.targets[0].cartesian.as_deref().unwrap().frame.clone()),
        Err(stiffid_core::Error::Program { line, .. }) => Err(line),
        Err(other) => panic!("{other}"),
    }
}

#[test]
fn a_user_frame_set_from_a_register_at_the_start_is_read_where_the_register_is_cartesian() {
    let elements = [
        "PR[9,1]=2000",
        "PR[9,2]=(-9500)",
        "PR[9,3]=(-1395)",
        "PR[9,4]=0",
        "PR[9,5]=0",
        "PR[9,6]=90",
        "PR[9,7]=0",
    ];
    let set = [&elements[..], &["UFRAME[9:STRIP]=PR[9]", "UFRAME_NUM=9"]].concat();
    let backup = |cartesian| vec![("POSREG.VA".to_string(), posreg(cartesian))];
    // Read: the frame the elements give, stated on the line that sets it (the file's line 10).
    let Ok(Frame::Stated(line, f)) = frame(&program(&set), &backup(true)) else {
        panic!("not read");
    };
    assert_eq!(line, 10);
    assert!((f.translation.vector - Vector3::new(2.0, -9.5, -1.395)).norm() < 1e-12);
    let x = f.rotation * Vector3::x();
    assert!((x - Vector3::y()).norm() < 1e-12, "{x}");
    // Refused on the line that sets it: a joint register, no POSREG.VA, an element missing, the
    // frame set after a label (not on every path before the motion only once).
    assert_eq!(frame(&program(&set), &backup(false)), Err(10));
    assert_eq!(frame(&program(&set), &[]), Err(10));
    let missing = [&elements[1..], &["UFRAME[9]=PR[9]"]].concat();
    assert_eq!(frame(&program(&missing), &backup(true)), Err(9));
    let labelled = [&["LBL[1]"], &set[..]].concat();
    assert_eq!(frame(&program(&labelled), &backup(true)), Err(11));
}
