//! The robot's mass along a compensated program: the breakthrough surge at each drilling exit
//! (the operation's thrust along the tool axis, the held mass of the posture) and the first
//! natural frequency of each milling point against the tooth-passing frequency, with the
//! chatter warning within 10%.

use crate::dynamics::held_mass;
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use stiffid::app::compensate::{run, Input, Request};
use stiffid::internal::common::warning::WarningKind;
use stiffid::internal::machining::compensate::{
    Compensated, Free, FreeVariables, Objective, Options, PathPoint,
};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::Language;
use stiffid::internal::observation::dynamics;
use stiffid::internal::robot::dynamics::operational_inertia;
use stiffid::{internal::setup, Coordinates, Setup};

const FANUC: &str = include_str!("../../../stiffid-core/presets/fanuc-r2000ic-165f.toml");
const HEADER: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

/// A drilling operation (thrust `k_f f D / 2` = 1000 N) on `T2` and a three-flute milling one
/// on `T1` turning at `rpm`.
fn process(rpm: f64) -> String {
    format!("[[operation]]\nname = \"drill\"\nkind = \"drilling\"\ntool_number = 2\n\
    [operation.tool]\ndiameter_mm = 10\n[operation.cut]\nfeed_per_rev_mm = 0.2\n\
    [operation.coefficients]\nspecific_energy_n_per_mm2 = 800\nspecific_thrust_n_per_mm2 = 1000\n\
    [[operation]]\nname = \"wall\"\ntool_number = 1\n[operation.tool]\ndiameter_mm = 20\nflutes = 3\n\
    [operation.cut]\nfeed_per_tooth_mm = 0.1\naxial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n\
    spindle_rpm = {rpm:?}\n[operation.coefficients]\npreset = \"al7075-t6\"\n")
}

/// The FANUC setup on its robot with a mass, centre and tensor on every joint, a spindle TCP
/// and a workpiece below the flange.
fn massive() -> Setup {
    massive_with_tcp(Vector3::new(0.0, 0.0, 0.25))
}

/// [`massive`] with the TCP at `tcp` (flange frame, m).
fn massive_with_tcp(tcp: Vector3<f64>) -> Setup {
    let masses = [300.0, 180.0, 120.0, 40.0, 20.0, 8.0];
    let mut parts = FANUC.split("[[joint]]\n");
    let mut text = parts.next().unwrap().to_string();
    for (i, part) in parts.enumerate() {
        let m = masses[i];
        text += &format!(
            "[[joint]]\nmass_kg = {m:?}\ncom_mm = [{:?}, 15.0, -25.0]\ninertia_kg_m2 = [{:?}, {:?}, {:?}, 0.01, 0, 0]\n{part}",
            40.0 * i as f64,
            m * 0.02,
            m * 0.025,
            m * 0.015
        );
    }
    let robot = stiffid::internal::robot::file::parse(&text, "fanuc-masses.toml").unwrap();
    setup::builtin("fanuc-r2000ic-165f")
        .unwrap()
        .to_builder()
        .with_robot(robot)
        .with_tcp(tcp)
        .with_workpiece(Isometry3::translation(1.3, -0.7, 0.4))
        .build()
        .unwrap()
}

/// Every point of a compensated program with its result and dynamics.
type Rows = Vec<(PathPoint, Compensated, Dynamics)>;

/// Compensates `program` (G-code) under `process`; every point with its result and dynamics.
fn compensate(s: &Setup, program: &str, process: &str) -> (stiffid::app::compensate::Report, Rows) {
    compensate_with(s, program, process, Options::for_setup(s)).unwrap()
}

/// [`compensate`] with `options`.
fn compensate_with(
    s: &Setup,
    program: &str,
    process: &str,
    options: Options,
) -> stiffid::Result<(stiffid::app::compensate::Report, Rows)> {
    let mut rows = Vec::new();
    let request = Request {
        names: Default::default(),
        setup: s,
        compliance: s.model_compliance("test").unwrap(),
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "p.nc".into(),
            text: program,
            data: None,
            language: Language::GCode,
            process_name: "p.toml".into(),
            process: file::parse(process, "p.toml").unwrap(),
            chord_tolerance: 1e-5,
            // A rotation about the tool axis reaches the controller in a robot program only.
            output: match options.free.tool_rotation() {
                Some(_) => Language::Robot(stiffid::internal::machining::program::Dialect::Krl),
                None => Language::GCode,
            },
            out_name: "p.src".into(),
            settings: Settings::default(),
        },
        options,
    };
    let report = run(
        request,
        |_, p: &[PathPoint], r: &[Compensated], d: &[Dynamics]| {
            for ((p, r), d) in p.iter().zip(r).zip(d) {
                rows.push((p.clone(), r.clone(), *d));
            }
            Ok::<(), stiffid::Error>(())
        },
    )?;
    Ok((report.report, rows))
}

