//! The place job: its optimum against a dense grid search of the same placements, the same
//! result whatever the number of threads, the setup written back, never worse than the own or
//! the reach-only placement, a path file placed as the G-code of its points, and its refusals.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::place::{self, Effort, Region, Request, Work};
use stiffid::internal::machining::compensate::{Aggregate, Compliance, Options, PathPoint, Target};
use stiffid::internal::machining::process::Process;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::presets;
use stiffid::{Error, Setup};

const SETUP: &str = include_str!("../../../../examples/milling/fanuc-milling.toml");

/// A 60 mm straight cut along the part's x, seven points, the tool down the part's -Z.
const LINE: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n(operation: wall)\nG21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-4 F300\nF1800\nG1 X10\nG1 X20\nG1 X30\nG1 X40\nG1 X50\nG1 X60\n";

struct Inputs {
    setup: Setup,
    compliance: Compliance,
    program: Program,
    process: Process,
    options: Options,
}

fn inputs(program: &str) -> Inputs {
    let setup =
        stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n))
            .unwrap();
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(setup.model())
    .unwrap();
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let program = machining::read(program, Language::GCode, 1e-4).unwrap();
    let options = Options::for_setup(&setup);
    Inputs {
        setup,
        compliance,
        program,
        process,
        options,
    }
}

fn request<'a>(i: &'a Inputs, region: Region, effort: Effort) -> Request<'a> {
    Request {
        setup: &i.setup,
        setup_text: SETUP,
        compliance: &i.compliance,
        work: Work::Program {
            program: &i.program,
            process: &i.process,
        },
        options: &i.options,
        region,
        objective: Aggregate::Max,
        margin: 5f64.to_radians(),
        max_condition: 1000.0,
        effort,
    }
}

/// x and y around the example's part, the rotation fixed.
const SMALL: Region = Region {
    x: [0.9, 1.5],
    y: [-0.9, -0.3],
    rotation: [0.0, 0.0],
    free: None,
};

#[test]
fn placements_optimum_equals_a_dense_grid_search() {
    let i = inputs(LINE);
    let r = request(&i, SMALL, Request::EFFORT);
    let own = *i.setup.workpiece().unwrap();
    // Every 10 mm of the region: 61 x 61 placements.
    let n = 61;
    let mut dense: Option<(f64, f64, f64)> = None;
    for a in 0..n {
        for b in 0..n {
            let x = SMALL.x[0] + (SMALL.x[1] - SMALL.x[0]) * a as f64 / (n - 1) as f64;
            let y = SMALL.y[0] + (SMALL.y[1] - SMALL.y[0]) * b as f64 / (n - 1) as f64;
            let pose = Isometry3::from_parts(Translation3::new(x, y, 0.4), own.rotation);
            if let Ok(e) = place::evaluate(&r, &pose).unwrap()
                && dense.is_none_or(|d| e.peak < d.0)
            {
                dense = Some((e.peak, x, y));
            }
        }
    }
    let (best, x, y) = dense.unwrap();
    let report = place::run(&r).unwrap();
    let p = report.placed.base_from_part.translation.vector;
    // The search reaches the grid's best to within what 10 mm of grid spacing leaves.
    assert!(
        report.placed.peak <= best * (1.0 + 1e-4),
        "{} vs {best}",
        report.placed.peak
    );
    assert!(
        report.placed.peak >= best * (1.0 - 1e-2),
        "{} vs {best}",
        report.placed.peak
    );
    assert!(
        (p.x - x).abs() < 0.015 && (p.y - y).abs() < 0.015,
        "{p:?} vs {x}, {y}"
    );
    // Its own figures are those of the placement written.
    let again = place::evaluate(&r, &report.placed.base_from_part)
        .unwrap()
        .unwrap();
    assert_eq!(again, report.placed);
    assert!(report.placed.peak <= report.reach.peak);
    assert!(report.placed.peak <= report.own.as_ref().unwrap().peak);
}

