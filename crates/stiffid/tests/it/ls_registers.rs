//! LS motions to position registers, read from the controller backup's `POSREG.VA` as the real
//! backups write it: compensated to the very target the same position inline in `/POS` takes,
//! written to a new position of the program (the register, shared by every program, left as it
//! is); refused naming the line where the program sets the register or calls a program the
//! backup does not hold.

use crate::ls_corpus::{compensated, compensated_in, independent, pose, refusal, setup};
use nalgebra::Translation3;
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::{parse_in, Context, Dialect};
use stiffid::Setup;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/programs/ls/");

/// A `POSREG.VA` as an R-30iB backup writes it (the format of the drilling cell's backup,
/// `wilder-backup/`: CRLF, three decimals, no zero before the point): PR[5] a Cartesian register
/// holding `rpi_tmpa.ls`'s `P[3]`, PR[7] a joint one holding its `P[1]`, PR[1] never set.
const POSREG: &str = "[*POSREG*]$POSREG  Storage: SHADOW  Access: RW  : ARRAY[1,200] OF Position Reg\r\n    [1,1] =   '' Uninitialized\r\n    [1,5] =   'PROBE' \r\n  Group: 1   Config: N U T, 0, 0, 0\r\n  X:  1620.000   Y:      .000   Z:  1930.000\r\n  W:   180.000   P:      .000   R:      .000\r\n    [1,7] =   'PARK'   Group: 1\r\n  J1 =    38.300 deg   J2 =    23.300 deg   J3 =   -34.000 deg \r\n  J4 =    45.700 deg   J5 =  -101.900 deg   J6 =   -48.300 deg \r\n\r\n    [1,9] =   'SHIFT' \r\n  Group: 1   Config: N U T, 0, 0, 0\r\n  X:    10.000   Y:    -5.000   Z:    20.000\r\n  W:      .000   P:      .000   R:      .000\r\n[*POSREG*]$MAXPREGNUM  Storage: CMOS  Access: RW  : INTEGER = 200\r\n";

/// The program with its two motions to `P[1]` and `P[3]` going to the registers holding them.
fn with_registers(straight: &str) -> String {
    straight
        .replace("   3:J P[1] 100% FINE ;", "   3:J PR[7:PARK] 100% FINE ;")
        .replace(
            "   5:L P[3] 50mm/sec FINE ;",
            "   5:L PR[5:PROBE] 50mm/sec FINE ;",
        )
}

/// `text` compensated on `s` with the backup `backup` (the milling example's stiffness).
fn run(
    s: &Setup,
    text: &str,
    backup: &[(String, String)],
) -> stiffid::Result<(String, Vec<Compensated>)> {
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(s.model())
    .unwrap();
    let options = Options::for_setup(s);
    compensated_in(s, &compliance, options, ("TMPA.ls", text), backup).map(|(o, r, _)| (o, r))
}

#[test]
fn a_position_register_of_posreg_va_compensates_as_the_same_position_inline() {
    let s = setup();
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let text = with_registers(&straight);
    let backup = vec![("backup/POSREG.VA".to_string(), POSREG.to_string())];
    let (out_p, p) = compensated(&s, "TMPA.ls", &straight).unwrap();
    let (out_r, r) = run(&s, &text, &backup).unwrap();
    assert_eq!(p.len(), 3);
    for (a, b) in p.iter().zip(&r) {
        assert_eq!(a.q, b.q);
        let most = (a.q_compensated - b.q_compensated).amax();
        assert!(most < 1e-12, "{most} rad");
    }
    // The loaded linear motion moves: it goes to the program's new position P[5] (numbered on
    // from P[3], one per motion to a register), written before /END with its bound; the
    // unloaded joint motion keeps its register.
    assert!(out_r.contains("   3:J PR[7:PARK] 100% FINE ;\n"), "{out_r}");
    assert!(out_r.contains("   5:L P[5] 50mm/sec FINE ;\n"), "{out_r}");
    assert!(
        out_r.contains("};\nP[5:\"0.1644 mm\"]{\n   GP1:\n\tUF : 1, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n\tX = 1619."),
        "{out_r}"
    );
    assert!(out_r.ends_with("};\n/END\n"), "{out_r}");
    // P[5] written holds what the straight program's P[3] is written as, to 1e-9 mm.
    let (inline, copied) = (independent(&out_p), independent(&out_r));
    assert_eq!((inline.len(), copied.len()), (3, 2));
    assert_eq!(copied[1].frames, inline[2].frames);
    for (a, b) in inline[2].values.iter().zip(&copied[1].values) {
        assert!((a - b).abs() < 1e-9, "{a} {b}");
    }
    assert_ne!(inline[2].values, [1620.0, 0.0, 1930.0, 180.0, 0.0, 0.0]);
    // The warning names the line and the register.
    let context = Context::of(&s).with_backup(&backup);
    let read = parse_in(&text, Dialect::FanucLs, &context).unwrap();
    assert_eq!(read.copied.len(), 2);
    assert!(
        read.copied[1].starts_with("line 9: L PR[5] read as backup/POSREG.VA line 3 holds it"),
        "{:?}",
        read.copied
    );
}