#[test]
fn each_drilling_exit_gets_the_surge_of_its_thrust_along_the_tool_axis() {
    let s = massive();
    let text = format!("{HEADER}T2\nG0 X0 Y0 Z10\nG81 X20 Y10 Z-8 R2 F120\nX40\nG80\n");
    let (report, rows) = compensate(&s, &text, &process(6000.0));
    let compliance = s.model_compliance("test").unwrap();
    let masses = dynamics::mass_model(s.arm()).0.expect("masses");
    let exits: Vec<_> = rows.iter().filter(|(_, _, d)| d.surge.is_some()).collect();
    assert_eq!(exits.len(), 2, "one exit per hole");
    for (_, r, d) in &rows {
        assert!(d.first_frequency.is_none() && d.tooth_passing.is_none());
        if d.surge.is_none() {
            continue;
        }
        let surge = d.surge.unwrap();
        // The thrust (1000 N) along the tool axis, against the held mass of the posture.
        assert!((surge.force - 1000.0).abs() < 1e-9);
        let tool_z = r.pose.rotation * Vector3::z();
        assert!((surge.direction + tool_z).norm() < 1e-12);
        let frames = s.robot().frames(&r.q);
        let m = masses.mass_matrix(s.robot(), &frames, Coordinates::Axis);
        let tcp = s.tool().tcp;
        let lambda = operational_inertia(&m, &frames.jacobian(&tcp, Coordinates::Axis)).unwrap();
        let mass = held_mass(&lambda, &tool_z);
        assert!((surge.mass - mass).abs() < 1e-9 * mass);
        // c from the model's deflection under a pure 1 N force along the drill.
        let unit = nalgebra::Vector6::new(-tool_z.x, -tool_z.y, -tool_z.z, 0.0, 0.0, 0.0);
        let points = stiffid::internal::observation::deflection::Points {
            arm: s.arm(),
            frames: &frames,
            loaded: &tcp,
            observed: &tcp,
        };
        let d = points.deflection(&unit, &compliance.h).displacement;
        let c = -tool_z.dot(&d.fixed_rows::<3>(0));
        let speed = 1000.0 * (c / mass).sqrt();
        assert!(
            (surge.speed - speed).abs() < 1e-9 * speed,
            "{} {speed}",
            surge.speed
        );
        assert!(
            surge.speed > 0.01 && surge.speed < 1.0,
            "{} m/s",
            surge.speed
        );
    }
    let ops = &report.program.as_ref().unwrap().dynamics;
    assert_eq!(ops.len(), 1);
    assert_eq!(ops[0].kind, "drilling");
    assert_eq!(ops[0].points, 2);
    let largest = exits
        .iter()
        .map(|(_, _, d)| d.surge.unwrap().speed)
        .fold(0.0, f64::max);
    assert!((ops[0].max_surge_mm_s.unwrap() - largest * 1e3).abs() < 1e-9);
}

#[test]
fn milling_points_get_their_first_frequency_and_a_chatter_warning_near_a_harmonic() {
    let s = massive();
    let text = format!("{HEADER}T1\nG0 X0 Y0 Z5\nG1 Z-2 F600\nG1 X30\nG1 X60 Y10\n");
    let (_, rows) = compensate(&s, &text, &process(6000.0));
    let compliance = s.model_compliance("test").unwrap();
    let masses = dynamics::mass_model(s.arm()).0.unwrap();
    let milled: Vec<_> = rows
        .iter()
        .filter(|(_, _, d)| d.first_frequency.is_some())
        .collect();
    assert!(milled.len() >= 3, "{}", milled.len());
    for (_, r, d) in &milled {
        let frames = s.robot().frames(&r.q);
        let posture = dynamics::posture(&masses, s.arm(), &frames, &s.tool().tcp, &compliance.h);
        let first = posture.modes.unwrap().frequencies[0];
        assert!((d.first_frequency.unwrap() - first).abs() < 1e-9 * first);
        // 6000 rpm x 3 flutes = 300 Hz.
        assert!((d.tooth_passing.unwrap() - 300.0).abs() < 1e-12);
        assert!(first > 1.0 && first < 100.0, "{first} Hz");
        // The modes agree with an independent generalised eigen-solution: det(K - w^2 M) = 0.
        let c = dynamics::joint_compliance(s.arm(), &frames, &s.tool().tcp, &compliance.h).unwrap();
        let k = c.try_inverse().unwrap();
        let w2 = (first * std::f64::consts::TAU).powi(2);
        let m = masses.mass_matrix(s.robot(), &frames, Coordinates::Axis);
        let min_sv = (k - m * w2).singular_values().min();
        assert!(min_sv < 1e-9 * k.norm(), "{min_sv}");
    }
    // A spindle speed whose tooth-passing frequency is 5% above the first frequency: chatter.
    let f1 = milled[0].2.first_frequency.unwrap();
    let rpm = f1 * 1.05 / 3.0 * 60.0;
    let (report, _) = compensate(&s, &text, &process(rpm));
    let chatter: Vec<_> = report
        .warnings
        .iter()
        .filter(|w| w.kind == WarningKind::Chatter)
        .collect();
    assert_eq!(chatter.len(), 1, "{:?}", report.warnings);
    assert!(
        chatter[0].message.contains("'wall'"),
        "{}",
        chatter[0].message
    );
    let op = &report.program.as_ref().unwrap().dynamics[0];
    assert_eq!(op.nearest_harmonic_order, Some(1));
    assert!(op.nearest_harmonic_pct.unwrap() <= 10.0);
    // Far from every harmonic (300 Hz): no warning.
    let (report, _) = compensate(&s, &text, &process(6000.0));
    assert!(report
        .warnings
        .iter()
        .all(|w| w.kind != WarningKind::Chatter));
}

