//! One campaign on a robot on a track, end to end with the readings as the tracker gives them
//! (`e1_mm` in every file): the simulated true cell of [`crate::true_cell`] (the true arm of
//! [`crate::true_robot`] on a 6 m track that bows and pitches) calibrated from unloaded readings
//! over the rail, its drives identified from raw load-step readings at several stations on the
//! calibrated cell, a G-code program that moves the track while it mills compensated, and
//! written back as G-code with `U` for a controller with its nominal kinematics (a straight
//! track, the nominal arm): its joint targets (the compensated angles at each point's `U`) and
//! its Cartesian targets (the G-code's points, run by the controller's inverse kinematics, the
//! orientation as programmed); and written as robot programs with the track's values (KRL `E1`,
//! RAPID `eax_a`, LS group 1's `E1`, INFORM's base axis `BC` in pulses), joint and Cartesian
//! targets, for the nominal controller and for one running the calibrated model.

use crate::campaign_paths::{identified, print, tracker};
use crate::true_cell::{readings, readings_with, stations, track_case, true_tcp, NOISE};
use crate::true_robot::{
    self, calibrated, postures, rectangle, row, written_from, Row, Truth, WRENCHES,
};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::internal::machining::compensate::Compensated;
use stiffid::internal::machining::program::cartesian::Frame;
use stiffid::internal::machining::program::generate::Targets;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::robot::ik;
use stiffid::internal::setup::{Controller, Kinematics, Pulses};
use stiffid::{Robot, Setup};

/// The station the part is milled at, m.
const STATION: f64 = 3.0;

/// A Yaskawa controller's pulses per degree of the six axes (S, L, U, R, B, T), not whole.
const PULSES_PER_DEG: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];

/// Its pulses per mm of the track.
const PULSES_PER_MM: f64 = 1000.0;

/// `setup` with the controller's pulses (`[controller] pulses_per_deg`, `external_pulses`).
fn with_pulses(setup: &Setup) -> Setup {
    let controller = Controller {
        pulses: Some(Pulses {
            per_deg: PULSES_PER_DEG,
            external: vec![PULSES_PER_MM],
        }),
        ..setup.workcell().controller().clone()
    };
    setup
        .to_builder()
        .with_controller(controller)
        .build()
        .unwrap()
}

/// [`rectangle`] with the track driven by `U` (mm): 3000 mm at the start, then 4 mm per mm of
/// `X`, so that the track moves while the tool mills.
fn rectangle_on_track() -> String {
    let mut text = String::from("(stiffid: external = U)\n");
    for line in rectangle().lines() {
        let x = (line.split_whitespace())
            .find_map(|w| w.strip_prefix('X'))
            .map(|x| x.parse::<f64>().unwrap());
        text += &match (line.starts_with("G0") || line.starts_with("G1"), x) {
            (true, Some(x)) => format!("{line} U{:.3}\n", STATION * 1e3 + 4.0 * x),
            _ => format!("{line}\n"),
        };
    }
    text
}

/// The part where `setup`'s robot on the carriage at [`STATION`] puts its tool at `q0`, the
/// tool along its -z.
fn with_part(setup: &Setup, q0: &Vector6<f64>) -> (Setup, Isometry3<f64>) {
    let frames = setup.robot().frames_at(q0, &[STATION]);
    let at = ik::tool_pose(&frames, &setup.tool().tcp);
    let part = at * UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let setup = setup.to_builder().with_workpiece(part).build().unwrap();
    (setup, part)
}

/// What a controller running `model` does with a target `target` (cell frame) and the track at
/// `s` (m): its arm's inverse kinematics from `previous` on its own model of the track (the
/// nominal one straight along x).
fn controller(
    model: &Robot,
    tcp: &nalgebra::Vector3<f64>,
    target: &Isometry3<f64>,
    s: f64,
    previous: &Vector6<f64>,
) -> Vector6<f64> {
    let on_rail = model.external().unwrap().carrier_pose(&[s]).inverse() * target;
    ik::solve(model, tcp, &on_rail, previous, &ik::Options::default())
        .unwrap()
        .q
}

