//! RAPID's loops, branches, jumps, handlers and routines around motions: each motion read where
//! it is; what a statement sets for the motions after it (configuration monitoring) followed
//! along every path, refused naming the line and the construct where the paths disagree.

use stiffid::internal::machining::program::{self, Dialect};
use stiffid::Error;

const EXT: &str = "[9E9,9E9,9E9,9E9,9E9,9E9]";

/// A module whose `main` holds `body`, its first line the module's line 3.
fn module(body: &str) -> String {
    format!("MODULE M\n  PROC main()\n{body}\n  ENDPROC\nENDMODULE\n")
}

fn motion(q1: f64) -> String {
    format!("MoveAbsJ [[{q1},0,0,0,30,0],{EXT}], v100, fine, tool0;")
}

/// The line and message of the refusal of `text`.
fn refused(text: &str) -> (u64, String) {
    match program::parse(text, Dialect::Rapid) {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("expected a refusal, got {other:?}\n{text}"),
    }
}

/// The motions of `text` read: line and first axis.
fn read(text: &str) -> Vec<(u64, f64)> {
    let p = program::parse(text, Dialect::Rapid).unwrap_or_else(|e| panic!("{e}\n{text}"));
    p.targets.iter().map(|t| (t.line, t.q_deg[0])).collect()
}

#[test]
fn a_motion_inside_a_construct_or_a_second_routine_is_read_where_it_is() {
    let m = motion(1.0);
    let cases: [(String, &[(u64, f64)]); 9] = [
        // A compact IF over two lines around a motion, inside a FOR inside a WHILE.
        (
            format!("    WHILE TRUE DO\n      FOR i FROM 1 TO 3 DO\n        IF (NOT skip)\n          {m}\n      ENDFOR\n    ENDWHILE"),
            &[(6, 1.0)],
        ),
        (format!("    {}\n    IF di1 = 1 THEN\n      {m}\n    ENDIF", motion(2.0)), &[(3, 2.0), (5, 1.0)]),
        (format!("    IF di1 = 1 THEN\n      SetDO do1, 1;\n    ELSE\n      {m}\n    ENDIF"), &[(6, 1.0)]),
        (format!("    TEST n\n    CASE 1:\n      {m}\n    ENDTEST"), &[(5, 1.0)]),
        (format!("    {m}\n  ERROR\n    {}", motion(3.0)), &[(3, 1.0), (5, 3.0)]),
        // Jumps and conditional leaves: each motion still where it is.
        (format!("    {m}\n    IF di1 = 1 GOTO skip;\n    {m}\n  skip:"), &[(3, 1.0), (5, 1.0)]),
        // A label is a statement of its own: the motion on the next line is read (it was taken
        // as the label's statement and passed over).
        (format!("  again:\n    {m}\n    IF di1 = 1 GOTO again;\n    {}", motion(2.0)), &[(4, 1.0), (6, 2.0)]),
        (format!("    {m}\n    IF di1 = 1 THEN\n      RETURN;\n    ENDIF\n    {m}"), &[(3, 1.0), (7, 1.0)]),
        (format!("    {m}\n    IF di1 = 1 RETURN;\n    {m}"), &[(3, 1.0), (5, 1.0)]),
    ];
    for (body, want) in cases {
        assert_eq!(read(&module(&body)), want, "{body}");
    }
    // Motions in two routines of the module, in the order of the text.
    let text = format!("MODULE M\n  PROC main()\n    {m}\n    side;\n  ENDPROC\n  PROC side()\n    {}\n  ENDPROC\nENDMODULE\n", motion(4.0));
    assert_eq!(read(&text), [(3, 1.0), (7, 4.0)]);
}

/// Configuration monitoring switched off on one path only: the linear motion after the branch
/// is refused naming its line and the construct, or left as found on request.
#[test]
fn configuration_monitoring_set_in_one_branch_only_refuses_the_motions_after_it() {
    let robtarget = format!("[[500,0,400],[0,0,1,0],[0,0,0,0],{EXT}]");
    let body = format!("    ConfL \\On;\n    IF di1 = 1 THEN\n      ConfL \\Off;\n    ENDIF\n    MoveL {robtarget}, v100, fine, tool0;\n    {}", motion(1.0));
    let text = module(&body);
    let (line, message) = refused(&text);
    assert_eq!(line, 7, "{message}");
    assert!(
        message.contains("ConfL \\Off is in force on one path through IF (line 4)"),
        "{message}"
    );
    let leave = program::Context::default().with_leave_refused(true);
    let p = program::parse_in(&text, Dialect::Rapid, &leave).unwrap();
    assert_eq!(p.left.len(), 1);
    assert_eq!(p.left[0].line, 7);
    assert_eq!(p.targets.len(), 1);
    assert_eq!(p.targets[0].line, 8);
}