/// Three holes drilled by `T2` (1000 N of thrust) on the FANUC with masses and a spindle whose
/// TCP is 120 mm off the flange axis (so that a turn about the tool z moves the whole arm).
fn holes() -> (Setup, String) {
    let s = massive_with_tcp(Vector3::new(0.12, 0.0, 0.25));
    let text =
        format!("{HEADER}T2\nG0 X0 Y0 Z10\nG81 X20 Y10 Z-8 R2 F120\nX120 Y-60\nX-80 Y90\nG80\n");
    (s, text)
}

/// The free tool axis with `objective`: steps of at most 20 deg (a 5 deg grid) within +-90 deg.
fn free_options(s: &Setup, objective: Objective) -> Options {
    let free = FreeVariables {
        free: vec![Free::ToolRotation(crate::compensate::rotation(90.0, 20.0))],
        minimise: objective,
        ..FreeVariables::default()
    };
    Options {
        free,
        ..Options::for_setup(s)
    }
}

/// The surge of 1000 N along the drill at the exit of `r` turned by `phi` about tool z from the
/// path's own rotation, by hand: inverse kinematics of the turned pose from the path's posture,
/// the mass matrix, Lambda and [`dynamics::surge`]; `None` where the pose is out of reach.
fn surge_turned(s: &Setup, r: &Compensated, phi: f64) -> Option<f64> {
    let z = |a: f64| UnitQuaternion::from_axis_angle(&Vector3::z_axis(), a);
    let own = r.pose * z(-r.tool_rotation);
    let target = own * z(phi);
    let start = r.q_before.expect("the path's posture");
    let tcp = s.tool().tcp;
    let q =
        stiffid::internal::robot::ik::solve(s.robot(), &tcp, &target, &start, &Default::default())
            .ok()?
            .q;
    let frames = s.robot().frames(&q);
    let masses = dynamics::mass_model(s.arm()).0.unwrap();
    let m = masses.mass_matrix(s.robot(), &frames, Coordinates::Axis);
    let lambda = operational_inertia(&m, &frames.jacobian(&tcp, Coordinates::Axis))?;
    let force = -(own.rotation * Vector3::z()) * 1000.0;
    let compliance = s.model_compliance("test").unwrap();
    dynamics::surge(
        &masses,
        s.arm(),
        &frames,
        &tcp,
        &lambda,
        &compliance,
        &force,
    )
    .map(|v| v.speed)
}

