//! Programs with external axes: KRL `E1..E6`, RAPID `eax_a..eax_f`, LS extended axes and group 2,
//! INFORM base and station axes read to their values and written back byte for byte but the
//! numbers that changed; refused against a cell that lacks an axis, a value outside its travel,
//! `9E9` in a used axis; a program that moves the track compensated with the track where it says.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::{self, Model, Options};
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::{self, external::cell_values, Dialect};
use stiffid::internal::machining::{self, Language};
use stiffid::internal::machining::{cell, gcode};
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis};
use stiffid::internal::robot::ik;
use stiffid::internal::robot::ik::tool_pose;
use stiffid::{internal::setup, Error};

const KRL: &str = "DEF track( )\nPTP {A1 10, A2 -80, A3 95, A4 0, A5 30, A6 -5, E1 1500.5, E2 0, E3 0, E4 0, E5 0, E6 0}\nDECL E6AXIS XP2={A1 11,A2 -79,A3 94,A4 0,A5 31,A6 -5,E1 1600,E2 45.25}\nLIN XP2 C_DIS\nEND\n";

const RAPID: &str = "MODULE Track\n  CONST jointtarget j1:=[[10,-20,30,0,45,0],[1500.5,0,9E9,9E9,9E9,9E9]];\n  PROC main()\n    MoveAbsJ j1, v100, fine, tool0;\n    MoveAbsJ [[11,-19,30,0,44,0],[1600, 45.25,9E+09,9E9,9E9,9E9]], v100, z10, tool0;\n  ENDPROC\nENDMODULE\n";

const LS: &str = "/PROG  TRACK\n/MN\n   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec CNT100 ;\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1=    10.000 deg,\tJ2=   -20.500 deg,\tJ3=    30.000 deg,\n\tJ4=     0.000 deg,\tJ5=   -45.000 deg,\tJ6=     5.000 deg,\n\tE1=  1500.500  mm\n   GP2:\n\tUF : 0, UT : 1,\n\tJ1=     0.000 deg,\tJ2=   -15.000 deg\n};\nP[2]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1=    11.000 deg,\tJ2=   -20.000 deg,\tJ3=    30.000 deg,\n\tJ4=     0.000 deg,\tJ5=   -44.000 deg,\tJ6=     5.000 deg,\n\tE1=  1600.000  mm\n   GP2:\n\tUF : 0, UT : 1,\n\tJ1=    45.250 deg,\tJ2=   -15.000 deg\n};\n/END\n";

const INFORM: &str = "/JOB\r\n//NAME TRACK\r\n//POS\r\n///NPOS 2,2,2,0,0,0\r\n///TOOL 0\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=1000,-2050,3000,0,-4500,500\r\nC00001=1100,-2000,3000,0,-4400,500\r\nBC00000=150050\r\nBC00001=160000\r\n///POSTYPE ANGLE\r\n///ANGLE\r\nEC00000=0.000,-15.000\r\nEC00001=45.250,-15.000\r\n//INST\r\n///DATE 2026/11/25 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1,BS1,ST1\r\n'stiffid: pulses_per_deg = 100 100 100 100 100 100\r\n'stiffid: external_pulses = 100\r\nNOP\r\nMOVJ C00000 BC00000 EC00000 VJ=50.00\r\nMOVL C00001 BC00001 EC00001 V=100.0 PL=0\r\nEND\r\n";

fn x() -> nalgebra::Unit<Vector3<f64>> {
    Vector3::x_axis()
}

/// A track along x (0 to 6 m) and a turntable about z through (2.5, 0, 0) (-360 to 360 deg),
/// with a tilt about x through the same point (-90 to 90 deg) when `tilt`.
fn cell(tilt: bool) -> ExternalAxes {
    let turn = 360f64.to_radians();
    let mut axes = vec![
        ExternalAxis::linear("track", x(), 0.0, 6.0),
        ExternalAxis::rotary(
            "table",
            Vector3::new(2.5, 0.0, 0.0),
            Vector3::z_axis(),
            -turn,
            turn,
        ),
    ];
    if tilt {
        let quarter = 90f64.to_radians();
        axes.push(ExternalAxis::rotary(
            "tilt",
            Vector3::new(2.5, 0.0, 0.0),
            x(),
            -quarter,
            quarter,
        ));
    }
    ExternalAxes::new(axes).unwrap()
}

/// A program, its language, its external axes' names, the first two targets' external values
/// and the first target's axes.
type Case = (
    &'static str,
    Dialect,
    &'static [&'static str],
    Vec<Option<f64>>,
    Vec<Option<f64>>,
    [f64; 6],
);

