//! Joint targets taught on the robot or computed by a controller's inverse kinematics
//! (`[controller] joint_targets`): a KRL program of joint targets computed from nominal poses by
//! the nominal controller's inverse kinematics, on a calibrated robot (its DH lengths up to
//! 1.2 mm and angles 1 mrad off the nominal): `computed` lands the true loaded tool on the
//! programmed nominal poses, `taught` corrects the deflection only (the tool lands where the
//! calibrated robot goes at the program's angles, millimetres off), and a setup that says
//! neither is refused naming the field and both choices.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use std::fmt::Write;
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::model::Compliance;
use stiffid::internal::robot::ik::{self, tool_pose};
use stiffid::internal::robot::{presets, CALIBRATED};
use stiffid::{Coordinates, Error, Robot, Setup};

/// The KUKA milling example's setup, its robot a calibrated one and its controller the nominal
/// preset, `more` added to `[controller]`.
fn setup(more: &str) -> Setup {
    setup_on(&calibrated(), more, true)
}

/// [`setup`] with the calibrated robot file `robot`, with or without the example's
/// `[workpiece]`.
fn setup_on(robot: &str, more: &str, workpiece: bool) -> Setup {
    let text = include_str!("../../../../../../examples/milling/kuka-milling.toml");
    let text = match workpiece {
        true => text.to_string(),
        false => text[..text.find("[workpiece]").unwrap()].to_string(),
    };
    let text = text.replacen(
        "robot = \"kuka-kr210-robond\"",
        "robot = \"calibrated.toml\"",
        1,
    ) + "\n[controller]\nkinematics = \"nominal\"\nrobot = \"kuka-kr210-robond\"\n"
        + more;
    stiffid::internal::setup::parse(&text, "cell.toml", |name, _| match name {
        "calibrated.toml" => stiffid::internal::robot::file::parse(robot, name),
        other => presets::get(other),
    })
    .unwrap()
}
/// The KR 210 preset as a calibrated robot file: lengths 0.6 to 1.2 mm and one twist 1 mrad off.
fn calibrated() -> String {
    let text = include_str!("../../../../../stiffid-core/presets/kuka-kr210-robond.toml");
    let name = "name = \"KUKA KR 210 (Udacity RoboND kr210 model)\"";
    assert!(text.contains(name));
    let mut out = text.replacen(name, &format!("name = \"KR 210{CALIBRATED}\""), 1);
    for (from, to) in [
        ("d_mm = 750.0", "d_mm = 750.8"),
        ("a_mm = 1250.0", "a_mm = 1251.2"),
        ("d_mm = 1500.0", "d_mm = 1499.4"),
        ("d_mm = 193.0", "d_mm = 193.6"),
        (
            "alpha_deg = 0.0\nd_mm = 0.0\nlower_deg = -210.0",
            "alpha_deg = 0.0573\nd_mm = 0.0\nlower_deg = -210.0",
        ),
    ] {
        assert!(out.contains(from), "{from}");
        out = out.replacen(from, to, 1);
    }
    out
}

/// The program's nominal TCP poses: a 120 mm line cut along the part's x at its surface, the tool
/// down the part's -z (`[workpiece]` at (2000, 0, 550) mm), then the axis angles the nominal
/// controller's inverse kinematics computes for them, deg.
fn computed(nominal: &Robot, tcp: &Vector3<f64>) -> (Vec<Isometry3<f64>>, Vec<[f64; 6]>) {
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let mut q = Vector6::new(0.0, 30.0, 0.0, 0.0, 60.0, 0.0).map(f64::to_radians);
    let mut poses = Vec::new();
    let mut angles = Vec::new();
    for x in [-60.0, -20.0, 20.0, 60.0] {
        let p = Isometry3::from_parts(Translation3::new(2.0 + x * 1e-3, 0.0, 0.55), down);
        q = ik::solve(nominal, tcp, &p, &q, &ik::Options::default())
            .unwrap()
            .q;
        poses.push(p);
        angles.push(q.map(f64::to_degrees).into());
    }
    (poses, angles)
}

