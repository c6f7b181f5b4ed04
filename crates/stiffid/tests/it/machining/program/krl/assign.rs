//! Points a KRL program assigns from points the files declare (`XP2 = XP1`, `XP2.Z = XP2.Z - 9`,
//! `XP3 = XP1 : {X 60, ..}`): computed where every path that reaches the motion agrees, the
//! motion compensated to a new point the `.dat` declares beside the others; refused naming the
//! line where the run decides.

use stiffid::internal::machining::program::{self, Dialect};
use stiffid::Error;

const SRC: &str = "DEF mill( )\n$TOOL = {X 0, Y 0, Z 250, A 0, B 0, C 0}\n$BASE = {X 2000, Y 0, Z 550, A 0, B 0, C 0}\nPTP XP1\n$VEL.CP = 0.03\nXP2 = XP1\nXP2.Z = XP2.Z - 9\nLIN XP2 C_DIS\nXP3 = XP1\nXP3 = XP1 : {X 60, Y 0, Z 0, A 0, B 0, C 0}\nLIN XP3\nEND\n";
const DAT: &str = "DEFDAT mill\nDECL E6POS XP1={X 0, Y -100, Z 5, A 0, B 0, C 180, S 'B010', T 'B101001'}\nDECL E6POS XP2={X 0, Y 0, Z 0, A 0, B 0, C 0, S 'B010', T 'B101001'}\nDECL E6POS XP3={X 0, Y 0, Z 0, A 0, B 0, C 0, S 'B010', T 'B101001'}\nENDDAT\n";
/// [`DAT`] with the values the assignments give declared.
const DECLARED: &str = "DEFDAT mill\nDECL E6POS XP1={X 0, Y -100, Z 5, A 0, B 0, C 180, S 'B010', T 'B101001'}\nDECL E6POS XP2={X 0, Y -100, Z -4, A 0, B 0, C 180, S 'B010', T 'B101001'}\nDECL E6POS XP3={X 60, Y -100, Z 5, A 0, B 0, C 180, S 'B010', T 'B101001'}\nENDDAT\n";

#[test]
fn an_assigned_point_is_computed_and_compensated_as_its_value_declared() {
    let p = super::backup::run((SRC, Some(DAT)), &[]).unwrap();
    let data = p.data.unwrap();
    assert!(
        p.text.contains("LIN XP2_S7 C_DIS") && p.text.contains("LIN XP3_S10"),
        "{}",
        p.text
    );
    assert!(
        p.text.contains("XP2 = XP1\nXP2.Z = XP2.Z - 9\n"),
        "{}",
        p.text
    );
    // The same path with the values declared: the same compensated points.
    let src = SRC.replace("XP2 = XP1\nXP2.Z = XP2.Z - 9\n", "");
    let src = src.replace(
        "XP3 = XP1\nXP3 = XP1 : {X 60, Y 0, Z 0, A 0, B 0, C 0}\n",
        "",
    );
    let q = super::backup::run((&src, Some(DECLARED)), &[]).unwrap();
    let declared = q.data.unwrap();
    for (a, b) in [("XP2_S7", "XP2"), ("XP3_S10", "XP3")] {
        let (x, y) = (
            super::backup::members(&data, a),
            super::backup::members(&declared, b),
        );
        assert!(
            x.iter().zip(&y).all(|(u, v)| (u - v).abs() < 1e-6),
            "{a} {x:?} {b} {y:?}"
        );
    }
}

/// A rapid to a point computed from a cut point, on a spindle without mass: the cut point is
/// compensated in the `.dat`, the rapid not at all; the motion still names the computed point's
/// own declaration, since at run time the assignment reads the compensated cut point.
#[test]
fn a_computed_point_the_compensation_leaves_is_declared_as_computed() {
    let src = "DEF mill( )\n$TOOL = {X 0, Y 0, Z 250, A 0, B 0, C 0}\n$BASE = {X 2000, Y 0, Z 550, A 0, B 0, C 0}\n$VEL.CP = 0.03\nLIN XP1\nXP3 = XP1\nXP3 = XP1 : {X 60, Y 0, Z 0, A 0, B 0, C 0}\nPTP XP3\nEND\n";
    let massless = |setup: &str| {
        (setup.lines())
            .filter(|l| !l.starts_with("mass_kg") && !l.starts_with("centre_of_mass_mm"))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    let p = super::backup::run_with(&massless, (src, Some(DAT)), &[]).unwrap();
    let data = p.data.unwrap();
    let cut = super::backup::members(&data, "XP1");
    assert!((cut[2] - 5.0).abs() > 1e-6, "{data}");
    assert!(p.text.contains("\nPTP XP3_S7 ;"), "{}", p.text);
    let rapid = super::backup::members(&data, "XP3_S7");
    let declared = [60.0, -100.0, 5.0, 0.0, 0.0, 180.0];
    assert!(
        rapid
            .iter()
            .zip(declared)
            .all(|(u, v)| (u - v).abs() < 1e-6),
        "{rapid:?}"
    );
}

#[test]
fn an_assigned_point_the_run_decides_is_refused_naming_the_line() {
    let cases = [
        // Assigned in one branch only.
        (
            "XP2 = XP1\n",
            "IF $IN[1] THEN\nXP2 = XP1\nENDIF\n",
            10,
            "depends on the path taken through IF (line 6)",
        ),
        // Moved to in a loop before the body assigns it.
        (
            "XP2 = XP1\nXP2.Z = XP2.Z - 9\nLIN XP2 C_DIS\n",
            "FOR I = 1 TO 2\nLIN XP2 C_DIS\nXP2 = XP1\nENDFOR\n",
            7,
            "is assigned on line 8 in the FOR loop of line 6",
        ),
        // Before any assignment: the value the last run left.
        (
            "XP2 = XP1\nXP2.Z = XP2.Z - 9\nLIN XP2 C_DIS\n",
            "LIN XP2 C_DIS\nXP2 = XP1\n",
            6,
            "XP2 is assigned on line 7",
        ),
        // From a value only the run gives.
        (
            "XP2 = XP1\n",
            "XP2 = $POS_ACT\n",
            8,
            "assigned on line 6 from '$POS_ACT'",
        ),
    ];
    for (from, to, line, says) in cases {
        let src = SRC.replace(from, to);
        match program::parse_with_data(&src, Some(DAT), Dialect::Krl) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(says), "{message}");
            }
            other => panic!("{to}: {other:?}"),
        }
    }
}
