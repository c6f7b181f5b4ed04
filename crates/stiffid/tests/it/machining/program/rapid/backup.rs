//! A RAPID module with the other modules of its task (the controller's backup): the targets,
//! tools and work objects they declare read there; a target of another module compensated is
//! declared again in the module, `LOCAL`, after its `MODULE` line; the other module never
//! written.

use stiffid::internal::machining::program::{self, cartesian::Frame, Dialect};
use stiffid::Error;

const EXT: &str = "[9E9,9E9,9E9,9E9,9E9,9E9]";

fn program_text() -> String {
    "MODULE Cut\n  PROC main()\n    MoveAbsJ home1, v100, fine, tool0;\n    MoveAbsJ j1, v100, fine, tool0;\n    MoveL p10, v100, fine, tSpindle\\WObj:=wTable;\n  ENDPROC\nENDMODULE\n".to_string()
}

fn data_module() -> String {
    format!("MODULE CellData(SYSMODULE)\n  TASK PERS jointtarget j1 := [[1,2,3,4,5,6],{EXT}]; ! taught\n  CONST jointtarget home1 := [[0,0,0,0,30,0],{EXT}];\n  PERS tooldata tSpindle := [TRUE,[[0,0,250],[1,0,0,0]],[5,[0,0,100],[1,0,0,0],0,0,0]];\n  PERS wobjdata wTable := [FALSE,TRUE,\"\",[[1000,0,500],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n  CONST robtarget p10 := [[100,0,50],[0,0,1,0],[0,0,0,0],{EXT}];\nENDMODULE\n")
}