#[test]
fn every_dialect_reads_its_external_axes_and_writes_back_only_what_changed() {
    let cases: [Case; 4] = [
        (
            KRL,
            Dialect::Krl,
            &["E1", "E2", "E3", "E4", "E5", "E6"],
            vec![
                Some(1500.5),
                Some(0.0),
                Some(0.0),
                Some(0.0),
                Some(0.0),
                Some(0.0),
            ],
            vec![Some(1600.0), Some(45.25), None, None, None, None],
            [10.0, -80.0, 95.0, 0.0, 30.0, -5.0],
        ),
        (
            RAPID,
            Dialect::Rapid,
            &["eax_a", "eax_b"],
            vec![Some(1500.5), Some(0.0)],
            vec![Some(1600.0), Some(45.25)],
            [10.0, -20.0, 30.0, 0.0, 45.0, 0.0],
        ),
        (
            LS,
            Dialect::FanucLs,
            &["E1", "GP2 J1", "GP2 J2"],
            vec![Some(1500.5), Some(0.0), Some(-15.0)],
            vec![Some(1600.0), Some(45.25), Some(-15.0)],
            [10.0, -20.5, 30.0, 0.0, -45.0, 5.0],
        ),
        (
            INFORM,
            Dialect::Inform,
            &["BC1", "EC1", "EC2"],
            vec![Some(1500.5), Some(0.0), Some(-15.0)],
            vec![Some(1600.0), Some(45.25), Some(-15.0)],
            [10.0, -20.5, 30.0, 0.0, -45.0, 5.0],
        ),
    ];
    for (text, dialect, axes, first, second, q) in cases {
        let p = program::parse(text, dialect).unwrap();
        assert_eq!(p.axes, axes, "{dialect:?}");
        assert_eq!(p.targets.len(), 2, "{dialect:?}");
        assert_eq!(p.targets[0].q_deg, q, "{dialect:?}");
        assert_eq!(p.targets[0].external, first, "{dialect:?}");
        assert_eq!(p.targets[1].external, second, "{dialect:?}");
        let q_read: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
        assert_eq!(p.write(&q_read).unwrap(), text, "{dialect:?}");
        // The track of the second target 12.5 mm further and its first axis 0.25 deg more: those
        // two numbers change, nothing else.
        let mut e: Vec<Vec<Option<f64>>> = p.targets.iter().map(|t| t.external.clone()).collect();
        e[1][0] = Some(1612.5);
        let mut q_new = q_read.clone();
        q_new[1][0] += 0.25;
        let out = p.write_with_external(&q_new, &e).unwrap();
        let again = program::parse(&out, dialect).unwrap();
        assert_eq!(again.targets[1].external[0], Some(1612.5), "{dialect:?}");
        assert_eq!(again.targets[1].external[1..], second[1..], "{dialect:?}");
        assert_eq!(again.targets[0].external, first, "{dialect:?}");
        assert!(
            (again.targets[1].q_deg[0] - q_new[1][0]).abs() <= 1e-9,
            "{dialect:?}"
        );
        assert_eq!(
            out.len() - text.len(),
            match dialect {
                // KRL, RAPID, LS: "1612.500000000" for "1600" (or "1600.000"), the axis with 9 decimals.
                Dialect::Krl => 10 + 10,
                Dialect::Rapid => 10 + 10,
                Dialect::FanucLs => 6 + 6,
                // INFORM: whole pulses, 161250 for 160000 and 1125 for 1100.
                Dialect::Inform => 0,
            },
            "{dialect:?}: {out}"
        );
    }
}

/// `PTP XHOME` passes through as the controller holds it, in a cell with external axes too:
/// no target (its values are the controller's, whether `home_deg` or the `.dat` gives them),
/// named as passed through; the motion after it is read with its external values.
#[test]
fn xhome_in_a_cell_with_external_axes_passes_through() {
    let text = "DEF track( )\nPTP XHOME\nPTP {A1 10, A2 -80, A3 95, A4 0, A5 30, A6 -5, E1 1500.5, E2 0}\nEND\n";
    let home = program::Context {
        home_deg: Some([0.0, -90.0, 90.0, 0.0, 30.0, 0.0]),
        ..Default::default()
    };
    let dat = "DEFDAT track\nDECL E6AXIS XHOME={A1 0,A2 -90,A3 90,A4 0,A5 30,A6 0,E1 2000,E2 90}\nENDDAT\n";
    for context in [home, home.with_data(Some(dat))] {
        let p = program::parse_in(text, Dialect::Krl, &context).unwrap();
        assert_eq!(p.targets.len(), 1);
        assert_eq!(p.targets[0].line, 3);
        assert_eq!(p.left.len(), 1);
        assert_eq!(p.left[0].line, 2);
        assert!(
            p.left[0].why.contains("home position, passed through"),
            "{}",
            p.left[0].why
        );
        let e = cell_values(&p, Some(&cell(false))).unwrap();
        assert_eq!(e[0], vec![1.5005, 0.0]);
    }
}

