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
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(setup.model())
    .unwrap();
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
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
    compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        bounds.extend(r.iter().map(|r| r.budget.bound));
        Ok(())
    })?;
    Ok(bounds)
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
