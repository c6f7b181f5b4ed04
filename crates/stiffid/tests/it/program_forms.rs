//! Every motion form of KRL, RAPID and FANUC LS: read (in the order of the motions, round-tripping
//! byte for byte and taking changed values back) or refused naming its line and what to do.

use stiffid::internal::machining::program::{self, Dialect};
use stiffid::Error;

/// How a program reads: its targets (motion line, axis angles), or refused (line, a word of the
/// message).
enum Reads {
    Targets(&'static [(u64, [f64; 6])]),
    Refused(u64, &'static str),
}
use Reads::{Refused, Targets};

const Q1: [f64; 6] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
const Q2: [f64; 6] = [-10.0, 20.5, -30.0, 0.0, 45.0, -60.0];

fn krl(body: &str) -> String {
    format!("DEF p( )\n{body}\nEND\n")
}

const KRL_DECLS: &str = "DECL E6AXIS XP2={A1 -10,A2 20.5,A3 -30,A4 0,A5 45,A6 -60,E1 0}\nE6AXIS XP1={A1 1,A2 2,A3 3,A4 4,A5 5,A6 6}";

fn krl_cases() -> Vec<(String, Reads)> {
    let lit1 = "{A1 1, A2 2, A3 3, A4 4, A5 5, A6 6}";
    vec![
        (krl(&format!("PTP {lit1} C_PTP\nLIN {{E6AXIS: A1 -10,A2 20.5,A3 -30,A4 0,A5 45,A6 -60,E1 0}} C_DIS")), Targets(&[(2, Q1), (3, Q2)])),
        (krl(&format!("SPTP {lit1}\nSLIN {lit1} WITH $VEL = {{CP 0.2}}")), Targets(&[(2, Q1), (3, Q1)])),
        // Named points in the order of the motions, not of the declarations; one visited twice.
        (krl(&format!("{KRL_DECLS}\nPTP XP1\nlin xp2 c_dis ; cut\nLIN XP1")), Targets(&[(4, Q1), (5, Q2), (6, Q1)])),
        // Motions the file does not say exactly.
        (krl("DECL E6POS XP1={X 1,Y 2,Z 3,A 0,B 0,C 0,S 6}\nLIN XP1"), Refused(2, "only one of S and T")),
        (krl("PTP XP9"), Refused(2, "not a point declared in the .src, and no .dat beside it")),
        (krl("PTP $AXIS_RET"), Refused(2, "a system variable")),
        (krl(&format!("{KRL_DECLS}\nSPL XP1")), Refused(4, "spline")),
        (krl(&format!("{KRL_DECLS}\nSPLINE\nSLIN XP1\nENDSPLINE")), Refused(4, "spline")),
        (krl(&format!("PTP {lit1}\nCIRC {lit1}, {lit1}")), Refused(3, "a circle through axis angles")),
        (krl("PTP_REL {A1 5}"), Refused(2, "relative")),
        (krl("LIN {X 1, Y 2, Z 3, A 0, B 0}"), Refused(2, "no C")),
        (krl("LIN {X 1, Y 2, Z 3, A 0, B 0, C 0, A1 5}"), Refused(2, "both axis angles (A1..) and a Cartesian pose")),
        (krl("PTP {A1 5}"), Refused(2, "axis 2")),
        (krl(&format!("{KRL_DECLS}\nPTP XP1 : {{A1 5}}")), Refused(4, "geometric operator")),
        (krl(&format!("{KRL_DECLS}\nXP1.A1 = 7\nPTP XP1")), Refused(5, "assigned on line 4")),
        (krl("DECL E6AXIS XP1\nPTP XP1"), Refused(3, "without a value")),
        // Motions in a loop and in a second routine, each read where it is.
        (krl(&format!("FOR I = 1 TO 3\nPTP {lit1}\nENDFOR")), Targets(&[(3, Q1)])),
        (format!("DEF a( )\nPTP {lit1}\nEND\nDEF b( )\nPTP {lit1}\nEND\n"), Targets(&[(2, Q1), (5, Q1)])),
        ("DEFDAT p\nDECL E6AXIS XP1={A1 1,A2 2,A3 3,A4 4,A5 5,A6 6}\nENDDAT\n".to_string(), Refused(1, "give the .src")),
    ]
}

fn rapid(decls: &str, body: &str) -> String {
    format!("MODULE M\n{decls}\n  PROC main()\n{body}\n  ENDPROC\nENDMODULE\n")
}

const EXT: &str = "[9E9,9E9,9E9,9E9,9E9,9E9]";

fn rapid_cases() -> Vec<(String, Reads)> {
    let lit1 = format!("[[1,2,3,4,5,6],{EXT}]");
    // A jointtarget over two lines, a comment with ';' in between.
    let two = format!(
        "  CONST jointtarget j2 := [[-10, 20.5, -30, ! first three; then\n    0, 45, -60],{EXT}];"
    );
    vec![
        (rapid("", &format!("    MoveAbsJ {lit1}, v100, z10, tool0;\n    MoveAbsJ\\Conc, {lit1}\\NoEOffs, v100, fine, tool0;")), Targets(&[(4, Q1), (5, Q1)])),
        (rapid(&format!("{two}\n  CONST jointtarget j1:={lit1};"), "    MoveAbsJ j1, v100, z10, tool0;\n    moveabsj J2 \\NoEOffs, v100, z10, tool0;\n    MoveAbsJ j1, v100, fine, tool0;"), Targets(&[(6, Q1), (7, Q2), (8, Q1)])),
        (rapid("", &format!("    MoveAbsJ {lit1}, v100, z10, tool0; MoveAbsJ {lit1}, v10, fine, tool0;")), Targets(&[(4, Q1), (4, Q1)])),
        (rapid("", "    MoveL\\Conc, p1, v100, z10, tool0;"), Refused(4, "MoveL p1: not a robtarget declared")),
        (rapid("", "    MoveJ p1, v100, z10, tool0;"), Refused(4, "not a robtarget declared")),
        (rapid("", "    MoveJ Offs(p1, 0, 0, 10), v100, z10, tool0;"), Refused(4, "MoveJ p1: not a robtarget declared")),
        (rapid("", "    TriggL p1, v100, trig1, z10, tool0;"), Refused(4, "triggered")),
        (rapid("", "    MoveLDO p1, v100, z10, tool0, do1, 1;"), Refused(4, "does not follow")),
        (rapid("", "    SearchL\\Stop, di1, sp, p1, v100, tool0;"), Refused(4, "search")),
        (rapid("", "    ArcLStart p1, v100, seam1, weld1, fine, tool1;"), Refused(4, "ArcLStart p1: not a robtarget declared in this module")),
        (rapid("", "    ArcC p1, p2, v100, seam1, weld1, z10, tool1;"), Refused(4, "ArcC p1: not a robtarget declared in this module")),
        (rapid("", "    MoveExtJ j1, v100, fine;"), Refused(4, "external axes")),
        (rapid("", "    MoveAbsJ CalcJointT(p1, tool0), v100, fine, tool0;"), Refused(4, "CalcJointT(..), a function the controller computes")),
        (rapid("", "    MoveAbsJ jx, v100, fine, tool0;"), Refused(4, "not a jointtarget declared")),
        (rapid("  VAR jointtarget j1;", "    MoveAbsJ j1, v100, fine, tool0;"), Refused(4, "without a value")),
        (rapid(&format!("  VAR jointtarget j1 := {lit1};"), "    j1.robax.rax_1 := 7;\n    MoveAbsJ j1, v100, fine, tool0;"), Refused(5, "assigned on line 4")),
        (rapid("", &format!("    FOR i FROM 1 TO 3 DO\n      MoveAbsJ {lit1}, v100, fine, tool0;\n    ENDFOR")), Targets(&[(5, Q1)])),
        (format!("MODULE M\n  PROC a()\n    MoveAbsJ {lit1}, v1, fine, tool0;\n  ENDPROC\n  PROC b()\n    MoveAbsJ {lit1}, v1, fine, tool0;\n  ENDPROC\nENDMODULE\n"), Targets(&[(3, Q1), (6, Q1)])),
    ]
}

fn ls(mn: &str, positions: &[(u64, [f64; 6])]) -> String {
    let mut s = format!("/PROG  P\n/ATTR\n/MN\n{mn}\n/POS\n");
    for (i, q) in positions {
        s += &format!(
            "P[{i}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {} deg,\tJ2= {} deg,\tJ3= {} deg,\n\tJ4= {} deg,\tJ5= {} deg,\tJ6= {} deg\n}};\n",
            q[0], q[1], q[2], q[3], q[4], q[5]
        );
    }
    s + "/END\n"
}

/// The `/POS` line and a Cartesian position `P[1]` in the world for tool frame 1.
const CARTESIAN_P1: &str = "/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n\tX = 1194.000 mm,\tY = 924.900 mm,\tZ = 539.500 mm,\n\tW = 163.100 deg,\tP = 1.500 deg,\tR = -1.000 deg\n};\n";

fn ls_cases() -> Vec<(String, Reads)> {
    let pos = [(1, Q1), (2, Q2)];
    let inc = [(1, Q1), (2, [0.5, 0.0, -1.0, 0.0, 0.0, 2.0])];
    vec![
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2:\"cut\"] 50mm/sec CNT100 ACC80 ;", &pos), Targets(&[(4, Q1), (5, Q2)])),
        // The order of the motions, not of /POS; a comment instruction; one position visited twice.
        (ls("   1:  ! approach ;\n   2:J P[2] 20% FINE ;\n   3:L P[1] 10cm/min CR50 ;\n   4:J P[2] 20% CNT100 ;", &pos), Targets(&[(5, Q2), (6, Q1), (7, Q2)])),
        // An increment after a FINE motion: the previous target plus the position.
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 10mm/sec FINE INC ;", &inc), Targets(&[(4, Q1), (5, [1.5, 2.0, 2.0, 4.0, 5.0, 8.0])])),
        (ls("   1:J P[1] 100% CNT100 ;\n   2:L P[2] 10mm/sec FINE INC ;", &inc), Refused(5, "end the previous motion FINE")),
        (ls("   1:L P[2] 10mm/sec FINE INC ;", &inc), Refused(4, "INC")),
        // A joint increment from a Cartesian position: its start angles are the controller's.
        (ls("   1:J P[1] 100% FINE ;\n   2:J P[2] 50% FINE INC ;", &inc[1..]).replace("/POS\n", CARTESIAN_P1), Refused(5, "J P[2] INC: an increment of the axis angles from the previous target (line 4), a Cartesian position")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE Offset,PR[1] ;", &pos), Refused(5, "Offset,PR[1]: a position register holds its value on the controller")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE Tool_Offset ;", &pos), Refused(5, "no TOOL_OFFSET CONDITION")),
        (ls("   1:J PR[1] 100% FINE ;", &pos), Refused(4, "position register")),
        (ls("   1:  PR[1:pick]=LPOS ;\n   2:J PR[1:pick] 100% FINE ;", &pos), Refused(5, "J PR[1]: the position register is set on line 4 as the program runs (PR[1:pick]=LPOS)")),
        (ls("   1:L P[R[1]] 100mm/sec FINE ;", &pos), Refused(4, "computed on the controller")),
        // A circular motion: its via point then its end, both on its line.
        (ls("   1:J P[1] 100% FINE ;\n   2:C P[2]\n    :  P[1] 100mm/sec FINE ;", &pos), Targets(&[(4, Q1), (5, Q2), (5, Q1)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:C P[2] Tool_Offset,PR[3]\n    :  P[1] 100mm/sec FINE ;", &pos), Refused(5, "Tool_Offset,PR[3]: a position register holds its value on the controller")),
        (ls("   1:J P[1] 100% FINE ;\n   2:C P[2]\n    :  PR[1] 100mm/sec FINE ;", &pos), Refused(5, "position register")),
        (ls("   1:J P[1] 100% FINE ;\n   2:A P[2] 100mm/sec CNT100 ;", &pos), Refused(5, "circular")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE Skip,LBL[1] ;", &pos), Refused(5, "SKIP,LBL[1]: a jump")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE COORD ;", &pos), Refused(5, "COORD: coordinated motion")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE Wjnt ;", &pos), Refused(5, "WJNT: an option")),
        // Options that change neither the path nor its end, an output early, a register's CNT.
        (ls("   1:J P[1] R[1:joint speed]% CNT R[2:corner value] ;\n   2:L P[2] 50mm/sec FINE TB .5sec,CALL X PTH\n    :  Arc Start[1] ;", &pos), Targets(&[(4, Q1), (5, Q2)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE Arc Weld[1] ;", &pos), Refused(5, "Arc Start[..] or Arc End[..]")),
        // Unnumbered lines after a closed instruction are instructions of their own: a motion, a
        // call between two motions.
        (ls("   1:J P[1] 100% FINE ;\n    :L P[2] 50mm/sec FINE ;", &pos), Targets(&[(4, Q1), (5, Q2)])),
        (ls("   1:J P[1] 100% FINE ;\n    :  CALL SUB ;\n    :L P[2] 50mm/sec FINE ;", &pos), Refused(5, "a call between two motions")),
        (ls("   1:J P[9] 100% FINE ;", &pos), Refused(4, "no position P[9]")),
        // Around the motions: what cannot change the path passes, what can is refused.
        (ls("   1:UFRAME_NUM=0 ;\n   2:  PAYLOAD[1] ;\n   3:  RUN LOG ;\n   4:J P[1] 100% FINE ;\n   5:  DO[1]=ON ;\n   6:  WAIT 1.00(sec) ;\n   7:  R[1]=R[1]+1 ;\n   8:  // L P[9] 10mm/sec FINE ;\n   9:L P[2] 50mm/sec FINE ;\n  10:  CALL SUB ;", &pos), Targets(&[(7, Q1), (12, Q2)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:  CALL SUB ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "a call between two motions")),
        // A macro instruction: a program run by its name, which may move the robot.
        (ls("   1:J P[1] 100% FINE ;\n   2:  GO_HOME ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "GO_HOME: a macro (a program the controller runs by its name) between two motions")),
        (ls("   1:J P[1] 100% FINE ;\n   2:  Open_Grip(2) ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "Open_Grip(2): a macro")),
        (ls("   1:  GO_HOME ;\n   2:J P[1] 100% FINE ;\n   3:L P[2] 50mm/sec FINE ;\n   4:  PAUSE ;\n   5:  TC_ONLINE (ON) ;\n   6:  GO_HOME ;", &pos), Targets(&[(5, Q1), (6, Q2)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:  PAUSE ;\n   3:  TC_ONLINE (DI[43]) ;\n   4:L P[2] 50mm/sec FINE ;", &pos), Targets(&[(4, Q1), (7, Q2)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:  WAIT DI[1]=ON TIMEOUT,LBL[1] ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "jump")),
        (ls("   1:  UFRAME[1]=PR[1] ;\n   2:J P[1] 100% FINE ;", &pos), Refused(4, "sets a frame's value")),
        (ls("   1:J P[1] 100% FINE ;\n   2:  END ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "the program ends here")),
        (ls("   1:J P[1] 100% FINE ;\n   2:  Weave Sine[1] ;\n   3:L P[2] 50mm/sec FINE ;\n   4:  Weave End ;", &pos), Refused(5, "weave across the path")),
        // A loop: its motion read where it is.
        (ls("   1:LBL[1] ;\n   2:J P[1] 100% FINE ;\n   3:JMP LBL[1] ;", &pos), Targets(&[(5, Q1)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:  JMP LBL[1] ;\n   3:L P[2] 50mm/sec FINE ;\n   4:  LBL[1] ;", &pos), Refused(5, "JMP LBL[1]: the motion on line 6 after it is reached by no path")),
        // ArcTool touch sensing shifts the motions up to its end by an offset found at run time.
        (ls("   1:J P[1] 100% FINE ;\n   2:  Touch Offset PR[20] ;\n   3:L P[2] 50mm/sec FINE ;\n   4:  Touch Offset End ;", &pos), Refused(5, "Touch Offset PR[20]: touch sensing (ArcTool) shifts every motion after it")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE ;\n   3:  Touch Offset End ;", &pos), Targets(&[(4, Q1), (5, Q2)])),
        // A program in German: its keywords read as their English twins.
        (ls("   1:  LABEL[1] ;\n   2:J P[1] 100% FINE ;\n   3:L P[2] 500mm/sek FINE ;\n   4:  WENN (F[1]),SPRUNG LABEL[1] ;", &pos), Targets(&[(5, Q1), (6, Q2)])),
        (ls("   1:J P[1] 100% FINE ;\n   2:  SONST,SPRUNG LABEL[2] ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "no LBL[2] in the program")),
        (ls("   1:J P[1] 100% FINE ;\n   2:  AUFRUF MAKRO000 ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "AUFRUF MAKRO000: a call between two motions")),
        (ls("   1:J P[1] 100% FINE ;\n   2:  ENDE ;\n   3:L P[2] 50mm/sec FINE ;", &pos), Refused(5, "the program ends here")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 10mm/sek CNT0 ACC250 Interrupt,LABEL[1] ;", &pos), Refused(5, "INTERRUPT,LABEL[1]: a jump")),
        (ls("   1:J P[1] 100% FINE ;\n   2:L P[2] 50mm/sec FINE WKZ_Offset ,PR[2] ;", &pos), Refused(5, "a position register holds its value on the controller")),
        (ls("   1:  AUFRUF INIT ;\n   2:  LABEL[1] ;\n   3:J P[1] 100% FINE ;\n   4:L P[2] 50mm/sek CNT0 ;\n   5:  AUFRUF MAKRO000 ;\n   6:  ENDE ;", &pos), Targets(&[(6, Q1), (7, Q2)])),
        (ls("   1:J P[1] 100% FINE ;", &[]), Refused(4, "no position P[1]")),
        (ls("", &pos), Refused(1, "no motion to a target found")),
    ]
}

#[test]
fn every_motion_form_reads_in_motion_order_and_round_trips_or_is_refused_naming_its_line() {
    let all = [
        (Dialect::Krl, krl_cases()),
        (Dialect::Rapid, rapid_cases()),
        (Dialect::FanucLs, ls_cases()),
    ];
    for (dialect, cases) in all {
        for (text, reads) in cases {
            let parsed = program::parse(&text, dialect);
            match (reads, parsed) {
                (Targets(expected), Ok(p)) => {
                    let got: Vec<(u64, [f64; 6])> =
                        p.targets.iter().map(|t| (t.line, t.q_deg)).collect();
                    assert_eq!(got, expected, "{dialect:?}\n{text}");
                    // Unchanged: byte for byte; every target moved by the same amount: read back.
                    let same: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
                    assert_eq!(p.write(&same).unwrap(), text, "{dialect:?}");
                    let moved: Vec<[f64; 6]> = same
                        .iter()
                        .map(|q| q.map(|v| v + 0.012_345_678_9))
                        .collect();
                    let again = program::parse(&p.write(&moved).unwrap(), dialect).unwrap();
                    for (t, q) in again.targets.iter().zip(&moved) {
                        for (a, b) in t.q_deg.iter().zip(q) {
                            assert!((a - b).abs() <= 1e-9, "{dialect:?}: {a} {b}\n{text}");
                        }
                    }
                }
                (Refused(line, word), Err(Error::Program { line: l, message })) => {
                    assert_eq!(l, line, "{dialect:?}: {message}\n{text}");
                    assert!(message.contains(word), "{dialect:?}: {word}: {message}");
                }
                (_, other) => panic!("{dialect:?}: {other:?}\n{text}"),
            }
        }
    }
}

/// A point visited twice takes one value: visits compensated alike are written once, visits
/// compensated apart are refused naming both lines. An `INC` position takes the increment between
/// the compensated targets.
#[test]
fn a_shared_point_takes_one_value_and_an_increment_the_compensated_difference() {
    let text = ls(
        "   1:J P[1] 100% FINE ;\n   2:L P[2] 10mm/sec FINE ;\n   3:J P[1] 100% FINE ;",
        &[(1, Q1), (2, Q2)],
    );
    let p = program::parse(&text, Dialect::FanucLs).unwrap();
    let mut q: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    q[2][0] += 1e-3;
    match p.write(&q) {
        Err(Error::Program { line: 6, message }) => {
            assert!(message.contains("lines 4 and 6"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    q[0][0] += 1e-3;
    let again = program::parse(&p.write(&q).unwrap(), Dialect::FanucLs).unwrap();
    assert_eq!(again.targets[0].q_deg[0], 1.001);
    assert_eq!(again.targets[2].q_deg[0], 1.001);

    let text = ls(
        "   1:J P[1] 100% FINE ;\n   2:L P[2] 10mm/sec FINE INC ;",
        &[(1, Q1), (2, [0.5, 0.0, -1.0, 0.0, 0.0, 2.0])],
    );
    let p = program::parse(&text, Dialect::FanucLs).unwrap();
    let q = [
        [1.25, 2.0, 3.0, 4.0, 5.0, 6.0],
        [1.5, 2.0, 2.0, 4.0, 5.0, 8.5],
    ];
    let out = p.write(&q).unwrap();
    assert!(out.contains("J1= 0.250000000 deg"), "{out}");
    assert!(out.contains("J6= 2.500000000 deg"), "{out}");
    assert!(
        out.contains("J3= -1 deg"),
        "unchanged increments stay: {out}"
    );
    let again = program::parse(&out, Dialect::FanucLs).unwrap();
    assert_eq!(again.targets[1].q_deg, q[1]);
}