/// The surge objective: at every drilling exit the rotation chosen gives the least surge over
/// the whole grid of angles (an exhaustive search by hand), never more than the path's own;
/// the reported surge is at the rotation chosen; and it chooses otherwise than the deflection.
#[test]
fn the_free_tool_axis_chooses_the_rotation_of_least_surge_at_every_drilling_exit() {
    let (s, text) = holes();
    let run = |objective| {
        compensate_with(&s, &text, &process(6000.0), free_options(&s, objective)).unwrap()
    };
    let (report, rows) = run(Objective::Surge);
    let (_, by_deflection) = run(Objective::Deflection);
    let grid: Vec<f64> = (-18..=18).map(|k| (5.0 * k as f64).to_radians()).collect();
    let exits: Vec<usize> = (0..rows.len())
        .filter(|&i| rows[i].2.surge.is_some())
        .collect();
    assert_eq!(exits.len(), 3, "one exit per hole");
    let (mut differ, mut gained) = (0, 0.0f64);
    for &i in &exits {
        let (_, r, d) = &rows[i];
        let chosen = d.surge.unwrap().speed;
        let before = d.surge_before.unwrap().speed;
        // The reported surges are those at the rotation chosen and at the path's own.
        let by_hand = surge_turned(&s, r, r.tool_rotation).unwrap();
        assert!(
            (chosen - by_hand).abs() < 1e-6 * by_hand,
            "{chosen} {by_hand}"
        );
        let own = surge_turned(&s, r, 0.0).unwrap();
        assert!((before - own).abs() < 1e-6 * own, "{before} {own}");
        assert!(grid.iter().any(|a| (a - r.tool_rotation).abs() < 1e-9));
        // The least over the grid, within the tie-breaking cost; never above the path's own.
        let least = grid
            .iter()
            .filter_map(|&a| surge_turned(&s, r, a))
            .fold(f64::INFINITY, f64::min);
        assert!(
            chosen <= least * (1.0 + 1e-5),
            "line {}: {chosen} > {least}",
            rows[i].0.line
        );
        assert!(chosen <= before * (1.0 + 1e-12));
        gained = gained.max(1.0 - chosen / before);
        // The deflection's choice at the same exit.
        let (_, other, od) = &by_deflection[i];
        assert!(od.surge.is_some() && od.surge_before.is_some());
        if (other.tool_rotation - r.tool_rotation).abs() > 1e-9 {
            differ += 1;
            assert!(od.surge.unwrap().speed > chosen, "line {}", rows[i].0.line);
        }
    }
    assert!(
        differ >= 1,
        "the surge chose the deflection's rotation at every exit"
    );
    assert!(
        gained > 0.01,
        "the surge objective gained {:.2}% at most",
        100.0 * gained
    );
    // The operation reports the largest surge before and after.
    let op = &report.program.as_ref().unwrap().dynamics[0];
    let largest =
        |f: &dyn Fn(&Dynamics) -> f64| exits.iter().map(|&i| f(&rows[i].2)).fold(0.0, f64::max);
    assert!((op.max_surge_mm_s.unwrap() - 1e3 * largest(&|d| d.surge.unwrap().speed)).abs() < 1e-9);
    let before = op.max_surge_before_mm_s.unwrap();
    assert!((before - 1e3 * largest(&|d| d.surge_before.unwrap().speed)).abs() < 1e-9);
}

/// The surge objective refuses, naming the option, a robot without masses and a program
/// without a drilling exit.
#[test]
fn the_surge_objective_needs_masses_and_a_drilling_exit() {
    let refused =
        |r: stiffid::Result<(stiffid::app::compensate::Report, Rows)>, words: &str| match r {
            Err(stiffid::Error::InvalidOption { option, message }) => {
                assert_eq!(option, stiffid::JobOption::Minimise);
                assert!(message.contains(words), "{message}");
            }
            other => panic!("{:?}", other.map(|_| ())),
        };
    let (s, text) = holes();
    let plain = setup::builtin("fanuc-r2000ic-165f")
        .unwrap()
        .to_builder()
        .with_tcp(s.tool().tcp)
        .with_workpiece(*s.workpiece().unwrap())
        .build()
        .unwrap();
    let options = free_options(&plain, Objective::Surge);
    refused(
        compensate_with(&plain, &text, &process(6000.0), options),
        "no link masses",
    );
    let milled = format!("{HEADER}T1\nG0 X0 Y0 Z5\nG1 Z-2 F600\nG1 X30\n");
    let options = free_options(&s, Objective::Surge);
    refused(
        compensate_with(&s, &milled, &process(6000.0), options),
        "drilling exit",
    );
}

#[test]
fn a_robot_without_masses_gives_no_operation_dynamics() {
    // The FANUC preset has no masses: no point has a surge or a frequency, and the program's
    // list of operation dynamics is empty (not one entry per operation claiming a singularity).
    let s = setup::builtin("fanuc-r2000ic-165f")
        .unwrap()
        .to_builder()
        .with_tcp(Vector3::new(0.0, 0.0, 0.25))
        .with_workpiece(Isometry3::translation(1.3, -0.7, 0.4))
        .build()
        .unwrap();
    assert!(dynamics::mass_model(s.arm()).0.is_none());
    let text = format!("{HEADER}T1\nG0 X0 Y0 Z5\nG1 Z-2 F600\nG1 X30\nG1 X60 Y10\n");
    let (report, rows) = compensate(&s, &text, &process(6000.0));
    assert!(rows.iter().all(|(_, _, d)| d.first_frequency.is_none()));
    assert!(report.program.as_ref().unwrap().dynamics.is_empty());
    // The same program on the robot with masses has the milling operation's entry.
    let (report, _) = compensate(&massive(), &text, &process(6000.0));
    assert_eq!(report.program.as_ref().unwrap().dynamics.len(), 1);
}
