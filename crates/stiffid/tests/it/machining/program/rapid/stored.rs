//! A RAPID module as its controller stores it (`robtarget`s declared in the module, a `tooldata`
//! turned on the flange, a `wobjdata` of a user frame and an object frame, `Offs`, `MoveC`),
//! compensated and run on the simulated true robot of [`crate::true_robot`]: a controller
//! simulated from the compensated module's text alone (its own reading of the declarations,
//! its nominal inverse kinematics in the `confdata` named) moves the true robot, whose TCP
//! error is measured in the tracker's frame.

use super::module::{pose, rpy};
use crate::true_robot::{row, Row, Truth};
use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::cartesian::flags::ConfigurationData;
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::rapid::ConfData;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::ik;
use stiffid::{Robot, Setup};

/// The tool's turn on the flange (roll, pitch, yaw, deg).
const TOOL_RPY_DEG: [f64; 3] = [0.0, 20.0, 30.0];

/// The work object's object frame in its user frame: 100 mm along x, 15 deg about z.
fn object_in_user() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.1, -0.05, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 15f64.to_radians()),
    )
}

/// The cut in the part frame, mm: a 60 x 40 mm rectangle around the part's origin, its right
/// side an arc through (40, 0) (a `MoveC`).
const CUT: [(f64, f64); 8] = [
    (-30.0, -20.0),
    (0.0, -20.0),
    (30.0, -20.0),
    (40.0, 0.0),
    (30.0, 20.0),
    (0.0, 20.0),
    (-30.0, 20.0),
    (-30.0, -20.0),
];

/// The module: the cut's points declared (their `confdata` the nominal controller's postures
/// from `q0`), an approach by `Offs` 20 mm above the first, the arc as `MoveC`.
fn module(setup: &Setup, nominal: &Robot, q0: &Vector6<f64>) -> String {
    let c = setup.workcell().controller();
    let part = *setup.workpiece().unwrap();
    let wobj = setup.program_world().inverse() * part;
    let turn = rpy(TOOL_RPY_DEG);
    let tool = Isometry3::from_parts(Translation3::from(setup.tool().tcp), turn);
    // The tool down the part's -z.
    let down = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI);
    let mut previous = *q0;
    let mut text = format!(
        "MODULE Rect\n  PERS tooldata tMill:=[TRUE,{},[12,[0,0,150],[1,0,0,0],0,0,0]];\n  PERS wobjdata wRect:=[FALSE,TRUE,\"\",{},{}];\n",
        pose(&(c.adapter * tool)),
        pose(&(wobj * object_in_user().inverse())),
        pose(&object_in_user()),
    );
    let names: Vec<String> = (0..CUT.len())
        .map(|k| format!("p{}", 10 * (k + 1)))
        .collect();
    for (name, (x, y)) in std::iter::once(&"pStart".to_string())
        .chain(&names)
        .zip(std::iter::once(&CUT[0]).chain(&CUT))
    {
        let local = Isometry3::from_parts(Translation3::new(x * 1e-3, y * 1e-3, 0.0), down);
        let flange_axes = part * local * turn.inverse();
        let q = ik::solve(
            nominal,
            &setup.tool().tcp,
            &flange_axes,
            &previous,
            &ik::Options::default(),
        )
        .unwrap()
        .q;
        previous = q;
        let ConfData([a, b, cf, d]) = ConfData::of(&Configuration::of(nominal, &q));
        let p = pose(&local);
        text += &format!(
            "  CONST robtarget {name}:=[{},[{a},{b},{cf},{d}],[9E9,9E9,9E9,9E9,9E9,9E9]];\n",
            &p[1..p.len() - 1]
        );
    }
    let motion = |m: &str, target: &str, zone: &str| {
        format!("    {m} {target}, v20, {zone}, tMill\\WObj:=wRect;\n")
    };
    text += "  PROC main()\n";
    text += &motion("MoveJ", "Offs(pStart,0,0,20)", "fine").replace("v20", "v200");
    text += &motion("MoveL", &names[0], "fine");
    text += &motion("MoveL", &names[1], "z1");
    text += &motion("MoveL", &names[2], "z1");
    text += &motion("MoveC", &format!("{}, {}", names[3], names[4]), "z1");
    for n in &names[5..] {
        text += &motion("MoveL", n, "z1");
    }
    text + "  ENDPROC\nENDMODULE\n"
}

/// The numbers of a text (mm, quaternions, `confdata`).
fn numbers(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | 'e' | 'E')))
        .filter_map(|t| t.parse::<f64>().ok())
        .collect()
}

