//! RAPID's `MoveC`, `Offs` and `RelTool` with constant arguments and a turned tool: read to the
//! poses the manual defines (checked against values worked by hand), resolved to the postures
//! the module was made from, written back so that the same calls land on the compensated poses,
//! and refused where a point's visits would need two values or an argument is the controller's.

use super::module::{data, in_wobj, postures, resolved, robtarget, rpy, setup, TOOL_RPY_DEG};
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::program::{self, speed::Speed, Dialect};
use stiffid::internal::machining::Program;
use stiffid::Error;

const EXT: &str = "[9E9,9E9,9E9,9E9,9E9,9E9]";

fn close(a: &Isometry3<f64>, b: &Isometry3<f64>) -> bool {
    (a.translation.vector - b.translation.vector).norm() < 1e-12
        && a.rotation.angle_to(&b.rotation) < 1e-12
}

#[test]
fn offs_reltool_and_movec_read_to_the_poses_the_manual_defines() {
    // p: 180 deg about y (q1..q4 = 0, 0, 1, 0): the tool's z down the frame's -z.
    let text = format!(
        "MODULE M\n  CONST robtarget p:=[[500,100,400],[0,0,1,0],[0,0,0,0],{EXT}];\n  PROC main()\n    MoveJ p, v100, fine, tool0;\n    MoveL Offs(p, 10, -20, 30), v100, fine, tool0;\n    MoveL RelTool (p, 0, 0, 100 \\Rz:=90), v100, fine, tool0;\n    MoveC Offs(p,0,50,0), RelTool(p,0,0,0\\Rx:=10), v200, z10, tool0;\n  ENDPROC\nENDMODULE\n"
    );
    let p = program::parse(&text, Dialect::Rapid).unwrap();
    let (s45, c5, s5) = (
        0.5f64.sqrt(),
        5f64.to_radians().cos(),
        5f64.to_radians().sin(),
    );
    let at = |x: f64, y: f64, z: f64, q: [f64; 4]| {
        Isometry3::from_parts(
            Translation3::new(x * 1e-3, y * 1e-3, z * 1e-3),
            UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3])),
        )
    };
    // By hand: Offs adds in the frame; RelTool moves along the tool's z (here the frame's -z)
    // and turns about the tool's axes: (0,0,1,0)(cos 45, 0, 0, sin 45) = (0, sin 45, cos 45, 0),
    // (0,0,1,0)(cos 5, sin 5, 0, 0) = (0, 0, cos 5, -sin 5).
    let want = [
        (4, at(500.0, 100.0, 400.0, [0.0, 0.0, 1.0, 0.0])),
        (5, at(510.0, 80.0, 430.0, [0.0, 0.0, 1.0, 0.0])),
        (6, at(500.0, 100.0, 300.0, [0.0, s45, s45, 0.0])),
        (7, at(500.0, 150.0, 400.0, [0.0, 0.0, 1.0, 0.0])),
        (7, at(500.0, 100.0, 400.0, [0.0, 0.0, c5, -s5])),
    ];
    assert_eq!(p.targets.len(), want.len());
    for (t, (line, pose)) in p.targets.iter().zip(&want) {
        let c = t.cartesian.as_deref().unwrap();
        assert_eq!(t.line, *line);
        assert!(
            close(&c.pose(), pose),
            "line {line}: {} against {pose}",
            c.pose()
        );
    }
    // MoveC's two points at its path speed.
    assert_eq!(p.targets[3].speed, Speed::Path(0.2));
    assert_eq!(p.targets[4].speed, Speed::Path(0.2));
}