#[test]
fn data_of_another_module_is_read_there_and_a_changed_target_declared_locally() {
    let text = program_text();
    // Alone: refused naming the line and where to give the data.
    match program::parse(&text, Dialect::Rapid) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 3);
            assert!(message.contains("--backup"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    let backup = vec![("TASK1/SYSMOD/CellData.sys".to_string(), data_module())];
    let context = program::Context::default().with_backup(&backup);
    let p = program::parse_in(&text, Dialect::Rapid, &context).unwrap();
    assert_eq!(p.targets.len(), 3);
    assert_eq!(p.targets[0].q_deg, [0.0, 0.0, 0.0, 0.0, 30.0, 0.0]);
    assert_eq!(p.targets[1].q_deg, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    let c = p.targets[2].cartesian.as_deref().unwrap();
    assert!((c.position_mm - nalgebra::Vector3::new(100.0, 0.0, 50.0)).norm() < 1e-12);
    // The tool and work object of the other module, named by the motion that uses them (its
    // line 5): a line of the other module would name another line of this one.
    assert!(matches!(&c.tool, Frame::Stated(5, f) if (f.translation.z - 0.25).abs() < 1e-12));
    assert!(matches!(&c.frame, Frame::Stated(5, f) if (f.translation.x - 1.0).abs() < 1e-12));
    // A tool of the other module refused: at the motion, naming the module and its line.
    let stationary = data_module().replace("tSpindle := [TRUE", "tSpindle := [FALSE");
    let held = vec![("TASK1/SYSMOD/CellData.sys".to_string(), stationary)];
    let p = program::parse_in(
        &text,
        Dialect::Rapid,
        &program::Context::default().with_backup(&held),
    );
    let tool = p.map(|p| p.targets[2].cartesian.as_deref().unwrap().tool.clone());
    match tool {
        Ok(Frame::Unknown(5, why)) => assert!(
            why.contains("robhold FALSE") && why.contains("(CellData.sys, line 4)"),
            "{why}"
        ),
        other => panic!("{other:?}"),
    }
    // The tool declared in a second module too: alike, one value; with another value, refused
    // at the motion naming both modules.
    for (tcp, refused) in [("[0,0,250]", false), ("[0,0,260]", true)] {
        let second = format!("MODULE Other\n  PERS tooldata tSpindle := [TRUE,[{tcp},[1,0,0,0]],[5,[0,0,100],[1,0,0,0],0,0,0]];\nENDMODULE\n");
        let two = [backup.clone(), vec![("Other.mod".to_string(), second)]].concat();
        let p = program::parse_in(
            &text,
            Dialect::Rapid,
            &program::Context::default().with_backup(&two),
        )
        .unwrap();
        match &p.targets[2].cartesian.as_deref().unwrap().tool {
            Frame::Unknown(5, why) if refused => assert!(
                why.contains("tspindle is declared in TASK1/SYSMOD/CellData.sys (line 4) and in Other.mod (line 2) with two values"),
                "{why}"
            ),
            Frame::Stated(5, _) if !refused => {}
            other => panic!("{tcp}: {other:?}"),
        }
    }
    // j1 compensated: declared again in the module, LOCAL instead of TASK, its comment kept;
    // home1 unchanged: not declared again.
    let joint = program::parse_in(
        &text.replace("    MoveL p10, v100, fine, tSpindle\\WObj:=wTable;\n", ""),
        Dialect::Rapid,
        &context,
    )
    .unwrap();
    let q = [joint.targets[0].q_deg, [1.0, 2.5, 3.0, 4.0, 5.0, 6.0]];
    let out = joint.write(&q).unwrap();
    assert_eq!(
        out,
        format!("MODULE Cut\n  LOCAL PERS jointtarget j1 := [[1.000000000,2.500000000,3.000000000,4.000000000,5.000000000,6.000000000],{EXT}]; ! taught\n  PROC main()\n    MoveAbsJ home1, v100, fine, tool0;\n    MoveAbsJ j1, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n")
    );
    let back = program::parse_in(&out, Dialect::Rapid, &context).unwrap();
    assert_eq!(back.targets[1].q_deg, q[1]);
}

/// A datum declared global in two modules of the task with two values is ambiguous (the
/// controller refuses the task, or holds one value of a `PERS`): refused at the motion naming
/// both; alike, or `LOCAL` in one module (seen by it alone), read. A module cut off, refused.
#[test]
fn a_datum_two_modules_declare_with_two_values_is_refused_naming_both() {
    let text = program_text();
    let backup = vec![("TASK1/SYSMOD/CellData.sys".to_string(), data_module())];
    // A target, speed or num declared global in two modules with two values is ambiguous:
    // refused at the motion naming both; alike, or LOCAL in the other module (seen by it
    // alone), read. The program's own global declaration counts as one of the two.
    let p10 = format!("robtarget p10 := [[100,0,50],[0,0,1,0],[0,0,0,0],{EXT}];");
    let moved = p10.replace("[100,0,50]", "[100,0,60]");
    for (second, own, refused) in [
        (format!("CONST {p10}"), "", None),
        (format!("CONST {moved}"), "", Some("TASK1/SYSMOD/CellData.sys (line 6)")),
        (format!("LOCAL CONST {moved}"), "", None),
        (String::new(), "  CONST robtarget p10 := [[100,0,50],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n", None),
        (String::new(), "  VAR robtarget p10 := [[100,0,60],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n", Some("this module (line 2)")),
        (String::new(), "  LOCAL VAR robtarget p10 := [[100,0,60],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n", None),
    ] {
        let other = format!("MODULE Other\n  {second}\nENDMODULE\n");
        let two = [backup.clone(), vec![("Other.mod".to_string(), other)]].concat();
        let text = text.replace("MODULE Cut\n", &format!("MODULE Cut\n{own}"));
        let p = program::parse_in(
            &text,
            Dialect::Rapid,
            &program::Context::default().with_backup(&two),
        );
        match (p, refused) {
            (Err(Error::Program { line, message }), Some(first)) => {
                assert_eq!(line, 5 + u64::from(!own.is_empty()), "{message}");
                let both = format!("p10 is declared in {first} and in Other.mod (line 2)");
                let both = match own.is_empty() {
                    true => both,
                    false => format!("p10 is declared in {first} and in TASK1/SYSMOD/CellData.sys (line 6)"),
                };
                assert!(message.contains(&both), "{message}");
            }
            (Ok(p), None) => {
                let c = p.targets[2].cartesian.as_deref().unwrap();
                let z = if own.contains("60]") { 60.0 } else { 50.0 };
                assert!((c.position_mm.z - z).abs() < 1e-12, "{second}{own}");
            }
            (other, _) => panic!("{second}{own}: {other:?}"),
        }
    }
    // A num another module sets as the task runs: the run's, refused naming that module.
    let offs = text.replace("MoveL p10,", "MoveL Offs(p10, 0, 0, dz),");
    let nums = |set: &str| {
        let other =
            format!("MODULE Other\n  PERS num dz := 5;\n  PROC s()\n{set}  ENDPROC\nENDMODULE\n");
        [backup.clone(), vec![("Other.mod".to_string(), other)]].concat()
    };
    let (quiet, set) = (nums(""), nums("    dz := 7;\n"));
    let context = |b| program::Context::default().with_backup(b);
    assert!(program::parse_in(&offs, Dialect::Rapid, &context(&quiet)).is_ok());
    match program::parse_in(&offs, Dialect::Rapid, &context(&set)) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 5, "{message}");
            assert!(
                message.contains("dz is set in Other.mod on its line 4"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    // A module of the task cut off (no ENDMODULE): refused naming the file.
    let cut = vec![(
        "TASK1/SYSMOD/CellData.sys".to_string(),
        data_module().replace("ENDMODULE\n", ""),
    )];
    match program::parse_in(
        &text,
        Dialect::Rapid,
        &program::Context::default().with_backup(&cut),
    ) {
        Err(Error::Parse {
            source_name,
            message,
        }) => {
            assert_eq!(source_name, "TASK1/SYSMOD/CellData.sys");
            assert!(message.contains("without ENDMODULE"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// A real RobotStudio task (`Tutorial-Simple_Module1.mod`, SOURCES.md): its tool `smc_gripper`
/// is declared in the task's other module, `CalibData.mod`; alone the tool is the controller's,
/// with that module as the backup it is the one stated there (its line 2).
#[test]
fn a_real_task_reads_its_tool_from_its_other_module() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/programs/rapid");
    let text = std::fs::read_to_string(format!("{dir}/Tutorial-Simple_Module1.mod")).unwrap();
    let calib = std::fs::read_to_string(format!("{dir}/Tutorial-Simple_CalibData.mod")).unwrap();
    let alone = program::parse(&text, Dialect::Rapid).unwrap();
    let c = alone.targets[1].cartesian.as_deref().unwrap();
    assert!(
        matches!(&c.tool, Frame::Unknown(_, why) if why.contains("smc_gripper") && why.contains("--backup")),
        "{:?}",
        c.tool
    );
    let backup = vec![("CalibData.mod".to_string(), calib)];
    let context = program::Context::default().with_backup(&backup);
    let p = program::parse_in(&text, Dialect::Rapid, &context).unwrap();
    assert_eq!(p.targets.len(), alone.targets.len());
    let c = p.targets[1].cartesian.as_deref().unwrap();
    // CalibData.mod's line 2, named by the motion (line 48) that uses it.
    assert!(matches!(&c.tool, Frame::Stated(48, _)), "{:?}", c.tool);
}

/// A target another module of the task assigns at run time (a welding cell's `pSafe := CRobT()`
/// in its data module): the motion that uses it is refused naming that module and its line,
/// never a line of the program's own.
#[test]
fn a_target_another_module_assigns_is_refused_naming_that_module() {
    let data = format!("MODULE CellData\n  PERS robtarget pSafe := [[500,0,400],[0,0,1,0],[0,0,0,0],{EXT}];\n  PROC Teach()\n    pSafe := CRobT();\n  ENDPROC\nENDMODULE\n");
    let text =
        "MODULE Cut\n  PROC main()\n    MoveL pSafe, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n";
    let backup = vec![("TASK1/PROGMOD/CellData.mod".to_string(), data)];
    let context = program::Context::default().with_backup(&backup);
    match program::parse_in(text, Dialect::Rapid, &context) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 3, "{message}");
            assert!(
                message.contains("assigned in CellData.mod on its line 4"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