/// The true cell's TCP error (m) at every compensated point `results` commanded to `qs` with the
/// track at `s` (as compensated to `track`, m), the targets registered through the tracker at
/// `frame`.
fn errors(
    truth: &Truth,
    frame: &Isometry3<f64>,
    results: &[Compensated],
    (commanded, track): (&[(Vector6<f64>, f64)], f64),
) -> Row {
    assert_eq!(results.len(), commanded.len());
    let e: Vec<f64> = (results.iter().zip(commanded))
        .map(|(r, (q, s))| {
            assert!((r.external.as_slice()[0] - s).abs() < track, "{s}");
            let want = frame.inverse() * Point3::from(r.pose.translation.vector);
            (true_tcp(truth, *s, q, &r.wrench) - want.coords).norm()
        })
        .collect();
    row(&e)
}

/// Path (5): the track cell calibrated from unloaded readings with `e1_mm` (gravity from the
/// link masses), its drives identified from raw load-step readings with `e1_mm` at four
/// stations on the calibrated cell (the tracker where the calibration put it), a G-code program
/// that drives the track by `U` compensated and written back for the nominal controller: joint
/// targets and the G-code's Cartesian targets land on the true cell within 3x the held-out
/// calibration error plus the predicted deflection's standard deviation, and within 0.05 mm,
/// where the nominal controller alone misses by millimetres.
/// The track cell's campaign: the truth, the tracker's registration, the calibrated setup (the
/// part placed, the nominal controller named), the identified drives, the held-out RMS (m),
/// the start posture, the part frame and the nominal robot (on its straight track).
pub(crate) struct Campaign {
    truth: Truth,
    frame: Isometry3<f64>,
    setup: Setup,
    compliance: stiffid::internal::model::Compliance,
    held_rms: f64,
    q0: Vector6<f64>,
    part: Isometry3<f64>,
    nominal: Robot,
}

