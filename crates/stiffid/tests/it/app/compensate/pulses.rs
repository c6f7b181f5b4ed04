//! A job in encoder pulses against the bound it must keep
//! (`stiffid::app::compensate::resolution`): coarse pulses (`pulses_per_deg = [1, ..]`,
//! a whole degree per pulse) are refused naming the field, the controller's own are written.

use nalgebra::Vector6;
use stiffid::app::compensate::resolution::rounding;
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::ik::tool_pose;
use stiffid::internal::robot::presets;
use stiffid::Error;

/// The milling example's cell with the controller's `pulses_per_deg`.
fn setup(per_deg: &str) -> stiffid::Setup {
    let text = include_str!("../../../../../../examples/milling/fanuc-milling.toml");
    let text = format!("{text}\n[controller]\npulses_per_deg = {per_deg}\n");
    stiffid::internal::setup::parse(&text, "cell.toml", |name, _| presets::get(name)).unwrap()
}

/// The milling example's pocket compensated on `setup` and written as an INFORM job: its bounds
/// (m), or the error.
fn job(setup: &stiffid::Setup) -> stiffid::Result<Vec<f64>> {
    job_warned(setup, "4").map(|(b, _)| b)
}

/// [`job`] at the axial depth `depth_mm` (the example's 4), with the job's warnings.
fn job_warned(setup: &stiffid::Setup, depth_mm: &str) -> stiffid::Result<(Vec<f64>, Vec<String>)> {
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(setup.model())
    .unwrap();
    let process = stiffid::internal::machining::process::file::parse(
        &include_str!("../../../../../../examples/milling/aluminium.toml").replacen(
            "axial_depth_mm = 4",
            &format!("axial_depth_mm = {depth_mm}"),
            1,
        ),
        "aluminium.toml",
    )
    .unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "pocket.nc".into(),
            text: include_str!("../../../../../../examples/milling/pocket.nc"),
            data: None,
            language: Language::GCode,
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-4,
            output: Language::Robot(Dialect::Inform),
            out_name: "pocket.jbi".into(),
            settings: Settings::default(),
        },
        options: Options::for_setup(setup),
    };
    let mut bounds = Vec::new();
    let outcome = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        bounds.extend(r.iter().map(|r| r.budget.bound));
        Ok(())
    })?;
    let warnings = outcome.warnings.iter().map(|w| w.message.clone()).collect();
    Ok((bounds, warnings))
}

/// The TCP motion of writing a posture in whole pulses: within the sum of each axis's half pulse
/// at the TCP (finite differences of the forward kinematics), hundredths of a mm at a
/// controller's pulses, tens of mm at one pulse per degree.
#[test]
fn rounding_is_within_each_axis_half_pulse_at_the_tcp() {
    let s = setup("[1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7]");
    let per_deg: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];
    let q = Vector6::new(10.3, 20.7, -30.4, 40.6, -50.2, 60.45).map(f64::to_radians);
    let tcp = s.tool().tcp;
    let at = |q: &Vector6<f64>| tool_pose(&s.robot().frames(q), &tcp).translation.vector;
    let half: f64 = (0..6)
        .map(|k| {
            let mut p = q;
            p[k] += (0.5 / per_deg[k]).to_radians();
            (at(&p) - at(&q)).norm()
        })
        .sum();
    let r = rounding(s.robot(), &tcp, &q, &per_deg);
    assert!(r > 1e-7 && r <= half * (1.0 + 1e-6), "{r} {half}");
    // One pulse per degree: the axes rounded to whole degrees, by hand.
    let whole = q.map(|v| v.to_degrees().round().to_radians());
    let coarse = rounding(s.robot(), &tcp, &q, &[1.0; 6]);
    assert!(
        (coarse - (at(&whole) - at(&q)).norm()).abs() < 1e-12,
        "{coarse}"
    );
    assert!(coarse > 1e-3, "{coarse}");
}

/// Issue #80: a job whose pulses round every axis to a whole degree (or to nothing, 1e-6 per
/// degree) is refused naming the field, never written with bounds of tenths of a mm; the
/// controller's pulses are written.
#[test]
fn coarse_pulses_are_refused_naming_the_field() {
    let bounds = job(&setup("[1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7]")).unwrap();
    assert!(!bounds.is_empty());
    for coarse in ["[1, 1, 1, 1, 1, 1]", "[1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6]"] {
        match job(&setup(coarse)) {
            Err(Error::InvalidField { field, message }) => {
                assert_eq!(field, "controller.pulses_per_deg", "{message}");
                assert!(
                    message.contains("rounding the axes to whole pulses moves the TCP by"),
                    "{message}"
                );
                assert!(
                    message.contains("more than the most the compensation corrects or bounds"),
                    "{message}"
                );
            }
            other => panic!("{coarse}: {other:?}"),
        }
    }
}

/// Pulses finer than a tenth of a mm at the TCP but coarser than what the compensation moves
/// (a light cut on a real controller's resolution) write the job with a warning stating the
/// rounding, never refuse it: somewhere between one pulse per degree (refused) and the
/// controller's 1341 (written silently) lies such a resolution.
#[test]
fn pulses_finer_than_a_controllers_resolution_are_written_with_the_rounding_stated() {
    let mut stated = None;
    // A light cut: 0.02 mm deep, the tool's weight and a few newtons of the process.
    for per_deg in [20.0, 40.0, 80.0, 160.0, 320.0, 640.0, 1280.0, 2560.0] {
        let s = setup(&format!("{:?}", [per_deg; 6]));
        let Ok((bounds, warnings)) = job_warned(&s, "0.02") else {
            continue;
        };
        assert!(!bounds.is_empty());
        if let Some(w) = warnings
            .iter()
            .find(|w| w.contains("rounding the axes to whole pulses"))
        {
            stated = Some((per_deg, w.clone()));
        }
    }
    let (per_deg, w) = stated.expect("a resolution between the compensation and 0.1 mm");
    assert!(
        w.contains("within a controller's resolution (0.1 mm)"),
        "{per_deg}: {w}"
    );
    let mm: f64 = w
        .split("moves the TCP by ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(mm > 0.0 && mm <= 0.1, "{w}");
}
