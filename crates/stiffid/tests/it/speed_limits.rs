//! The axes' speed limits at the program's feed (`compensate`'s free variables): on the track's
//! trim line a slow track keeps the free station's every move within its speed (checked from the
//! stations the job writes, against the feed and the TCP distance of the path file's rows),
//! where without the limit the optimum moves the track faster; a joint's limit binds the free
//! tool rotation; the path's own moves are kept when they break it themselves; bad values are
//! refused naming the file and the field; a URDF's speeds on some joints only survive the
//! calibrated robot file (`inf` for the others).

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use std::sync::Arc;
use stiffid::app::compensate::{self, document::Document, Input, Report};
use stiffid::internal::machining::compensate::{
    self as comp, speed_shares, Aggregate, Compensated, Free, FreeVariables, Objective, Options,
    PathPoint, Target,
};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::ExternalValues;
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Error, Setup};

const TRACK: &str = include_str!("../../../../examples/track/track-cell.toml");

/// The track cell, its track's largest speed `mm_s` (none: no limit).
fn track_cell(mm_s: Option<f64>) -> Setup {
    let text = match mm_s {
        None => TRACK.to_string(),
        Some(v) => TRACK.replacen(
            "offset_mm = 0.0\n",
            &format!("offset_mm = 0.0\nmax_speed_mm_s = {v}\n"),
            1,
        ),
    };
    setup::parse(&text, "track-cell.toml", |r, _| presets::get(r)).unwrap()
}

/// The trim line with a `feed_mm_s` column of `feed` (mm/s), and each row's x (mm).
fn trim(feed: f64) -> (String, Vec<f64>) {
    let text = include_str!("../../../../examples/track/trim.csv");
    let mut out = String::new();
    let mut x = Vec::new();
    for line in text.lines() {
        match line {
            l if l.starts_with('#') => out += &format!("{l}\n"),
            l if l.starts_with("x_mm") => out += &format!("{l},feed_mm_s\n"),
            l => {
                x.push(l.split(',').next().unwrap().parse::<f64>().unwrap());
                out += &format!("{l},{feed}\n");
            }
        }
    }
    (out, x)
}

/// The trim line compensated with the station free (+-1500 mm in 50 mm steps, the worst
/// bound): the report (its document) and each point's station chosen, mm.
fn on_track(s: &Setup, text: &str) -> (Report, Vec<f64>) {
    let options = Options {
        free: FreeVariables {
            free: vec![Free::Station(crate::compensate::station(1500.0, 50.0))],
            aggregate: Aggregate::Max,
            ..FreeVariables::default()
        },
        ..Options::for_setup(s)
    };
    let request = compensate::Request {
        names: Default::default(),
        setup: s,
        compliance: s.model_compliance("test").unwrap(),
        input: Input::Path {
            name: "trim.csv".into(),
            text,
            frame: Frame::Base,
        },
        options,
    };
    let mut stations = Vec::new();
    let report = compensate::run(
        request,
        |_, _: &[PathPoint], r: &[Compensated], _: &[Dynamics]| {
            stations.extend(r.iter().map(|r| r.external.as_slice()[0] * 1e3));
            Ok::<(), Error>(())
        },
    )
    .unwrap();
    (report.report, stations)
}

/// The track's highest share of `mm_s` along the path: each move's `|de| / (v dt)`, `dt` the
/// row's x step over the feed.
fn highest_share(stations: &[f64], x: &[f64], (feed, mm_s): (f64, f64)) -> f64 {
    (1..x.len())
        .map(|i| (stations[i] - stations[i - 1]).abs() / (mm_s * (x[i] - x[i - 1]).abs() / feed))
        .fold(0.0, f64::max)
}

#[test]
fn a_slow_track_keeps_the_free_station_within_its_speed() {
    let (feed, mm_s) = (100.0, 40.0);
    let (text, x) = trim(feed);
    let (free, unlimited) = on_track(&track_cell(None), &text);
    let free = free.document();
    // Without the limit the optimum follows the tool: 50 mm steps in 0.5 s, 2.5 times 40 mm/s.
    let before = highest_share(&unlimited, &x, (feed, mm_s));
    assert!((before - 2.5).abs() < 1e-9, "{before}");
    assert!(!free.speed_limits.checked);
    let (limited_report, limited) = on_track(&track_cell(Some(mm_s)), &text);
    let doc = limited_report.document();
    let after = highest_share(&limited, &x, (feed, mm_s));
    assert!(after <= 1.0 + 1e-12, "{after}");
    assert!(doc.speed_limits.checked);
    let track = doc.speed_limits.axes.iter().find(|a| a.axis == "track");
    let track = track.unwrap();
    assert_eq!(track.max_speed_mm_s, Some(40.0));
    assert!(track.chosen_highest_share.unwrap() <= 1.0);
    assert!(doc.feasibility.as_ref().unwrap().moves_refused_speed > 0);
    // A limit never lowers the worst bound.
    let peak = |d: &Document<'_>| d.summary.budget.max_bound_mm.unwrap();
    assert!(peak(&doc) >= peak(&free) - 1e-12);
}

