//! A RAPID module as a controller stores it, built for the tests from postures of the FANUC
//! milling example: `robtarget`s declared in the module in a `wobjdata` (`uframe` then
//! `oframe`) for a `tooldata` whose frame is turned on the flange, the setup's `[tool]` turned
//! the same (`tcp_rpy_deg`).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector6};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::program::cartesian::flags::ConfigurationData;
use stiffid::internal::machining::program::cartesian::Frame;
use stiffid::internal::machining::program::rapid::ConfData;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::{ik, presets};
use stiffid::Setup;

const SETUP: &str = include_str!("../../../../../../../examples/milling/fanuc-milling.toml");

/// The tool's turn on the flange, roll, pitch, yaw (deg): the spindle's axis along the
/// flange's x.
pub(super) const TOOL_RPY_DEG: [f64; 3] = [0.0, -90.0, 30.0];

/// The example's setup with its tool turned by `rpy_deg` (`[tool] tcp_rpy_deg`).
pub(super) fn setup(rpy_deg: [f64; 3]) -> Setup {
    let line = format!(
        "tcp_mm = [6.9, 245.3, 319.3]\ntcp_rpy_deg = [{}, {}, {}]",
        rpy_deg[0], rpy_deg[1], rpy_deg[2]
    );
    let text = SETUP.replacen("tcp_mm = [6.9, 245.3, 319.3]", &line, 1);
    assert_ne!(text, SETUP);
    stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

/// The turn of roll, pitch, yaw (deg) about the fixed x, y, z axes: `Rz(yaw) Ry(pitch) Rx(roll)`.
pub(super) fn rpy(rpy_deg: [f64; 3]) -> UnitQuaternion<f64> {
    let [r, p, y] = rpy_deg.map(f64::to_radians);
    UnitQuaternion::from_axis_angle(&nalgebra::Vector3::z_axis(), y)
        * UnitQuaternion::from_axis_angle(&nalgebra::Vector3::y_axis(), p)
        * UnitQuaternion::from_axis_angle(&nalgebra::Vector3::x_axis(), r)
}

/// The user frame and object frame of the module's work object, world frame, m.
pub(super) fn wobj() -> (Isometry3<f64>, Isometry3<f64>) {
    let u = Isometry3::from_parts(
        Translation3::new(1.2, -0.6, 0.35),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 25f64.to_radians()),
    );
    let o = Isometry3::from_parts(
        Translation3::new(0.04, 0.02, 0.0),
        UnitQuaternion::from_euler_angles(0.0, 0.0, -10f64.to_radians()),
    );
    (u, o)
}

/// A RAPID pose `[[x,y,z],[q1,q2,q3,q4]]` of a frame (m to mm), 9 decimals.
pub(super) fn pose(f: &Isometry3<f64>) -> String {
    let p = f.translation.vector * 1e3;
    let q = f.rotation.quaternion();
    let s = if q.w < 0.0 { -1.0 } else { 1.0 };
    format!(
        "[[{:.9},{:.9},{:.9}],[{:.9},{:.9},{:.9},{:.9}]]",
        p.x,
        p.y,
        p.z,
        s * q.w,
        s * q.i,
        s * q.j,
        s * q.k
    )
}

/// The `tooldata` and `wobjdata` declarations of the module for `setup`'s tool turned by
/// `tool_rpy_deg`.
pub(super) fn data(setup: &Setup, tool_rpy_deg: [f64; 3]) -> String {
    let tool = Isometry3::from_parts(Translation3::from(setup.tool().tcp), rpy(tool_rpy_deg));
    let (u, o) = wobj();
    format!(
        "  PERS tooldata tSpindle:=[TRUE,{},[12,[0,0,150],[1,0,0,0],0,0,0]];\n  TASK PERS wobjdata wobjPart:=[FALSE,TRUE,\"\",{},{}];\n",
        pose(&tool),
        pose(&u),
        pose(&o)
    )
}

/// Postures near the setup's start: `n` of them, each 2 deg further on axis 1 and 1.5 deg on
/// axis 3.
pub(super) fn postures(setup: &Setup, n: usize) -> Vec<Vector6<f64>> {
    let q0 = Options::for_setup(setup).q0;
    (0..n)
        .map(|k| {
            let mut q = q0;
            q[0] += (2.0 * k as f64).to_radians();
            q[2] += (1.5 * k as f64).to_radians();
            q
        })
        .collect()
}

/// The tool's pose at `q` in the work object (m): the flange's axes turned by the tool's
/// `tool_rpy_deg`.
pub(super) fn in_wobj(setup: &Setup, tool_rpy_deg: [f64; 3], q: &Vector6<f64>) -> Isometry3<f64> {
    let robot = setup.controller_robot().unwrap();
    let mut at = ik::tool_pose(&robot.frames(q), &setup.tool().tcp);
    at.rotation *= rpy(tool_rpy_deg);
    let (u, o) = wobj();
    (setup.program_world() * u * o).inverse() * at
}