#[test]
fn program_values_are_checked_against_the_cell() {
    let two = cell(false);
    let three = cell(true);
    // In the cell's order, SI.
    let p = program::parse(LS, Dialect::FanucLs).unwrap();
    let e = cell_values(&p, Some(&three)).unwrap();
    assert!((e[1][0] - 1.6).abs() < 1e-15);
    assert!((e[1][1] - 45.25f64.to_radians()).abs() < 1e-15);
    assert!((e[0][2] + 15f64.to_radians()).abs() < 1e-15);
    let k = program::parse(KRL, Dialect::Krl).unwrap();
    let e = cell_values(&k, Some(&two)).unwrap();
    assert!((e[0][0] - 1.5005).abs() < 1e-15 && e[0][1] == 0.0 && e[0].len() == 2);
    // KUKA's zeros for axes that do not exist are no motion of them.
    let plain = KRL
        .replace(", E1 1500.5, E2 0", ", E1 0, E2 0")
        .replace(",E1 1600,E2 45.25", "");
    let k = program::parse(&plain, Dialect::Krl).unwrap();
    assert_eq!(cell_values(&k, None).unwrap(), vec![Vec::<f64>::new(); 2]);
    let refused = |text: &str, dialect: Dialect, cell: Option<&ExternalAxes>| {
        let p = program::parse(text, dialect).unwrap();
        match cell_values(&p, cell) {
            Err(Error::Program { line, message }) => (line, message),
            other => panic!("{dialect:?}: {other:?}"),
        }
    };
    // An axis the cell lacks: a fixed-base robot, or the tilt of a cell without one.
    let (line, m) = refused(KRL, Dialect::Krl, None);
    assert_eq!(line, 2);
    assert!(
        m.contains("E1 1500.5") && m.contains("no external axes"),
        "{m}"
    );
    let (line, m) = refused(LS, Dialect::FanucLs, Some(&two));
    assert_eq!(line, 3);
    assert!(
        m.contains("GP2 J2 -15") && m.contains("track (mm), table (deg)"),
        "{m}"
    );
    let (line, m) = refused(INFORM, Dialect::Inform, None);
    assert_eq!(line, 23);
    assert!(m.contains("BC1 1500.5"), "{m}");
    // A job without the track's base axis on a track cell: its station's first axis is no
    // track value (it stood in the track's place, 0 and 45.25 deg read as mm).
    let stations = INFORM
        .replace("///NPOS 2,2,2", "///NPOS 2,0,2")
        .replace("BC00000=150050\r\nBC00001=160000\r\n", "")
        .replace(" BC0000", " X")
        .replace(" X0 ", " ")
        .replace(" X1 ", " ")
        .replace("RB1,BS1,ST1", "RB1,ST1");
    let (line, m) = refused(&stations, Dialect::Inform, Some(&three));
    assert_eq!(line, 21, "{m}");
    assert!(
        m.contains("EC1: the program's axis carrying the part (a positioner's axis) stands where the cell's external axis 1 (track) carries the arm"),
        "{m}"
    );
    // 9E9 in a used axis.
    let (line, m) = refused(
        &RAPID.replace("[1500.5,0,", "[1500.5,9E9,"),
        Dialect::Rapid,
        Some(&two),
    );
    assert_eq!(line, 4);
    assert!(
        m.contains("eax_b") && m.contains("table") && m.contains("9E9"),
        "{m}"
    );
    // Outside the travel: the track's 6000 mm.
    let (line, m) = refused(
        &LS.replace("1600.000  mm", "6000.500  mm"),
        Dialect::FanucLs,
        Some(&three),
    );
    assert_eq!(line, 4);
    assert!(
        m.contains("E1 6000.5 mm") && m.contains("track") && m.contains("0 to 6000 mm"),
        "{m}"
    );
}

