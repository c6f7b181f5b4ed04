//! Every frame in a generated program is the controller's: with a pedestal (`[robot_base]`) and
//! an adapter plate (`[robot_flange]`) in the setup, the controller's own robot file (the preset,
//! neither offset in it) run at the compensated axis angles, with the tool the program states,
//! puts the tool on the target the program states in its base, work object or user frame 0,
//! for KRL, RAPID and LS. The controller is simulated here from the program's text alone.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector6};
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::generate::{Settings, Targets};
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::presets;

const PEDESTAL: &str =
    "[robot_base]\nxyz_mm = [250.0, -120.0, 500.0]\nrpy_deg = [0.0, 0.0, 20.0]\n";
const ADAPTER: &str = "[robot_flange]\nxyz_mm = [0.0, 0.0, 100.0]\nrpy_deg = [0.0, 0.0, 30.0]\n";

/// The FANUC milling cell on a pedestal with an adapter plate, its part where the robot reaches
/// it as in the example (the part frame moved with the pedestal).
fn mounted_setup() -> stiffid::Setup {
    mounted_setup_with("")
}

/// The tool's turn on the flange of [`turned_setup`] (roll, pitch, yaw, deg): `Rz(yaw) Ry(pitch)
/// Rx(roll)`.
const TOOL_TURN_DEG: [f64; 3] = [10.0, -25.0, 40.0];

/// [`mounted_setup`] with its tool frame turned on the flange by [`TOOL_TURN_DEG`].
fn turned_setup() -> stiffid::Setup {
    let [r, p, y] = TOOL_TURN_DEG;
    mounted_setup_with(&format!("tcp_rpy_deg = [{r}, {p}, {y}]\n"))
}

/// The turn of [`TOOL_TURN_DEG`], from its three axes.
fn tool_turn() -> UnitQuaternion<f64> {
    let [r, p, y] = TOOL_TURN_DEG.map(f64::to_radians);
    UnitQuaternion::from_axis_angle(&nalgebra::Vector3::z_axis(), y)
        * UnitQuaternion::from_axis_angle(&nalgebra::Vector3::y_axis(), p)
        * UnitQuaternion::from_axis_angle(&nalgebra::Vector3::x_axis(), r)
}

/// [`mounted_setup`] with `tool` (lines) added to its `[tool]`.
fn mounted_setup_with(tool: &str) -> stiffid::Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let pedestal = Isometry3::from_parts(
        Translation3::new(0.25, -0.12, 0.5),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 20f64.to_radians()),
    );
    let part = pedestal * Isometry3::translation(1.3, -0.7, 0.3);
    let (p, (r, pi, y)) = (part.translation.vector * 1e3, part.rotation.euler_angles());
    let workpiece = format!(
        "base_from_part = {{ xyz_mm = [{}, {}, {}], rpy_deg = [{}, {}, {}] }}",
        p.x,
        p.y,
        p.z,
        r.to_degrees(),
        pi.to_degrees(),
        y.to_degrees()
    );
    let text = text
        .replace(
            "base_from_part = { xyz_mm = [1300, -700, 400], rpy_deg = [0, 0, 0] }",
            &workpiece,
        )
        .replacen(
            "\n[tool]",
            &format!("\n{PEDESTAL}\n{ADAPTER}\n[tool]\n{tool}"),
            1,
        )
        .replacen(
            "\n[loading]",
            "mass_kg = 12.0\ncentre_of_mass_mm = [10.0, 0.0, 150.0]\n\n[loading]",
            1,
        );
    stiffid::internal::setup::parse(&text, "mounted.toml", |name, _| presets::get(name)).unwrap()
}

/// The milling example's pocket with each arc a straight move to its end: every point of the
/// path a target of the program (an arc would be a circular move through two of its points).
fn straight() -> String {
    (include_str!("../../../../examples/milling/pocket.nc").lines())
        .map(|l| match l.strip_prefix("G3 ").or(l.strip_prefix("G2 ")) {
            Some(words) => {
                let kept: Vec<&str> = (words.split_whitespace())
                    .filter(|w| !w.starts_with(['I', 'J', 'K', 'R']))
                    .collect();
                format!("G1 {}\n", kept.join(" "))
            }
            None => format!("{l}\n"),
        })
        .collect()
}

