//! Cartesian stiffness of one posture (target: under 1 microsecond) and compensating a
//! 10 000-point path on the FANUC R-2000iC/165F cell, postures given (under 100 ms on 2 cores) and
//! poses given, inverse kinematics included (under 1 s); and the same path with the jackknife+
//! prediction interval of every point's deflection, from the drives identified on the FANUC data
//! with leave-one-posture-out cross-validation (43 folds; target: under 50 ms beyond the
//! compensation); and the poses with one free variable, the rotation about the spindle on a grid
//! of 13 angles, minimising the worst point's error bound (the target: under 1 s); on the
//! example robot on a track, a 1 m trim line of 10 000 points with the station free (13 stations,
//! one free variable) and with the station and the rotation free (13 x 13 states).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Translation3, Vector6};
use std::hint::black_box;
use stiffid::internal::identify::cross_validation::{cross_validate, Method};
use stiffid::internal::identify::prediction::calibrate;
use stiffid::internal::identify::Identify;
use stiffid::internal::machining::compensate::{self, Options, PathPoint, Target};
use stiffid::internal::model::Compliance;
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::observation::Observations;
use stiffid::internal::robot::ik::{self, tool_pose};
use stiffid::internal::{observation::cartesian, setup};

/// The drives identified on the FANUC data with their jackknife+ calibration, as `identify
/// --cross-validate --out` stores them.
fn identified_with_prediction(s: &setup::Setup) -> Compliance {
    let text = include_str!("../../../examples/data/fanuc-r2000ic-165f/measurements.csv");
    let mut file = stiffid::internal::io::measurements::parse(text).unwrap();
    file.to_base_frame(s).unwrap();
    let obs = Observations::from_measurements(s.arm(), &file.measurements).unwrap();
    let id = obs.least_squares().unwrap();
    let cv = cross_validate(&obs, &id, obs.postures, Method::LeastSquares).unwrap();
    Compliance {
        h: nalgebra::DVector::from_column_slice(id.compliance.as_slice()),
        covariance: None,
        prediction: Some(calibrate(&obs, &cv, s.noise().displacement_sd())),
        own_weight: None,
        region: Default::default(),
        model_form: None,
    }
}

fn benches(c: &mut Criterion) {
    let s = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let q = s.test_postures()[0];
    let h = s.model_compliance("the bench").unwrap().h;
    c.bench_function("Cartesian stiffness of one posture (frames, J, K_x)", |b| {
        b.iter(|| {
            let frames = s.robot().frames(black_box(&q));
            cartesian::stiffness(s.arm(), &frames, &s.tool().tcp, &h)
        })
    });
    let frames = s.robot().frames(&q);
    c.bench_function("Cartesian stiffness, frames given (J, K_x)", |b| {
        b.iter(|| cartesian::stiffness(s.arm(), black_box(&frames), &s.tool().tcp, &h))
    });
    c.bench_function("Cartesian compliance, frames given (J, C_x)", |b| {
        b.iter(|| cartesian::compliance(s.arm(), black_box(&frames), &s.tool().tcp, &h))
    });
    let start = tool_pose(&frames, &s.tool().tcp);
    let n = 10_000;
    let poses: Vec<PathPoint> = (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            // 300 mm along x and 100 mm along y, 0.03 mm steps.
            target: Target::Pose(Translation3::new(3e-5 * i as f64, -1e-5 * i as f64, 0.0) * start),
            wrench: Vector6::new(0.0, 200.0, 0.0, 0.0, 0.0, 0.0),
            frame: Frame::Tool,
            external: stiffid::internal::robot::external::ExternalValues::NONE,
        })
        .collect();
    let compliance = s.model_compliance("the bench").unwrap();
    let options = Options {
        q0: q,
        ik: ik::Options::default(),
        free: compensate::FreeVariables::default(),
        level: 0.95,
        max_iterations: compensate::MAX_ITERATIONS,
        force_tolerance: compensate::budget::DEFAULT_FORCE_TOLERANCE,
        max_error: None,
        feasible: compensate::Feasible::for_setup(&s),
        map: false,
        map_over: compensate::MapVariable::Rotation,
        refine: 0,
    };
    let solved = compensate::path(s.arm(), &compliance, &poses, &options).unwrap();
    let postures: Vec<PathPoint> = poses
        .iter()
        .zip(&solved)
        .map(|(p, r)| PathPoint {
            target: Target::Posture(r.q),
            ..p.clone()
        })
        .collect();
    let mut group = c.benchmark_group("compensate 10 000 points");
    group.sample_size(10);
    group.bench_function("postures given", |b| {
        b.iter(|| compensate::path(s.arm(), &compliance, black_box(&postures), &options).unwrap())
    });
    group.bench_function("poses given (inverse kinematics)", |b| {
        b.iter(|| compensate::path(s.arm(), &compliance, black_box(&poses), &options).unwrap())
    });
    let identified = identified_with_prediction(&s);
    group.bench_function("postures given, identified drives", |b| {
        let plain = Compliance {
            prediction: None,
            own_weight: None,
            ..identified.clone()
        };
        b.iter(|| compensate::path(s.arm(), &plain, black_box(&postures), &options).unwrap())
    });
    group.bench_function(
        "postures given, identified drives, 95% jackknife+ intervals",
        |b| {
            b.iter(|| {
                compensate::path(s.arm(), &identified, black_box(&postures), &options).unwrap()
            })
        },
    );
    // One free variable: the rotation about the spindle, +-30 deg on a 5 deg grid (13 angles),
    // chosen by dynamic programming to minimise the worst point's error bound.
    let rotation = compensate::FreeRange::checked(&compensate::Variable::ToolRotation, 30.0, 5.0);
    let free = compensate::FreeVariables {
        free: vec![compensate::Free::ToolRotation(rotation.unwrap())],
        minimise: compensate::Objective::Bound,
        aggregate: compensate::Aggregate::Max,
    };
    let free_options = Options {
        free,
        ..options.clone()
    };
    group.bench_function(
        "poses given, free tool axis (13 angles) minimising the worst bound",
        |b| {
            b.iter(|| {
                compensate::path(s.arm(), &identified, black_box(&poses), &free_options).unwrap()
            })
        },
    );
    track(&mut group);
    group.finish();
}

