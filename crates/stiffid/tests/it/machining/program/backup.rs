//! Programs read with their controller's backup (`stiffid_machining::program::backup`): FANUC
//! `SYSFRAME.VA`'s user and tool frames take the place of the setup's `[controller]` tables,
//! agree with them or are refused naming both.

use super::numbered::{plan, setup, square};
use nalgebra::Vector6;
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::robot::presets;
use stiffid::Setup;
use stiffid_core::setup::Pulses;
use stiffid_core::Error;
use stiffid_machining::program::generate::generate;
use stiffid_machining::program::{Context, Dialect};

const SETUP: &str = include_str!("../../../../../../examples/milling/fanuc-milling.toml");

/// A number as a FANUC controller writes it in a `.VA` file: three decimals, no zero before
/// the point (`-.500`).
fn fanuc(v: f64) -> String {
    let s = format!("{v:.3}");
    match s.strip_prefix("-0.") {
        Some(r) => format!("-.{r}"),
        None => s.strip_prefix("0.").map_or(s.clone(), |r| format!(".{r}")),
    }
}

/// A `SYSFRAME.VA` as an R-30iB backup writes it, user frame 2 at `base` and tool frame 3 at
/// `tool` (X, Y, Z mm, W, P, R deg), the other entries unset or zero.
fn sysframe(base: [f64; 6], tool: [f64; 6]) -> String {
    let pose = |p: [f64; 6]| {
        let v = p.map(fanuc);
        format!(
            "  Group: 1   Config: N D B, 0, 0, 0\n  X: {:>9}   Y: {:>9}   Z: {:>9}\n  W: {:>9}   P: {:>9}   R: {:>9}\n",
            v[0], v[1], v[2], v[3], v[4], v[5]
        )
    };
    format!(
        "[*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[1,9] OF POSITION\n    [1,1] =\n{}    [1,2] = 'PART'\n{}    [1,3] =   '' Uninitialized\n[*SYSTEM*]$MNUFRAMENUM  Storage: CMOS  Access: RW  : ARRAY[1] OF BYTE\n  [1] = 2\n[*SYSTEM*]$MNUTOOL  Storage: SHADOW  Access: RW  : ARRAY[1,10] OF POSITION\n    [1,1] = '' Uninitialized\n    [1,3] = 'SPINDLE'\n{}[*SYSTEM*]$MNUTOOLNUM  Storage: CMOS  Access: RW  : ARRAY[1] OF BYTE\n  [1] = 3\n",
        pose([0.0; 6]),
        pose(base),
        pose(tool)
    )
}

/// The axis angles of LS program `text` read with `backup` and resolved on `s`.
fn read(s: &Setup, text: &str, backup: &[(String, String)]) -> stiffid_core::Result<Vec<[f64; 6]>> {
    let context = Context::default().with_backup(backup);
    let read = machining::read_in(text, Language::Robot(Dialect::FanucLs), 1e-4, &context)?;
    let read = machining::resolve(&read, s, None, &Options::for_setup(s))?;
    let Program::Robot(r) = read.into_owned() else {
        panic!()
    };
    Ok(r.targets.iter().map(|t| t.q_deg).collect())
}

fn message(e: Error) -> (u64, String) {
    match e {
        Error::Program { line, message } => (line, message),
        other => panic!("{other:?}"),
    }
}

