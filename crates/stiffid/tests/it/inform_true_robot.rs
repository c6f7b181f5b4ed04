//! An INFORM job stored as its controller stores it (no `'stiffid:` comment, no `///POSTYPE`,
//! tool file 1 in the setup's `[controller] tools`, the pulses the setup's) compensated and run
//! on the simulated true robot of [`crate::true_robot`]: it lands within 0.05 mm mean, each
//! written position the compensated angles to half a pulse (read back independently).

use crate::true_robot::{
    calibrated, dh_case, postures, q0, rectangle, row, with_part, written_from, Truth, WRENCHES,
};
use nalgebra::{Point3, Translation3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::app::compensate::{self as compensate, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::generate::{Settings, Targets};
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::setup::{Controller, JointTargets, NumberedFrames, Pulses};
use stiffid::Setup;

/// A GP-sized robot's pulses per degree (S, L, U, R, B, T).
const PER_DEG: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];

/// The job a controller stores for the postures `q` (rad): pulses without a form line, tool
/// file 1, a joint move to the first and linear moves after it.
fn stored_job(q: &[Vector6<f64>]) -> String {
    let n = q.len();
    let mut text =
        format!("/JOB\r\n//NAME WELD\r\n//POS\r\n///NPOS {n},0,0,0,0,0\r\n///TOOL 1\r\n");
    for (i, q) in q.iter().enumerate() {
        let p: Vec<String> = (q.iter().zip(&PER_DEG))
            .map(|(v, per)| ((v.to_degrees() * per).round() as i64).to_string())
            .collect();
        text += &format!("C{i:05}={}\r\n", p.join(","));
    }
    text += "//INST\r\n///DATE 2026/11/27 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\nDOUT OT#(1) ON\r\n";
    for i in 0..n {
        text += &match i {
            0 => format!("MOVJ C{i:05} VJ=20.00\r\n"),
            _ => format!("MOVL C{i:05} V=20.0 PL=0\r\n"),
        };
    }
    text + "DOUT OT#(1) OFF\r\nEND\r\n"
}

/// The positions of a job read independently: each `Cnnnnn=` line's pulses over [`PER_DEG`],
/// rad.
fn positions(text: &str) -> Vec<Vector6<f64>> {
    (text
        .lines()
        .filter(|l| l.starts_with('C') && l.contains('=')))
    .map(|l| {
        let values = l.split_once('=').unwrap().1.split(',');
        let deg: Vec<f64> = (values.zip(&PER_DEG))
            .map(|(v, per)| v.trim().parse::<i64>().unwrap() as f64 / per)
            .collect();
        Vector6::from_iterator(deg.into_iter().map(f64::to_radians))
    })
    .collect()
}

/// `job` compensated on `setup` and written back: its text and every target's result.
fn compensated(
    setup: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    q0: &Vector6<f64>,
    job: &str,
) -> (String, Vec<Compensated>) {
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let mut options = Options::for_setup(setup);
    options.q0 = *q0;
    let inform = Language::Robot(Dialect::Inform);
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance: compliance.clone(),
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "weld.jbi".into(),
            text: job,
            data: None,
            language: inform,
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output: inform,
            out_name: "weld.jbi".into(),
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
    (
        crate::common::program_text(report.report.program.unwrap()),
        results,
    )
}

#[test]
fn a_stored_inform_job_lands_on_the_true_robot() {
    let case = dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let truth = Truth::new(&case.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = truth.readings(&fit, &WRENCHES, &mut rng);
    let held_postures = postures(12, &mut rng, case.angles);
    let held = truth.readings(&held_postures, &WRENCHES[..1], &mut rng);
    let (setup, compliance, frame, _, _) = calibrated(&case, case.gravity, &data, &held);
    let compliance = compliance.unwrap();
    let q0 = q0(&case);
    let (setup, _) = with_part(&setup, &q0);
    // The milled rectangle's postures, stored as the controller stores a job.
    let output = (Language::Robot(Dialect::Krl), Targets::Joint);
    let (_, points) = written_from(&setup, &compliance, (&q0, &rectangle()), output);
    let job = stored_job(&points.iter().map(|r| r.q).collect::<Vec<_>>());
    assert!(!job.contains("'stiffid") && !job.contains("POSTYPE"));
    let c = setup.workcell().controller();
    let tool = c.adapter * Translation3::from(setup.tool().tcp);
    let controller = Controller {
        pulses: Some(Pulses {
            per_deg: PER_DEG,
            external: Vec::new(),
        }),
        tools: NumberedFrames::new("controller.tools", &[(1, tool)]).unwrap(),
        // The job holds postures of the true robot (the calibrated one's, as taught on it).
        joint_targets: Some(JointTargets::Taught),
        ..c.clone()
    };
    let setup = setup
        .to_builder()
        .with_controller(controller)
        .build()
        .unwrap();
    let (text, results) = compensated(&setup, &compliance, &q0, &job);
    let written = positions(&text);
    assert_eq!(written.len(), results.len());
    let half = (0.5 / PER_DEG.iter().copied().fold(f64::MAX, f64::min)).to_radians();
    let errors: Vec<f64> = (written.iter().zip(&results))
        .map(|(q, r)| {
            assert!((q - r.q_compensated).amax() <= half + 1e-12);
            let want = frame.inverse() * Point3::from(r.pose.translation.vector);
            (truth.tcp_at(q, &r.wrench) - want.coords).norm()
        })
        .collect();
    let landed = row(&errors);
    eprintln!(
        "stored INFORM job: TCP error mean {:.4} mm, max {:.4} mm",
        landed.mean * 1e3,
        landed.max * 1e3
    );
    assert!(landed.mean <= 0.05e-3, "{landed:?}");
}