/// The trim line of `examples/track` (1 m, 0.1 mm steps, the robot parked at 3000 mm) with the
/// station free (+-60 mm in 10 mm steps), alone and with the rotation (+-30 deg in 5 deg steps),
/// minimising the worst point's bound.
fn track(group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>) {
    use nalgebra::{Isometry3, UnitQuaternion, Vector3};
    use stiffid::internal::machining::compensate::{
        Aggregate, Free, FreeRange, FreeVariables, Variable,
    };
    use stiffid::internal::robot::external::ExternalValues;
    let text = include_str!("../../../examples/track/track-cell.toml");
    let s = setup::parse(text, "track-cell.toml", |name, _| {
        stiffid::internal::robot::presets::get(name)
    })
    .unwrap();
    let compliance = s.model_compliance("the bench").unwrap();
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let e = ExternalValues::new(&[3.0, 0.0, 0.0]).unwrap();
    let points: Vec<PathPoint> = (0..10_000)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(Isometry3::from_parts(
                Vector3::new(2.5 + 1e-4 * i as f64, 1.5, 0.9).into(),
                down,
            )),
            wrench: Vector6::new(-150.0, 250.0, -80.0, 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: e,
        })
        .collect();
    let alone = Options {
        free: FreeVariables {
            free: vec![Free::Station(
                FreeRange::checked(&Variable::Station, 60.0, 10.0).unwrap(),
            )],
            aggregate: Aggregate::Max,
            ..FreeVariables::default()
        },
        ..Options::for_setup(&s)
    };
    group.bench_function(
        "track, free station (13 stations) minimising the worst bound",
        |b| {
            b.iter(|| {
                compensate::path_on_track(s.arm(), &compliance, black_box(&points), &alone).unwrap()
            })
        },
    );
    let mut both = alone.clone();
    let rotation = FreeRange::checked(&Variable::ToolRotation, 30.0, 5.0).unwrap();
    both.free.set(Free::ToolRotation(rotation));
    group.bench_function(
        "track, station and rotation (13 x 13 states), worst bound",
        |b| {
            b.iter(|| {
                compensate::path_on_track(s.arm(), &compliance, black_box(&points), &both).unwrap()
            })
        },
    );
}

criterion_group!(compensate_benches, benches);
criterion_main!(compensate_benches);