/// The FANUC milling example on its fixed base, the largest speeds `rad_s` of its axes.
fn fanuc(rad_s: Vector6<f64>) -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let s = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let robot = s.robot().clone().with_max_speeds(rad_s).unwrap();
    s.to_builder().with_robot(robot).build().unwrap()
}

/// 8 points of a line along x, the tool down, under a force that turns 40 deg about z from
/// point to point.
fn line() -> Vec<PathPoint> {
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    (0..8)
        .map(|i| {
            let a = (40.0 * i as f64).to_radians();
            PathPoint {
                line: i as u64 + 2,
                target: Target::Pose(Isometry3::from_parts(
                    Vector3::new(1.3 + 0.01 * i as f64, -0.8, 0.4).into(),
                    down,
                )),
                wrench: Vector6::new(400.0 * a.cos(), 400.0 * a.sin(), -200.0, 0.0, 0.0, 0.0),
                frame: Frame::Base,
                external: ExternalValues::NONE,
            }
        })
        .collect()
}

/// The line compensated with the tool rotation free (+-30 deg in 5 deg steps), one second
/// between points.
fn rotated(s: &Setup) -> Vec<Compensated> {
    let mut options = Options {
        free: FreeVariables {
            free: vec![Free::ToolRotation(crate::compensate::rotation(30.0, 5.0))],
            minimise: Objective::Deflection,
            ..FreeVariables::default()
        },
        ..Options::for_setup(s)
    };
    let times: Vec<Option<f64>> = (0..8).map(|i| (i > 0).then_some(1.0)).collect();
    options.feasible.move_times = Some(Arc::from(times));
    let compliance = s.model_compliance("test").unwrap();
    comp::path(s.arm(), &compliance, &line(), &options).unwrap()
}

/// Each move's change of every axis, rad, with whether it is the path's own (no rotation at
/// either end).
fn moves(r: &[Compensated]) -> Vec<(Vector6<f64>, bool)> {
    (1..r.len())
        .map(|i| {
            let own = r[i].tool_rotation == 0.0 && r[i - 1].tool_rotation == 0.0;
            ((r[i].q - r[i - 1].q).abs(), own)
        })
        .collect()
}

#[test]
fn a_joint_speed_binds_the_free_tool_rotation() {
    let free = rotated(&fanuc(Vector6::repeat(f64::INFINITY)));
    // The axis that moves most in a move that turns the tool, and by how much.
    let (k, most) = (moves(&free).iter().filter(|m| !m.1))
        .flat_map(|m| (0..6).map(move |k| (k, m.0[k])))
        .fold((0, 0.0), |b, c| if c.1 > b.1 { c } else { b });
    assert!(most > 1e-3, "the rotation turns no axis: {most}");
    // Half that speed on that axis: a move that turns the tool keeps within it.
    let mut limit = Vector6::repeat(f64::INFINITY);
    limit[k] = most / 2.0;
    let s = fanuc(limit);
    let bound = rotated(&s);
    for (m, own) in moves(&bound) {
        assert!(
            own || m[k] <= most / 2.0 + 1e-12,
            "axis {}: {}",
            k + 1,
            m[k]
        );
    }
    assert!(bound.iter().map(|r| r.removed.speed).sum::<usize>() > 0);
    // The shares the document reports agree: the library's own at one second.
    let robot = s.robot();
    for i in 1..bound.len() {
        let at = |r: &Compensated| (r.q, ExternalValues::NONE);
        let ((q0, e0), (q1, e1)) = (at(&bound[i - 1]), at(&bound[i]));
        let share = speed_shares(robot, 1.0, (&q0, &e0), (&q1, &e1))[k];
        assert!((share - (q1[k] - q0[k]).abs() / (most / 2.0)).abs() < 1e-12);
    }
}

#[test]
fn the_paths_own_moves_are_kept_when_they_break_the_limit() {
    // Every axis at 1e-6 rad/s: the path's own moves along the line break it.
    let s = fanuc(Vector6::repeat(1e-6));
    let r = rotated(&s);
    assert!(
        moves(&r).iter().all(|m| m.1),
        "only the path's own moves remain"
    );
    assert!(r.iter().all(|r| r.tool_rotation == 0.0));
    let (q0, q1) = (r[0].q, r[1].q);
    let e = ExternalValues::NONE;
    let shares = speed_shares(s.robot(), 1.0, (&q0, &e), (&q1, &e));
    assert!(shares.iter().any(|v| *v > 1.0), "{shares:?}");
}