/// The KRL program of joint targets `q_deg`: a joint motion to the first, linear ones (cutting)
/// to the others, each value with 9 decimals as a controller's offline program writes them.
fn krl(q_deg: &[[f64; 6]]) -> String {
    let mut text = String::from("DEF cut( )\n");
    for (i, q) in q_deg.iter().enumerate() {
        let motion = if i == 0 { "PTP" } else { "LIN" };
        let a: Vec<String> = (q.iter().enumerate())
            .map(|(k, v)| format!("A{} {v:.9}", k + 1))
            .collect();
        let _ = writeln!(text, "{motion} {{{}}}", a.join(", "));
    }
    text + "END\n"
}

/// The program compensated on `s` by the compensate job, and each point's result.
fn run(s: &Setup, compliance: &Compliance, text: &str) -> stiffid::Result<Vec<Compensated>> {
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup: s,
        compliance: compliance.clone(),
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "cut.src".into(),
            text,
            data: None,
            language: Language::Robot(Dialect::Krl),
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-4,
            output: Language::Robot(Dialect::Krl),
            out_name: "cut.src".into(),
            settings: Settings::default(),
        },
        options: Options::for_setup(s),
    };
    let mut results = Vec::new();
    compensate::run::<Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })?;
    Ok(results)
}

/// Where the true robot (the calibrated one, noise-free) puts the tool commanded to `qc` under
/// `wrench` (base frame, at the TCP): its drives (axis springs) deflected by `h .* J^T W`.
fn lands(
    truth: &Robot,
    h: &Vector6<f64>,
    tcp: &Vector3<f64>,
    qc: &Vector6<f64>,
    wrench: &Vector6<f64>,
) -> Vector3<f64> {
    let j = truth.frames(qc).jacobian(tcp, Coordinates::Axis);
    let dq = (j.transpose() * wrench).component_mul(h);
    tool_pose(&truth.frames(&(qc + dq)), tcp).translation.vector
}

#[test]
fn joint_targets_computed_by_a_nominal_controller_land_on_its_poses() {
    let unstated = setup("");
    let nominal = unstated.controller_robot().unwrap().clone();
    let truth = unstated.robot().clone();
    let tcp = unstated.tool().tcp;
    let (poses, q_deg) = computed(&nominal, &tcp);
    let text = krl(&q_deg);
    let file = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../../../examples/milling/kuka-stiffness.json"
    ))
    .unwrap();
    let compliance = file.compliance(unstated.model()).unwrap();
    let h = Vector6::from_fn(|j, _| compliance.h[j]);
    // Unstated: refused naming the field, both choices and how far apart the two robots are.
    let e = run(&unstated, &compliance, &text).unwrap_err().to_string();
    for word in [
        "controller.joint_targets",
        "\"taught\"",
        "\"computed\"",
        "line ",
        " mm from",
    ] {
        assert!(e.contains(word), "{word}: {e}");
    }
    // The nominal robot itself (no calibration): nothing to say, the program compensated.
    let plain = stiffid::internal::setup::parse(
        include_str!("../../../../../../examples/milling/kuka-milling.toml"),
        "kuka-milling.toml",
        |name, _| presets::get(name),
    )
    .unwrap();
    assert_eq!(run(&plain, &compliance, &text).unwrap().len(), poses.len());
    // How far the calibrated robot is from the nominal poses at the program's angles.
    let off: Vec<f64> = (poses.iter().zip(&q_deg))
        .map(|(p, q)| {
            let q = Vector6::from(*q).map(f64::to_radians);
            let at = tool_pose(&truth.frames(&q), &tcp).translation.vector;
            (at - p.translation.vector).norm()
        })
        .collect();
    assert!(off.iter().all(|d| *d > 1e-3), "{off:?}");
    for (choice, expect_on_nominal) in [("computed", true), ("taught", false)] {
        let s = setup(&format!("joint_targets = \"{choice}\"\n"));
        let results = run(&s, &compliance, &text).unwrap();
        assert_eq!(results.len(), poses.len());
        let mut worst: f64 = 0.0;
        for (i, r) in results.iter().enumerate() {
            let landed = lands(&truth, &h, &tcp, &r.q_compensated, &r.wrench);
            // The loaded tool under a real cut: the force is there.
            if i > 0 {
                assert!(r.wrench.fixed_rows::<3>(0).norm() > 50.0, "{}", r.wrench);
            }
            let q = Vector6::from(q_deg[i]).map(f64::to_radians);
            let aim = match expect_on_nominal {
                true => poses[i].translation.vector,
                false => tool_pose(&truth.frames(&q), &tcp).translation.vector,
            };
            worst = worst.max((landed - aim).norm());
            if !expect_on_nominal {
                let miss = (landed - poses[i].translation.vector).norm();
                assert!((miss - off[i]).abs() < 1e-9, "{miss} {}", off[i]);
            }
        }
        eprintln!("joint_targets = {choice}: the true tool {worst:e} m from its aim, {:.3} to {:.3} mm from the nominal poses at the program's angles", off.iter().copied().fold(f64::INFINITY, f64::min) * 1e3, off.iter().copied().fold(0.0, f64::max) * 1e3);
        assert!(worst < 1e-9, "{choice}: {worst:e} m");
    }
}

