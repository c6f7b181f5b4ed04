//! A real program as found, with a work offset (`G54`), tool length offsets (`G43` of two
//! tools, from the process's tool table), full-circle arcs and spindle codes (LinuxCNC's
//! `hk_ba20_testmill.ngc`, corpus `linuxcnc-two-tools.ngc`), and a Fusion 360 post's contour with
//! `G54`, arcs and spindle codes (`fusion360-personal-arcs.nc`), each compensated and run as joint
//! targets on the simulated true robot of [`crate::true_robot`]: it lands within 0.05 mm mean of
//! its path, as the rectangle of the campaign does.

use crate::true_robot::{
    calibrated, dh_case, joint_targets, postures, q0, row, with_part, written_with, Truth, WRENCHES,
};
use nalgebra::{Point3, UnitQuaternion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::internal::machining::gcode::ProgramFrames;
use stiffid::internal::machining::program::generate::Targets;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;

pub(crate) fn corpus(name: &str) -> String {
    let path = format!(
        "{}/tests/data/programs/gcode/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

/// The campaign's true robot, the setup calibrated on it with the part placed and the tool
/// down (the programs state no tool orientation), its compliance, the tracker's frame, the
/// start and the held-out RMS (m).
pub(crate) struct Prepared {
    pub(crate) truth: Truth,
    pub(crate) setup: stiffid::Setup,
    pub(crate) compliance: stiffid::internal::model::Compliance,
    pub(crate) frame: nalgebra::Isometry3<f64>,
    pub(crate) q0: nalgebra::Vector6<f64>,
    pub(crate) held_rms: f64,
}

pub(crate) fn prepared() -> Prepared {
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
    Prepared {
        truth,
        setup,
        compliance: compliance.unwrap(),
        frame,
        q0,
        held_rms,
    }
}

#[test]
fn a_real_program_with_work_offset_tool_lengths_and_arcs_lands_on_the_true_robot() {
    let Prepared {
        truth,
        setup,
        compliance,
        frame,
        q0,
        held_rms,
    } = prepared();
    // LinuxCNC's two tools (G54, G43 of both, full circles), and a Fusion 360 post's contour as
    // found (G54, 32 arcs, S5000 M3).
    for (name, process, at_least) in [
        ("linuxcnc-two-tools.ngc", "process-two-tools.toml", 100),
        ("fusion360-personal-arcs.nc", "process-fusion360.toml", 30),
    ] {
        let (program, process) = (corpus(name), corpus(process));
        let output = (Language::Robot(Dialect::Krl), Targets::Joint);
        let (krl, results) = written_with(&setup, &compliance, (&q0, &program, &process), output);
        let qs = joint_targets(&krl);
        assert_eq!(qs.len(), results.len());
        assert!(results.len() > at_least, "{name}: {}", results.len());
        let errors: Vec<f64> = (qs.iter().zip(&results))
            .map(|(q, r)| {
                let want = frame.inverse() * Point3::from(r.pose.translation.vector);
                (truth.tcp_at(q, &r.wrench) - want.coords).norm()
            })
            .collect();
        let landed = row(&errors);
        eprintln!(
            "{name} on the true robot: TCP error mean {:.4} mm, max {:.4} mm (held-out RMS {:.4} mm)",
            landed.mean * 1e3,
            landed.max * 1e3,
            held_rms * 1e3
        );
        assert!(landed.mean <= 0.05e-3, "{name}: {landed:?}");
    }
}
