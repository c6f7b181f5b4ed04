//! Every iterative solver says why it stopped: inverse kinematics in its error, the
//! compensation's Newton steps per point and in the compensate document, the non-negative least
//! squares in the identify document, with a `not-converged` warning when a result comes from
//! steps stopped at their limit. (The calibration's fit, the robust reweighting and the
//! non-negative least squares at its limit are tested beside their code.)

use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid::app::compensate::{run, Input, Report, Request};
use stiffid::internal::common::stop::Stop;
use stiffid::internal::common::warning::WarningKind;
use stiffid::internal::machining::compensate::{self, Compensated, Options, PathPoint};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::ik::{self, tool_pose};
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Error, Setup};

#[test]
fn the_nonnegative_fit_says_why_it_stopped_in_the_identify_document() {
    use stiffid::app::identify::{self, Options, Request};
    use stiffid::app::measurements::Data;
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let measured = crate::common::paper_measurements(&setup);
    // Displacements with the wrong sign: every compliance of the bounded fit sits at 0.
    let flipped: Vec<_> = (measured.iter().cloned())
        .map(|mut m| {
            m.displacement = -m.displacement;
            m
        })
        .collect();
    let run = |data: &[stiffid::internal::observation::Measurement], nonnegative: bool| {
        let report = identify::run(Request::<&[u8]> {
            progress: &(),
            setup_name: "paper".into(),
            setup: &setup,
            data: Data::Measurements(data.to_vec()),
            options: Options {
                nonnegative,
                ..Options::default()
            },
        })
        .unwrap();
        let document = serde_json::to_value(report.document()).unwrap();
        (report.warnings().to_vec(), document)
    };
    for data in [&measured, &flipped] {
        let (warnings, document) = run(data, true);
        assert_eq!(document["method"], "nonnegative-least-squares");
        assert_eq!(document["nonnegative_stop_reason"], "converged");
        assert!(!(warnings.iter()).any(|w| w.kind == WarningKind::NotConverged));
    }
    assert_eq!(
        run(&flipped, true).1["active_bounds"],
        serde_json::json!([true, true, true, true, true, true])
    );
    let (_, plain) = run(&measured, false);
    assert_eq!(plain["method"], "least-squares");
    assert_eq!(plain.get("nonnegative_stop_reason"), None);
}

#[test]
fn inverse_kinematics_says_why_a_pose_was_not_reached() {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let tcp = Vector3::new(0.1, 0.05, 0.25);
    let q0 = Vector6::new(-0.5, 0.2, -0.1, 0.3, -0.8, 0.4);
    let q = q0 + Vector6::new(0.3, -0.2, 0.25, -0.3, 0.2, 0.3);
    let target = tool_pose(&robot.frames(&q), &tcp);
    let options = ik::Options::default();
    let solved = ik::solve(&robot, &tcp, &target, &q0, &options).unwrap();
    assert!(solved.position_error <= options.position_tolerance);
    assert!(solved.iterations > 1, "{}", solved.iterations);
    // One step from 0.3 rad away, no restart: the descent is cut short, and the error says so.
    let one = ik::Options {
        max_iterations: 1,
        restarts: 0,
        ..options
    };
    let (position_error_mm, stop, starts, message) =
        unreachable(ik::solve(&robot, &tcp, &target, &q0, &one));
    assert_eq!((stop, starts), (Stop::IterationLimit, 1));
    assert!(position_error_mm > 1.0, "{position_error_mm}");
    assert!(
        message.contains("the closest of 1 start stopped at iteration-limit")
            && message.contains("more steps (max_iterations)"),
        "{message}"
    );
    // Ten metres away: every start creeps towards the edge of the workspace until its steps run
    // out, 6.9 m short.
    let far = Isometry3::translation(10.0, 0.0, 1.0);
    let (position_error_mm, stop, starts, message) =
        unreachable(ik::solve(&robot, &tcp, &far, &q0, &options));
    assert_eq!((stop, starts), (Stop::IterationLimit, 9));
    assert!(position_error_mm > 5000.0, "{position_error_mm}");
    assert!(
        message.contains("outside the workspace")
            && message.contains("the closest of 9 starts stopped at iteration-limit"),
        "{message}"
    );
}