/// A pose `[[x,y,z],[q1,q2,q3,q4]]` from its seven numbers (mm).
fn pose_of(v: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3),
        UnitQuaternion::from_quaternion(Quaternion::new(v[3], v[4], v[5], v[6])),
    )
}

/// A target as the controller reads it: the tool's pose (its world, m) and the `confdata`.
type Read = (Isometry3<f64>, [i64; 4]);

/// What the controller reads from the module: the tool frame on the flange, and every target.
fn controller_view(text: &str) -> (Isometry3<f64>, Vec<Read>) {
    let after = |key: &str| -> Vec<f64> {
        let l = text.lines().find(|l| l.contains(key)).unwrap();
        numbers(&l[l.find(":=").unwrap() + 2..])
    };
    let tool = pose_of(&after("tooldata tMill"));
    let w = after("wobjdata wRect");
    let wobj = pose_of(&w[..7]) * pose_of(&w[7..14]);
    let point = |name: &str| {
        let v = after(&format!("robtarget {name}:"));
        (
            pose_of(&v[..7]),
            [v[7], v[8], v[9], v[10]].map(|c| c as i64),
        )
    };
    let mut targets = Vec::new();
    for l in text.lines().map(str::trim) {
        let Some((m, rest)) = l.split_once(' ') else {
            continue;
        };
        if !matches!(m, "MoveJ" | "MoveL" | "MoveC") {
            continue;
        }
        let args: Vec<&str> = rest.split(',').map(str::trim).collect();
        let points: Vec<(Isometry3<f64>, [i64; 4])> =
            if let Some(inner) = args[0].strip_prefix("Offs(") {
                let (p, conf) = point(inner);
                let d = [args[1], args[2], args[3].trim_end_matches(')')]
                    .map(|a| a.parse::<f64>().unwrap() * 1e-3);
                vec![(Isometry3::translation(d[0], d[1], d[2]) * p, conf)]
            } else if m == "MoveC" {
                vec![point(args[0]), point(args[1])]
            } else {
                vec![point(args[0])]
            };
        targets.extend(points.into_iter().map(|(p, c)| (wobj * p, c)));
    }
    (tool, targets)
}

/// Compensates the module on `setup` (the setup's tool turned as the module's) with
/// `compliance`: the compensated module and every target's result.
fn compensated(
    setup: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    q0: &Vector6<f64>,
    text: &str,
) -> (String, Vec<Compensated>) {
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let mut options = Options::for_setup(setup);
    options.q0 = *q0;
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance: compliance.clone(),
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "Rect.mod".into(),
            text,
            data: None,
            language: Language::Robot(Dialect::Rapid),
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output: Language::Robot(Dialect::Rapid),
            out_name: "Rect-compensated.mod".into(),
            settings: Settings::default(),
        },
        options,
    };
    let mut results = Vec::new();
    let report = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    (report.report.program.unwrap().text, results)
}

/// What the stored module compensated on `setup` (its part set, its tracker registered at
/// `frame`) does on the true robot, run by the nominal controller (`nominal`) from the
/// compensated text: the TCP error's mean and largest (m).
pub(crate) fn stored_landing(
    truth: &Truth,
    nominal: &Robot,
    (setup, compliance): (&Setup, &stiffid::internal::model::Compliance),
    q0: &Vector6<f64>,
    frame: &Isometry3<f64>,
) -> Row {
    let turned = (setup.to_builder())
        .with_tcp_rotation(rpy(TOOL_RPY_DEG))
        .build()
        .unwrap();
    let text = module(&turned, nominal, q0);
    let (out, results) = compensated(&turned, compliance, q0, &text);
    let (tool, targets) = controller_view(&out);
    assert_eq!(targets.len(), results.len(), "{out}");
    let world = turned.program_world();
    assert_eq!(
        turned.workcell().controller().adapter,
        Isometry3::identity()
    );
    let mut previous = results[0].q;
    let errors: Vec<f64> = (targets.iter().zip(&results))
        .map(|((target, conf), r)| {
            // The flange's axes at the TCP: the tool's turned back.
            let mut at = world * target;
            at.rotation *= tool.rotation.inverse();
            let tcp = tool.translation.vector;
            let q = ik::solve(nominal, &tcp, &at, &previous, &ik::Options::default())
                .unwrap()
                .q;
            assert_eq!(ConfData::of(&Configuration::of(nominal, &q)).0, *conf);
            assert!(
                (q - r.q_compensated).amax() < 1e-6,
                "{}",
                (q - r.q_compensated).amax()
            );
            previous = q;
            let want = frame.inverse() * Point3::from(r.pose.translation.vector);
            (truth.tcp_at(&q, &r.wrench) - want.coords).norm()
        })
        .collect();
    row(&errors)
}
