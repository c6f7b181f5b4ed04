//! The free lead and tilt of the tool axis ([`FreeVariables::lead_tilt`]): the dynamic programming's
//! optimum equals an exhaustive search over every path of leans on a small grid (each lean's
//! bound computed independently, at the pose leaned by hand); no point's bound rises; every
//! chosen axis lies within the cone at the lead and tilt stated; the loaded tool lands on the
//! leaned pose; a cone for drilling and bad values are refused naming the field or option; a
//! streamed path's grid too large is refused naming its states per point and the most points.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::{
    self, Aggregate, Free, FreeVariables, LeadTilt, Model, Objective, Options, PathPoint, Target,
};
use stiffid::internal::machining::{self, process, Language};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::ExternalValues;
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Error, JobOption, Setup};

/// The FANUC milling example (a fixed base).
pub(crate) fn milling() -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap()
}

/// The path's own tool orientation: z pointing down.
fn down() -> UnitQuaternion<f64> {
    UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0)
}

/// `n` points of a line along +x (the feed), the tool pointing down, a base-frame force.
pub(crate) fn line(n: usize) -> Vec<PathPoint> {
    (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(Isometry3::from_parts(
                Vector3::new(1.30 + 0.05 * i as f64, -0.8, 0.4).into(),
                down(),
            )),
            wrench: Vector6::new(-300.0, 200.0, -250.0, 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: ExternalValues::NONE,
        })
        .collect()
}

/// The pose of `p` leaned by hand: its tool z turned towards the feed `f = +x` by `lead` and
/// towards `c = z x f` by `tilt` (rad), about the TCP.
fn leaned(p: &PathPoint, lead: f64, tilt: f64) -> Isometry3<f64> {
    let Target::Pose(pose) = &p.target else {
        unreachable!()
    };
    let z = pose.rotation * Vector3::z();
    let f = Vector3::x();
    let c = z.cross(&f);
    let axis = c * lead - f * tilt;
    Isometry3::from_parts(
        pose.translation,
        UnitQuaternion::from_scaled_axis(axis) * pose.rotation,
    )
}

/// Lead and tilt free within `cone_deg` in `step_deg` steps, minimising the bound.
fn options(s: &Setup, cone_deg: f64, step_deg: f64, aggregate: Aggregate) -> Options {
    let free = FreeVariables {
        free: vec![Free::LeadTilt(
            LeadTilt::checked(Some(cone_deg), step_deg).unwrap(),
        )],
        aggregate,
        ..FreeVariables::default()
    };
    Options {
        free,
        ..Options::for_setup(s)
    }
}

/// Point `i`'s bound at `(lead, tilt)` (rad), compensated alone at the pose leaned by hand.
fn bound_at(s: &Setup, points: &[PathPoint], i: usize, lead: f64, tilt: f64) -> Option<f64> {
    let p = PathPoint {
        target: Target::Pose(leaned(&points[i], lead, tilt)),
        ..points[i].clone()
    };
    let compliance = s.model_compliance("test").unwrap();
    let r = compensate::path(s.arm(), &compliance, &[p], &Options::for_setup(s)).ok()?;
    Some(r[0].budget.bound)
}