/// A module whose motions visit, from postures near the start, a declared point, `Offs` and
/// `RelTool` of declared points, and a circle, in the work object with the turned tool.
fn module_of_postures() -> (stiffid::Setup, String, Vec<Vector6<f64>>) {
    let s = setup(TOOL_RPY_DEG);
    let qs = postures(&s, 5);
    let poses: Vec<Isometry3<f64>> = qs.iter().map(|q| in_wobj(&s, TOOL_RPY_DEG, q)).collect();
    let offs = Isometry3::from(Translation3::new(0.0, 0.0, 0.05));
    let rel = Isometry3::from_parts(
        Translation3::new(0.01, 0.0, -0.02),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 15f64.to_radians()),
    );
    // The declared points: where the calls must land, their displacements taken back.
    let decl = |name: &str, pose: &Isometry3<f64>, q: &Vector6<f64>| {
        format!("  CONST robtarget {name}:={};\n", robtarget(&s, pose, q))
    };
    let mut text = format!("MODULE Cell\n{}", data(&s, TOOL_RPY_DEG));
    text += &decl("pHome", &poses[0], &qs[0]);
    text += &decl("pAbove", &(offs.inverse() * poses[1]), &qs[1]);
    text += &decl("pTurned", &(poses[2] * rel.inverse()), &qs[2]);
    text += &decl("pCir", &poses[3], &qs[3]);
    text += &decl("pEnd", &poses[4], &qs[4]);
    text += "  PROC main()\n";
    text += "    MoveJ pHome, v500, fine, tSpindle\\WObj:=wobjPart;\n";
    text += "    MoveL Offs(pAbove,0,0,50), v100, z1, tSpindle\\WObj:=wobjPart;\n";
    text +=
        "    MoveL RelTool(pTurned, 10, 0, -20 \\Rz:=15), v100, z1, tSpindle\\WObj:=wobjPart;\n";
    text += "    MoveC pCir, pEnd, v50, fine, tSpindle\\WObj:=wobjPart;\n";
    text += "  ENDPROC\nENDMODULE\n";
    (s, text, qs)
}

/// An optional argument set apart by a comma (`tool, \\WObj:=wobj`, `v100, \\V:=120`, as RoboDK's
/// ABB post writes them) is read as without it: the work object is not dropped (the point would
/// be read in the world frame), the postures are those of the module without commas, the module
/// written back byte for byte; `tool, \\Corr` is refused as `tool\\Corr` is.
#[test]
fn optional_arguments_after_a_comma_are_read_as_without_it() {
    let (s, text, qs) = module_of_postures();
    let commas = text
        .replace("tSpindle\\WObj", "tSpindle, \\WObj")
        .replace("v100, z1,", "v100,\\V:=120, z1 , \\Z:=2,");
    assert_eq!(commas.matches(", \\WObj").count(), 4);
    let Program::Robot(p) = resolved(&s, &commas).unwrap() else {
        panic!("a robot program")
    };
    assert_eq!(p.targets.len(), qs.len());
    for (t, q) in p.targets.iter().zip(&qs) {
        let d = (Vector6::from(t.q_deg) - q.map(f64::to_degrees)).amax();
        assert!(d < 1e-6, "line {}: {d} deg", t.line);
    }
    let same: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    assert_eq!(p.write(&same).unwrap(), commas);
    let corrected = commas.replacen("wobjPart;", "wobjPart, \\Corr;", 2);
    let e = resolved(&s, &corrected).unwrap_err().to_string();
    assert!(e.contains("line ") && e.contains("\\Corr"), "{e}");
}

#[test]
fn a_module_with_offsets_and_a_turned_tool_resolves_to_its_postures_and_writes_back_where_they_land(
) {
    let (s, text, qs) = module_of_postures();
    let Program::Robot(p) = resolved(&s, &text).unwrap() else {
        panic!("a robot program")
    };
    let got: Vec<Vector6<f64>> = p.targets.iter().map(|t| Vector6::from(t.q_deg)).collect();
    assert_eq!(got.len(), qs.len());
    for (g, q) in got.iter().zip(&qs) {
        let q = q.map(f64::to_degrees);
        assert!((g - q).amax() < 1e-6, "{g} against {q}");
    }
    // Unchanged: byte for byte.
    let same: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    assert_eq!(p.write(&same).unwrap(), text);
    // Compensated: the calls are kept, the declared points move so that they land on the new
    // postures' poses.
    let moved: Vec<[f64; 6]> = same
        .iter()
        .enumerate()
        .map(|(k, q)| q.map(|v| v + 0.01 * (k + 1) as f64))
        .collect();
    let out = p.write(&moved).unwrap();
    for call in [
        "Offs(pAbove,0,0,50)",
        "RelTool(pTurned, 10, 0, -20 \\Rz:=15)",
        "MoveC pCir, pEnd",
    ] {
        assert!(out.contains(call), "{call}\n{out}");
    }
    let Program::Robot(again) = resolved(&s, &out).unwrap() else {
        panic!("a robot program")
    };
    for (t, q) in again.targets.iter().zip(&moved) {
        let d = (Vector6::from(t.q_deg) - Vector6::from(*q)).amax();
        assert!(d < 1e-6, "line {}: {d} deg", t.line);
    }
    // The poses read back are the forward kinematics of the compensated postures.
    for (t, q) in again.targets.iter().zip(&moved) {
        let want = in_wobj(&s, TOOL_RPY_DEG, &Vector6::from(*q).map(f64::to_radians));
        let c = t.cartesian.as_deref().unwrap();
        let d = (c.pose().translation.vector - want.translation.vector).norm();
        assert!(d < 1e-9, "line {}: {d} m", t.line);
    }
}

