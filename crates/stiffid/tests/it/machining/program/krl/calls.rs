//! A KRL program calling routines of other modules: a module the backup holds (`MY_PATH.src`
//! with its `.dat`) read where it is called, its motions compensated in place in its own files
//! with the frames in force at the call, the frames it leaves followed after the call; a call
//! between two motions of a routine no file holds refused naming the call (left, with
//! `--leave-refused`), the controller's own routines passed.

use nalgebra::Vector3;
use stiffid::internal::machining::program::{self, cartesian::Frame, Dialect};
use stiffid::Error;

const MAIN: &str = "DEF cell( )\n$TOOL = {X 0, Y 0, Z 250, A 0, B 0, C 0}\n$BASE = {X 1000, Y 0, Z 500, A 0, B 0, C 0}\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}\nMY_PATH( )\nLIN {X 10, Y 0, Z 40, A 0, B 0, C 180}\nEND\n";
const PATH_SRC: &str = "&ACCESS RVP\nDEF MY_PATH( )\nLIN XQ1 C_DIS\nLIN {X 20, Y 5, Z 30, A 0, B 0, C 180}\n$BASE = {X 1200, Y 0, Z 500, A 0, B 0, C 0}\nEND\n";
const PATH_DAT: &str =
    "DEFDAT MY_PATH\nDECL E6POS XQ1={X 20, Y 0, Z 30, A 0, B 0, C 180, S 2, T 10}\nENDDAT\n";

fn backup(src: &str, dat: Option<&str>) -> Vec<(String, String)> {
    let mut files = vec![("KRC/R1/Program/my_path.src".to_string(), src.to_string())];
    if let Some(d) = dat {
        files.push(("KRC/R1/Program/my_path.dat".to_string(), d.to_string()));
    }
    files
}

