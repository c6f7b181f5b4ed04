//! A RAPID module calling the `PROC`s of the task's other modules (the controller's backup): each
//! read where it is called, its motions compensated in place in its own module, its parameters
//! bound to the caller's declared data; a call of a procedure the task does not hold, between two
//! motions, refused naming the call.

use stiffid::internal::machining::program::{self, cartesian::Frame, Dialect};
use stiffid::Error;

const EXT: &str = "[9E9,9E9,9E9,9E9,9E9,9E9]";

/// The task's other module: a procedure moving to its parameter and to its own target.
fn handling() -> String {
    format!("MODULE Handling\n  CONST jointtarget jSafe := [[0,-10,10,0,60,0],{EXT}];\n  PROC Other()\n    MoveAbsJ [[9,9,9,9,9,9],{EXT}], v100, fine, tool0;\n  ENDPROC\n  PROC GoVia(jointtarget jTo, \\num speed)\n    MoveAbsJ jSafe, v100, z10, tool0; ! clear\n    MoveAbsJ jTo, v100, fine, tool0;\n  ENDPROC\n  PROC Idle()\n    WaitTime 1;\n  ENDPROC\nENDMODULE\n")
}

fn program_text() -> String {
    format!("MODULE Cell\n  CONST jointtarget j1 := [[1,2,3,4,5,6],{EXT}];\n  PROC main()\n    MoveAbsJ [[0,0,0,0,30,0],{EXT}], v100, fine, tool0;\n    Idle;\n    GoVia j1;\n    SetDO do1, 1;\n    MoveAbsJ [[0,0,0,0,40,0],{EXT}], v100, fine, tool0;\n  ENDPROC\nENDMODULE\n")
}

fn backup() -> Vec<(String, String)> {
    vec![("TASK1/PROGMOD/Handling.mod".to_string(), handling())]
}

#[test]
fn a_procedure_of_another_module_is_read_where_it_is_called_and_written_in_its_module() {
    let text = program_text();
    // Alone: the call of a procedure the module does not hold, between two motions, is refused.
    match program::parse(&text, Dialect::Rapid) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 5, "{message}");
            assert!(
                message.starts_with("Idle: a call of a procedure") && message.contains("--backup"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    // Left as found with --leave-refused: named, the motions around it compensated.
    let context = program::Context::default().with_leave_refused(true);
    let left = program::parse_in(&text, Dialect::Rapid, &context).unwrap();
    assert_eq!(left.targets.len(), 2);
    assert_eq!((left.left[0].line, left.left[1].line), (5, 6));
    let backup = backup();
    let context = program::Context::default().with_backup(&backup);
    let p = program::parse_in(&text, Dialect::Rapid, &context).unwrap();
    // In the order the robot moves: the program's, the procedure's two (its own jSafe, then the
    // caller's j1 bound to its parameter), the program's; `Other` is not called, `Idle` moves
    // nothing.
    let read: Vec<(u64, [f64; 6], Option<&str>)> = (0..p.targets.len())
        .map(|i| (p.targets[i].line, p.targets[i].q_deg, p.called_in(i)))
        .collect();
    let file = Some("TASK1/PROGMOD/Handling.mod");
    assert_eq!(
        read,
        vec![
            (4, [0.0, 0.0, 0.0, 0.0, 30.0, 0.0], None),
            (7, [0.0, -10.0, 10.0, 0.0, 60.0, 0.0], file),
            (8, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], file),
            (8, [0.0, 0.0, 0.0, 0.0, 40.0, 0.0], None),
        ]
    );
    // Written: j1 in the program's declaration, jSafe in the other module, every other byte as
    // read; the module returned under its name as given.
    let mut q: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    q[1][1] = -10.5;
    q[2][0] = 1.25;
    let external = vec![Vec::new(); 4];
    let (written, data, called) = p.write_files(&q, &external).unwrap();
    assert_eq!(data, None);
    assert_eq!(
        written,
        text.replace("[[1,2,3,4,5,6]", "[[1.250000000,2,3,4,5,6]")
    );
    assert_eq!(called.len(), 1);
    assert_eq!(called[0].0, "TASK1/PROGMOD/Handling.mod");
    assert_eq!(
        called[0].1,
        handling().replace("[[0,-10,10,0,60,0]", "[[0,-10.500000000,10,0,60,0]")
    );
    // A procedure that moves nothing: its module is not written.
    let quiet = text.replace("    GoVia j1;\n", "");
    let p = program::parse_in(&quiet, Dialect::Rapid, &context).unwrap();
    let q: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    let (_, _, called) = p.write_files(&q, &vec![Vec::new(); q.len()]).unwrap();
    assert!(called.is_empty());
}