/// A malformed program and what its refusal holds: the language, the line and a word.
type Malformed = (String, Dialect, u64, &'static str);

/// External axes' values malformed in RAPID, KRL and LS.
fn malformed_axes() -> Vec<Malformed> {
    vec![
        (
            RAPID.replace("[1500.5,0,9E9,9E9,9E9,9E9]", "[1500.5,0,9E9]"),
            Dialect::Rapid,
            2,
            "eax_",
        ),
        (
            KRL.replace("E2 45.25", "E2 45.25, E2 3"),
            Dialect::Krl,
            3,
            "E2 given twice",
        ),
        (
            LS.replace("E1=  1600.000  mm", "E1=  1600.000  cm"),
            Dialect::FanucLs,
            21,
            "mm or deg",
        ),
        (
            LS.replace(
                "   GP2:\n\tUF : 0, UT : 1,\n\tJ1=    45.250",
                "   GP3:\n\tUF : 0, UT : 1,\n\tJ1=    45.250",
            ),
            Dialect::FanucLs,
            22,
            "third motion group",
        ),
        // A group's number was its first digit: GP12 was read as group 1.
        (
            LS.replace("   GP2:\n\tUF : 0, UT : 1,\n\tJ1=    45.250", "   GP12:\n\tUF : 0, UT : 1,\n\tJ1=    45.250"),
            Dialect::FanucLs,
            22,
            "GP12: a third motion group",
        ),
        (
            LS.replacen("   GP1:", "   GP1_0:", 1),
            Dialect::FanucLs,
            7,
            "GP1_0: expected a motion group number, GP1 or GP2",
        ),
        // A motion without its line number was passed over: the program lost a target.
        (
            LS.replace("   2:L P[2] 50mm/sec CNT100 ;", "L P[2] 50mm/sec CNT100 ;"),
            Dialect::FanucLs,
            4,
            "'L P[2] 50mm/sec CNT100 ;': expected a numbered instruction ('4: L P[4] ..') or a continuation (': ..') in /MN",
        ),
        // A motion whose keyword is lost or mistyped was passed over as an instruction.
        (
            LS.replace("   2:L P[2]", "   2:X P[2]"),
            Dialect::FanucLs,
            4,
            "X P[2] 50mm/sec CNT100: names a position P[i] but is no motion stiffid reads",
        ),
        (
            LS.replace("   2:L P[2]", "   2:L] P[2]"),
            Dialect::FanucLs,
            4,
            "L] P[2] 50mm/sec CNT100: names a position P[i]",
        ),
        (
            LS.replace("   2:L P[2]", "   2 L P[2]"),
            Dialect::FanucLs,
            4,
            "'2 L P[2] 50mm/sec CNT100 ;': expected a numbered instruction",
        ),
    ]
}

/// INFORM jobs malformed: pulses, positions, moves and instructions stiffid does not read.
fn malformed_inform_jobs() -> Vec<Malformed> {
    vec![
        (
            INFORM.replace("'stiffid: pulses_per_deg = 100 100 100 100 100 100\r\n", ""),
            Dialect::Inform,
            22,
            "pulses_per_deg",
        ),
        (
            INFORM.replace(
                "= 100 100 100 100 100 100",
                "= 100 -3.03707932596608e-309 100 100 100 100",
            ),
            Dialect::Inform,
            20,
            "from 1e-6 to 1e9",
        ),
        (
            INFORM
                .replace("= 100 100 100 100 100 100", "= 1e-6 100 100 100 100 100")
                .replace("C00000=1000,", &format!("C00000=1{},", "0".repeat(303))),
            Dialect::Inform,
            23,
            "not a finite angle",
        ),
        (
            INFORM
                .replace("external_pulses = 100", "external_pulses = 1e-6")
                .replace("BC00000=150050", &format!("BC00000=1{}", "0".repeat(303))),
            Dialect::Inform,
            10,
            "not a finite value",
        ),
        (
            INFORM.replace("'stiffid: external_pulses = 100\r\n", ""),
            Dialect::Inform,
            22,
            "external_pulses",
        ),
        (
            INFORM.replace("MOVL C00001", "MOVS C00001"),
            Dialect::Inform,
            24,
            "MOVS",
        ),
        (
            INFORM.replace("MOVL C00001", "IMOV C00001"),
            Dialect::Inform,
            24,
            "IMOV",
        ),
        (
            INFORM.replace("MOVJ C00000", "MOVJ P000"),
            Dialect::Inform,
            23,
            "position variable",
        ),
        (
            INFORM.replace("V=100.0 PL=0", "V=100.0 UNTIL IN#(1)=ON"),
            Dialect::Inform,
            24,
            "UNTIL",
        ),
        (
            INFORM.replace("NOP\r\n", "NOP\r\nCALL JOB:OTHER\r\n"),
            Dialect::Inform,
            23,
            "CALL",
        ),
        (
            INFORM.replace("C00001=1100,", "C00001=1100.5,"),
            Dialect::Inform,
            9,
            "whole number of pulses",
        ),
        (
            INFORM.replace("///NPOS 2,2,2", "///NPOS 3,2,2"),
            Dialect::Inform,
            4,
            "///NPOS declares 3 C positions",
        ),
        (
            INFORM.replace("MOVJ C00000 BC00000", "MOVJ C00000 BC00007"),
            Dialect::Inform,
            23,
            "BC00007: no such position",
        ),
        (
            INFORM
                .replace(
                    "///POSTYPE PULSE\r\n///PULSE\r\nC00000",
                    "///POSTYPE ROBOT\r\n///RECTAN\r\nC00000",
                )
                .replace("BC00000=", "///POSTYPE PULSE\r\n///PULSE\r\nBC00000="),
            Dialect::Inform,
            25,
            "Cartesian",
        ),
    ]
}

#[test]
fn malformed_external_axes_and_inform_jobs_are_refused_naming_the_line() {
    let cases = [malformed_axes(), malformed_inform_jobs()].concat();
    for (text, dialect, line, word) in cases {
        match program::parse(&text, dialect) {
            Err(Error::Program { line: l, message }) => {
                assert!(message.contains(word), "{word}: {message}");
                assert_eq!(l, line, "{message}");
            }
            other => panic!("{dialect:?} {word}: {other:?}"),
        }
    }
}

const PROCESS: &str = "[tool]\ndiameter_mm = 20\nflutes = 3\nhelix_deg = 30\n[cut]\nfeed_per_tooth_mm = 0.1\n\
    axial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n[coefficients]\npreset = \"al7075-t6\"\n";

/// The LS program of [`a_program_that_moves_the_track_is_compensated_with_the_track_where_it_says`]:
/// the arm at `q` (deg) while the track carries it along `E1`; the same as an INFORM job in
/// pulses (1e6 per deg, 1000 per mm) with the track's base axis `BC` and the table's station
/// axis, coordinated (`SMOVL .. +MOVJ EC..`).
fn track_programs(q: &Vector6<f64>) -> [(String, Dialect); 2] {
    let mut ls = String::from("/PROG  TRACK\n/MN\n");
    for i in 1..=3 {
        ls += &format!("{i:>4}:L P[{i}] 10mm/sec FINE ;\n");
    }
    ls += "/POS\n";
    for (i, e) in ["1500.000", "1560.000", "1620.000"].iter().enumerate() {
        ls += &format!(
            "P[{}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {:.6} deg,\tJ2= {:.6} deg,\tJ3= {:.6} deg,\n\tJ4= {:.6} deg,\tJ5= {:.6} deg,\tJ6= {:.6} deg,\n\tE1= {e} mm\n   GP2:\n\tUF : 0, UT : 1,\n\tJ1= 0.000 deg\n}};\n",
            i + 1, q[0], q[1], q[2], q[3], q[4], q[5]
        );
    }
    ls += "/END\n";
    let pulses: Vec<String> = q
        .iter()
        .map(|v| format!("{}", (v * 1e6).round() as i64))
        .collect();
    let mut jbi = String::from("/JOB\r\n//NAME TRACK\r\n//POS\r\n///NPOS 3,3,3,0,0,0\r\n///TOOL 1\r\n///POSTYPE PULSE\r\n///PULSE\r\n");
    for i in 0..3 {
        jbi += &format!("C0000{i}={}\r\n", pulses.join(","));
    }
    for (i, e) in ["1500000", "1560000", "1620000"].iter().enumerate() {
        jbi += &format!("BC0000{i}={e}\r\n");
    }
    for i in 0..3 {
        jbi += &format!("EC0000{i}=0\r\n");
    }
    jbi += "//INST\r\n///ATTR SC,RW\r\n///GROUP1 RB1,BS1\r\n///GROUP2 ST1\r\n'stiffid: pulses_per_deg = 1e6 1e6 1e6 1e6 1e6 1e6\r\n'stiffid: external_pulses = 1000 1000\r\nNOP\r\n";
    for i in 0..3 {
        jbi += &format!("SMOVL C0000{i} BC0000{i} V=10.0  +MOVJ EC0000{i}\r\n");
    }
    jbi += "END\r\n";
    [(ls, Dialect::FanucLs), (jbi, Dialect::Inform)]
}

/// The arm holds one posture while the track carries it 60 mm at a time along x: the tool
/// moves over the part along +x, so it cuts (on a fixed base it would stand still), and each
/// target is compensated in the arm's frame on its carriage: the loaded tool lands on the
/// nominal one in the cell to 0.1 micrometre, the posture is the fixed-base compensation under
/// the same wrench, and the track's values are written back as read. The same as an INFORM job
/// (its base axis the track, in pulses); on a robot without the track, refused naming the line.
#[test]
fn a_program_that_moves_the_track_is_compensated_with_the_track_where_it_says() {
    let base = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let robot = base.robot().clone().with_external(Some(cell(false)));
    let s = base.to_builder().with_robot(robot).build().unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let pose = Isometry3::from_parts(
        Vector3::new(1.3, -0.7, 0.4).into(),
        UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0),
    );
    let options = Options::for_setup(&s);
    let q = ik::solve(
        s.robot(),
        &s.tool().tcp,
        &pose,
        &options.q0,
        &ik::Options::default(),
    )
    .unwrap()
    .q
    .map(f64::to_degrees);
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let cases = track_programs(&q).into_iter().zip([
        (
            "E1= 1620.000 mm",
            "1620.000",
            "6100.000",
            5,
            "E1 6100 mm",
            3,
        ),
        (
            "BC00002=1620000\r\n",
            "1620000",
            "6100000",
            26,
            "BC1 6100 mm",
            24,
        ),
    ]);
    for ((text, dialect), (kept, at, beyond, line, says, first)) in cases {
        let program = machining::read(&text, Language::Robot(dialect), 1e-5).unwrap();
        let report =
            machining::compensate(s.arm(), None, &compliance, &program, &process, &options)
                .unwrap();
        for (i, (p, r)) in report.points.iter().zip(&report.results).enumerate() {
            // The down-milling force, about 300 N, with +x along the feed (the track's motion).
            let f = p.wrench.fixed_rows::<3>(0).norm();
            assert!(
                f > 100.0 && f < 1000.0 && p.wrench[0] > 0.0,
                "{dialect:?} {i}: {}",
                p.wrench
            );
            // The nominal pose in the cell: on the carriage, 1.5 m + 60 mm per target along x.
            let track = 1.5 + 0.06 * i as f64;
            assert!(
                (r.pose.translation.vector
                    - pose.translation.vector
                    - Vector3::new(track, 0.0, 0.0))
                .norm()
                    < 1e-6,
                "{dialect:?}"
            );
            // The loaded tool on the carriage lands on the nominal one to 0.1 micrometre.
            let loaded = model.loaded_pose(&r.q_compensated, &p.wrench);
            let cell_loaded = Isometry3::translation(track, 0.0, 0.0) * loaded;
            assert!((cell_loaded.translation.vector - r.pose.translation.vector).norm() < 1e-7);
            // The fixed-base compensation under the same wrench.
            let alone =
                compensate::path(s.arm(), &compliance, std::slice::from_ref(p), &options).unwrap();
            assert!((alone[0].q_compensated - r.q_compensated).amax() < 1e-12);
            assert!((r.q_compensated - r.q).amax() > 1e-6, "compensated");
        }
        let written = program::parse(&report.program, dialect).unwrap();
        // Written back in its resolution: 1e-6 deg in pulses, 1e-9 deg in LS.
        for (t, r) in written.targets.iter().zip(&report.results) {
            let q = Vector6::from(t.q_deg) - r.q_compensated.map(f64::to_degrees);
            assert!(q.amax() <= 1e-6, "{dialect:?}");
        }
        assert_eq!(written.targets[2].external, vec![Some(1620.0), Some(0.0)]);
        assert!(report.program.contains(kept), "{}", report.program);
        // Beyond the track's travel: refused naming the line and the axis, nothing compensated.
        let beyond =
            machining::read(&text.replace(at, beyond), Language::Robot(dialect), 1e-5).unwrap();
        let refusals = [
            (s.arm(), &beyond, line, says),
            (
                base.arm(),
                &program,
                first,
                "the robot has no external axes",
            ),
        ];
        for (arm, program, line, says) in refusals {
            match machining::compensate(arm, None, &compliance, program, &process, &options) {
                Err(Error::Program { line: l, message }) => {
                    assert_eq!(l, line, "{dialect:?}: {message}");
                    assert!(message.contains(says), "{message}");
                }
                other => panic!("{other:?}"),
            }
        }
    }
}