/// The paper's COMAU with its TCP, and a path of its first four test postures under 300 N.
/// The position error (mm), stop reason, starts and message of an unreachable pose's error.
fn unreachable<T: std::fmt::Debug>(result: Result<T, Error>) -> (f64, Stop, usize, String) {
    match result.unwrap_err() {
        e @ Error::Unreachable {
            position_error_mm,
            stop,
            starts,
            ..
        } => (position_error_mm, stop, starts, e.to_string()),
        e => panic!("{e:?}"),
    }
}

fn comau_path() -> (Setup, String) {
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    let s = paper
        .to_builder()
        .with_tcp(paper.tool().tcp)
        .build()
        .unwrap();
    let mut text = String::from("q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n");
    for (i, q) in s.test_postures().iter().take(4).enumerate() {
        let deg: Vec<String> = q.iter().map(|a| a.to_degrees().to_string()).collect();
        text += &format!("{},{},0,{}\n", deg.join(","), 50.0 * i as f64, -300.0);
    }
    (s, text)
}

/// The compensate job on `comau_path` with at most `max_iterations` Newton steps per point: the
/// report and every point's result.
fn compensated(max_iterations: usize) -> Result<(Report, Vec<Compensated>), Error> {
    let (s, text) = comau_path();
    let request = Request {
        names: Default::default(),
        setup: &s,
        compliance: s.model_compliance("test").unwrap(),
        input: Input::Path {
            name: "path.csv".into(),
            text: &text,
            frame: Frame::Base,
        },
        options: Options {
            max_iterations,
            ..Options::for_setup(&s)
        },
    };
    let mut results = Vec::new();
    let report = run(
        request,
        |_, _: &[PathPoint], r: &[Compensated], _: &[Dynamics]| {
            results.extend_from_slice(r);
            Ok::<(), Error>(())
        },
    )?;
    Ok((report.report, results))
}

/// The compensate document's `summary` of `report`, as JSON.
fn summary(report: &Report) -> serde_json::Value {
    serde_json::to_value(report).unwrap()["summary"].clone()
}

#[test]
fn the_compensation_says_why_its_newton_steps_stopped() {
    // Left to their limit, every point's steps converge: no warning.
    let (report, full) = compensated(compensate::MAX_ITERATIONS).unwrap();
    assert_eq!(full.len(), 3);
    for c in &full {
        assert_eq!(c.stop, Stop::Converged);
        assert!(c.residual_position <= 1e-10);
        assert!((2..=6).contains(&c.iterations), "{}", c.iterations);
    }
    let kinds: Vec<WarningKind> = report.warnings.iter().map(|w| w.kind).collect();
    assert!(!kinds.contains(&WarningKind::NotConverged), "{kinds:?}");
    let s = summary(&report);
    assert_eq!(s["stop_reason"], "converged");
    assert_eq!(s["not_converged"], 0);

    // Two steps leave a residual within the 0.1 um required but above the aim: kept, with the
    // reason per point, in the document and in a warning.
    let (report, cut) = compensated(2).unwrap();
    let stopped: Vec<usize> = (0..cut.len())
        .filter(|&i| cut[i].stop == Stop::IterationLimit)
        .collect();
    assert!(!stopped.is_empty());
    for (c, f) in cut.iter().zip(&full) {
        assert_eq!(c.iterations, f.iterations.min(2));
        match c.stop {
            Stop::IterationLimit => {
                assert!(c.residual_position > 1e-10);
                assert!(c.residual_position <= 1e-7);
            }
            stop => assert_eq!((stop, c.q_compensated), (Stop::Converged, f.q_compensated)),
        }
    }
    let s = summary(&report);
    assert_eq!(s["stop_reason"], "iteration-limit");
    assert_eq!(s["not_converged"], stopped.len());
    let warning = (report.warnings.iter())
        .find(|w| w.kind == WarningKind::NotConverged)
        .unwrap();
    let lines: Vec<String> = stopped.iter().map(|i| (i + 2).to_string()).collect();
    assert!(
        warning.message.contains("stopped at their limit of 2 at")
            && warning.message.contains(&lines.join(", ")),
        "{}",
        warning.message
    );

    // One step leaves more than the 0.1 um required: the point is refused, with the reason.
    let e = compensated(1).unwrap_err().to_string();
    assert!(e.contains("after 1 Newton steps (iteration-limit"), "{e}");
    // And no step at all is not an option.
    let e = compensated(0).unwrap_err().to_string();
    assert!(e.contains("compensate::Options.max_iterations"), "{e}");
}