#[test]
fn the_placement_is_the_same_whatever_the_threads_and_the_setup_reads_back() {
    let i = inputs(LINE);
    let region = Region {
        rotation: [-30f64.to_radians(), 30f64.to_radians()],
        ..SMALL
    };
    let effort = Effort {
        grid: 3,
        samples: 8,
        starts: 2,
        seed: 5,
    };
    let r = request(&i, region, effort);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| place::run(&r).unwrap());
    let many = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(|| place::run(&r).unwrap());
    assert_eq!(one.placed, many.placed);
    assert_eq!(one.reach, many.reach);
    assert_eq!(one.setup_text, many.setup_text);
    let written =
        stiffid::internal::setup::parse(&one.setup_text, "placed.toml", |n, _| presets::get(n))
            .unwrap();
    let w = written.workpiece().unwrap();
    let p = &one.placed.base_from_part;
    assert!((w.translation.vector - p.translation.vector).norm() < 1e-8);
    assert!(w.rotation.angle_to(&p.rotation) < 1e-9);
    // Everything but the [workpiece] table as read.
    let kept = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| !l.starts_with("base_from_part"))
            .map(String::from)
            .collect()
    };
    assert_eq!(kept(&one.setup_text), kept(SETUP));
    // Turned within +-30 deg about the base z axis, never tilted.
    let (roll, pitch, yaw) = p.rotation.euler_angles();
    assert!(roll.abs() < 1e-12 && pitch.abs() < 1e-12 && yaw.abs() <= 30f64.to_radians() + 1e-12);
}

#[test]
fn bad_requests_are_refused_naming_the_field() {
    let i = inputs(LINE);
    let inverted = Region {
        x: [1.5, 0.9],
        ..SMALL
    };
    let e = place::run(&request(&i, inverted, Request::EFFORT)).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidField { field, message } if field == "region_mm" && message.starts_with("1500, 900: expected")),
        "{e}"
    );
    let mut r = request(&i, SMALL, Request::EFFORT);
    r.effort.grid = 1;
    let e = place::run(&r).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidField { field, .. } if field == "grid"),
        "{e}"
    );
    // Out of reach: 5 m away.
    let far = Region {
        x: [5.0, 5.5],
        ..SMALL
    };
    let e = place::run(&request(&i, far, Request::EFFORT)).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidField { field, message } if field == "region_mm" && message.contains("no placement")),
        "{e}"
    );
}

/// The G-code line's points as a path file gives them for placement: each TCP pose and its
/// base-frame wrench in the part frame (at the own placement, what the G-code's process gives).
fn as_path(i: &Inputs) -> Vec<PathPoint> {
    let own = *i.setup.workpiece().unwrap();
    let arm = i.setup.arm();
    let report = machining::compensate(
        arm,
        Some(&own),
        &i.compliance,
        &i.program,
        &i.process,
        &i.options,
    )
    .unwrap();
    let back = own.rotation.inverse();
    report
        .points
        .iter()
        .map(|p| {
            let Target::Pose(pose) = p.target else {
                panic!("a G-code point is a pose")
            };
            assert_eq!(p.frame, Frame::Base);
            let f = back * p.wrench.fixed_rows::<3>(0).into_owned();
            let m = back * p.wrench.fixed_rows::<3>(3).into_owned();
            PathPoint {
                line: p.line,
                target: Target::Pose(own.inverse() * pose),
                wrench: Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z),
                frame: Frame::Base,
                external: p.external,
            }
        })
        .collect()
}