fn program(setup: &stiffid::Setup, dialect: Dialect) -> (String, Vec<Compensated>) {
    let (compliance, process) = (
        crate::common::milling_compliance(setup),
        crate::common::milling_process(),
    );
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "pocket.nc".into(),
            text: &straight(),
            data: None,
            language: Language::GCode,
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-4,
            output: Language::Robot(dialect),
            out_name: format!("pocket.{}", Language::Robot(dialect).extension()),
            settings: Settings {
                targets: Targets::Cartesian,
                ..Settings::default()
            },
        },
        options: Options::for_setup(setup),
    };
    let mut results = Vec::new();
    let report = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    (
        crate::common::program_text(report.report.program.unwrap()),
        results,
    )
}

/// The numbers of a `name value` or `name = value unit` list after `prefix` on a line.
fn numbers(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .filter_map(|t| t.parse::<f64>().ok())
        .collect()
}

/// A KRL frame `{X .., Y .., Z .., A .., B .., C ..}` (mm, deg; `R = Rz(A) Ry(B) Rx(C)`).
fn krl_frame(v: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3),
        UnitQuaternion::from_euler_angles(v[5].to_radians(), v[4].to_radians(), v[3].to_radians()),
    )
}

/// A RAPID pose `[[x,y,z],[q1,q2,q3,q4]]` (mm).
fn rapid_pose(v: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3),
        UnitQuaternion::from_quaternion(Quaternion::new(v[3], v[4], v[5], v[6])),
    )
}

/// What the controller reads from a program: its tool (from its flange) and each target as a
/// tool pose in its world.
fn controller_view(dialect: Dialect, text: &str) -> (Isometry3<f64>, Vec<Isometry3<f64>>) {
    let line = |prefix: &str| {
        text.lines()
            .find_map(|l| l.find(prefix).map(|i| &l[i + prefix.len()..]))
            .unwrap_or_else(|| panic!("{prefix}: {text}"))
    };
    match dialect {
        Dialect::Krl => {
            let tool = krl_frame(&numbers(line("$TOOL =")));
            let base = krl_frame(&numbers(line("$BASE =")));
            let targets = text
                .lines()
                .filter_map(|l| l.split_once("{E6POS:"))
                .map(|(_, rest)| base * krl_frame(&numbers(rest.split('S').next().unwrap())))
                .collect();
            (tool, targets)
        }
        Dialect::Rapid => {
            let tooldata = numbers(line("PERS tooldata tspindle := [TRUE,"));
            // The centre of mass from the controller's flange: the adapter's turn and stand-off.
            let turn = 30f64.to_radians();
            let cog = [10.0 * turn.cos(), 10.0 * turn.sin(), 250.0];
            for (k, want) in cog.iter().enumerate() {
                assert!((tooldata[8 + k] - want).abs() < 1e-6, "{tooldata:?}");
            }
            let tool = rapid_pose(&tooldata[..7]);
            let wobj = rapid_pose(&numbers(line("PERS wobjdata wpart := [FALSE,TRUE,\"\","))[..7]);
            let targets = text
                .lines()
                .filter_map(|l| {
                    l.trim()
                        .strip_prefix("MoveL ")
                        .or(l.trim().strip_prefix("MoveJ "))
                })
                .map(|rest| wobj * rapid_pose(&numbers(rest)[..7]))
                .collect();
            (tool, targets)
        }
        Dialect::FanucLs => {
            let ut = |name: &str| numbers(line(&format!("! UT1 {name} =")))[0];
            let tool = krl_frame(&[ut("X"), ut("Y"), ut("Z"), ut("R"), ut("P"), ut("W")]);
            let lines: Vec<&str> = text.lines().collect();
            let targets = (0..lines.len())
                .filter(|&i| lines[i].trim_start().starts_with("X ="))
                .map(|i| {
                    let xyz = numbers(lines[i]);
                    let wpr = numbers(lines[i + 1]);
                    // W about x, P about y, R about z: R = Rz(R) Ry(P) Rx(W).
                    krl_frame(&[xyz[0], xyz[1], xyz[2], wpr[2], wpr[1], wpr[0]])
                })
                .collect();
            (tool, targets)
        }
        Dialect::Inform => unreachable!("INFORM jobs are not generated"),
    }
}