/// A `robtarget` literal of `pose` (m) with the `confdata` of `q`.
pub(super) fn robtarget(setup: &Setup, pose_m: &Isometry3<f64>, q: &Vector6<f64>) -> String {
    let ConfData([a, b, c, d]) =
        ConfData::of(&Configuration::of(setup.controller_robot().unwrap(), q));
    let p = pose(pose_m);
    format!(
        "[{},[{a},{b},{c},{d}],[9E9,9E9,9E9,9E9,9E9,9E9]]",
        &p[1..p.len() - 1]
    )
}

/// The program read and resolved on `setup` (the axis angles of its Cartesian targets).
pub(super) fn resolved(setup: &Setup, text: &str) -> stiffid::Result<Program> {
    let p = machining::read(
        text,
        Language::Robot(stiffid::internal::machining::program::Dialect::Rapid),
        1e-4,
    )?;
    Ok(machining::resolve(&p, setup, None, &Options::for_setup(setup))?.into_owned())
}

/// A `robtarget` literal nested a million brackets deep, which the reader, recursing into each
/// bracket, overflowed the stack on (the process aborted): refused naming its line and the
/// nesting the data types have.
#[test]
fn a_literal_nested_deeper_than_any_data_type_is_refused_naming_its_line() {
    let deep = format!("{}1{}", "[".repeat(1_000_000), "]".repeat(1_000_000));
    let text = format!("MODULE M\n  CONST robtarget p1 := {deep};\n  PROC main()\n    MoveL p1, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n");
    match stiffid::internal::machining::program::parse(
        &text,
        stiffid::internal::machining::program::Dialect::Rapid,
    ) {
        Err(stiffid::Error::Program { line, message }) => {
            assert_eq!(line, 2, "{message}");
            assert!(
                message.contains("robtarget")
                    && message.contains("not a literal (balanced brackets, nested at most 8 deep)"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// Data a motion reads, refused naming its line: a frame's position beyond 100 m (1e308 mm made
/// the pose "inf mm away" from reach), a quaternion component beyond 1 (its norm was "inf"), a
/// name declared twice (the last declaration was read).
#[test]
fn data_beyond_the_limits_or_declared_twice_is_refused_naming_its_line() {
    let target = "[[500,0,400],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]";
    let module = |data: &str, target: &str| {
        format!("MODULE M\n{data}\n  PROC main()\n    MoveL {target}, v100, fine, tool0\\WObj:=wp;\n  ENDPROC\nENDMODULE\n")
    };
    let wobj = |xyz: &str| {
        format!("  PERS wobjdata wp := [FALSE,TRUE,\"\",[[{xyz}],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];")
    };
    let parse = |text: &str| {
        stiffid::internal::machining::program::parse(
            text,
            stiffid::internal::machining::program::Dialect::Rapid,
        )
    };
    // The work object is refused by the motion in it, when its frame is resolved.
    let p = parse(&module(&wobj("1e308,0,550"), target)).unwrap();
    match &p.targets[0].cartesian.as_ref().unwrap().frame {
        Frame::Unknown(2, why) => assert!(
            why.contains("x 1e308: outside -100000 to 100000 mm"),
            "{why}"
        ),
        other => panic!("{other:?}"),
    }
    let twice = format!(
        "{}\n  CONST robtarget p1 := {target};\n  CONST robtarget P1 := {target};",
        wobj("0,0,0")
    );
    let cases = [
        (
            module(
                &wobj("0,0,0"),
                &target.replace("[0,0,1,0]", "[0,0,1e308,0]"),
            ),
            4,
            "the orientation's quaternion has a component 1e308: expected a unit quaternion",
        ),
        (
            module(&twice, "p1"),
            6,
            "robtarget p1 is declared twice, on line 3 and on line 4",
        ),
        // An optional argument given twice (the first was read), a routine never closed (the
        // next routine's motions were read as its own).
        (
            module(&wobj("0,0,0"), target).replace("\\WObj:=wp;", "\\WObj:=wp\\WObj:=wobj0;"),
            4,
            "\\wobj given twice after the tool",
        ),
        (
            module(&wobj("0,0,0"), target)
                .replace("fine, tool0\\WObj:=wp;", "fine \\WObj:=wp, tool0;"),
            4,
            "\\wobj before the tool",
        ),
        (
            module(&wobj("0,0,0"), target).replace("  ENDPROC\n", "    IF (a Pick;\n  ENDPROC\n"),
            5,
            "IF: no instruction after its condition",
        ),
        (
            module(&wobj("0,0,0"), target).replace("  ENDPROC\n", "  PROC second()\n"),
            3,
            "the routine main has no ENDPROC before line 5",
        ),
    ];
    for (text, line, needle) in cases {
        match parse(&text) {
            Err(stiffid::Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}\n{text}");
                assert!(message.contains(needle), "{message}");
            }
            other => panic!("{needle}: {other:?}\n{text}"),
        }
    }
}
