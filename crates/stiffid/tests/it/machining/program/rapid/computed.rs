//! Values a RAPID module computes from what it states: `Offs`/`RelTool` of `num` data declared
//! with a value the module never sets (and their arithmetic), and the elements of a target array
//! declared with its values; anything the run sets refused naming the line.

use stiffid::internal::machining::program::{self, Dialect};
use stiffid::Error;

const EXT: &str = "[9E9,9E9,9E9,9E9,9E9,9E9]";

fn module(decl: &str, body: &str) -> String {
    format!("MODULE M\n  CONST robtarget p := [[500,0,400],[0,0,1,0],[0,0,0,0],{EXT}];\n{decl}  PROC main()\n{body}  ENDPROC\nENDMODULE\n")
}

fn at_mm(p: &program::JointProgram, i: usize) -> nalgebra::Vector3<f64> {
    p.targets[i]
        .cartesian
        .as_deref()
        .unwrap()
        .pose()
        .translation
        .vector
        * 1e3
}

fn refused(text: &str) -> (u64, String) {
    match program::parse(text, Dialect::Rapid) {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{other:?}"),
    }
}

#[test]
fn offs_of_num_data_the_module_states_is_read_and_data_the_run_sets_refused() {
    let decl = "  CONST num dz := 50;\n  VAR num dx := 10;\n  PERS num half := dz / 2;\n";
    let body = "    MoveL Offs(p, dx, -half, dz * 2 - (dx + 5)), v100, fine, tool0;\n    MoveL RelTool(p, 0, 0, -dz), v100, fine, tool0;\n";
    let p = program::parse(&module(decl, body), Dialect::Rapid).unwrap();
    assert!(
        (at_mm(&p, 0) - nalgebra::Vector3::new(510.0, -25.0, 485.0)).norm() < 1e-9,
        "{:?}",
        at_mm(&p, 0)
    );
    // RelTool along the tool's z, here the world's -z: 50 mm up.
    assert!(
        (at_mm(&p, 1) - nalgebra::Vector3::new(500.0, 0.0, 450.0)).norm() < 1e-9,
        "{:?}",
        at_mm(&p, 1)
    );
    // Set as the module runs: followed along every path where each gives it a value the module
    // states; else refused at the motion, naming the line where the run's value enters.
    let rows: [(&str, Result<f64, &str>); 10] = [
        ("    dx := 20;\n", Ok(520.0)),
        ("    dx := 20;\n    Incr dx;\n", Ok(521.0)),
        ("    dx := half - 5;\n    IF di1 = 1 THEN\n      Add dx, 3;\n    ELSE\n      dx := 23;\n    ENDIF\n", Ok(523.0)),
        ("    Incr dx;\n", Err("dx is set on line 7, and at the start of the routine on line 6")),
        ("    Nudge dx;\n", Err("dx is set on line 7")),
        ("    IF di1 = 1 dx := 30;\n", Err("dx is set on line 7")),
        ("    dx := 20;\n    FOR dx FROM 1 TO 2 DO\n      MoveL Offs(p, dx, 0, 0), v100, fine, tool0;\n    ENDFOR\n", Err("dx is set on line 7")),
        ("    dx := 20;\n  again:\n    dx := dx + 1;\n    IF dx < 30 GOTO again;\n", Err("in a routine with a GOTO")),
        ("    dx := 20;\n    IF di1 = 1 THEN\n      dx := 30;\n    ENDIF\n", Err("set differently on the paths through IF (line 8)")),
        ("    dx := 20;\n    WHILE di1 = 1 DO\n      MoveL p, v100, fine, tool0;\n      dx := dx + 1;\n    ENDWHILE\n", Err("set on line 10 inside the loop on line 8")),
    ];
    for (set, want) in rows {
        let text = module(decl, &(set.to_string() + body));
        let first = 7 + set.matches('\n').count() as u64;
        match want {
            Ok(x) => {
                let p =
                    program::parse(&text, Dialect::Rapid).unwrap_or_else(|e| panic!("{set}: {e}"));
                let at = at_mm(&p, p.targets.len() - 2);
                assert!((at.x - x).abs() < 1e-9, "{set}: {at:?}");
            }
            Err(said) => {
                let (l, message) = refused(&text);
                assert_eq!(l, first, "{set}: {message}");
                assert!(message.contains(said), "{set}: {message}");
            }
        }
    }
    // A CONST passed to a procedure is not set by it.
    let p = program::parse(
        &module(decl, &format!("    Nudge dz;\n{body}")),
        Dialect::Rapid,
    );
    assert_eq!(p.unwrap().targets.len(), 2);
    let (_, message) = refused(&module(decl, &body.replace("-half", "Abs(half)")));
    assert!(message.contains("abs(..), a function"), "{message}");
}