#[test]
fn programs_state_the_tool_and_positions_in_the_controllers_frames() {
    // The controller runs the robot file as it is: no pedestal, no adapter.
    let controller = presets::get("fanuc-r2000ic-165f").unwrap();
    assert_eq!(controller.controller_world().translation.z, 0.670);
    let adapter = UnitQuaternion::from_axis_angle(&nalgebra::Vector3::z_axis(), 30f64.to_radians());
    for (setup, turn) in [
        (mounted_setup(), UnitQuaternion::identity()),
        (turned_setup(), tool_turn()),
    ] {
        assert!(
            (controller.base().translation.vector - setup.robot().base().translation.vector).norm()
                > 0.4
        );
        for dialect in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
            let (text, results) = program(&setup, dialect);
            let (tool, targets) = controller_view(dialect, &text);
            // The adapter is in the tool: its 100 mm stand-off and 30 deg turn, then the tool's own
            // turn ([tool] tcp_rpy_deg).
            assert!(
                (tool.translation.vector.z - (0.1 + setup.tool().tcp.z)).abs() < 1e-6,
                "{dialect:?}: {tool}"
            );
            assert!(
                tool.rotation.angle_to(&(adapter * turn)) < 1e-6,
                "{dialect:?}"
            );
            assert_eq!(targets.len(), results.len(), "{dialect:?}");
            let mut worst: (f64, f64) = (0.0, 0.0);
            for (target, r) in targets.iter().zip(&results) {
                let q: Vector6<f64> = r.q_compensated;
                // In the controller's world (FANUC's: 670 mm above the robot file's base).
                let reached =
                    (controller.controller_world()).inv_mul(&controller.frames(&q).flange) * tool;
                worst.0 = worst
                    .0
                    .max((reached.translation.vector - target.translation.vector).norm());
                worst.1 = worst.1.max(reached.rotation.angle_to(&target.rotation));
            }
            assert!(worst.0 < 2e-8 && worst.1 < 1e-7, "{dialect:?}: {worst:?}");
        }
    }
}

/// A compensated G-code path written as a Cartesian program reads back to the compensated
/// postures: each target's pose and configuration data as written, and the controller's inverse
/// kinematics in the configuration named giving the compensated axis angles again, with the
/// pedestal, the adapter plate, the work object and the tool of the mounted cell.
#[test]
fn written_cartesian_programs_read_back_to_their_targets() {
    use stiffid::internal::machining::program::cartesian::{Cartesian, Flags, Frame};
    use stiffid::internal::robot::configuration::Configuration;
    for (setup, turn) in [
        (mounted_setup(), UnitQuaternion::identity()),
        (turned_setup(), tool_turn()),
    ] {
        let robot = setup.controller_robot().unwrap();
        let tcp = setup.tool().tcp;
        let world = setup.program_world();
        for dialect in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
            let (text, results) = program(&setup, dialect);
            let read =
                stiffid::internal::machining::read(&text, Language::Robot(dialect), 1e-4).unwrap();
            let options = Options::for_setup(&setup);
            let resolved =
                stiffid::internal::machining::resolve(&read, &setup, None, &options).unwrap();
            let stiffid::internal::machining::Program::Robot(p) = resolved.as_ref() else {
                panic!("a robot program")
            };
            assert_eq!(p.targets.len(), results.len(), "{dialect:?}");
            let (mut pose_error, mut angle_error, mut q_error) = (0f64, 0f64, 0f64);
            for (t, r) in p.targets.iter().zip(&results) {
                let c: &Cartesian = t.cartesian.as_deref().expect("a Cartesian target");
                let frame = match &c.frame {
                    Frame::World => world,
                    Frame::Stated(_, f) => world * f,
                    other => panic!("{dialect:?}: {other:?}"),
                };
                let stated = frame * c.pose();
                // The tool's axes: the flange's turned by the tool's turn.
                let mut written =
                    stiffid::internal::robot::ik::tool_pose(&robot.frames(&r.q_compensated), &tcp);
                written.rotation *= turn;
                pose_error = pose_error
                    .max((stated.translation.vector - written.translation.vector).norm() * 1e3);
                angle_error =
                    angle_error.max(stated.rotation.angle_to(&written.rotation).to_degrees());
                let arm = Configuration::of(robot, &r.q_compensated);
                assert_eq!(c.flags, Some(Flags::of(dialect, &arm)), "{dialect:?}");
                let q = Vector6::from(t.q_deg);
                q_error = q_error.max((q - r.q_compensated.map(f64::to_degrees)).amax());
            }
            // RAPID's quaternion is written to 1e-9: its rotation to about 1e-7 deg.
            let angle = if dialect == Dialect::Rapid {
                2e-7
            } else {
                1e-9
            };
            assert!(
                pose_error <= 1e-9 && angle_error <= angle,
                "{dialect:?}: {pose_error} mm {angle_error} deg"
            );
            // The turned tool's postures take the written decimals (RAPID's quaternion to 1e-9)
            // through a less well conditioned wrist: up to 4 times the straight tool's.
            let scale = if turn == UnitQuaternion::identity() {
                1.0
            } else {
                4.0
            };
            let read_back = scale * crate::cartesian_programs::read_back(dialect);
            assert!(q_error <= read_back, "{dialect:?}: {q_error} deg");
        }
    }
}