/// Calibrates the track cell from unloaded readings with `e1_mm` (gravity from the link
/// masses), identifies its drives from raw load-step readings with `e1_mm` at four stations on
/// the calibrated cell (the tracker where the calibration put it), places the part.
fn campaign() -> Campaign {
    let case = track_case();
    let arm = true_robot::dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let truth = Truth::new(&arm.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = readings(&truth, &fit, &stations(30, 5), &WRENCHES[..1], &mut rng);
    let held_q = postures(12, &mut rng, case.angles);
    let held_s: Vec<f64> = (0..12).map(|i| 0.25 + 0.5 * i as f64).collect();
    let held = readings(&truth, &held_q, &held_s, &WRENCHES[..1], &mut rng);
    let (setup, _, frame, held_rms, _) = calibrated(&case, Gravity::Masses, &data, &held);
    let setup = setup
        .to_builder()
        .with_tracker(tracker(frame))
        .build()
        .unwrap();
    // Raw load steps with the track's position, read at four stations.
    let steps_q = postures(20, &mut rng, case.angles);
    let text = readings_with(
        &truth,
        &steps_q,
        Some(&stations(20, 5)),
        &WRENCHES,
        NOISE,
        &mut rng,
    );
    assert!(text.starts_with("posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,e1_mm,"));
    let compliance = identified(&setup, &text);
    let nominal_h = case.setup.nominal_compliance().unwrap() * 1.3;
    for j in 0..3 {
        let relative = compliance.h[j] / nominal_h[j] - 1.0;
        assert!(relative.abs() < 0.05, "drive {}: {relative:e}", j + 1);
    }
    let q0 = true_robot::q0(&case);
    let (setup, part) = with_part(&setup, &q0);
    Campaign {
        truth,
        frame,
        setup,
        compliance,
        held_rms,
        q0,
        part,
        nominal: case.setup.robot().clone(),
    }
}

#[test]
fn a_track_cell_campaign_with_external_values_lands_on_the_true_cell() {
    let Campaign {
        truth,
        frame,
        setup,
        compliance,
        held_rms,
        q0,
        part,
        nominal,
    } = campaign();
    let nominal = &nominal;
    let gcode = rectangle_on_track();
    let tcp = setup.tool().tcp;
    // G-code written back for the nominal controller, U as read: its points the Cartesian
    // targets, the compensated angles at each point's U the joint targets.
    let output = (Language::GCode, Targets::Joint);
    let (text, results) = written_from(&setup, &compliance, (&q0, &gcode), output);
    let joint: Vec<(Vector6<f64>, f64)> = (results.iter())
        .map(|r| (r.q_compensated, r.external.as_slice()[0]))
        .collect();
    let joint = errors(&truth, &frame, &results, (&joint, 1e-9));
    let g = stiffid::internal::machining::gcode::parse(&text, 1e-5).unwrap();
    assert_eq!(g.external.0, vec!['U']);
    assert_eq!(g.points.len(), results.len());
    let mut previous = results[0].q;
    let commanded: Vec<(Vector6<f64>, f64)> = (g.points.iter())
        .map(|p| {
            let target =
                part * Isometry3::from_parts(Translation3::from(p.position), p.orientation);
            let s = p.external[0] * 1e-3;
            previous = controller(nominal, &tcp, &target, s, &previous);
            (previous, s)
        })
        .collect();
    let gcode_row = errors(&truth, &frame, &results, (&commanded, 1e-9));
    // The nominal controller alone: the rigid targets on its straight track.
    let mut previous = results[0].q;
    let alone: Vec<(Vector6<f64>, f64)> = (results.iter())
        .map(|r| {
            let s = r.external.as_slice()[0];
            previous = controller(nominal, &tcp, &r.pose, s, &previous);
            (previous, s)
        })
        .collect();
    let alone = errors(&truth, &frame, &results, (&alone, 1e-9));
    let std: Vec<f64> = results
        .iter()
        .filter_map(|r| r.translation_norm_std)
        .collect();
    let expected = held_rms + std.iter().sum::<f64>() / std.len().max(1) as f64;
    let path = "track cell (e1_mm throughout)";
    print(path, "nominal controller, no stiffid", &alone);
    print(path, "joint targets", &joint);
    print(path, "G-code (Cartesian targets)", &gcode_row);
    eprintln!(
        "{path}: expected (held-out + deflection sd) {:.4} mm",
        expected * 1e3
    );
    for r in [joint, gcode_row] {
        assert!(r.mean <= 3.0 * expected, "{r:?} vs {expected}");
        assert!(r.mean <= 0.05e-3, "{r:?}");
    }
    assert!(alone.mean > 1e-3, "{alone:?}");
}

/// A target read back: its axis angles (rad) or its Cartesian pose (cell frame), the track's
/// value (m).
type ReadBack = (Option<Vector6<f64>>, Option<Isometry3<f64>>, f64);

/// One robot program's targets read back: per target the axis angles (rad) or the Cartesian
/// pose (cell frame: its frame as the program states it), and the track's value (m).
fn read_back(text: &str, dialect: Dialect) -> Vec<ReadBack> {
    // An INFORM job's pulses are the setup's ([`with_pulses`]).
    let pulses = Pulses {
        per_deg: PULSES_PER_DEG,
        external: vec![PULSES_PER_MM],
    };
    let context = stiffid::internal::machining::program::Context {
        home_deg: None,
        backup: &[],
        pulses: Some(&pulses),
        tool: None,
        data: None,
        machine: None,
        ..Default::default()
    };
    let program = stiffid::internal::machining::program::parse_in(text, dialect, &context).unwrap();
    assert_eq!(program.axes.len(), 1, "{:?}", program.axes);
    (program.targets.iter())
        .map(|t| {
            let s = t.external[0].unwrap() * 1e-3;
            let pose = t.cartesian.as_ref().map(|c| {
                let frame = match &c.frame {
                    Frame::Stated(_, f) => *f,
                    Frame::World | Frame::Numbered(_, 0) => Isometry3::identity(),
                    other => panic!("{other:?}"),
                };
                frame * c.pose()
            });
            let q = t
                .cartesian
                .is_none()
                .then(|| Vector6::from(t.q_deg).map(f64::to_radians));
            (q, pose, s)
        })
        .collect()
}

/// The track cell's campaign written as KRL, RAPID, LS and INFORM programs with the track's
/// values in each language's form (INFORM: a base axis in pulses, joint targets whatever is
/// asked), joint and Cartesian targets, for the nominal controller and for one running the
/// calibrated model (its track's error motions included): read back, every target gives the
/// compensated angles (joint targets, to 1e-8 deg; INFORM to half a pulse) or, run by the controller's inverse
/// kinematics on its own track, the compensated angles (to 1e-6 rad), the track's value as
/// compensated; on the true cell each program lands within 3x the held-out calibration error
/// plus the predicted deflection's standard deviation, and within 0.05 mm.
#[test]
fn robot_programs_for_the_track_cell_land_on_the_true_cell() {
    let c = campaign();
    let gcode = rectangle_on_track();
    let tcp = c.setup.tool().tcp;
    // RAPID's tooldata states the tool's mass (joint targets move with it too): a light spindle.
    let payload = stiffid::internal::setup::Payload {
        mass: 1e-3,
        centre: tcp,
        inertia: nalgebra::Matrix3::zeros(),
    };
    let calibrated = (c.setup.to_builder())
        .with_controller(Controller {
            kinematics: Kinematics::Calibrated,
            ..Default::default()
        })
        .build()
        .unwrap();
    let path = "track cell, robot programs";
    for (who, setup, model) in [
        ("nominal", &c.setup, &c.nominal),
        ("calibrated", &calibrated, c.setup.robot()),
    ] {
        for dialect in Dialect::ALL {
            for targets in [Targets::Joint, Targets::Cartesian] {
                let setup = match (dialect, targets) {
                    (Dialect::Rapid, _) => {
                        setup.to_builder().with_payload(payload).build().unwrap()
                    }
                    (Dialect::Inform, _) => with_pulses(setup),
                    _ => setup.clone(),
                };
                // INFORM writes whole pulses: its values are exact to half a pulse.
                let (per_deg, per_mm) = match dialect {
                    Dialect::Inform => (
                        PULSES_PER_DEG.iter().copied().fold(f64::MAX, f64::min),
                        PULSES_PER_MM,
                    ),
                    _ => (f64::INFINITY, f64::INFINITY),
                };
                let output = (Language::Robot(dialect), targets);
                let (text, results) = written_from(&setup, &c.compliance, (&c.q0, &gcode), output);
                let read = read_back(&text, dialect);
                assert_eq!(read.len(), results.len());
                let mut previous = results[0].q;
                let track = 0.5e-3 / per_mm + 1e-9;
                let commanded: Vec<(Vector6<f64>, f64)> = (read.iter().zip(&results))
                    .map(|((q, pose, s), r)| {
                        assert!((s - r.external.as_slice()[0]).abs() < track, "{s}");
                        let q = match (q, pose) {
                            (Some(q), _) => *q,
                            (None, Some(pose)) => controller(model, &tcp, pose, *s, &previous),
                            _ => unreachable!(),
                        };
                        // A language that writes no pose writes the axis angles (pulses).
                        let poses = (dialect.controller().generator())
                            .is_some_and(|g| g.writes_cartesian());
                        let tolerance = match (targets, poses) {
                            (Targets::Cartesian, true) => 1e-6,
                            _ => 1e-9 + (0.5 / per_deg).to_radians(),
                        };
                        assert!(
                            (q - r.q_compensated).amax() < tolerance,
                            "{who} {dialect:?} {targets:?}: {}",
                            (q - r.q_compensated).amax()
                        );
                        previous = q;
                        (q, *s)
                    })
                    .collect();
                let row = errors(&c.truth, &c.frame, &results, (&commanded, track));
                let std: Vec<f64> = results
                    .iter()
                    .filter_map(|r| r.translation_norm_std)
                    .collect();
                let expected = c.held_rms + std.iter().sum::<f64>() / std.len().max(1) as f64;
                let what = format!("{who} controller, {dialect:?}, {} targets", targets.name());
                print(path, &what, &row);
                assert!(row.mean <= 3.0 * expected, "{what}: {row:?} vs {expected}");
                assert!(row.mean <= 0.05e-3, "{what}: {row:?}");
            }
        }
    }
}

/// `[controller] pulses_per_deg` and `external_pulses` on the track cell: read as given, the
/// external count the cell's (one track), every number within 1e-6 to 1e9; anything else refused
/// naming the file and the field, never a job in wrong pulses.
#[test]
fn the_controllers_pulses_are_read_and_checked_against_the_cell() {
    let robot = true_robot::dh_robot_text()
        + "\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1.0, 0.0, 0.0]\nlimits_mm = [0.0, 6000.0]\n";
    let read = |controller: &str| {
        let text = true_robot::setup_text("robot.toml", "") + "\n[controller]\n" + controller;
        stiffid::internal::setup::parse(&text, "cell.toml", |_, _| {
            stiffid::internal::robot::file::parse(&robot, "robot.toml")
        })
    };
    let setup = read("pulses_per_deg = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7]\nexternal_pulses = [1000]\n").unwrap();
    let pulses = setup.workcell().controller().pulses.clone().unwrap();
    assert_eq!(pulses.per_deg, PULSES_PER_DEG);
    assert_eq!(pulses.external, vec![PULSES_PER_MM]);
    // The arm at a station of the track (what a design for the fixed arm, `select --for
    // calibration --station`, works on) keeps the robot's pulses and drops the track's with it.
    let at = setup.at_station(&[2.0]).unwrap();
    assert!(at.robot().external().is_none());
    let kept = at.workcell().controller().pulses.clone().unwrap();
    assert_eq!((kept.per_deg, kept.external.len()), (PULSES_PER_DEG, 0));
    // Without external_pulses the track is written in mm.
    let setup = read("pulses_per_deg = [1000, 1000, 1000, 1000, 1000, 1000]\n").unwrap();
    assert!(setup
        .workcell()
        .controller()
        .pulses
        .as_ref()
        .unwrap()
        .external
        .is_empty());
    let six = "pulses_per_deg = [1000, 1000, 1000, 1000, 1000, 1000]\n";
    for (controller, field, words) in [
        (
            format!("{six}external_pulses = [1000, 1000]\n"),
            "cell.toml: controller.external_pulses",
            "2 numbers for 1 external axes",
        ),
        (
            format!("{six}external_pulses = [nan]\n"),
            "cell.toml: controller.external_pulses",
            "NaN is outside [1e-6, 1e9] pulses per deg or mm",
        ),
        (
            "pulses_per_deg = [1000, 1000, -1000, 1000, 1000, 1000]\n".into(),
            "cell.toml: controller.pulses_per_deg[3]",
            "-1000 is outside",
        ),
        (
            "pulses_per_deg = [1000, 1000, 1000, 1000, 1000, 2e9]\n".into(),
            "cell.toml: controller.pulses_per_deg[6]",
            "is outside",
        ),
        (
            "external_pulses = [1000]\n".into(),
            "cell.toml: controller.external_pulses",
            "without pulses_per_deg",
        ),
    ] {
        match read(&controller) {
            Err(stiffid::Error::InvalidField { field: f, message }) => {
                assert_eq!(f, field, "{controller}: {message}");
                assert!(message.contains(words), "{controller}: {message}");
            }
            other => panic!("{controller}: {other:?}"),
        }
    }
}