/// The base's x (mm) a Cartesian target moves in.
fn base_x(t: &program::JointTarget) -> f64 {
    match &t.cartesian.as_deref().unwrap().frame {
        Frame::Stated(_, f) => f.translation.vector.x * 1e3,
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_called_module_of_the_backup_is_read_where_it_is_called() {
    let files = backup(PATH_SRC, Some(PATH_DAT));
    let context = program::Context::default().with_backup(&files);
    let p = program::parse_in(MAIN, Dialect::Krl, &context).unwrap();
    // The program's two motions, then the module's two, in their own file.
    assert_eq!(p.targets.len(), 4);
    let lines: Vec<u64> = p.targets.iter().map(|t| t.line).collect();
    assert_eq!(lines, [4, 6, 3, 4]);
    assert_eq!(p.called_in(1), None);
    // A point of the module's .dat, an aggregate of its .src.
    assert_eq!(p.called_in(2), Some("KRC/R1/Program/my_path.dat"));
    assert_eq!(p.called_in(3), Some("KRC/R1/Program/my_path.src"));
    // The module's motions move in the base in force at the call, with its tool.
    let q1 = p.targets[2].cartesian.as_deref().unwrap();
    assert!((q1.position_mm - Vector3::new(20.0, 0.0, 30.0)).norm() < 1e-12);
    assert_eq!(base_x(&p.targets[2]), 1000.0);
    assert_eq!(base_x(&p.targets[3]), 1000.0);
    // The base it leaves is the one the program's motion after the call moves in.
    assert_eq!(base_x(&p.targets[1]), 1200.0);
}

#[test]
fn a_called_module_is_written_in_place_every_other_byte_as_read() {
    let joint = "DEF cell( )\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}\nMY_PATH( )\nPTP {A1 5, A2 -90, A3 90, A4 0, A5 45, A6 0}\nEND\n";
    let src = "DEF MY_PATH( )\n; approach\nPTP XJ1\nPTP {A1 2, A2 -80, A3 80, A4 0, A5 40, A6 0} C_PTP\nEND\n";
    let dat = "DEFDAT MY_PATH\nDECL E6AXIS XJ1={A1 1, A2 -85, A3 85, A4 0, A5 40, A6 0}\nENDDAT\n";
    let files = backup(src, Some(dat));
    let context = program::Context::default().with_backup(&files);
    let p = program::parse_in(joint, Dialect::Krl, &context).unwrap();
    assert_eq!(p.targets.len(), 4);
    let mut q: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    q[2][0] = 1.5;
    q[3][1] = -80.25;
    let (main, data, called) = p.write_files(&q, &vec![Vec::new(); 4]).unwrap();
    assert_eq!(main, joint);
    assert_eq!(data, None);
    assert_eq!(called.len(), 2);
    assert_eq!(called[0].0, "KRC/R1/Program/my_path.src");
    assert_eq!(called[0].1, src.replace("A2 -80,", "A2 -80.250000000,"));
    assert_eq!(called[1].0, "KRC/R1/Program/my_path.dat");
    assert_eq!(called[1].1, dat.replace("A1 1,", "A1 1.500000000,"));
}

#[test]
fn a_call_no_file_holds_between_two_motions_is_refused_naming_it() {
    let p = |text: &str, leave: bool| {
        let context = program::Context {
            leave_refused: leave,
            ..program::Context::default()
        };
        program::parse_in(text, Dialect::Krl, &context)
    };
    match p(MAIN, false) {
        Err(Error::Program { line: 5, message }) => {
            assert!(
                message.starts_with("MY_PATH( ): a call between two motions"),
                "{message}"
            );
            assert!(message.contains("--backup"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    // Held in the backup, but not as a module's first routine: said so.
    let global = [
        (
            "cell/tools.src",
            "DEF tools( )\nEND\nGLOBAL DEF my_path( )\nEND\n",
            "a GLOBAL routine of cell/tools.src, line 3",
        ),
        (
            "cell/my_path.src",
            "DEF path2( )\nEND\n",
            "opens with the routine PATH2 on line 1, not MY_PATH",
        ),
    ];
    for (file, text, says) in global {
        let files = vec![(file.to_string(), text.to_string())];
        let context = program::Context::default().with_backup(&files);
        match program::parse_in(MAIN, Dialect::Krl, &context) {
            Err(Error::Program { line: 5, message }) => {
                assert!(
                    message.contains(says) && message.contains("a routine stiffid does not read"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
    // Left as found, named.
    let left = p(MAIN, true).unwrap();
    assert_eq!(left.targets.len(), 2);
    assert_eq!(left.left.len(), 1);
    assert_eq!(left.left[0].line, 5);
    // Before the first motion, after the last, or the controller's own routines: passed.
    let before = MAIN
        .replace("MY_PATH( )\n", "")
        .replace("PTP {", "GRIP(1)\nPTP {");
    assert!(p(&before, false).is_ok());
    let after = MAIN
        .replace("MY_PATH( )\n", "")
        .replace("END\n", "GRIP(1)\nEND\n");
    assert!(p(&after, false).is_ok());
    let own = MAIN.replace("MY_PATH( )", "BAS(#VEL_PTP, 20)\nPULSE($OUT[3], TRUE, 0.5)");
    assert!(p(&own, false).is_ok());
    // A routine the setup's [controller.io] maps a process event to (its spindle, say).
    use stiffid::internal::setup::program_io::{Io, ProcessEvent};
    let io = Io::default()
        .with(ProcessEvent::SpindleCw, &["my_path(5000)"])
        .unwrap();
    let mapped = program::Context {
        io: Some(&io),
        ..program::Context::default()
    };
    assert!(program::parse_in(MAIN, Dialect::Krl, &mapped).is_ok());
    // In a loop with a motion, a call before the motion runs after it on the next run.
    let looped =
        "DEF cell( )\nLOOP\nGRIP( )\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}\nENDLOOP\nEND\n";
    assert!(matches!(
        p(looped, false),
        Err(Error::Program { line: 3, .. })
    ));
    // In a routine of the file called between two motions.
    let sub = "DEF cell( )\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}\nGRIP_IT( )\nPTP {A1 5, A2 -90, A3 90, A4 0, A5 45, A6 0}\nEND\nDEF GRIP_IT( )\nGRIP(1)\nEND\n";
    assert!(matches!(p(sub, false), Err(Error::Program { line: 7, .. })));
}

#[test]
fn a_called_module_that_calls_itself_or_refuses_is_named_at_the_call() {
    let again = PATH_SRC.replace("$BASE = {X 1200, Y 0, Z 500, A 0, B 0, C 0}", "CELL( )");
    let mut files = backup(&again, Some(PATH_DAT));
    files.push(("KRC/R1/Program/cell.src".to_string(), MAIN.to_string()));
    let context = program::Context::default().with_backup(&files);
    match program::parse_in(MAIN, Dialect::Krl, &context) {
        Err(Error::Program { line: 5, message }) => {
            assert!(message.contains("calls itself"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    // Without its .dat, the module's point is declared nowhere: named with its file and line;
    // its .src cut before END, or its .dat without DEFDAT: named with the file.
    let cut = PATH_SRC.replace("END\n", "");
    let headless = PATH_DAT.replace("DEFDAT MY_PATH\n", "");
    for (src, dat, says) in [
        (PATH_SRC, None, "MY_PATH( ): my_path.src line 3: LIN XQ1"),
        (
            &cut,
            Some(PATH_DAT),
            "MY_PATH( ): my_path.src line 5: the program ends on '$BASE",
        ),
        (
            PATH_SRC,
            Some(&headless),
            "MY_PATH( ): my_path.dat opens on its line 1 with 'DECL",
        ),
    ] {
        let files = backup(src, dat);
        let context = program::Context::default().with_backup(&files);
        match program::parse_in(MAIN, Dialect::Krl, &context) {
            Err(Error::Program { line: 5, message }) => {
                assert!(message.starts_with(says), "{message}")
            }
            other => panic!("{other:?}"),
        }
    }
}

/// A module called twice with other bases in force: its Cartesian motions refused (the paths'
/// frames joined), naming both calls; called in a loop that changes the base after it, the same.
#[test]
fn a_module_called_with_other_frames_is_refused_where_they_matter() {
    let files = backup(PATH_SRC, Some(PATH_DAT));
    let context = program::Context::default().with_backup(&files);
    let twice = MAIN.replace(
        "LIN {X 10",
        "$BASE = {X 900, Y 0, Z 500, A 0, B 0, C 0}\nMY_PATH( )\nLIN {X 10",
    );
    let unknown = |text: &str| {
        let p = program::parse_in(text, Dialect::Krl, &context).unwrap();
        match &p.targets[3].cartesian.as_deref().unwrap().frame {
            Frame::Unknown(_, why) => why.clone(),
            other => panic!("{other:?}"),
        }
    };
    let why = unknown(&twice);
    assert!(
        why.contains("the calls of MY_PATH (lines 5 and 7)"),
        "{why}"
    );
    let looped = MAIN.replace(
        "MY_PATH( )\n",
        "LOOP\nMY_PATH( )\n$BASE = {X 900, Y 0, Z 500, A 0, B 0, C 0}\nENDLOOP\n",
    );
    let why = unknown(&looped);
    assert!(why.contains("LOOP (line 5)"), "{why}");
}

/// Compensated by the command's job: the module called is written beside the program under its
/// own name, its `.src` and `.dat` together, its points compensated in place with the cut's
/// load and every other byte as read.
#[test]
fn the_job_writes_the_called_module_beside_the_program() {
    let main = "DEF mill( )\n$TOOL = {X 0, Y 0, Z 250, A 0, B 0, C 0}\n$BASE = {X 2000, Y 0, Z 550, A 0, B 0, C 0}\n$VEL.CP = 0.03\nLIN {X 0, Y -100, Z 5, A 0, B 0, C 180, S 'B010', T 'B101001'}\nMY_CUT( )\nLIN {X 60, Y -100, Z 5, A 0, B 0, C 180, S 'B010', T 'B101001'}\nEND\n";
    let src = "DEF MY_CUT( )\n; the cut\nLIN XC1 C_DIS\nLIN XC2\nEND\n";
    let dat = "DEFDAT MY_CUT\nDECL E6POS XC1={X 0, Y -100, Z -4, A 0, B 0, C 180, S 'B010', T 'B101001'}\nDECL E6POS XC2={X 60, Y -100, Z -4, A 0, B 0, C 180, S 'B010', T 'B101001'}\nENDDAT\n";
    let files = vec![
        ("R1/Program/MY_CUT.src".to_string(), src.to_string()),
        ("R1/Program/MY_CUT.dat".to_string(), dat.to_string()),
    ];
    let p = super::backup::run((main, None), &files).unwrap();
    assert_eq!(p.subprograms.len(), 1);
    let f = &p.subprograms[0];
    assert_eq!(f.name, "MY_CUT");
    assert_eq!(f.text, src);
    let written = f.data.as_deref().unwrap();
    let (read, new): (Vec<&str>, Vec<&str>) = (dat.lines().collect(), written.lines().collect());
    assert_eq!(read.len(), new.len());
    for (a, b) in read.iter().zip(&new) {
        if !a.starts_with("DECL") {
            assert_eq!(a, b);
            continue;
        }
        // Moved by the deflection under the cut, less than 5 mm; the rest as read.
        let x = |l: &str| -> Vec<f64> {
            let inner = &l[l.find('{').unwrap() + 1..l.find(", S").unwrap()];
            (inner.split(','))
                .map(|m| m.split_whitespace().nth(1).unwrap().parse().unwrap())
                .collect()
        };
        let moved = (0..3)
            .map(|k| (x(a)[k] - x(b)[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(moved > 1e-3 && moved < 5.0, "{a} -> {b}");
        // The status as read (the turn is the compensated posture's).
        assert_eq!(
            a[a.find(", S").unwrap()..a.find(", T").unwrap()],
            b[b.find(", S").unwrap()..b.find(", T").unwrap()]
        );
    }
    // The program itself as read but its own targets (and the bound comments).
    assert_eq!(p.text.lines().nth(5), Some("MY_CUT( )"));
}