/// FANUC's world (user frame 0) lies on axis 1 at the height of axis 2 (ROS-Industrial's
/// `fanuc_r2000ic_support`: 670 mm above the R-2000iC/165F's foot). With the wrist bent down at
/// `J5 = -90 deg` and every other axis at 0, the R-2000iC/165F's flange is 312 + 1280 = 1592 mm
/// out and 1075 + 225 - 215 = 1085 mm above axis 2 (its data sheet's arm lengths): the LS
/// position written there says so, and the position read back is that posture again.
#[test]
fn an_ls_position_is_in_fanucs_world_at_the_height_of_axis_2() {
    use nalgebra::Vector3;
    use stiffid::internal::machining::program::generate::{generate, Move, Plan, Target, Tool};
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml")
        .replace("tcp_mm = [6.9, 245.3, 319.3]", "tcp_mm = [0, 0, 0]");
    let setup =
        stiffid::internal::setup::parse(&text, "flange.toml", |n, _| presets::get(n)).unwrap();
    assert_eq!(
        setup.program_world(),
        Isometry3::translation(0.0, 0.0, 0.670)
    );
    let robot = setup.robot();
    let q = Vector6::new(0.0, 0.0, 0.0, 0.0, -90f64.to_radians(), 0.0);
    let targets = [Target::new(robot, &Vector3::zeros(), &q)];
    let flange = setup.program_world().inv_mul(&targets[0].pose);
    assert!((flange.translation.vector * 1e3 - Vector3::new(1592.0, 0.0, 1085.0)).norm() < 1e-9);
    assert!((flange.rotation * Vector3::z() + Vector3::z()).norm() < 1e-12);
    let plan = Plan {
        dialect: Dialect::FanucLs,
        name: "DOWN",
        targets: &targets,
        moves: &[Move::Rapid],
        tool: Tool {
            frame: Isometry3::identity(),
            payload: None,
        },
        work: Isometry3::identity(),
        world: setup.program_world(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses: None,
        settings: Settings::default(),
    };
    let ls = generate(&plan).unwrap().files.remove(0).text;
    assert!(ls.contains("UF : 0, UT : 1,"), "{ls}");
    assert!(
        ls.contains("X = 1592.000000000 mm,\tY = 0.000000000 mm,\tZ = 1085.000000000 mm,"),
        "{ls}"
    );
    let read =
        stiffid::internal::machining::read(&ls, Language::Robot(Dialect::FanucLs), 1e-4).unwrap();
    let resolved =
        stiffid::internal::machining::resolve(&read, &setup, None, &Options::for_setup(&setup))
            .unwrap();
    let stiffid::internal::machining::Program::Robot(p) = resolved.as_ref() else {
        panic!("a robot program")
    };
    let back = Vector6::from(p.targets[0].q_deg).map(f64::to_radians);
    assert!((back - q).amax() < 1e-9, "{back}");
}