const GCODE: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n(stiffid: external = U C)\nG0 X0 Y0 Z5 U0 C0\nG1 Z0 F600\nG1 X40 U20 C5\nG1 Y30 C10\n";

/// A track along x and a turntable about z through (1330, -680) mm, next to the part's origin.
fn gcode_cell() -> ExternalAxes {
    let turn = 360f64.to_radians();
    ExternalAxes::new(vec![
        ExternalAxis::linear("track", x(), 0.0, 6.0),
        ExternalAxis::rotary(
            "table",
            Vector3::new(1.33, -0.68, 0.0),
            Vector3::z_axis(),
            -turn,
            turn,
        ),
    ])
    .unwrap()
}

/// G-code's `U` and `C` drive the track and the table (the header's table); the tool is sent on
/// its carriage to the part's point where the table turned it, the loaded tool lands on the
/// programmed point of the part to 0.1 micrometre, and the program is written back in the part's
/// frame with its `U` and `C` words as read.
#[test]
fn gcode_drives_the_cells_axes_by_its_header_table() {
    let g = gcode::parse(GCODE, 1e-5).unwrap();
    assert_eq!(g.external, (vec!['U', 'C'], 2));
    let e: Vec<Vec<f64>> = g.points.iter().map(|p| p.external.clone()).collect();
    assert_eq!(
        e,
        vec![
            vec![0.0, 0.0],
            vec![0.0, 0.0],
            vec![20.0, 5.0],
            vec![20.0, 10.0]
        ]
    );
    // Inches and increments: U in inches under G20, added under G91; C in deg either way.
    let inch = gcode::parse(&format!("{GCODE}G20 G91 G1 U1 C-2 F10\n"), 1e-5).unwrap();
    let last = &inch.points.last().unwrap().external;
    assert!((last[0] - 45.4).abs() < 1e-12 && last[1] == 8.0, "{last:?}");

    let part = Isometry3::translation(1.3, -0.7, 0.4);
    let base = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let robot = base.robot().clone().with_external(Some(gcode_cell()));
    let s = base
        .to_builder()
        .with_robot(robot)
        .with_workpiece(part)
        .build()
        .unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let program = machining::read(GCODE, Language::GCode, 1e-5).unwrap();
    let options = Options::for_setup(&s);
    let report = machining::compensate(
        s.arm(),
        s.workpiece(),
        &compliance,
        &program,
        &process,
        &options,
    )
    .unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let cell = gcode_cell();
    let again = gcode::parse(&report.program, 1e-5).unwrap();
    for (((p, r), point), written) in report
        .points
        .iter()
        .zip(&report.results)
        .zip(&g.points)
        .zip(&again.points)
    {
        let si = cell.to_si(&point.external);
        // The part's frame from the arm's frame on its carriage.
        let part_from_arm =
            part.inverse() * cell.positioner_pose(&si).inverse() * cell.carrier_pose(&si);
        let loaded = model.loaded_pose(&r.q_compensated, &p.wrench);
        assert!(
            (part_from_arm
                .transform_point(&loaded.translation.vector.into())
                .coords
                - point.position)
                .norm()
                < 1e-7,
            "{}",
            point.line
        );
        let sent = tool_pose(&s.robot().frames(&r.q_compensated), &s.tool().tcp);
        assert!(
            (part_from_arm
                .transform_point(&sent.translation.vector.into())
                .coords
                - written.position)
                .norm()
                < 1e-9
        );
        assert_eq!(written.external, point.external);
        // The nominal pose, in the cell: the part's point where the table turned it.
        let in_cell = (cell.positioner_pose(&si) * part)
            .transform_point(&point.position.into())
            .coords;
        assert!(
            (r.pose.translation.vector - in_cell).norm() < 1e-7,
            "{}",
            point.line
        );
    }
    assert!(report.program.contains("U20 C5") && report.program.contains("C10"));
    // The table turned 5 deg between the second and third points: the cut's force turns with the
    // path over the part, not with the floor.
    assert!((report.results[2].q_compensated - report.results[2].q).amax() > 1e-6);
}

