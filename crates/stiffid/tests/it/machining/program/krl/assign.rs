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
    // The same path with XP2's value declared and XP3's computed in the motion (`LIN XP1 :
    // {..}`, a FRAME): the same compensated points, the motion naming its new point.
    let src = SRC.replace("XP2 = XP1\nXP2.Z = XP2.Z - 9\n", "");
    let src = src.replace(
        "XP3 = XP1\nXP3 = XP1 : {X 60, Y 0, Z 0, A 0, B 0, C 0}\nLIN XP3\n",
        "LIN XP1 : {X 60, Y 0, Z 0, A 0, B 0, C 0} ; a cut\n",
    );
    let q = super::backup::run((&src, Some(DECLARED)), &[]).unwrap();
    assert!(q.text.contains("\nLIN XP1_S7 ; a cut ;"), "{}", q.text);
    let declared = q.data.unwrap();
    assert!(declared.contains("DECL FRAME XP1_S7={X "), "{declared}");
    for (a, b) in [("XP2_S7", "XP2"), ("XP3_S10", "XP1_S7")] {
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

/// The `z` a case reads (mm), or the line and words of its refusal.
type Expected = Result<f64, (u64, &'static str)>;

/// Numbers of the files (`REAL`, `INT`, `BOOL` of the `.dat` and `$config.dat`) read in point
/// arithmetic and conditions where every path agrees (`INT / INT` as integers, an `IF` or
/// `SWITCH` the files decide read down its taken branch only); refused naming the line where the
/// run decides.
#[test]
fn numbers_of_the_files_are_read_where_every_path_agrees() {
    let dat = DAT.replace(
        "ENDDAT",
        "DECL REAL rDepth=9.0\nDECL INT nCut=7\nDECL BOOL bDeep=TRUE\nDECL INT nRecipe=3\nENDDAT",
    );
    let config = "DEFDAT $CONFIG PUBLIC\nDECL GLOBAL REAL rGlobal=4.5\nENDDAT\n".to_string();
    let files = [("KRC/R1/System/$config.dat".to_string(), config)];
    let context = program::Context::default()
        .with_data(Some(&dat))
        .with_backup(&files);
    let z = |p: &program::JointProgram| p.targets[1].cartesian.as_deref().unwrap().position_mm.z;
    let cases: [(&str, Expected); 12] = [
        ("XP2.Z = XP2.Z - rDepth\n", Ok(-4.0)),
        ("XP2.Z = XP2.Z - 2 * rGlobal\n", Ok(-4.0)),
        // 7 / 2 is 3 in KRL.
        ("XP2.Z = XP2.Z - nCut / 2 * 3\n", Ok(-4.0)),
        ("IF bDeep AND (nCut > 6) THEN\nXP2.Z = XP2.Z - 9\nELSE\nXP2.Z = XP2.Z - 1\nENDIF\n", Ok(-4.0)),
        ("SWITCH nRecipe\nCASE 1\nXP2.Z = XP2.Z - 1\nCASE 2, 3\nXP2.Z = XP2.Z - 9\nDEFAULT\nXP2.Z = 0\nENDSWITCH\n", Ok(-4.0)),
        ("rDepth = $IN[3]\nXP2.Z = XP2.Z - rDepth\n", Err((9, "RDEPTH is assigned on line 7 from '$IN[3]'"))),
        ("IF $IN[1] THEN\nrDepth = 2\nENDIF\nXP2.Z = XP2.Z - rDepth\n", Err((11, "depends on the path taken through IF (line 7)"))),
        ("FOR nCut = 1 TO 3\nXP2.Z = XP2.Z - nCut\nENDFOR\n", Err((10, "in the FOR loop of line 7"))),
        // A loop whose motions read its variable: unrolled, each run its own value.
        ("FOR nCut = 3 TO 1 STEP -2\nXP2.Z = XP1.Z - nCut\nLIN XP2\nENDFOR\n", Ok(2.0)),
        ("FOR nCut = 1 TO 3 STEP 0\nXP2.Z = XP1.Z - nCut\nLIN XP2\nENDFOR\n", Err((7, "STEP 0"))),
        ("XP2.Z = XP2.Z - rNone\n", Err((8, "RNONE is no number declared"))),
        ("IF NOT bDeep THEN\nXP2.Z = XP2.Z - 9\n", Err((7, "IF without its ENDIF"))),
    ];
    for (to, expected) in cases {
        let src = SRC.replace("XP2.Z = XP2.Z - 9\n", to);
        match (program::parse_in(&src, Dialect::Krl, &context), expected) {
            (Ok(p), Ok(want)) => assert!((z(&p) - want).abs() < 1e-9, "{to}: {}", z(&p)),
            (Err(Error::Program { line, message }), Err((l, says))) => {
                assert_eq!(line, l, "{to}: {message}");
                assert!(message.contains(says), "{to}: {message}");
            }
            (other, _) => panic!("{to}: {other:?}"),
        }
    }
}