#[test]
fn constructs_without_motions_leave_the_motions_as_read() {
    let body = format!(
        "    {}\n    IF di1 = 1 THEN\n      SetDO do1, 1;\n    ENDIF\n    IF moveCount > 2 SetDO do2, 0;\n    WHILE di3 = 0 DO\n      capacity := capacity + 1;\n    ENDWHILE\n    {}",
        motion(1.0),
        motion(2.0)
    );
    let text = module(&body);
    let p = program::parse(&text, Dialect::Rapid).unwrap();
    let read: Vec<(u64, f64)> = p.targets.iter().map(|t| (t.line, t.q_deg[0])).collect();
    assert_eq!(read, [(3, 1.0), (11, 2.0)]);
    // A routine without motions may loop and jump: it is not the path.
    let text = format!("MODULE M\n  PROC main()\n    {}\n  ENDPROC\n  PROC wait()\n    WHILE TRUE DO\n      IF di1 = 1 GOTO out;\n    ENDWHILE\n  out:\n  ENDPROC\nENDMODULE\n", motion(3.0));
    let p = program::parse(&text, Dialect::Rapid).unwrap();
    assert_eq!(p.targets.len(), 1);
}

#[test]
fn a_module_without_motions_says_so() {
    let (line, message) =
        refused("MODULE M\n  PROC main()\n    SetDO do1, 1;\n  ENDPROC\nENDMODULE\n");
    assert_eq!(line, 1);
    assert!(
        message.contains("no motion instruction in the module (MoveAbsJ, MoveL, MoveJ, MoveC); it holds 1 routine (main (line 2))"),
        "{message}"
    );
}

#[test]
fn motions_whose_path_the_program_does_not_hold_are_refused_naming_them() {
    let m = motion(1.0);
    let robtarget = format!("[[500,0,400],[0,0,1,0],[0,0,0,0],{EXT}]");
    let cases = [
        // After a motion the reader takes, an EGM motion in a routine of its own: the module's
        // path is the sensor's (Externally Guided Motion), so it is refused, not read as one point.
        (format!("    {m}\n    EGMRunJoint egm_id, EGM_STOP_HOLD, \\J1 \\J2 \\J3 \\J4 \\J5 \\J6 \\CondTime:=1.0;"), 4, "EGMRunJoint: an Externally Guided Motion"),
        (format!("    {m}\n    EGMMoveL egm_id, {robtarget}, v10, fine, tool0;"), 4, "EGMMoveL: an Externally Guided Motion"),
        (format!("    {m}\n    WHILE TRUE DO\n      EGMRunPose egm_id, EGM_STOP_HOLD;\n    ENDWHILE"), 5, "EGMRunPose: an Externally Guided Motion"),
        (format!("    {m}\n    IndAMove Station_A, 2\\ToAbsNum:=90, 20;"), 4, "IndAMove: an independent axis motion"),
        (format!("    {m}\n    ContactL \\DesiredTorque:=2.5, {robtarget}, v10, tool0;"), 4, "ContactL: a motion that stops where contact is made"),
        (format!("    {m}\n    PathRecMoveBwd \\ID:=fixture_id;"), 4, "PathRecMoveBwd: a motion along a path the controller recorded"),
        // `\Corr`: a sensor's correction added to the path at run time.
        (format!("    {m}\n    MoveL {robtarget}, v100, z10, tool0\\Corr;"), 4, "\\Corr (tool tool0): the path is corrected at run time"),
    ];
    for (body, line, words) in cases {
        let text = module(&body);
        let (l, message) = refused(&text);
        assert_eq!(l, line, "{message}\n{text}");
        assert!(message.contains(words), "{message}\n{text}");
    }
}