#[test]
fn a_gcode_axis_table_the_cell_does_not_match_is_refused_naming_the_line() {
    let parse_err = |text: String| match gcode::parse(&text, 1e-5) {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{other:?}"),
    };
    let (line, m) = parse_err(GCODE.replace("external = U C", "external = U X"));
    assert!(line == 2 && m.contains("'X' is no axis letter"), "{m}");
    let (line, m) = parse_err(GCODE.replace(
        "(stiffid: external = U C)",
        "(stiffid: rotary = abc)\n(stiffid: external = U C)",
    ));
    assert!(line == 3 && m.contains("turn the tool"), "{m}");
    let (line, m) = parse_err(GCODE.replace("G0 X0 Y0 Z5 U0 C0", "G0 X0 Y0 Z5 U0"));
    assert!(line == 3 && m.contains("C: a motion before"), "{m}");
    let (line, m) = parse_err(format!("{GCODE}G2 X60 Y50 I20 J0 U30\n"));
    assert!(line == 7 && m.contains("arc"), "{m}");
    let g = |text: &str| gcode::parse(text, 1e-5).unwrap();
    let values = |text: &str, cell: Option<&ExternalAxes>| match cell::gcode_values(&g(text), cell)
    {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{other:?}"),
    };
    let (line, m) = values(GCODE, None);
    assert!(line == 2 && m.contains("the robot has none"), "{m}");
    let (line, m) = values(
        &GCODE.replace("U C", "C U").replace("U0 C0", "C0 U0"),
        Some(&gcode_cell()),
    );
    assert!(
        line == 2 && m.contains("C is a rotary letter and drives the cell's linear axis track"),
        "{m}"
    );
    let (line, m) = values(
        &GCODE
            .replace("external = U C", "external = U")
            .replace(" C0", "")
            .replace(" C5", "")
            .replace(" C10", ""),
        Some(&gcode_cell()),
    );
    assert!(
        line == 2 && m.contains("1 letters for the cell's 2 external axes"),
        "{m}"
    );
    let plain = GCODE
        .replace("(stiffid: external = U C)\n", "")
        .replace(" U0 C0", "")
        .replace(" U20 C5", "")
        .replace(" C10", "");
    let (line, m) = values(&plain, Some(&gcode_cell()));
    assert!(line == 2 && m.contains("(stiffid: external = U C)"), "{m}");
    let (line, m) = values(&GCODE.replace("U20", "U7000"), Some(&gcode_cell()));
    assert!(
        line == 5 && m.contains("U 7000 mm") && m.contains("0 to 6000 mm"),
        "{m}"
    );
}