#[test]
fn an_array_of_targets_declared_with_values_is_read_by_element() {
    let decl = format!("  CONST robtarget pts{{3}} := [[[600,0,400],[0,0,1,0],[0,0,0,0],{EXT}],\n    [[600,100,400],[0,0,1,0],[0,0,0,0],{EXT}],[[600,200,400],[0,0,1,0],[0,0,0,0],{EXT}]];\n  CONST num last := 3;\n  CONST jointtarget js{{2}} := [[[0,0,0,0,30,0],{EXT}],[[0,0,0,0,40,0],{EXT}]];\n");
    let body = "    MoveAbsJ js{2}, v100, fine, tool0;\n    MoveL pts{2}, v100, fine, tool0;\n    MoveL Offs(pts{last}, 0, 0, 10), v100, fine, tool0;\n    MoveL pts{last - 2}, v100, fine, tool0;\n";
    let text = module(&decl, body);
    let p = program::parse(&text, Dialect::Rapid).unwrap();
    assert_eq!(p.targets[0].q_deg, [0.0, 0.0, 0.0, 0.0, 40.0, 0.0]);
    for (i, want) in [
        (1, [600.0, 100.0, 400.0]),
        (2, [600.0, 200.0, 410.0]),
        (3, [600.0, 0.0, 400.0]),
    ] {
        assert!(
            (at_mm(&p, i) - nalgebra::Vector3::from(want)).norm() < 1e-9,
            "{i}: {:?}",
            at_mm(&p, i)
        );
    }
    // Written back: the element's numbers in the array's declaration, nothing else.
    let joint = program::parse(&module(&decl, "    MoveAbsJ js{2}, v100, fine, tool0;\n    MoveAbsJ js{1}, v100, fine, tool0;\n    MoveAbsJ js{2}, v100, fine, tool0;\n"), Dialect::Rapid).unwrap();
    let mut q: Vec<[f64; 6]> = joint.targets.iter().map(|t| t.q_deg).collect();
    q[0][4] = 40.5;
    q[2][4] = 40.5;
    let out = joint.write(&q).unwrap();
    assert!(
        out.contains("[[[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]],[[0,0,0,0,40.500000000,0]"),
        "{out}"
    );
    // One element visited twice, compensated apart: refused naming both lines.
    q[2][4] = 40.25;
    let e = joint.write(&q).unwrap_err().to_string();
    assert!(e.contains("lines 8 and 10"), "{e}");
    // Beyond the array, or an index the run gives: refused naming the line.
    let (line, message) = refused(&module(&decl, "    MoveL pts{4}, v100, fine, tool0;\n"));
    assert!(
        line == 8 && message.contains("beyond the array"),
        "{message}"
    );
    let (line, message) = refused(&module(&decl, "    MoveL pts{n}, v100, fine, tool0;\n"));
    assert!(
        line == 8 && message.contains("n is not a num declared"),
        "{message}"
    );
    // Two dimensions: a row of targets per first index.
    let t = |x: f64, y: f64| format!("[[{x},{y},400],[0,0,1,0],[0,0,0,0],{EXT}]");
    let grid = format!(
        "  CONST num last := 3;\n  VAR robtarget grid{{2,2}} := [[{},{}],\n    [{},{}]];\n",
        t(700.0, 0.0),
        t(700.0, 50.0),
        t(750.0, 0.0),
        t(750.0, 50.0)
    );
    let body = "    MoveL grid{2,1}, v100, fine, tool0;\n    MoveL Offs(grid{1, last - 1}, 0, 0, 5), v100, fine, tool0;\n";
    let p = program::parse(&module(&grid, body), Dialect::Rapid).unwrap();
    assert!((at_mm(&p, 0) - nalgebra::Vector3::new(750.0, 0.0, 400.0)).norm() < 1e-9);
    assert!((at_mm(&p, 1) - nalgebra::Vector3::new(700.0, 50.0, 405.0)).norm() < 1e-9);
}