/// A motion whose instruction has a stray character (`Mov%eL`, `MoveL]`, a letter outside ASCII)
/// was passed over as a statement stiffid does not read, dropping its target: refused naming
/// the line, as the controller refuses to load it.
#[test]
fn a_statement_rapid_cannot_read_is_refused_not_passed_over() {
    for (instruction, shown) in [
        ("Mov%eAbsJ", "'Mov%eAbsJ'"),
        ("MoveAbsJ]", "'MoveAbsJ]'"),
        ("MoveAbs\u{e9}J", "'MoveAbs\u{e9}J'"),
    ] {
        let text = module(&format!(
            "    {}\n    {}",
            motion(1.0),
            motion(2.0).replace("MoveAbsJ", instruction)
        ));
        let (line, message) = refused(&text);
        assert_eq!(line, 4, "{message}");
        assert!(
            message.contains(&format!("{shown}: not a RAPID statement")),
            "{message}"
        );
    }
}

/// Arc welding motions are the linear and circular motions they are: `ArcLStart`, `ArcL`,
/// `ArcC` (circle point, end point) and `ArcLEnd`, their seam and weld data passed over.
#[test]
fn arc_welding_motions_are_read_as_the_motions_they_are() {
    let p = |x: f64| format!("[[{x},0,400],[0,0,1,0],[0,0,0,0],{EXT}]");
    let body = format!(
        "    ArcLStart {}, v100, seam1, weld1, fine, tool0;\n    ArcL {}, v20, seam1, weld1\\Weave:=weave1, z1, tool0;\n    ArcC {}, {}, v20, seam1, weld1, z1, tool0;\n    ArcLEnd {}, v20, seam1, weld1, fine, tool0;",
        p(500.0), p(510.0), p(520.0), p(530.0), p(540.0)
    );
    let text = module(&body);
    let read = program::parse(&text, Dialect::Rapid).unwrap();
    let x: Vec<(u64, f64)> = (read.targets.iter())
        .map(|t| (t.line, t.cartesian.as_deref().unwrap().position_mm.x))
        .collect();
    assert_eq!(
        x,
        [(3, 500.0), (4, 510.0), (5, 520.0), (5, 530.0), (6, 540.0)]
    );
    // The path speed of each linear motion, m/s.
    assert_eq!(read.targets[1].speed, program::speed::Speed::Path(0.02));
}

/// A routine's parameter list running on over the next lines (`VAR robtarget arcStart,` opening
/// the second, as a welding cell's module writes it) is the header's, no declaration; and the
/// editor's statement placeholder `<SMT>`, which the controller loads and stops at, moves nothing
/// (RAPID kernel, "Placeholders"): the motions around both are read.
#[test]
fn a_header_over_two_lines_and_a_placeholder_are_read_as_the_controller_reads_them() {
    let text = "MODULE Weld\n  CONST robtarget p10:=[[500,0,400],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n  PROC main()\n    MoveJ p10, v100, fine, tool0;\n    <SMT>\n  ENDPROC\n  PROC LoadSlot(num slot, VAR bool used,\n                VAR robtarget arcStart, VAR robtarget arcEnd)\n    MoveL Offs(p10, 0, 0, 50), v100, fine, tool0;\n  ENDPROC\nENDMODULE\n";
    let p = stiffid::internal::machining::program::parse(
        text,
        stiffid::internal::machining::program::Dialect::Rapid,
    )
    .unwrap();
    let lines: Vec<u64> = p.targets.iter().map(|t| t.line).collect();
    assert_eq!(lines, [4, 9]);
}