/// An LS axis in the unit of the other kind of axis is refused naming the line and the axis, and
/// so is one axis in two units.
#[test]
fn ls_units_are_checked_against_the_axes_kinds() {
    let refused = |text: &str| {
        let p = program::parse(text, Dialect::FanucLs);
        match p.and_then(|p| cell_values(&p, Some(&cell(true)))) {
            Err(Error::Program { line, message }) => (line, message),
            other => panic!("{other:?}"),
        }
    };
    let (line, message) = refused(&LS.replace("  mm\n", "  deg\n"));
    assert_eq!(line, 11);
    assert!(
        message.contains("E1 in deg") && message.contains("(track) is linear, its values in mm"),
        "{message}"
    );
    let rotary_in_mm = LS
        .replace("J1=     0.000 deg", "J1=     0.000 mm")
        .replace("J1=    45.250 deg", "J1=    45.250 mm");
    let (line, message) = refused(&rotary_in_mm);
    assert_eq!(line, 14);
    assert!(
        message.contains("GP2 J1 in mm") && message.contains("(table) is rotary"),
        "{message}"
    );
    let mixed = LS.replace("E1=  1600.000  mm", "E1=  1600.000  deg");
    let (line, message) = refused(&mixed);
    assert_eq!(line, 21);
    assert!(
        message.contains("E1 in deg: the same axis is in mm on line 11"),
        "{message}"
    );
}