#[test]
fn a_for_loop_over_an_array_is_read_once_per_value_of_its_variable() {
    let decl = format!("  CONST robtarget pts{{3}} := [[[600,0,400],[0,0,1,0],[0,0,0,0],{EXT}],\n    [[600,100,400],[0,0,1,0],[0,0,0,0],{EXT}],[[600,200,400],[0,0,1,0],[0,0,0,0],{EXT}]];\n  CONST num n := 3;\n");
    let body = |head: &str| {
        format!("    {head}\n      MoveL pts{{i}}, v100, fine, tool0;\n      MoveL Offs(pts{{i}}, 0, 0, i * 10), v100, fine, tool0;\n    ENDFOR\n")
    };
    let p = program::parse(
        &module(&decl, &body("FOR i FROM 1 TO n DO")),
        Dialect::Rapid,
    )
    .unwrap();
    let read: Vec<(u64, [f64; 3])> = (0..p.targets.len())
        .map(|i| (p.targets[i].line, at_mm(&p, i).into()))
        .collect();
    let mut want = Vec::new();
    for i in 0..3 {
        let y = 100.0 * i as f64;
        want.push((8, [600.0, y, 400.0]));
        want.push((9, [600.0, y, 410.0 + 10.0 * i as f64]));
    }
    for ((l, a), (m, b)) in read.iter().zip(&want) {
        assert_eq!(l, m);
        assert!(
            (nalgebra::Vector3::from(*a) - nalgebra::Vector3::from(*b)).norm() < 1e-9,
            "{read:?}"
        );
    }
    assert_eq!(read.len(), 6);
    // Backwards.
    let p = program::parse(
        &module(&decl, &body("FOR i FROM 3 TO 1 STEP -2 DO")),
        Dialect::Rapid,
    )
    .unwrap();
    assert_eq!(p.targets.len(), 4);
    assert!((at_mm(&p, 2) - nalgebra::Vector3::new(600.0, 0.0, 400.0)).norm() < 1e-9);
    // A loop of many statements around one motion: refused before it holds them all.
    let many = "      WaitTime 0;\n".repeat(50);
    let text = module(
        &decl,
        &body("FOR i FROM 1 TO 4900 DO")
            .replace("      MoveL pts{i}", &(many + "      MoveL pts{1}")),
    );
    let (l, message) =
        refused(&text.replace("Offs(pts{i}, 0, 0, i * 10)", "Offs(pts{1}, 0, 0, i)"));
    assert!(
        l == 7 && message.contains("more than 200000 statements"),
        "{message}"
    );
    // STEP 0, a loop beyond the limit, bounds the run gives: refused naming the line.
    for (head, line, said) in [
        ("FOR i FROM 1 TO 3 STEP 0 DO", 7, "STEP 0"),
        ("FOR i FROM 1 TO 1E9 DO", 7, "more than 10000"),
        ("FOR i FROM 1 TO m DO", 8, "its index i is not a num"),
    ] {
        let (l, message) = refused(&module(&decl, &body(head)));
        assert_eq!(l, line, "{head}: {message}");
        assert!(message.contains(said), "{head}: {message}");
    }
}