/// `pAbove` visited directly and by `Offs(pAbove, ..)`: the two visits need two values once
/// compensated, so the second is a copy declared on the line after `pAbove`'s, `pAbove_2`, which
/// the `Offs` names; read back, each motion goes to its compensated posture.
#[test]
fn a_point_visited_directly_and_by_offs_becomes_two_points_when_the_visits_need_two_values() {
    let (s, text, _) = module_of_postures();
    let text = text.replacen(
        "    MoveJ pHome,",
        "    MoveJ pAbove, v500, fine, tSpindle\\WObj:=wobjPart;\n    MoveJ pHome,",
        1,
    );
    let Program::Robot(p) = resolved(&s, &text).unwrap() else {
        panic!("a robot program")
    };
    let moved: Vec<[f64; 6]> = (p.targets.iter().enumerate())
        .map(|(k, t)| t.q_deg.map(|v| v + 0.01 * (k + 1) as f64))
        .collect();
    let out = p.write(&moved).unwrap();
    let lines: Vec<&str> = out.lines().collect();
    assert!(
        lines[4]
            .trim_start()
            .starts_with("CONST robtarget pAbove:="),
        "{out}"
    );
    assert!(
        lines[5]
            .trim_start()
            .starts_with("CONST robtarget pAbove_2:="),
        "{out}"
    );
    assert!(out.contains("MoveL Offs(pAbove_2,0,0,50)"), "{out}");
    assert!(out.contains("    MoveJ pAbove, v500"), "{out}");
    let Program::Robot(again) = resolved(&s, &out).unwrap() else {
        panic!("a robot program")
    };
    for (t, q) in again.targets.iter().zip(&moved) {
        let d = (Vector6::from(t.q_deg) - Vector6::from(*q)).amax();
        assert!(d < 1e-6, "line {}: {d} deg", t.line);
    }
}

#[test]
fn tools_work_objects_and_arguments_the_module_cannot_state_are_refused_naming_the_line() {
    let (s, text, _) = module_of_postures();
    let wobj_line = 3;
    let cases = [
        // A tool turned otherwise than the setup's (its quaternion the flange's).
        (setup([0.0, 0.0, 0.0]), text.clone(), 2, "not the setup's"),
        (
            s.clone(),
            text.replacen("[FALSE,TRUE,\"\"", "[TRUE,TRUE,\"\"", 1),
            wobj_line,
            "robhold TRUE",
        ),
        (
            s.clone(),
            text.replacen("[FALSE,TRUE,\"\"", "[FALSE,FALSE,\"STN1\"", 1),
            wobj_line,
            "ufprog FALSE: a user frame the mechanical unit \"STN1\"",
        ),
        (
            s.clone(),
            text.replacen("Offs(pAbove,0,0,50)", "Offs(pAbove,0,0,dz)", 1),
            11,
            "z = 'dz' is not a number",
        ),
        (
            s.clone(),
            text.replacen("\\Rz:=15", "\\Rz:=15\\Lin", 1),
            12,
            "\\Lin: not a switch",
        ),
        (
            s.clone(),
            text.replacen("Offs(pAbove,0,0,50)", "Offs(pAbove,0,50)", 1),
            11,
            "expected 4 arguments",
        ),
        (
            s.clone(),
            text.replacen("Offs(pAbove,0,0,50)", "CRobT()", 1),
            11,
            "computed on the controller",
        ),
        (
            s.clone(),
            text.replacen("MoveC pCir, pEnd", "MoveC pCir", 1),
            13,
            "a circle point, an end point",
        ),
        (
            s.clone(),
            text.replacen("MoveC pCir, pEnd, v50", "MoveC pCir, pEnd, v50 \\T:=2", 1),
            0,
            "",
        ),
    ];
    for (setup, text, line, words) in cases {
        let result = resolved(&setup, &text);
        if line == 0 {
            // A circle in a given time: read, its speed left to the controller.
            let Program::Robot(p) = result.unwrap() else {
                panic!()
            };
            assert!(
                matches!(&p.targets[4].speed, Speed::Unread(why) if why.contains("whole circle"))
            );
            continue;
        }
        match result {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(words), "{message}");
            }
            other => panic!("{words}: {other:?}"),
        }
    }
    assert_eq!(rpy([0.0, 0.0, 0.0]), UnitQuaternion::identity());
}