#[test]
fn a_procedures_tool_and_target_arguments_are_the_callers_declared_data() {
    let tool = "PERS tooldata tGrip := [TRUE,[[0,0,150],[1,0,0,0]],[2,[0,0,50],[1,0,0,0],0,0,0]];";
    let data = format!("MODULE Cell\n  {tool}\n  CONST robtarget pA := [[400,0,300],[0,0,1,0],[0,0,0,0],{EXT}];\n  VAR robtarget pB := [[400,0,300],[0,0,1,0],[0,0,0,0],{EXT}];\n  PROC main()\n    Pick pA, tGrip;\n    pB := CRobT();\n    Pick pB, tGrip;\n  ENDPROC\nENDMODULE\n");
    let pick = "MODULE Grip\n  PROC Pick(robtarget p, PERS tooldata t)\n    MoveL Offs(p, 0, 0, 50), v100, z10, t;\n    MoveL p, v100, fine, t;\n  ENDPROC\nENDMODULE\n";
    let backup = vec![("Grip.mod".to_string(), pick.to_string())];
    let context = program::Context::default().with_backup(&backup);
    // pB is assigned at run time: the call passing it refused naming the call and the motion.
    match program::parse_in(&data, Dialect::Rapid, &context) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 8, "{message}");
            assert!(
                message.starts_with("Pick: Grip.mod line 3:")
                    && message.contains("assigned on line 7"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let once = data.replace("    pB := CRobT();\n    Pick pB, tGrip;\n", "");
    let p = program::parse_in(&once, Dialect::Rapid, &context).unwrap();
    assert_eq!(p.targets.len(), 2);
    for (t, z) in p.targets.iter().zip([350.0, 300.0]) {
        let c = t.cartesian.as_deref().unwrap();
        let at = c.pose().translation.vector * 1e3;
        assert!(
            (at - nalgebra::Vector3::new(400.0, 0.0, z)).norm() < 1e-9,
            "{at:?}"
        );
        assert!(
            matches!(&c.tool, Frame::Stated(_, f) if (f.translation.z - 0.15).abs() < 1e-12),
            "{:?}",
            c.tool
        );
    }
    // An argument computed at run time: refused naming the call.
    let computed = once.replace("Pick pA, tGrip;", "Pick Offs(pA, 0, 0, 10), tGrip;");
    match program::parse_in(&computed, Dialect::Rapid, &context) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 6, "{message}");
            assert!(message.contains("computed at run time"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn calls_that_never_end_or_shift_the_path_are_refused_and_inert_ones_passed() {
    let ping = format!("MODULE A\n  PROC Ping()\n    MoveAbsJ [[0,0,0,0,30,0],{EXT}], v100, fine, tool0;\n    Pong;\n  ENDPROC\nENDMODULE\n");
    let pong = "MODULE B\n  PROC Pong()\n    Ping;\n  ENDPROC\nENDMODULE\n";
    let backup = vec![
        ("A.mod".to_string(), ping),
        ("B.mod".to_string(), pong.to_string()),
    ];
    // Two modules declaring one procedure: the task does not load.
    let twice = [
        backup.clone(),
        vec![(
            "C.mod".to_string(),
            "MODULE C\n  PROC Ping()\n  ENDPROC\nENDMODULE\n".to_string(),
        )],
    ]
    .concat();
    let context = program::Context::default().with_backup(&twice);
    let text = "MODULE Cell\n  PROC main()\n    Ping;\n  ENDPROC\nENDMODULE\n";
    match program::parse_in(text, Dialect::Rapid, &context) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 3, "{message}");
            assert!(
                message.contains("PROC Ping is declared in A.mod and in C.mod"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let context = program::Context::default().with_backup(&backup);
    match program::parse_in(text, Dialect::Rapid, &context) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 3, "{message}");
            assert!(message.starts_with("Ping: A.mod line 4: Pong: B.mod line 3: Ping: the procedure calls itself through A.mod.ping, B.mod.pong"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    let m = |between: &str| {
        format!("MODULE Cell\n  PROC main()\n    MoveAbsJ [[0,0,0,0,30,0],{EXT}], v100, fine, tool0;\n    {between}\n    MoveAbsJ [[0,0,0,0,40,0],{EXT}], v100, fine, tool0;\n  ENDPROC\nENDMODULE\n")
    };
    for inert in [
        "WaitTime 1;",
        "SetDO do1, 1;",
        "TPWrite \"x\";",
        "AccSet 50, 100;",
        "IF di1 = 1 AND NOT done SetDO do1, 1;",
        "IF n > 1.5E-3 n := n - 1;",
    ] {
        let p = program::parse(&m(inert), Dialect::Rapid);
        assert!(p.is_ok(), "{inert}: {p:?}");
    }
    // A call the task does not hold before the first motion: the path is the file's.
    let first = m("WaitTime 1;").replace("PROC main()\n", "PROC main()\n    Init;\n");
    assert_eq!(
        program::parse(&first, Dialect::Rapid)
            .unwrap()
            .targets
            .len(),
        2
    );
    for (between, said) in [
        ("PDispOn \\ExeP:=p1, p1, tool0;", "program displacement"),
        ("%\"proc\" + \"1\"%;", "late-bound"),
        ("IF ok Unknown;", "Unknown: a call of a procedure neither"),
        (
            "IF a > 1 AND NOT (b = \"x\") GripperOpen 2;",
            "GripperOpen: a call",
        ),
    ] {
        match program::parse(&m(between), Dialect::Rapid) {
            Err(Error::Program { line, message }) => {
                assert_eq!(line, 4, "{message}");
                assert!(message.contains(said), "{message}");
            }
            other => panic!("{between}: {other:?}"),
        }
    }
    // Left as found: named, the motions around it read.
    let leave = program::Context::default().with_leave_refused(true);
    let p = program::parse_in(&m("IF ok Unknown;"), Dialect::Rapid, &leave).unwrap();
    assert_eq!((p.targets.len(), p.left.len(), p.left[0].line), (2, 1, 4));
}
