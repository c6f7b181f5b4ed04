//! The place job: its optimum against a dense grid search of the same placements, the same
//! result whatever the number of threads, the setup written back, never worse than the own or
//! the reach-only placement, and its refusals.

use nalgebra::{Isometry3, Translation3};
use stiffid::app::place::{self, search::Effort, Region, Request};
use stiffid::machining::compensate::{Aggregate, Compliance, Options};
use stiffid::machining::process::Process;
use stiffid::machining::{self, Language, Program};
use stiffid::robot::presets;
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
    let setup = stiffid::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap();
    let compliance =
        stiffid::io::stiffness::parse(include_str!("../../../../examples/milling/stiffness.json"))
            .unwrap()
            .compliance(setup.model())
            .unwrap();
    let process = stiffid::machining::process::file::parse(
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
        program: &i.program,
        process: &i.process,
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
            if let Ok(e) = place::evaluate(&r, &pose).unwrap() {
                if dense.is_none_or(|d| e.peak < d.0) {
                    dense = Some((e.peak, x, y));
                }
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
        stiffid::setup::parse(&one.setup_text, "placed.toml", |n, _| presets::get(n)).unwrap();
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
