//! A real program as found, with a work offset (`G54`), tool length offsets (`G43` of two
//! tools, from the process's tool table), full-circle arcs and spindle codes (LinuxCNC's
//! `hk_ba20_testmill.ngc`, corpus `linuxcnc-two-tools.ngc`), compensated and run as joint
//! targets on the simulated true robot of [`crate::true_robot`]: it lands within 0.05 mm mean of
//! its path, as the rectangle of the campaign does.

use crate::true_robot::{
    calibrated, dh_case, joint_targets, postures, q0, row, with_part, written_with, Truth, WRENCHES,
};
use nalgebra::{Point3, UnitQuaternion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::machining::gcode::ProgramFrames;
use stiffid::machining::program::generate::Targets;
use stiffid::machining::program::Dialect;
use stiffid::machining::Language;

fn corpus(name: &str) -> String {
    let path = format!(
        "{}/tests/data/programs/gcode/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

#[test]
fn a_real_program_with_work_offset_tool_lengths_and_arcs_lands_on_the_true_robot() {
    let case = dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(78);
    let truth = Truth::new(&case.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = truth.readings(&fit, &WRENCHES, &mut rng);
    let held_postures = postures(12, &mut rng, case.angles);
    let held = truth.readings(&held_postures, &WRENCHES[..1], &mut rng);
    let (setup, compliance, frame, held_rms, _) = calibrated(&case, case.gravity, &data, &held);
    let q0 = q0(&case);
    let (setup, _) = with_part(&setup, &q0);
    // The program states no tool orientation: the setup's [workpiece] tool_rpy_deg does.
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let frames = ProgramFrames {
        tool: Some(down),
        ..Default::default()
    };
    let setup = setup
        .to_builder()
        .with_program_frames(frames)
        .build()
        .unwrap();
    let program = corpus("linuxcnc-two-tools.ngc");
    let process = corpus("process-two-tools.toml");
    let output = (Language::Robot(Dialect::Krl), Targets::Joint);
    let (krl, results) = written_with(
        &setup,
        &compliance.unwrap(),
        (&q0, &program, &process),
        output,
    );
    let qs = joint_targets(&krl);
    assert_eq!(qs.len(), results.len());
    // Both tools' circles: 2 x (approach, plunge, circle, retract) and the final moves.
    assert!(results.len() > 100, "{}", results.len());
    let errors: Vec<f64> = (qs.iter().zip(&results))
        .map(|(q, r)| {
            let want = frame.inverse() * Point3::from(r.pose.translation.vector);
            (truth.tcp_at(q, &r.wrench) - want.coords).norm()
        })
        .collect();
    let landed = row(&errors);
    eprintln!(
        "linuxcnc-two-tools.ngc on the true robot: TCP error mean {:.4} mm, max {:.4} mm (held-out RMS {:.4} mm)",
        landed.mean * 1e3,
        landed.max * 1e3,
        held_rms * 1e3
    );
    assert!(landed.mean <= 0.05e-3, "{landed:?}");
}