#[test]
fn a_position_register_the_run_sets_or_a_program_not_given_may_set_is_refused_naming_the_line() {
    let s = setup();
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let backup = vec![("backup/POSREG.VA".to_string(), POSREG.to_string())];
    let read = |text: &str, backup: &[(String, String)]| {
        parse_in(text, Dialect::FanucLs, &Context::of(&s).with_backup(backup)).map(|_| ())
    };
    let why = |text: &str, backup: &[(String, String)]| refusal(&read(text, backup).unwrap_err());
    let text = with_registers(&straight);
    // Set by the program after the motion (its next run starts from it).
    let set = text.replace("   6:  DO[103]=OFF ;", "   6:  PR[5,3:PROBE]=PR[5,3]+10 ;");
    let (line, message) = why(&set, &backup);
    assert_eq!(line, 9, "{message}");
    assert!(
        message.contains("the position register is set on line 10"),
        "{message}"
    );
    // With --leave-refused, that motion is left as found, named, the others read.
    let context = Context::of(&s)
        .with_backup(&backup)
        .with_leave_refused(true);
    let p = parse_in(&set, Dialect::FanucLs, &context).unwrap();
    assert_eq!(p.targets.iter().map(|t| t.line).collect::<Vec<_>>(), [7, 8]);
    assert_eq!(p.left.len(), 1);
    assert_eq!(p.left[0].line, 9);
    assert!(p.left[0]
        .why
        .starts_with("L PR[5]: the position register is set on line 10"));
    // By a skip option's capture.
    let skip = text.replace(
        "   6:  DO[103]=OFF ;",
        "   6:L P[2] 50mm/sec FINE Skip,LBL[1],PR[5]=LPOS ;",
    );
    assert!(why(&skip, &backup).1.contains("set on line 10"));
    // A program called that the backup holds sets it; one it does not hold may.
    let call = text.replace("   6:  DO[103]=OFF ;", "   6:  CALL PROBE ;");
    let (line, message) = why(&call, &backup);
    assert_eq!(line, 7, "{message}");
    assert!(
        message.contains("line 10 calls PROBE, which the backup does not hold as PROBE.LS"),
        "{message}"
    );
    let probe = "/PROG  PROBE\n/ATTR\n/MN\n   1:  PR[5]=LPOS ;\n/POS\n/END\n".to_string();
    let mut held = backup.clone();
    held.push(("backup/PROBE.LS".into(), probe.clone()));
    let (_, message) = why(&call, &held);
    assert!(
        message.contains(
            "line 10 calls PROBE: backup/PROBE.LS: the position register is set on line 4"
        ),
        "{message}"
    );
    held[1].1 = probe.replace("PR[5]=LPOS", "R[1]=1");
    assert!(read(&call, &held).is_ok());
    // No POSREG.VA; a register never set.
    assert!(why(&text, &[])
        .1
        .contains("give the controller's backup with its POSREG.VA"));
    let unset = text.replace("PR[5:PROBE]", "PR[1]");
    let (line, message) = why(&unset, &backup);
    assert_eq!(line, 9);
    assert!(
        message.contains("backup/POSREG.VA line 2 gives PR[1] no value (Uninitialized)"),
        "{message}"
    );
}