/// A motion to a routine's parameter (`PROC Buffer_Out(robtarget pBuffer)`, as a cell's buffer
/// routine takes its station's point) is refused for its value being the caller's, naming the
/// routine and its line, where the module never calls it; called, the routine is read at each
/// call with that call's arguments (a declared target, `num` data the module states), and a
/// call whose argument the run gives is refused naming the motion and the call.
#[test]
fn a_routine_with_parameters_is_read_at_each_call_with_its_arguments() {
    let routine = "  PROC Buffer_Out(num nBuffer, robtarget pBuffer)\n    MoveL Offs(pBuffer, 0, 0, nBuffer * 10), v100, fine, tool0;\n    MoveL pBuffer, v100, fine, tool0;\n  ENDPROC\n";
    // Not called: read where it is, each parameter hiding the module's datum of its name.
    let hidden = format!("  CONST robtarget pBuffer := [[1,0,400],[0,0,1,0],[0,0,0,0],{EXT}];\n  CONST num nBuffer := 2;\n");
    let text = format!("MODULE Buffer\n{hidden}{routine}ENDMODULE\n");
    let (line, message) = refused(&text);
    assert_eq!(line, 5, "{message}");
    assert!(
        message.contains("is a parameter of Buffer_Out (line 4)"),
        "{message}"
    );
    let data = format!("  CONST robtarget p1 := [[500,0,400],[0,0,1,0],[0,0,0,0],{EXT}];\n  CONST robtarget p2 := [[600,0,400],[0,0,1,0],[0,0,0,0],{EXT}];\n  CONST num n := 3;\n");
    let main = "  PROC main()\n    Buffer_Out n, p1;\n    Buffer_Out n - 1, p2;\n  ENDPROC\n";
    let text = format!("MODULE Buffer\n{data}{main}{routine}ENDMODULE\n");
    let p = program::parse(&text, Dialect::Rapid).unwrap_or_else(|e| panic!("{e}"));
    let read: Vec<(u64, f64, f64)> = (p.targets.iter())
        .map(|t| {
            let at = t.cartesian.as_deref().unwrap().pose().translation.vector * 1e3;
            (t.line, at.x.round(), at.z.round())
        })
        .collect();
    assert_eq!(
        read,
        [
            (10, 500.0, 430.0),
            (11, 500.0, 400.0),
            (10, 600.0, 420.0),
            (11, 600.0, 400.0)
        ]
    );
    // Written: each call's point in its own declaration, the routine as read; one point at
    // two calls compensated apart, refused naming the motion.
    let joints = format!("MODULE J\n  CONST jointtarget j1 := [[1,0,0,0,30,0],{EXT}];\n  CONST jointtarget j2 := [[2,0,0,0,30,0],{EXT}];\n  PROC main()\n    Go j1;\n    Go j2;\n  ENDPROC\n  PROC Go(jointtarget j)\n    MoveAbsJ j, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n");
    let p = program::parse(&joints, Dialect::Rapid).unwrap();
    let q = [
        [1.5, 0.0, 0.0, 0.0, 30.0, 0.0],
        [2.5, 0.0, 0.0, 0.0, 30.0, 0.0],
    ];
    let out = p.write(&q).unwrap();
    assert_eq!(
        out,
        joints
            .replace("[[1,0,0,0,30,0]", "[[1.500000000,0,0,0,30,0]")
            .replace("[[2,0,0,0,30,0]", "[[2.500000000,0,0,0,30,0]")
    );
    // One point at two calls compensated apart: the later call names a copy declared after it.
    let twice = joints.replace("Go j2;", "Go j1;");
    let out = program::parse(&twice, Dialect::Rapid)
        .unwrap()
        .write(&q)
        .unwrap();
    assert!(out.contains("    Go j1;\n    Go j1_2;\n"), "{out}");
    assert!(out.contains("CONST jointtarget j1_2 := [[2.5"), "{out}");
    let back = program::parse(&out, Dialect::Rapid).unwrap();
    let read: Vec<[f64; 6]> = back.targets.iter().map(|t| t.q_deg).collect();
    assert_eq!(read, q);
    // One call whose motions need two values of its one argument: refused naming the call.
    let two = joints.replace(
        "    MoveAbsJ j, v100, fine, tool0;\n",
        "    MoveAbsJ j, v100, fine, tool0;\n    MoveAbsJ j, v100, fine, tool0;\n",
    );
    let two = program::parse(&two, Dialect::Rapid).unwrap();
    let q4 = [q[0], [1.25, 0.0, 0.0, 0.0, 30.0, 0.0], q[1], q[1]];
    let e = two.write(&q4).unwrap_err().to_string();
    assert!(e.contains("the point named on line 5"), "{e}");
    // An argument the run gives: refused at the motion, naming the call.
    for (call, said) in [
        (
            "Buffer_Out nCount, p1;",
            "nbuffer is the argument 'nCount' of the call on line 6",
        ),
        (
            "Buffer_Out n, CRobT();",
            "pbuffer is the argument 'CRobT()' of the call on line 6",
        ),
    ] {
        let text = text.replace("Buffer_Out n, p1;", call);
        let (line, message) = refused(&text);
        assert_eq!(line, 10, "{message}");
        assert!(
            message.contains(said) && message.contains("called on line 6"),
            "{message}"
        );
    }
}