#[test]
fn bad_speeds_and_feeds_are_refused_naming_the_file_and_the_field() {
    let robot = include_str!("../../../stiffid-core/presets/kuka-kr210-robond.toml");
    let with = |v: &str| {
        robot.replacen(
            "convention =",
            &format!("max_speed_deg_s = {v}\nconvention ="),
            1,
        )
    };
    let err = |r: stiffid::Result<stiffid::Robot>| r.unwrap_err().to_string();
    let zero = err(stiffid::internal::robot::file::parse(
        &with("[0, 100, 100, 100, 100, 100]"),
        "kr210.toml",
    ));
    assert!(zero.contains("kr210.toml: max_speed_deg_s[1]"), "{zero}");
    let high = err(stiffid::internal::robot::file::parse(
        &with("[100, 100, 100, 100, 100, 2e4]"),
        "kr210.toml",
    ));
    assert!(high.contains("max_speed_deg_s[6]"), "{high}");
    let five = err(stiffid::internal::robot::file::parse(
        &with("[100, 100, 100, 100, 100]"),
        "kr210.toml",
    ));
    assert!(
        five.contains("kr210.toml") && five.contains("max_speed_deg_s"),
        "{five}"
    );
    let ok = stiffid::internal::robot::file::parse(
        &with("[100, 100, 100, 100, 100, 360]"),
        "kr210.toml",
    );
    assert!((ok.unwrap().max_speeds()[5] - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    // A rotary speed on the linear track.
    let wrong = TRACK.replacen(
        "offset_mm = 0.0\n",
        "offset_mm = 0.0\nmax_speed_deg_s = 10\n",
        1,
    );
    let wrong = setup::parse(&wrong, "cell.toml", |r, _| presets::get(r)).unwrap_err();
    let wrong = wrong.to_string();
    assert!(
        wrong.contains("cell.toml") && wrong.contains("(track).max_speed_deg_s"),
        "{wrong}"
    );
    let negative = TRACK.replacen(
        "offset_mm = 0.0\n",
        "offset_mm = 0.0\nmax_speed_mm_s = -5\n",
        1,
    );
    let negative = setup::parse(&negative, "cell.toml", |r, _| presets::get(r)).unwrap_err();
    assert!(
        negative.to_string().contains("max_speed_mm_s"),
        "{negative}"
    );
    // A feed of 0 in a path file: its line and column.
    let (text, _) = trim(0.0);
    let feeds = stiffid::internal::machining::path::feeds(&text)
        .unwrap_err()
        .to_string();
    assert!(
        feeds.contains("feed_mm_s") && feeds.contains("line 3"),
        "{feeds}"
    );
}

/// A URDF with `<limit velocity>` on joints 1-3 only (0: none on 4-6) gives a calibrated robot
/// file that reads back with the same limits on 1-3 and none on 4-6 (`inf`); `inf` is accepted
/// in a robot file, NaN, -inf, 0, negatives and more than 10 000 deg/s are refused naming the
/// axis.
#[test]
fn partial_urdf_speeds_survive_the_calibrated_robot_file() {
    use stiffid::internal::metrology::calibration::error_model::MeasuredIn;
    use stiffid::internal::metrology::calibration::{
        gravity, robot_file, ErrorModel, Estimate, Geometry,
    };
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/comau-nj165.urdf");
    let urdf = std::fs::read_to_string(path).unwrap();
    let parts: Vec<&str> = urdf.split(r#"velocity="2""#).collect();
    assert_eq!(parts.len(), 7, "six joints with a velocity");
    let mut text = parts[0].to_string();
    for (part, v) in parts[1..].iter().zip(["1.5", "2", "2.5", "0", "0", "0"]) {
        text += &format!(r#"velocity="{v}""#);
        text += part;
    }
    let robot = stiffid::internal::robot::urdf::parse(&text, "partial.urdf", None).unwrap();
    let want = [1.5, 2.0, 2.5, f64::INFINITY, f64::INFINITY, f64::INFINITY];
    assert_eq!(robot.max_speeds().as_slice(), want);
    let points = [Vector3::new(0.1, 0.0, 0.2)];
    let terms = gravity::Terms::none(&robot);
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Base, Geometry::Full, terms).unwrap();
    let estimate = Estimate {
        frame: Isometry3::identity(),
        values: model.nominal(),
    };
    let file = robot_file::robot_toml(&model, &estimate).unwrap();
    assert!(file.contains("max_speed_deg_s = ["), "{file}");
    let back = stiffid::internal::robot::file::parse(&file, "calibrated.toml").unwrap();
    for (got, want) in back.max_speeds().iter().zip(want) {
        match want.is_finite() {
            true => assert!((got - want).abs() < 1e-12 * want, "{got} {want}"),
            false => assert_eq!(*got, f64::INFINITY),
        }
    }
    // In a robot file: inf is no limit; NaN, -inf, 0, negatives and above 10 000 are refused.
    let robot = include_str!("../../../stiffid-core/presets/kuka-kr210-robond.toml");
    let with = |v: &str| {
        let line = format!("max_speed_deg_s = [100, 100, {v}, 100, 100, 100]\nconvention =");
        stiffid::internal::robot::file::parse(
            &robot.replacen("convention =", &line, 1),
            "kr210.toml",
        )
    };
    assert_eq!(with("inf").unwrap().max_speeds()[2], f64::INFINITY);
    for bad in ["nan", "-inf", "0", "-5", "10001"] {
        let message = with(bad).unwrap_err().to_string();
        assert!(
            message.contains("kr210.toml: max_speed_deg_s[3]"),
            "{bad}: {message}"
        );
    }
}