/// `Offset,PR[9]` and `Tool_Offset,PR[9]` (a translation of 10, -5, 20 mm held in `POSREG.VA`)
/// compensate as the position moved by it in the user frame, or in the tool frame: the same
/// postures, and the position written is the one the offset lands on the compensated pose
/// (to the 9 decimals written).
#[test]
fn an_offset_by_a_position_register_of_posreg_va_compensates_as_the_moved_position() {
    let s = setup();
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let p3 = "   X = 1620.000 mm,  Y = 0.000 mm,  Z = 1930.000 mm,";
    // P[3] is W = 180 deg: the tool frame's y and z are the user frame's -y and -z.
    let user = "   X = 1630.000 mm,  Y = -5.000 mm,  Z = 1950.000 mm,";
    let tool = "   X = 1630.000 mm,  Y = 5.000 mm,  Z = 1910.000 mm,";
    // The register's value as the program sets it on every path before the motion (the backup's
    // X 99 mm replaced, Z kept), copied, or named by the offset condition in force.
    let elements =
        "   2:  UTOOL_NUM=1 ;\n  :  R[1]=5 ;\n  :  PR[9,1]=R[1]*2 ;\n  :  PR[9,2:SHIFT]=(-5) ;";
    let copied = "   2:  UTOOL_NUM=1 ;\n  :  PR[2]=PR[9]+PR[9]-PR[9] ;\n  :  OFFSET CONDITION PR[2],UFRAME[1] ;";
    let condition = "   2:  UTOOL_NUM=1 ;\n  :  TOOL_OFFSET CONDITION PR[9:SHIFT] ;";
    let x99 = POSREG.replace("X:    10.000   Y:    -5.000", "X:    99.000   Y:    -5.000");
    for (start, word, moved, shift, posreg) in [
        ("", "Offset,PR[9:SHIFT]", user, false, POSREG),
        ("", "Tool_Offset,PR[9:SHIFT]", tool, true, POSREG),
        (elements, "Offset,PR[9]", user, false, &x99),
        (copied, "Offset", user, false, POSREG),
        (condition, "Tool_Offset", tool, true, POSREG),
    ] {
        let backup = vec![("backup/POSREG.VA".to_string(), posreg.to_string())];
        let offset = straight.replace(
            "   5:L P[3] 50mm/sec FINE ;",
            &format!("   5:L P[3] 50mm/sec FINE {word} ;"),
        );
        let offset = match start {
            "" => offset,
            s => offset.replace("   2:  UTOOL_NUM=1 ;", s),
        };
        let shifted = straight.replacen(p3, moved, 1);
        assert!(offset != straight && shifted != straight);
        let (out_s, a) = compensated(&s, "TMPA.ls", &shifted).unwrap();
        let (out_o, b) = run(&s, &offset, &backup).unwrap();
        for (a, b) in a.iter().zip(&b) {
            assert!((a.q_compensated - b.q_compensated).amax() < 1e-12, "{word}");
        }
        assert!(out_o.contains(&format!("{word} ;")), "{out_o}");
        let (w_s, w_o) = (independent(&out_s)[2].values, independent(&out_o)[2].values);
        let t = Translation3::new(10e-3, -5e-3, 20e-3);
        let landed = match shift {
            true => pose(&w_o) * t,
            false => t * pose(&w_o),
        };
        let d = (landed.translation.vector - pose(&w_s).translation.vector).norm();
        // To the 9 decimals written (mm and deg).
        assert!(d < 1e-11, "{word}: {d} m");
        assert!(
            landed.rotation.angle_to(&pose(&w_s).rotation) < 1e-9,
            "{word}"
        );
    }
    let backup = vec![("backup/POSREG.VA".to_string(), POSREG.to_string())];
    // A register that turns, or a joint position offset: refused naming the line.
    let turning = POSREG.replace(
        "W:      .000   P:      .000   R:      .000\r\n[*POSREG*]$MAX",
        "W:      .000   P:      .000   R:     5.000\r\n[*POSREG*]$MAX",
    );
    let offset = straight.replace(
        "   5:L P[3] 50mm/sec FINE ;",
        "   5:L P[3] 50mm/sec FINE Offset,PR[9] ;",
    );
    let turned = vec![("POSREG.VA".to_string(), turning)];
    let context = Context::of(&s).with_backup(&turned);
    let (line, why) = refusal(&parse_in(&offset, Dialect::FanucLs, &context).unwrap_err());
    assert_eq!(line, 9, "{why}");
    assert!(
        why.contains("Offset,PR[9] (POSREG.VA line 11): the register turns"),
        "{why}"
    );
    let joint = straight.replace(
        "   3:J P[1] 100% FINE ;",
        "   3:J P[1] 100% FINE Offset,PR[9] ;",
    );
    let context = Context::of(&s).with_backup(&backup);
    let (line, why) = refusal(&parse_in(&joint, Dialect::FanucLs, &context).unwrap_err());
    assert_eq!(line, 7, "{why}");
    assert!(
        why.contains("an offset of a position in joint representation"),
        "{why}"
    );
    // A bare Offset without a condition set in the program; a condition in another user frame;
    // a register element that differs between the paths reaching the motion (a loop).
    let looped = "   2:  UTOOL_NUM=1 ;\n  :  R[1]=0 ;\n  :  LBL[1] ;\n  :  PR[9,1]=R[1] ;\n  :  R[1]=R[1]+10 ;";
    let other = "   2:  UTOOL_NUM=1 ;\n  :  OFFSET CONDITION PR[9],UFRAME[2] ;";
    for (start, word, line, expected) in [
        ("   2:  UTOOL_NUM=1 ;", "Offset", 9, "no OFFSET CONDITION before the motion"),
        (other, "Offset", 10, "puts the offset in UFRAME[2], the position is in another (UF : 1)"),
        (looped, "Offset,PR[9] ;\n  :  IF R[1]<50,JMP LBL[1]", 13, "set on line 9 as the program runs (PR[9,1]=R[1]) from a value the run gives (R[1] depends on the path taken to line 8: one path leaves 0 (line 7), another 10 (line 10)"),
    ] {
        let text = straight
            .replace("   5:L P[3] 50mm/sec FINE ;", &format!("   5:L P[3] 50mm/sec FINE {word} ;"))
            .replace("   2:  UTOOL_NUM=1 ;", start);
        let (l, why) = refusal(&parse_in(&text, Dialect::FanucLs, &context).unwrap_err());
        assert_eq!(l, line, "{why}");
        assert!(why.contains(expected), "{why}");
    }
}