#[test]
fn a_path_file_is_placed_as_the_gcode_of_its_points() {
    let i = inputs(LINE);
    let points = as_path(&i);
    let region = Region {
        rotation: [-40f64.to_radians(), 40f64.to_radians()],
        ..SMALL
    };
    let effort = Effort {
        grid: 3,
        samples: 8,
        starts: 1,
        seed: 2,
    };
    let g = request(&i, region, effort);
    let mut p = request(&i, region, effort);
    p.work = Work::Path(&points);
    // The part moved and turned: the poses and the wrenches turn with it in both.
    let mut feasible = 0;
    for (x, y, a) in [(1.3, -0.7, 0.0), (1.1, -0.5, 35.0), (1.4, -0.8, -30.0)] {
        let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), f64::to_radians(a));
        let pose = Isometry3::from_parts(Translation3::new(x, y, 0.4), turn);
        let (eg, ep) = (
            place::evaluate(&g, &pose).unwrap(),
            place::evaluate(&p, &pose).unwrap(),
        );
        assert_eq!(eg.is_ok(), ep.is_ok(), "{eg:?} vs {ep:?}");
        if let (Ok(eg), Ok(ep)) = (eg, ep) {
            feasible += 1;
            assert!(
                (eg.peak - ep.peak).abs() <= 1e-9 * eg.peak,
                "{eg:?} vs {ep:?}"
            );
            assert!((eg.sum - ep.sum).abs() <= 1e-9 * eg.sum, "{eg:?} vs {ep:?}");
            assert_eq!((eg.worst_line, eg.points), (ep.worst_line, ep.points));
        }
    }
    assert!(feasible >= 2, "{feasible}");
    let (rg, rp) = (place::run(&g).unwrap(), place::run(&p).unwrap());
    let (a, b) = (&rg.placed.base_from_part, &rp.placed.base_from_part);
    assert!((a.translation.vector - b.translation.vector).norm() < 1e-6);
    assert!(a.rotation.angle_to(&b.rotation) < 1e-6);
    assert!((rg.placed.peak - rp.placed.peak).abs() <= 1e-9 * rg.placed.peak);
    assert_eq!(rg.setup_text, rp.setup_text);
}

#[test]
fn robot_programs_and_axis_angle_rows_are_refused_naming_why() {
    let i = inputs(LINE);
    let krl = "DEF a( )\nPTP {A1 -90, A2 -10, A3 -20, A4 0, A5 -60, A6 180}\nEND\n";
    let krl = machining::read(krl, Language::Robot(Dialect::Krl), 1e-4).unwrap();
    let mut r = request(&i, SMALL, Request::EFFORT);
    r.work = Work::Program {
        program: &krl,
        process: &i.process,
    };
    let e = place::run(&r).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidField { field, message } if field == "program" && message.starts_with("a KUKA KRL program's targets are joint targets (E6AXIS, AXIS, line 2 the first)")),
        "{e}"
    );
    let rows = "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n-90,-10,-20,0,-60,180,0,0,-100\n";
    let rows = place::read_path(&i.setup, "rows.csv", rows, Frame::Base).unwrap();
    r.work = Work::Path(&rows);
    let e = place::run(&r).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidField { field, message } if field == "path" && message.starts_with("line 2: axis angles")),
        "{e}"
    );
}

#[test]
fn a_built_in_setup_is_written_with_the_workpiece_appended() {
    let text = stiffid::internal::setup::builtin_text("fanuc-r2000ic-165f").unwrap();
    let pose = Isometry3::from_parts(
        Translation3::new(1.2, -0.3, 0.45),
        UnitQuaternion::from_euler_angles(0.0, 0.0, -20f64.to_radians()),
    );
    let out = place::with_workpiece(text, &pose);
    assert!(out.starts_with(text));
    let read =
        stiffid::internal::setup::parse(&out, "placed.toml", |n, _| presets::get(n)).unwrap();
    let w = read.workpiece().unwrap();
    assert!((w.translation.vector - pose.translation.vector).norm() < 1e-12);
    assert!(w.rotation.angle_to(&pose.rotation) < 1e-9);
    assert_eq!(read.name(), "fanuc-r2000ic-165f");
}
