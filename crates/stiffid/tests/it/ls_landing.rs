//! An LS program as a FANUC controller stores it lands on the simulated true robot of
//! [`crate::true_robot`]: Cartesian positions in user frame 1 (the fixture) and tool frame 1 by
//! number, three decimals, `UFRAME_NUM=1`, `UTOOL_NUM=1`, the frames' values in the setup's
//! `[controller] bases` and `tools` as the controller holds them; compensated and run by the
//! controller's nominal inverse kinematics, within 0.05 mm mean.

use crate::campaign_paths::print;
use crate::ls_corpus::{compensated_with, independent, pose};
use crate::true_robot::{
    calibrated, dh_case, postures, q0, rectangle, row, with_part, written_from, Truth, WRENCHES,
};
use nalgebra::{Isometry3, Point3, Translation3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::program::cartesian::flags::ConfigurationData;
use stiffid::internal::machining::program::generate::Targets;
use stiffid::internal::machining::program::ls::Config;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::model::Compliance;
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::ik;
use stiffid::internal::setup::{Controller, NumberedFrames};
use stiffid::Setup;

/// The user frame the controller holds as number 1, in its world: the fixture, a little off the
/// part's true place as a taught frame is (0.2 mm, 0.01 deg: the program's positions are
/// taught in it, so they follow it).
fn fixture(world_from_part: &Isometry3<f64>) -> Isometry3<f64> {
    world_from_part
        * Isometry3::new(
            nalgebra::Vector3::new(2e-4, -1e-4, 0.0),
            nalgebra::Vector3::new(0.0, 0.0, 1e-2f64.to_radians()),
        )
}

/// `setup` whose controller holds the fixture as user frame 1 and the tool as tool frame 1.
fn with_frames(setup: &Setup, user: &Isometry3<f64>) -> Setup {
    let c = setup.workcell().controller();
    let tool = c.adapter * Translation3::from(setup.tool().tcp);
    let controller = Controller {
        tools: NumberedFrames::new("controller.tools", &[(1, tool)]).unwrap(),
        bases: NumberedFrames::new("controller.bases", &[(1, *user)]).unwrap(),
        ..c.clone()
    };
    setup
        .to_builder()
        .with_controller(controller)
        .build()
        .unwrap()
}

/// The program as the controller stores it: the `/MN` of `plain` (stiffid's uncompensated
/// program, in user frame 0) in user frame 1 by number, its positions `poses` (the setup's base
/// frame) at axis angles `qs` stated in user frame 1 (`world_from_user`, `base_from_world`)
/// with three decimals, as the controller writes them.
fn stored(
    plain: &str,
    (poses, arms): (&[Isometry3<f64>], &[String]),
    base_from_user: &Isometry3<f64>,
) -> String {
    let (mn, _) = plain.split_once("/POS").unwrap();
    let mn = mn
        .replace("UFRAME_NUM=0", "UFRAME_NUM=1")
        .replace("! set UTOOL[1] to the tool: ;", "! tool 1: the spindle ;");
    let mut out = mn + "/POS\n";
    for (i, (p, arm)) in poses.iter().zip(arms).enumerate() {
        let local = base_from_user.inverse() * p;
        let t = local.translation.vector * 1e3;
        let (w, pitch, r) = local.rotation.euler_angles();
        let _ = write!(
            out,
            "P[{}]{{\n   GP1:\n\tUF : 1, UT : 1,\t\tCONFIG : '{arm}',\n\tX = {:9.3}  mm,\tY = {:9.3}  mm,\tZ = {:9.3}  mm,\n\tW = {:9.3} deg,\tP = {:9.3} deg,\tR = {:9.3} deg\n}};\n",
            i + 1,
            t.x,
            t.y,
            t.z,
            w.to_degrees(),
            pitch.to_degrees(),
            r.to_degrees()
        );
    }
    out + "/END\n"
}

#[test]
fn an_ls_program_stored_in_frames_by_number_lands_on_the_true_robot() {
    let case = dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let truth = Truth::new(&case.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = truth.readings(&fit, &WRENCHES, &mut rng);
    let held_postures = postures(12, &mut rng, case.angles);
    let held = truth.readings(&held_postures, &WRENCHES[..1], &mut rng);
    let (setup, compliance, frame, held_rms, _) = calibrated(&case, case.gravity, &data, &held);
    let compliance = compliance.unwrap();
    let q0 = q0(&case);
    let (setup, part) = with_part(&setup, &q0);
    let world = setup.program_world();
    let user = fixture(&(world.inverse() * part));
    let setup = with_frames(&setup, &user);
    let nominal = case.setup.robot();
    // stiffid's program of the rectangle, uncompensated (no compliance): the nominal poses.
    let zero = Compliance {
        h: compliance.h.map(|_| 0.0),
        covariance: None,
        prediction: None,
        ..compliance.clone()
    };
    let output = (Language::Robot(Dialect::FanucLs), Targets::Cartesian);
    let (plain, nominal_results) = written_from(&setup, &zero, (&q0, &rectangle()), output);
    let poses: Vec<Isometry3<f64>> = nominal_results.iter().map(|r| r.pose).collect();
    let arms: Vec<String> = (nominal_results.iter())
        .map(|r| Config::of(&Configuration::of(nominal, &r.q)).to_string())
        .collect();
    let text = stored(&plain, (&poses, &arms), &(world * user));
    assert!(
        !text.contains("UF : 0") && !text.contains("set UTOOL"),
        "{text}"
    );
    // Compensated as found.
    let mut options = Options::for_setup(&setup);
    options.q0 = q0;
    let (out, results) =
        compensated_with(&setup, &compliance, options, ("rect.ls", &text)).unwrap();
    // Read back independently and run by the controller: its inverse kinematics of each
    // position in user frame 1, from the previous posture.
    let written = independent(&out);
    assert_eq!(written.len(), results.len());
    let mut previous = results[0].q;
    let errors: Vec<f64> = (written.iter().zip(&results))
        .map(|(w, r)| {
            assert_eq!(w.frames, (1, 1));
            let target = world * user * pose(&w.values);
            let tcp = &setup.tool().tcp;
            let q = ik::solve(nominal, tcp, &target, &previous, &ik::Options::default())
                .unwrap()
                .q;
            // Three decimals in, nine out: the controller's posture is the compensated one.
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
    let landed = row(&errors);
    let std: Vec<f64> = results
        .iter()
        .filter_map(|r| r.translation_norm_std)
        .collect();
    let expected = held_rms + std.iter().sum::<f64>() / std.len().max(1) as f64;
    print(
        "LS stored by number",
        "Cartesian positions in UF 1, UT 1",
        &landed,
    );
    assert!(landed.mean <= 3.0 * expected, "{landed:?} vs {expected}");
    assert!(landed.mean <= 0.05e-3, "{landed:?}");
}