/// What a hostile backup or header holds is refused naming the file or line: a register given
/// twice in `POSREG.VA`, two `POSREG.VA` that differ, a motion group mask (`DEFAULT_GROUP`)
/// that does not hold the groups the program (or a program it calls) moves; a `FOR` loop's bound
/// that is no number or register.
#[test]
fn a_hostile_backup_or_header_is_refused_naming_its_file_or_line() {
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let text = with_registers(&straight);
    let read = |text: &str, backup: &[(String, String)]| {
        parse_in(
            text,
            Dialect::FanucLs,
            &Context::default().with_backup(backup),
        )
    };
    let one = |va: String| vec![("backup/POSREG.VA".to_string(), va)];
    assert_eq!(read(&text, &one(POSREG.into())).unwrap().targets.len(), 3);
    // PR[7] given twice: its lines 6 and 14.
    let at = POSREG.find("    [1,9]").unwrap();
    let seven = &POSREG[POSREG.find("    [1,7]").unwrap()..at];
    let twice = format!("{}{seven}{}", &POSREG[..at], &POSREG[at..]);
    let (line, why) = refusal(&read(&text, &one(twice)).unwrap_err());
    assert_eq!(line, 7, "{why}");
    assert!(
        why.contains("$POSREG[1,7]: given on line 7 and again on line 11"),
        "{why}"
    );
    // PR[7] beyond the array the file declares (a file edited, or cut and joined).
    let small = POSREG.replacen("ARRAY[1,200]", "ARRAY[1,6]", 1);
    let (line, why) = refusal(&read(&text, &one(small)).unwrap_err());
    assert_eq!(line, 7, "{why}");
    assert!(
        why.contains("$POSREG[1,7]: beyond the ARRAY[1,6] line 1 declares"),
        "{why}"
    );
    // Two backups' POSREG.VA that differ.
    let mut two = one(POSREG.into());
    two.push((
        "other/posreg.va".into(),
        POSREG.replace("1620.000", "1600.000"),
    ));
    match read(&text, &two).unwrap_err() {
        stiffid::Error::Parse {
            source_name,
            message,
        } => {
            assert_eq!(source_name, "other/posreg.va");
            assert!(
                message.contains("differs from backup/POSREG.VA"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    two[1].1 = POSREG.into();
    assert!(read(&text, &two).is_ok());
    // A motion to an element of a register (a number).
    let element = text.replacen("J PR[7:PARK]", "J PR[7,1]", 1);
    let (line, why) = refusal(&read(&element, &one(POSREG.into())).unwrap_err());
    assert_eq!(line, 7, "{why}");
    assert!(
        why.starts_with("J PR[7,1]: an element of a position register"),
        "{why}"
    );
    // A mask holding no group 1, or not the group 2 a position gives.
    let mask = |m: &str| straight.replacen("= 1,*,*,*,*;", &format!("= {m};"), 1);
    for (m, says) in [
        ("*,1,*,*,*", "holds no motion group 1"),
        ("*,*,*,*,*", "holds no motion group 1"),
        ("1,x,*,*,*", "expected 1 or * for each motion group"),
    ] {
        let (line, why) = refusal(&read(&mask(m), &[]).unwrap_err());
        assert_eq!(line, 3, "{m}: {why}");
        assert!(why.contains(says), "{m}: {why}");
    }
    let second = straight.replacen(
        "J6 = -48.300 deg\n};",
        "J6 = -48.300 deg\n   GP2:\n   UF : 0, UT : 1,\n   J1 = 10.000 deg\n};",
        1,
    );
    assert_eq!(
        read(&second.replacen("= 1,*,*", "= 1,1,*", 1), &[])
            .unwrap()
            .axes,
        ["GP2 J1"]
    );
    let (line, why) = refusal(&read(&second, &[]).unwrap_err());
    assert_eq!(line, 3, "{why}");
    assert!(why.contains("on line 17 gives GP2"), "{why}");
    assert!(
        why.contains("does not hold motion group 2, yet its position on line"),
        "{why}"
    );
    // A called program whose mask holds no group 1: refused naming the call.
    let main = straight.replacen("   6:  DO[103]=OFF ;", "   6:  CALL PICK ;", 1);
    let pick = mask("*,1,*,*,*").replacen("/PROG  TMPA", "/PROG  PICK", 1);
    let (line, why) = refusal(&read(&main, &[("b/PICK.LS".into(), pick)]).unwrap_err());
    assert_eq!(line, 10, "{why}");
    assert!(
        why.starts_with("CALL PICK: b/PICK.LS line 3: DEFAULT_GROUP"),
        "{why}"
    );
    // A FOR loop's bound.
    let looped = straight
        .replacen("   4:L P[2]", "   4:  FOR R[1]=1 TO abc ;\n   4:L P[2]", 1)
        .replacen("   6:  DO[103]=OFF ;", "   6:  ENDFOR ;", 1);
    let (line, why) = refusal(&read(&looped, &[]).unwrap_err());
    assert_eq!(line, 8, "{why}");
    assert!(
        why.starts_with("FOR R[1]=1 TO abc: expected FOR R[i]=a TO b"),
        "{why}"
    );
}

/// An empty `SYSFRAME.VA` (or another file under the name) and a program called that is cut off
/// (no `/END`: its last lines, and any motion in them, lost) are refused naming the file.
#[test]
fn an_empty_frame_file_or_a_called_program_cut_off_is_refused_naming_the_file() {
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let read = |text: &str, backup: &[(String, String)]| {
        parse_in(
            text,
            Dialect::FanucLs,
            &Context::default().with_backup(backup),
        )
    };
    let frames = vec![("backup/SYSFRAME.VA".to_string(), "\r\n".to_string())];
    match read(&straight, &frames).unwrap_err() {
        stiffid::Error::Parse {
            source_name,
            message,
        } => {
            assert_eq!(source_name, "backup/SYSFRAME.VA");
            assert!(
                message.contains("holds neither $MNUFRAME nor $MNUTOOL"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let call = straight.replacen("   6:  DO[103]=OFF ;", "   6:  CALL SUB ;", 1);
    let cut = vec![(
        "backup/SUB.LS".to_string(),
        "/PROG  SUB\n/ATTR\n/MN\n   1:  DO[1]=ON ;\n".to_string(),
    )];
    let (line, why) = refusal(&read(&call, &cut).unwrap_err());
    assert_eq!(line, 10, "{why}");
    assert!(
        why.starts_with("CALL SUB: backup/SUB.LS line 4: the program ends on"),
        "{why}"
    );
}