/// An LS program in user frame 2 and tool frame 3 reads with a backup's `SYSFRAME.VA` on a setup
/// without tables as with the tables; both agreeing, as either; a tool frame they give
/// differently is refused naming both; an entry cut off names its file and line.
#[test]
fn sysframe_va_gives_the_frames_the_setups_tables_would() {
    let tables = setup("[6.9, 245.3, 319.3]", "[1300, -700, -270]");
    let (t, m) = square(&tables);
    let pulses = Pulses {
        per_deg: [1.0; 6],
        external: Vec::new(),
    };
    let text = generate(&plan(&tables, Dialect::FanucLs, &t, &m, &pulses))
        .unwrap()
        .files
        .remove(0)
        .text;
    assert!(text.contains("UF : 2, UT : 3,"), "{text}");
    let plain =
        stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n))
            .unwrap();
    let va = sysframe(
        [1300.0, -700.0, -270.0, 0.0, 0.0, 0.0],
        [6.9, 245.3, 319.3, 0.0, 0.0, 0.0],
    );
    let backup = vec![("cell/SYSFRAME.VA".to_string(), va.clone())];
    let close = |q: Vec<[f64; 6]>| {
        assert_eq!(q.len(), t.len());
        for (b, w) in q.iter().zip(&t) {
            let off = (Vector6::from(*b) - Vector6::from(w.q_deg)).amax();
            assert!(off <= 1e-6, "{off} deg");
        }
    };
    close(read(&plain, &text, &backup).unwrap());
    close(read(&tables, &text, &backup).unwrap());
    let (_, without) = message(read(&plain, &text, &[]).unwrap_err());
    assert!(
        without.contains("frame number 3 of the controller's tools"),
        "{without}"
    );
    let other = va.replace("X:     6.900", "X:     7.900");
    let other = vec![("SYSFRAME.VA".to_string(), other)];
    let (_, both) = message(read(&tables, &text, &other).unwrap_err());
    assert!(
        both.contains("frame number 3 of the controller's tools: the backup's SYSFRAME.VA line 15 ($MNUTOOL[1,3]) gives X 7.9 mm")
            && both.contains("the setup's [controller] tools X 6.9 mm"),
        "{both}"
    );
    // W, P, R as FANUC turns a frame (Rz(R) Ry(P) Rx(W)), the setup's rpy_deg the same way:
    // the two agree; W and P swapped do not.
    let turned = setup(
        "[6.9, 245.3, 319.3]",
        "[1300, -700, -270], rpy_deg = [1, 2, -0.5]",
    );
    let va_turned = |w: f64, p: f64| {
        let va = sysframe(
            [1300.0, -700.0, -270.0, w, p, -0.5],
            [6.9, 245.3, 319.3, 0.0, 0.0, 0.0],
        );
        assert!(va.contains("R:     -.500"), "{va}");
        vec![("SYSFRAME.VA".to_string(), va)]
    };
    let agreeing = read(&turned, &text, &va_turned(1.0, 2.0));
    assert!(agreeing.is_ok(), "{agreeing:?}");
    let (_, swapped) = message(read(&turned, &text, &va_turned(2.0, 1.0)).unwrap_err());
    assert!(
        swapped.contains("frame number 2 of the controller's bases"),
        "{swapped}"
    );
    // The tool frame's W, P, R line lost.
    let end = va.find("[*SYSTEM*]$MNUTOOLNUM").unwrap();
    let start = va[..end - 1].rfind('\n').unwrap() + 1;
    let cut = format!("{}{}", &va[..start], &va[end..]);
    let cut = vec![("SYSFRAME.VA".to_string(), cut)];
    match read(&plain, &text, &cut).unwrap_err() {
        Error::Parse {
            source_name,
            message,
        } => {
            assert_eq!(source_name, "SYSFRAME.VA");
            assert!(
                message.starts_with("line 15: $MNUTOOL[1,3]: expected X:"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// An LS program as a controller stores it: `mn` in `/MN`, joint positions `P[1]`, `P[2]`.
fn ls_program(name: &str, mn: &str) -> String {
    format!("/PROG  {name}\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n{mn}\n/POS\nP[1]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= 1.000 deg,\tJ2= 2.000 deg,\tJ3= 3.000 deg,\n\tJ4= 4.000 deg,\tJ5= 5.000 deg,\tJ6= 6.000 deg\n}};\nP[2]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= -10.000 deg,\tJ2= 20.500 deg,\tJ3= -30.000 deg,\n\tJ4= .000 deg,\tJ5= 45.000 deg,\tJ6= -60.000 deg\n}};\n/END\n")
}

/// A `CALL` or a macro between two LS motions is passed over when the backup holds the program
/// called and it (and every program it calls) moves nothing; refused naming its line without
/// the backup, when the called program moves, selects a frame, or the calls loop.
#[test]
fn an_ls_call_of_a_program_that_moves_nothing_is_passed_over() {
    let main = ls_program(
        "MAIN",
        "   1:J P[1] 100% FINE ;\n   2:  CALL GRIP(1) ;\n   3:  SPINDLE_ON ;\n   4:L P[2] 50mm/sec FINE ;",
    );
    let io = |name: &str, then: &str| {
        let mn = format!("   1:  DO[5]=ON ;\n   2:  WAIT DI[5]=ON TIMEOUT,LBL[9] ;\n   3:  {then} ;\n   4:  LBL[9] ;");
        (
            format!("backup/{name}.LS"),
            ls_program(name, &mn)
                .replace("P[1]{", "P[7]{")
                .replace("P[2]{", "P[8]{"),
        )
    };
    let read = |backup: &[(String, String)]| {
        let context = Context::default().with_backup(backup);
        stiffid_machining::program::parse_in(&main, Dialect::FanucLs, &context)
    };
    let (line, why) = message(read(&[]).unwrap_err());
    assert_eq!(line, 6);
    assert!(why.contains("a call between two motions"), "{why}");
    let quiet = [io("GRIP", "R[1]=R[1]+1"), io("SPINDLE_ON", "CALL GRIP(2)")];
    let q: Vec<[f64; 6]> = read(&quiet)
        .unwrap()
        .targets
        .iter()
        .map(|t| t.q_deg)
        .collect();
    assert_eq!(
        q,
        [
            [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            [-10.0, 20.5, -30.0, 0.0, 45.0, -60.0]
        ]
    );
    // A called program that calls itself: refused naming the call and the loop.
    let backup = [
        io("GRIP", "R[1]=R[1]+1"),
        io("SPINDLE_ON", "CALL SPINDLE_ON"),
    ];
    let (at, why) = message(read(&backup).unwrap_err());
    assert_eq!(at, 7, "{why}");
    assert!(
        why.contains("the program calls itself through SPINDLE_ON"),
        "{why}"
    );
    // One that moves is read where it is, in its own file; one that selects a tool frame moves
    // no joint position.
    let moves = [
        io("GRIP", "R[1]=R[1]+1"),
        io("SPINDLE_ON", "L P[7] 10mm/sec FINE"),
    ];
    let p = read(&moves).unwrap();
    assert_eq!(p.targets.len(), 3);
    assert_eq!(p.targets[2].q_deg, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(p.called_in(2), Some("backup/SPINDLE_ON.LS"));
    assert_eq!(p.called_in(1), None);
    let selects = [io("GRIP", "R[1]=R[1]+1"), io("SPINDLE_ON", "UTOOL_NUM=2")];
    assert_eq!(read(&selects).unwrap().targets.len(), 2);
}

/// A `CALL` of a program of the backup that moves: its motions compensated in place in its own
/// file, written beside the program; every other byte of both as read; a refusal inside it names
/// the call's line, the file and its own line.
#[test]
fn an_ls_call_of_a_program_that_moves_is_compensated_in_its_own_file() {
    let main = ls_program(
        "MAIN",
        "   1:J P[1] 100% FINE ;\n   2:  IF R[1]=1,CALL PICK ;\n   3:L P[2] 50mm/sec FINE ;",
    );
    let pick = ls_program(
        "PICK",
        "   1:  UTOOL_NUM=1 ;\n   2:L P[2] 20mm/sec FINE ;\n   3:J P[1] 50% FINE ;",
    );
    let backup = [("backup/PICK.LS".to_string(), pick.clone())];
    let context = Context::default().with_backup(&backup);
    let p = stiffid_machining::program::parse_in(&main, Dialect::FanucLs, &context).unwrap();
    let lines: Vec<(u64, Option<&str>)> = (0..4)
        .map(|i| (p.targets[i].line, p.called_in(i)))
        .collect();
    let file = Some("backup/PICK.LS");
    assert_eq!(lines, [(5, None), (7, None), (6, file), (7, file)]);
    let mut q: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    q[2][0] += 1.0;
    q[3][5] -= 0.5;
    let external = vec![Vec::new(); 4];
    let (written, data, called) = p.write_files(&q[..], &external).unwrap();
    assert_eq!((written.as_str(), data), (main.as_str(), None));
    assert_eq!(called.len(), 1);
    assert_eq!(called[0].0, "backup/PICK.LS");
    let expected = pick
        .replacen("J1= -10.000 deg", "J1= -9.000000000 deg", 1)
        .replacen("J6= 6.000 deg", "J6= 5.500000000 deg", 1);
    assert_eq!(called[0].1, expected);
    // A refusal inside the called program names the call, the file and its line.
    let bad = [(
        "backup/PICK.LS".to_string(),
        pick.replace("L P[2] 20mm/sec FINE", "L PR[2] 20mm/sec FINE"),
    )];
    let e = stiffid_machining::program::parse_in(
        &main,
        Dialect::FanucLs,
        &Context::default().with_backup(&bad),
    );
    let (at, why) = message(e.unwrap_err());
    assert_eq!(at, 6, "{why}");
    assert!(
        why.starts_with("CALL PICK: backup/PICK.LS line 6: L PR[2]: a position register"),
        "{why}"
    );
    // A call of a program the backup does not hold, before the called program's first motion,
    // sits between the caller's two motions: refused naming the call, the file and its line.
    let unheld = [(
        "backup/PICK.LS".to_string(),
        pick.replace("UTOOL_NUM=1", "CALL OPEN_GRIPPER"),
    )];
    let e = stiffid_machining::program::parse_in(
        &main,
        Dialect::FanucLs,
        &Context::default().with_backup(&unheld),
    );
    let (at, why) = message(e.unwrap_err());
    assert_eq!(at, 6, "{why}");
    assert!(
        why.starts_with("CALL PICK: backup/PICK.LS line 5: CALL OPEN_GRIPPER"),
        "{why}"
    );
}

/// A motion to a position register the backup's `POSREG.VA` does not hold is refused naming the
/// file.
#[test]
fn an_ls_motion_to_a_position_register_posreg_va_does_not_hold_is_refused_saying_why() {
    let main = ls_program(
        "MAIN",
        "   1:J P[1] 100% FINE ;\n   2:L PR[3:home] 50mm/sec FINE ;",
    );
    let backup = [("backup/POSREG.VA".to_string(), String::new())];
    let e = stiffid_machining::program::parse_in(
        &main,
        Dialect::FanucLs,
        &Context::default().with_backup(&backup),
    );
    let (at, why) = message(e.unwrap_err());
    assert_eq!(at, 6, "{why}");
    assert_eq!(
        why,
        "L PR[3]: backup/POSREG.VA holds no $POSREG entry (empty, cut off, or another file): expected the ASCII variable file a controller's backup writes beside POSREG.SV, its registers under '[*POSREG*]$POSREG ..'; give the backup's POSREG.VA"
    );
}

/// An LS program of 201 moves stiffid wrote split (a main program selecting the frames and
/// calling three parts), its parts given as the backup.
fn split(s: &Setup, per_file: usize) -> Vec<(String, String)> {
    let (t, m) = square(s);
    let t: Vec<_> = t.iter().cycle().take(201).cloned().collect();
    let m: Vec<_> = m.iter().cycle().take(201).cloned().collect();
    let pulses = Pulses {
        per_deg: [1.0; 6],
        external: Vec::new(),
    };
    let mut p = plan(s, Dialect::FanucLs, &t, &m, &pulses);
    p.settings.moves_per_file = per_file;
    let w = generate(&p).unwrap();
    (w.files.into_iter())
        .map(|f| (format!("out/{}.ls", f.name), f.text))
        .collect()
}

/// A split LS program stiffid wrote, its main file read back with its parts as the backup:
/// each part's Cartesian positions in the tool and user frames the main program selects and
/// declares, every posture the one of the same program written as one file, and compensated
/// the same; without the main program, a part's tool frame is not declared. A tool number
/// carried into the parts: positions in the frame in force (`UT : F`) take it, and a part's
/// positions in another tool frame than the one in force are refused naming the call, the part
/// and its line.
#[test]
fn a_split_ls_program_read_back_from_its_main_file_is_the_program_it_was() {
    let plain =
        stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n))
            .unwrap();
    let tables = setup("[6.9, 245.3, 319.3]", "[1300, -700, -270]");
    for s in [&plain, &tables] {
        let parts = split(s, 100);
        let whole = split(s, 1_000_000);
        assert_eq!((parts.len(), whole.len()), (4, 1));
        assert!(
            parts[0].1.contains("  10:  CALL HELD_01 ;\n"),
            "{}",
            parts[0].1
        );
        let one = read(s, &whole[0].1, &[]).unwrap();
        assert_eq!(one.len(), 201);
        assert_eq!(read(s, &parts[0].1, &parts[1..]).unwrap(), one);
        if std::ptr::eq(s, &plain) {
            continue;
        }
        let compliance = s.model_compliance("test").unwrap();
        let run = |(name, text): &(String, String), backup: &[(String, String)]| {
            let (_, r, called) = crate::ls_corpus::compensated_in(
                s,
                &compliance,
                Options::for_setup(s),
                (name, text),
                backup,
            )
            .unwrap();
            let q: Vec<_> = r.iter().map(|c| c.q_compensated).collect();
            (q, called.len())
        };
        let (q_whole, none) = run(&whole[0], &[]);
        let (q_split, three) = run(&parts[0], &parts[1..]);
        assert_eq!((none, three), (0, 3));
        assert!(q_whole.iter().zip(&q_whole[1..]).any(|(a, b)| a != b));
        for (a, b) in q_whole.iter().zip(&q_split) {
            assert!((a - b).amax() < 1e-12, "{}", (a - b).amax());
        }
    }
    // The part alone: its tool frame 1 is the main program's declaration.
    let parts = split(&plain, 100);
    let (_, why) = message(read(&plain, &parts[1].1, &[]).unwrap_err());
    assert!(
        why.contains("frame number 1 of the controller's tools"),
        "{why}"
    );
    // The tool number in force carried into the parts.
    let parts = split(&tables, 100);
    let expected = read(&tables, &parts[0].1, &parts[1..]).unwrap();
    let in_force: Vec<_> = (parts[1..].iter())
        .map(|(n, t)| (n.clone(), t.replace("UT : 3,", "UT : F,")))
        .collect();
    assert_ne!(in_force[0].1, parts[1].1);
    assert_eq!(read(&tables, &parts[0].1, &in_force).unwrap(), expected);
    let other = parts[0].1.replace("UTOOL_NUM=3 ;", "UTOOL_NUM=1 ;");
    let (line, why) = message(read(&tables, &other, &parts[1..]).unwrap_err());
    assert_eq!(line, 22, "{why}");
    assert!(
        why.starts_with("out/HELD_01.ls line 22: UT : 3: the position is in frame 3, and UTOOL_NUM=1 on line 30"),
        "{why}"
    );
}