/// A position register set from a position (`PR[1]=P[2]`) names the position in its value, not
/// as a motion: passed over, the two motions read.
#[test]
fn a_position_assigned_to_a_register_is_no_motion() {
    let text = LS.replace(
        "   2:L P[2] 50mm/sec CNT100 ;\n",
        "   2:L P[2] 50mm/sec CNT100 ;\n   3:  PR[1]=P[2] ;\n",
    );
    assert!(text.contains("PR[1]=P[2]"));
    let p = program::parse(&text, Dialect::FanucLs).unwrap();
    assert_eq!(p.targets.iter().map(|t| t.line).collect::<Vec<_>>(), [3, 4]);
}

/// A long LS program reads every position, in order, with its values (each new position's
/// number is checked against the others by a set; the time, linear in the positions, is the
/// `machining` bench's: 200 000 positions).
#[test]
fn a_long_ls_program_reads_every_position() {
    let n = 20_000;
    let mut text = String::from("/PROG  LONG\n/MN\n");
    for i in 1..=n {
        text += &format!("{i:6}:J P[{i}] 100% FINE ;\n");
    }
    text += "/POS\n";
    for i in 1..=n {
        let j1 = f64::from(i % 1000) * 0.01;
        text += &format!("P[{i}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {j1:.3} deg,\tJ2= -16.000 deg,\tJ3= -28.000 deg,\n\tJ4= 3.000 deg,\tJ5= -62.000 deg,\tJ6= 144.000 deg\n}};\n");
    }
    text += "/END\n";
    let p = program::parse(&text, Dialect::FanucLs).unwrap();
    assert_eq!(p.targets.len(), n as usize);
    for (k, t) in p.targets.iter().enumerate().step_by(997) {
        let i = k as u32 + 1;
        assert_eq!(t.line, u64::from(i) + 2);
        assert!(
            (t.q_deg[0] - f64::from(i % 1000) * 0.01).abs() < 1e-12,
            "{k}"
        );
        assert_eq!(t.q_deg[5], 144.0);
    }
}