#[test]
fn the_setups_tool_turn_is_roll_pitch_yaw_about_fixed_axes_within_its_limits() {
    let s = setup(TOOL_RPY_DEG);
    assert!(s.tool().rotation.angle_to(&rpy(TOOL_RPY_DEG)) < 1e-12);
    let message = match stiffid::internal::setup::parse(
        &include_str!("../../../../../../../examples/milling/fanuc-milling.toml").replacen(
            "tcp_mm = [6.9, 245.3, 319.3]",
            "tcp_mm = [6.9, 245.3, 319.3]\ntcp_rpy_deg = [0, 20000, 0]",
            1,
        ),
        "fanuc-milling.toml",
        |n, _| stiffid::internal::robot::presets::get(n),
    ) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a turn of 20000 deg read"),
    };
    assert!(message.contains("tool.tcp_rpy_deg"), "{message}");
}

/// `ConfL \Off` (RoboDK's ABB post writes it in every module): a `MoveL` keeps the arm's
/// configuration from the posture before it whatever its `confdata` says, as the controller
/// does with configuration monitoring off; with `ConfL \On` the `confdata` chooses.
#[test]
fn conf_l_off_keeps_the_configuration_of_the_posture_before() {
    let s = setup(TOOL_RPY_DEG);
    let qs = postures(&s, 2);
    let poses: Vec<Isometry3<f64>> = qs.iter().map(|q| in_wobj(&s, TOOL_RPY_DEG, q)).collect();
    // The second pose with the confdata of the wrist flipped (the same pose).
    let mut flipped = qs[1];
    flipped[3] += std::f64::consts::PI;
    flipped[4] = -flipped[4];
    flipped[5] += std::f64::consts::PI;
    let module = |conf: &str| {
        let mut text = format!("MODULE Cell\n{}", data(&s, TOOL_RPY_DEG));
        text += &format!(
            "  CONST robtarget p0:={};\n",
            robtarget(&s, &poses[0], &qs[0])
        );
        text += &format!(
            "  CONST robtarget p1:={};\n",
            robtarget(&s, &poses[1], &flipped)
        );
        text += &format!("  PROC main()\n    ConfL {conf};\n");
        text += "    MoveJ p0, v500, fine, tSpindle\\WObj:=wobjPart;\n";
        text += "    MoveL p1, v100, z1, tSpindle\\WObj:=wobjPart;\n  ENDPROC\nENDMODULE\n";
        text
    };
    let Program::Robot(off) = resolved(&s, &module("\\Off")).unwrap() else {
        panic!("a robot program")
    };
    let d = (Vector6::from(off.targets[1].q_deg) - qs[1].map(f64::to_degrees)).amax();
    assert!(d < 1e-6, "{d} deg");
    let on = resolved(&s, &module("\\On"));
    let kept = on.as_ref().ok().and_then(|p| match p {
        Program::Robot(p) => {
            Some((Vector6::from(p.targets[1].q_deg) - qs[1].map(f64::to_degrees)).amax())
        }
        _ => None,
    });
    assert!(kept.is_none_or(|d| d > 1.0), "{kept:?}");
}

/// The line (1-based) of `text` that holds `needle` first.
fn line_of(text: &str, needle: &str) -> u64 {
    text.lines().position(|l| l.contains(needle)).unwrap() as u64 + 1
}