/// A KRL program cutting along the part's x in the frame `base` (its `$BASE`, KRL's X Y Z A B
/// C), after a joint move to the example's start posture.
fn in_base(base: &str) -> String {
    format!("DEF cut( )\n$TOOL = {{X 0, Y 0, Z 250, A 0, B 0, C 0}}\n$BASE = {{{base}}}\nPTP {{A1 0, A2 30, A3 0, A4 0, A5 60, A6 0}}\nLIN {{X -40, Y 0, Z 0, A 0, B 0, C 180}}\nLIN {{X 0, Y 0, Z 0, A 0, B 0, C 180}}\nLIN {{X 40, Y 0, Z 0, A 0, B 0, C 180}}\nEND\n")
}

/// A frame taught in the nominal cell (the example's part frame as a KRL `$BASE`) on a
/// calibrated robot whose file locates the part 2.081 mm and 0.02 deg from it: its targets are
/// read in the located part's frame (as the same program stating that frame), and a note names
/// the frame's line and distance; a frame 100 mm away (another fixture) is read as stated, named
/// too.
#[test]
fn a_frame_taught_in_the_nominal_cell_is_read_where_the_calibration_located_the_part() {
    use stiffid::internal::machining::{self, Program};
    let located = "\n[part]\nxyz_mm = [2000.8, -1.2, 551.5]\nrpy_deg = [0.0, 0.0, 0.02]\n";
    let s = setup_on(
        &(calibrated() + located),
        "joint_targets = \"taught\"\n",
        false,
    );
    let read = |text: &str| {
        let p = machining::read(text, Language::Robot(Dialect::Krl), 1e-4).unwrap();
        match machining::resolve(&p, &s, None, &Options::for_setup(&s))
            .unwrap()
            .into_owned()
        {
            Program::Robot(r) => r,
            Program::GCode(_) => unreachable!(),
        }
    };
    let angles = |p: &stiffid::internal::machining::program::JointProgram| -> Vec<[f64; 6]> {
        p.targets.iter().map(|t| t.q_deg).collect()
    };
    let taught = read(&in_base("X 2000, Y 0, Z 550, A 0, B 0, C 0"));
    let there = read(&in_base("X 2000.8, Y -1.2, Z 551.5, A 0.02, B 0, C 0"));
    assert!(there.notes.is_empty(), "{:?}", there.notes);
    let apart = (angles(&taught).iter().zip(angles(&there)))
        .flat_map(|(a, b)| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max);
    assert!(apart < 1e-9, "{apart} deg");
    assert_eq!(taught.notes.len(), 1, "{:?}", taught.notes);
    for word in [
        "line 3",
        "2.081 mm",
        "0.0200 deg",
        "taught in the nominal cell",
        "located part's frame",
    ] {
        assert!(
            taught.notes[0].contains(word),
            "{word}: {}",
            taught.notes[0]
        );
    }
    // Another fixture, 100 mm along x: read as stated (its targets 100 mm further), named.
    let far = read(&in_base("X 2100, Y 0, Z 550, A 0, B 0, C 0"));
    assert!(
        far.notes[0].contains("not the part's frame"),
        "{:?}",
        far.notes
    );
    let moved = (angles(&far)[1].iter().zip(&angles(&there)[1]))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(moved > 0.5, "{moved} deg");
}