#[test]
fn the_leans_chosen_equal_the_exhaustive_optimum() {
    let s = milling();
    let points = line(4);
    let step = 5f64.to_radians();
    // A 5 x 5 grid of leans within a 10 deg cone: the 12 beyond it are not states.
    let bounds: Vec<Vec<Vec<Option<f64>>>> = (0..points.len())
        .map(|i| {
            (-2..=2)
                .map(|k| {
                    (-2..=2)
                        .map(|g| {
                            let (lead, tilt) = (k as f64 * step, g as f64 * step);
                            let inside = lead.hypot(tilt) <= 10f64.to_radians() + 1e-12;
                            inside
                                .then(|| bound_at(&s, &points, i, lead, tilt))
                                .flatten()
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    assert_eq!(
        bounds[0].iter().flatten().filter(|b| b.is_some()).count(),
        13
    );
    let compliance = s.model_compliance("test").unwrap();
    for aggregate in [Aggregate::Max, Aggregate::Sum] {
        let options = options(&s, 10.0, 5.0, aggregate);
        let results = compensate::path(s.arm(), &compliance, &points, &options).unwrap();
        let chosen: Vec<f64> = results.iter().map(|r| r.budget.bound).collect();
        // Each point's bound is the one computed by hand at the lead and tilt it states.
        for (i, r) in results.iter().enumerate() {
            let at = |v: f64| (v / step).round() as isize + 2;
            let by_hand = bounds[i][at(r.lead) as usize][at(r.tilt) as usize].unwrap();
            assert!((r.budget.bound - by_hand).abs() <= 1e-6 * by_hand, "{i}");
        }
        crate::free_station::assert_exhaustive_optimum(&chosen, &bounds, aggregate, (2, 2));
    }
}

/// With the rotation free too: no point's bound rises against the path's own axis; every chosen
/// axis (the forward kinematics of the chosen posture) makes with the path's own the angle
/// `sqrt(lead^2 + tilt^2)`, within the cone, leaning towards the feed by the lead and across it
/// by the tilt; lead and tilt change by at most one step between points; the TCP stays on the
/// path's point and the loaded tool at the compensated angles lands on the leaned pose to 0.1
/// micrometre.
#[test]
fn the_axis_chosen_lies_in_the_cone_and_the_tool_lands_on_it() {
    let s = milling();
    let points = line(12);
    let compliance = s.model_compliance("test").unwrap();
    let (cone, step) = (8f64.to_radians(), 2f64.to_radians());
    let mut options = options(&s, 8.0, 2.0, Aggregate::Max);
    options
        .free
        .set(Free::ToolRotation(crate::compensate::rotation(20.0, 10.0)));
    let results = compensate::path(s.arm(), &compliance, &points, &options).unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let z_own = down() * Vector3::z();
    let mut leaned_any = false;
    for (i, (p, r)) in points.iter().zip(&results).enumerate() {
        let before = r.bound_before.unwrap();
        assert!(r.budget.bound <= before * (1.0 + 1e-9), "{i}: rises");
        let z = r.pose.rotation * Vector3::z();
        let angle = z.dot(&z_own).clamp(-1.0, 1.0).acos();
        let a = r.lead.hypot(r.tilt);
        assert!(angle <= cone + 1e-9, "{i}: {angle} rad outside the cone");
        assert!((angle - a).abs() < 1e-7, "{i}: {angle} against {a}");
        let towards = z - z_own * z.dot(&z_own);
        let c = z_own.cross(&Vector3::x());
        if a > 0.0 {
            assert!(
                (towards.dot(&Vector3::x()) - a.sin() * r.lead / a).abs() < 1e-7,
                "{i}: lead"
            );
            assert!(
                (towards.dot(&c) - a.sin() * r.tilt / a).abs() < 1e-7,
                "{i}: tilt"
            );
        }
        leaned_any |= a > 0.0;
        if i > 0 {
            let previous = &results[i - 1];
            assert!(
                (r.lead - previous.lead).abs() <= step + 1e-12,
                "{i}: lead step"
            );
            assert!(
                (r.tilt - previous.tilt).abs() <= step + 1e-12,
                "{i}: tilt step"
            );
        }
        let Target::Pose(target) = &p.target else {
            unreachable!()
        };
        assert!((r.pose.translation.vector - target.translation.vector).norm() < 1e-9);
        let loaded = model.loaded_pose(&r.q_compensated, &r.wrench);
        let error = (loaded.translation.vector - target.translation.vector).norm();
        assert!(error < 1e-7, "{i}: {error} m");
        let turned = (loaded.rotation * Vector3::z()).angle(&z);
        assert!(turned < 1e-6, "{i}: the loaded axis {turned} rad off");
    }
    assert!(leaned_any, "the tool leans somewhere");
}

/// The lean of a pose by hand: the axis turned by `a = sqrt(lead^2 + tilt^2)`, towards the feed
/// by the lead and across it (`c = z x f`) by the tilt.
#[test]
fn the_lean_turns_the_axis_towards_the_feed_and_across_it() {
    let (z, f) = (-Vector3::z(), Vector3::x());
    let c = z.cross(&f);
    for (lead, tilt) in [(0.1, 0.0), (0.0, 0.07), (-0.05, 0.12), (0.0, 0.0)] {
        let turned = compensate::lean(&[f, c], lead, tilt) * z;
        let a: f64 = f64::hypot(lead, tilt);
        let expected =
            z * a.cos() + (f * lead + c * tilt) * if a > 0.0 { a.sin() / a } else { 0.0 };
        assert!((turned - expected).norm() < 1e-15, "{lead} {tilt}");
    }
}

/// A path file's lean needs its cone; bad values are refused naming the option.
#[test]
fn bad_cones_and_steps_are_refused_naming_the_option() {
    let refused = |cone: Option<f64>, step: f64| match LeadTilt::checked(cone, step) {
        Err(Error::InvalidOption { option, .. }) => option,
        other => panic!("{cone:?} {step}: {other:?}"),
    };
    for cone in [f64::NAN, -1.0, 0.0, 30.5, f64::INFINITY] {
        assert_eq!(refused(Some(cone), 0.5), JobOption::LeadTiltRange, "{cone}");
    }
    for step in [f64::NAN, -1.0, 0.0, 0.05, 10.5] {
        assert_eq!(refused(Some(10.0), step), JobOption::LeadTiltStep, "{step}");
    }
    assert_eq!(refused(None, 31.0), JobOption::LeadTiltStep);
    let surge = FreeVariables {
        free: vec![
            Free::ToolRotation(crate::compensate::rotation(10.0, 5.0)),
            Free::LeadTilt(LeadTilt::checked(Some(10.0), 2.0).unwrap()),
        ],
        minimise: Objective::Surge,
        ..FreeVariables::default()
    };
    let e = surge.validate();
    assert!(matches!(
        e,
        Err(Error::InvalidOption {
            option: JobOption::Minimise,
            ..
        })
    ));
    // A path file without a cone; a lean built by hand beyond the limits.
    let s = milling();
    let compliance = s.model_compliance("test").unwrap();
    let mut o = options(&s, 10.0, 2.0, Aggregate::Sum);
    o.free.set(Free::LeadTilt(LeadTilt {
        cone: None,
        ..o.free.lead_tilt().unwrap()
    }));
    let e = compensate::path(s.arm(), &compliance, &line(3), &o).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidOption { option: JobOption::LeadTiltRange, message } if message.contains("--free lead-tilt=-CONE..CONE")),
        "{e}"
    );
    o.free.set(Free::LeadTilt(LeadTilt {
        cone: Some(1.0),
        ..o.free.lead_tilt().unwrap()
    }));
    let e = compensate::path(s.arm(), &compliance, &line(3), &o).unwrap_err();
    assert!(
        matches!(
            e,
            Error::InvalidOption {
                option: JobOption::LeadTiltRange,
                ..
            }
        ),
        "{e}"
    );
    // A grid beyond the largest: 0.1 deg steps in a 30 deg cone on 2000 points.
    let o = options(&s, 30.0, 0.1, Aggregate::Sum);
    let e = compensate::path(s.arm(), &compliance, &line(2000), &o).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidOption { option: JobOption::LeadTiltStep, message } if message.contains("cells")),
        "{e}"
    );
}

/// A streamed path's grid past the limit is refused naming the states per path point and the
/// most points the limit allows (5e6 cells), not the points read when the check failed.
#[test]
fn a_streamed_grid_too_large_names_its_states_per_point() {
    let s = milling();
    let compliance = s.model_compliance("test").unwrap();
    let refused = |o: &Options| {
        let points = line(100).into_iter().map(Ok);
        match compensate::stream(s.arm(), &compliance, points, o, |_, _| Ok::<(), Error>(())) {
            Err(Error::InvalidOption { option, message }) => (option, message),
            other => panic!("{other:?}"),
        }
    };
    // 0.1 deg steps in a 30 deg cone: 601 x 601 = 361201 leans, floor(5e6 / 361201) = 13 points.
    let (option, message) = refused(&options(&s, 30.0, 0.1, Aggregate::Sum));
    assert_eq!(option, JobOption::LeadTiltStep);
    for part in [
        "0.1 deg within a cone of 30 deg makes 361201 leans x 1 rotations = 361201 states per path point",
        "at most 5e6 cells: at most 13 path points",
    ] {
        assert!(message.contains(part), "{part}: {message}");
    }
    assert!(!message.contains("x 14 path points"), "{message}");
    // With the rotation free in 1 deg steps over +-180 deg (361 rotations): 1.3e8 states.
    let mut o = options(&s, 30.0, 0.1, Aggregate::Sum);
    o.free
        .set(Free::ToolRotation(crate::compensate::rotation(180.0, 1.0)));
    let (_, message) = refused(&o);
    assert!(
        message.contains("361201 leans x 361 rotations = 130393561 states per path point"),
        "{message}"
    );
    assert!(
        message.contains("not one path point") && !message.contains("x 1 path"),
        "{message}"
    );
    // The rotation alone in 0.1 deg steps: 3601 rotations, at most 1388 points.
    let mut o = Options::for_setup(&s);
    o.free
        .set(Free::ToolRotation(crate::compensate::rotation(180.0, 0.1)));
    let points = line(1400).into_iter().map(Ok);
    let e = compensate::stream(s.arm(), &compliance, points, &o, |_, _| Ok::<(), Error>(()));
    let Err(Error::InvalidOption { option, message }) = e else {
        panic!("{e:?}");
    };
    assert_eq!(option, JobOption::ToolRotationStep);
    assert!(
        message.contains("3601 rotations = 3601 states per path point"),
        "{message}"
    );
    assert!(message.contains("at most 1388 path points"), "{message}");
}

const MILLING: &str = "name = \"finish\"\n[tool]\ndiameter_mm = 10\nflutes = 2\n[cut]\nfeed_per_tooth_mm = 0.05\naxial_depth_mm = 1\nradial_depth_mm = 2\nmode = \"down\"\n[coefficients]\npreset = \"al7075-t6\"\n";

/// A process file's cone: a milling operation's within [0, 30] deg, a drilling operation's
/// refused naming the file, the operation and why.
#[test]
fn a_process_file_gives_a_milling_cone_and_refuses_a_drilling_one() {
    let p = process::file::parse(&format!("{MILLING}[tool_axis]\ncone_deg = 10\n"), "p.toml");
    assert!((p.unwrap().operations[0].cone - 10f64.to_radians()).abs() < 1e-15);
    assert_eq!(
        process::file::parse(MILLING, "p.toml").unwrap().operations[0].cone,
        0.0
    );
    let e = process::file::parse(&format!("{MILLING}[tool_axis]\ncone_deg = 31\n"), "p.toml")
        .unwrap_err();
    assert!(e.to_string().contains("p.toml: tool_axis.cone_deg"), "{e}");
    let drilling = "[[operation]]\nname = \"holes\"\nkind = \"drilling\"\ntool = { diameter_mm = 8 }\ncut = { feed_per_rev_mm = 0.1 }\ncoefficients = { specific_energy_n_per_mm2 = 1000, specific_thrust_n_per_mm2 = 500 }\ntool_axis = { cone_deg = 5 }\n";
    let e = process::file::parse(drilling, "holes.toml").unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("holes.toml: operation[1].tool_axis.cone_deg") && text.contains("hole"),
        "{text}"
    );
}

/// A program takes each point's cone from its operation: the rapid moves keep the program's
/// axis, the cutting points lean within the operation's cone; a cone given as an option for a
/// program is refused (the process file gives it).
#[test]
fn a_program_leans_within_its_operations_cone() {
    let s = milling();
    let compliance = s.model_compliance("test").unwrap();
    let gcode = "(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90\nG0 X0 Y-100 Z10\nG1 Z0 F1000\nG1 X40\nG1 X80\nG1 X120 Y-90\nG1 X160\nG0 Z10\n";
    let program = machining::read(gcode, Language::GCode, 1e-5).unwrap();
    let process =
        process::file::parse(&format!("{MILLING}[tool_axis]\ncone_deg = 6\n"), "p.toml").unwrap();
    let mut o = options(&s, 6.0, 3.0, Aggregate::Max);
    o.free.set(Free::LeadTilt(LeadTilt {
        cone: None,
        ..o.free.lead_tilt().unwrap()
    }));
    let report =
        machining::compensate(s.arm(), s.workpiece(), &compliance, &program, &process, &o).unwrap();
    for (r, op) in report.results.iter().zip(&report.operations) {
        let a = r.lead.hypot(r.tilt);
        match op {
            None => assert_eq!(a, 0.0),
            Some(_) => assert!(a <= 6f64.to_radians() + 1e-12),
        }
        assert!(r.budget.bound <= r.bound_before.unwrap() * (1.0 + 1e-9));
    }
    o.free.set(Free::LeadTilt(LeadTilt {
        cone: Some(6f64.to_radians()),
        ..o.free.lead_tilt().unwrap()
    }));
    let e = machining::compensate(s.arm(), s.workpiece(), &compliance, &program, &process, &o)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::InvalidOption {
                option: JobOption::LeadTiltRange,
                ..
            }
        ),
        "{e}"
    );
}