/// A point assigned whole (`pTmp := Offs(pAbove, ..);`, `pRel := pTurned;`) is at its motion the
/// value its assignment gives: the same postures as the module that names the `Offs` at the
/// motion, written back where the assignment names its point (a second value of `pAbove`
/// declared as `pAbove_2` and named there); where the paths to the motion disagree, or the value
/// is the run's, refused naming the lines.
#[test]
fn a_point_assigned_whole_is_read_where_its_assignment_names_it_and_refused_where_paths_disagree() {
    let (s, text, _) = module_of_postures();
    let motion = "    MoveL Offs(pAbove,0,0,50), v100, z1, tSpindle\\WObj:=wobjPart;\n";
    let first = "    MoveJ pAbove, v500, fine, tSpindle\\WObj:=wobjPart;\n";
    let direct = text.replacen(motion, &format!("{first}{motion}"), 1);
    let assigned = direct
        .replacen("MODULE Cell\n", "MODULE Cell\n  VAR robtarget pTmp;\n  PERS robtarget pRel:=[[0,0,0],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n", 1)
        .replacen(motion, "    pTmp := Offs(pAbove,0,0,50);\n    MoveL pTmp, v100, z1, tSpindle\\WObj:=wobjPart;\n", 1)
        .replacen("RelTool(pTurned,", "RelTool(pRel,", 1)
        .replacen("  PROC main()\n", "  PROC main()\n    pRel := pTurned;\n", 1);
    let q = |t: &str| match resolved(&s, t).unwrap() {
        Program::Robot(p) => p,
        _ => panic!("a robot program"),
    };
    let (a, b) = (q(&direct), q(&assigned));
    assert_eq!(a.targets.len(), b.targets.len());
    for (x, y) in a.targets.iter().zip(&b.targets) {
        let d = (Vector6::from(x.q_deg) - Vector6::from(y.q_deg)).amax();
        assert!(d < 1e-9, "line {}: {d} deg", y.line);
    }
    let moved: Vec<[f64; 6]> = (b.targets.iter().enumerate())
        .map(|(k, t)| t.q_deg.map(|v| v + 0.01 * (k + 1) as f64))
        .collect();
    let out = b.write(&moved).unwrap();
    assert!(
        out.contains("    pTmp := Offs(pAbove_2,0,0,50);\n"),
        "{out}"
    );
    assert!(
        out.contains("    pRel := pTurned;\n") && out.contains("CONST robtarget pAbove_2:="),
        "{out}"
    );
    for (t, m) in q(&out).targets.iter().zip(&moved) {
        let d = (Vector6::from(t.q_deg) - Vector6::from(*m)).amax();
        assert!(d < 1e-6, "line {}: {d} deg", t.line);
    }
    let at = "    MoveL pTmp,";
    let set = "    pTmp := Offs(pAbove,0,0,50);\n";
    for (from, to, said) in [
        (set, "    IF di1 = 1 THEN\n      pTmp := Offs(pAbove,0,0,50);\n    ENDIF\n", "assigned differently on the paths through IF"),
        (at, "    pTmp.trans.z := pTmp.trans.z + 10;\n    MoveL pTmp,", "pTmp is assigned on line"),
        (at, "    IF di1 = 1 pTmp := pHome;\n    MoveL pTmp,", "pTmp is assigned on line"),
        (set, "    Prep;\n", "the call of prep on line"),
        (set, "    pTmp := CRobT();\n", "a value stiffid does not read"),
        (set, "    pTmp := pHome;\n    WHILE di1 = 1 DO\n      MoveL pTmp, v100, z1, tSpindle;\n      pTmp := Offs(pAbove,0,0,50);\n    ENDWHILE\n", "inside the loop"),
    ] {
        // A routine that sets the point, called before the motion.
        let prep = "  ENDPROC\n  PROC Prep()\n    pTmp := Offs(pAbove,0,0,50);\n  ENDPROC\nENDMODULE";
        let t = assigned.replacen(from, to, 1).replacen("  ENDPROC\nENDMODULE", prep, 1);
        let needle = if said == "inside the loop" { "      MoveL pTmp" } else { at };
        match resolved(&s, &t) {
            Err(Error::Program { line, message }) => {
                assert_eq!(line, line_of(&t, needle), "{said}: {message}");
                assert!(message.contains(said), "{said}: {message}");
            }
            other => panic!("{said}: {:?}", other.map(|_| ())),
        }
    }
}
