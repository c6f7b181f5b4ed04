//! `stiffid calibrate` as a user runs it: the default (`--gravity auto --maps auto`, the model
//! chosen by the ladder) beside the model it picks given explicitly, on three simulated
//! campaigns read with tracker noise (0.02 mm per coordinate):
//! - `ur10 100x1`: a UR10 (Universal Robots' DH table) read at one point 109 mm along the flange
//!   axis at 100 postures, the true robot with 0.5 mm / 0.5 mrad geometric errors and a joint
//!   error map on joints 2 and 5 (a small picked model: the real UR10's tracker data calls for
//!   maps of 32 harmonics on five or six joints, docs/performance.md);
//! - `loaded 100x3x1`: the COMAU of the built-in `zhang2021-comau-nj165` setup, its first
//!   measuring point read unloaded and under two wrenches at 100 postures within the setup's
//!   bounds (300 readings), the drives 30 % more compliant than the setup's nominal;
//! - `ur10 1000x1`: the UR10 at 1000 postures; and `--cross-validate` of them with the default
//!   model.
//!
//! Before criterion runs, each case is run once with its process CPU time printed
//! (`/proc/self/stat`: every thread's, what `time` reports as user + sys). With the environment
//! variable `STIFFID_BENCH_DATA` naming a folder, the readings files are written there too (to run
//! `stiffid calibrate` on them).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{DVector, Isometry3, Point3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::app::calibrate::{self, GravitySpec, Report, Request};
use stiffid::app::readings::Request as Readings;
use stiffid::internal::common::choice::Choice;
use stiffid::internal::metrology::calibration::error_model::{MeasuredIn, Observation, Target};
use stiffid::internal::metrology::calibration::gravity;
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::{motions, ErrorModel, Geometry};
use stiffid::internal::robot::external::ExternalValues;
use stiffid::internal::robot::Robot;
use stiffid::Setup;

/// The UR10 (standard DH, Universal Robots' published table), joints within +-360 deg.
fn ur10() -> Robot {
    use stiffid::internal::robot::dh::{self, Convention, Row};
    let half = std::f64::consts::FRAC_PI_2;
    let rows = [
        (0.0, half, 0.1273),
        (-0.612, 0.0, 0.0),
        (-0.5723, 0.0, 0.0),
        (0.0, half, 0.163941),
        (0.0, -half, 0.1157),
        (0.0, 0.0, 0.0922),
    ];
    let joints = rows.map(|(a, alpha, d)| {
        dh::joint(
            Convention::StandardDh,
            &Row {
                a,
                alpha,
                d,
                theta_offset: 0.0,
            },
        )
    });
    let two_pi = 2.0 * std::f64::consts::PI;
    let limits = stiffid::internal::common::limits::JointBox::new(
        Vector6::repeat(-two_pi),
        Vector6::repeat(two_pi),
    );
    Robot::new("UR10", "Universal Robots DH table", joints, limits).unwrap()
}

/// The COMAU setup with the UR10 and one measuring point 109 mm along the flange axis.
fn ur10_setup() -> Setup {
    let comau = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    comau
        .to_builder()
        .with_robot(ur10())
        .with_measuring_points(vec![Vector3::new(0.0, 0.0, 0.109)])
        .build()
        .unwrap()
}

/// `n` postures drawn within +-0.6 of each joint's range clipped to +-2.6 rad.
fn postures(robot: &Robot, n: usize, rng: &mut ChaCha8Rng) -> Vec<Vector6<f64>> {
    let l = robot.limits();
    (0..n)
        .map(|_| {
            Vector6::from_fn(|i, _| {
                let (lo, hi) = (l.lower[i].max(-2.6), l.upper[i].min(2.6));
                0.5 * (lo + hi) + 0.6 * (hi - lo) * (rng.random::<f64>() - 0.5)
            })
        })
        .collect()
}

/// The true values of `model`: 0.5 mm / 0.5 mrad on every joint error, the maps' coefficients
/// 0.1 mrad over their harmonic, the compliances 30 % above nominal.
fn truth(model: &ErrorModel, rng: &mut ChaCha8Rng) -> DVector<f64> {
    let mut x = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        let u = 2.0 * rng.random::<f64>() - 1.0;
        match p.target {
            Target::Map { harmonic, .. } => x[c] = 1e-4 * u / harmonic as f64,
            Target::Joint { .. } => x[c] += 5e-4 * u,
            _ if p.name.starts_with("compliance") => x[c] *= 1.3,
            _ => {}
        }
    }
    x
}

/// A readings file of `truth` at `qs` under `wrenches` (load steps when more than one), every
/// measuring point, with tracker noise.
fn readings(
    model: &ErrorModel,
    x: &DVector<f64>,
    qs: &[Vector6<f64>],
    wrenches: &[Vector6<f64>],
    rng: &mut ChaCha8Rng,
) -> String {
    let tracker = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.0, 0.0, 2.5));
    let noise = Normal::new(0.0, 2e-5).unwrap();
    let loaded = wrenches.len() > 1;
    let mut text = match loaded {
        true => stiffid::internal::io::readings::header_with_loads(),
        false => stiffid::internal::io::readings::header(),
    } + "\n";
    for (i, q) in qs.iter().enumerate() {
        let deg: Vec<String> = q.iter().map(|v| format!("{:?}", v.to_degrees())).collect();
        for (step, wrench) in wrenches.iter().enumerate() {
            for k in 0..model.points() {
                let o = Observation {
                    posture: i,
                    point: k,
                    q: *q,
                    measured: Vector3::zeros(),
                    wrench: *wrench,
                    e: ExternalValues::NONE,
                    table: false,
                    direction: Vector6::zeros(),
                };
                let b = model.predict(x, &[o]).unwrap()[0];
                let t = tracker.inverse() * Point3::from(b);
                let t = t.coords.map(|v| (v + noise.sample(rng)) * 1e3);
                let load = match loaded {
                    true => format!("{step},{:?},{:?},{:?},", wrench[0], wrench[1], wrench[2]),
                    false => String::new(),
                };
                text += &format!(
                    "P{},{},{},{load}{:?},{:?},{:?}\n",
                    i + 1,
                    k + 1,
                    deg.join(","),
                    t.x,
                    t.y,
                    t.z
                );
            }
        }
    }
    text
}

/// The UR10 campaign of `n` postures.
fn ur10_campaign(n: usize) -> (Setup, String) {
    let setup = ur10_setup();
    let robot = setup.robot();
    let points = &setup.tool().measuring_points;
    let model = ErrorModel::new(
        robot,
        points,
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(robot),
    )
    .unwrap()
    .with_maps([0, 8, 0, 0, 4, 0])
    .unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(n as u64);
    let x = truth(&model, &mut rng);
    let qs = postures(robot, n, &mut rng);
    let text = readings(&model, &x, &qs, &[Vector6::zeros()], &mut rng);
    (setup, text)
}

/// The COMAU's loaded campaign of 100 postures x 3 load steps x its first measuring point.
fn loaded_campaign() -> (Setup, String) {
    let comau = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let first = comau.tool().measuring_points[0];
    let setup = (comau.to_builder())
        .with_measuring_points(vec![first])
        .build()
        .unwrap();
    let robot = setup.robot();
    let model = ErrorModel::new(
        robot,
        &setup.tool().measuring_points,
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(robot),
    )
    .unwrap()
    .with_loads(&setup)
    .unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(25);
    let x = truth(&model, &mut rng);
    let l = setup.bounds();
    let qs: Vec<Vector6<f64>> = (0..100)
        .map(|_| {
            Vector6::from_fn(|i, _| l.lower[i] + (l.upper[i] - l.lower[i]) * rng.random::<f64>())
        })
        .collect();
    let wrenches = [
        Vector6::zeros(),
        Vector6::new(800.0, -300.0, -1200.0, 0.0, 0.0, 0.0),
        Vector6::new(-500.0, 900.0, 400.0, 0.0, 0.0, 0.0),
    ];
    let text = readings(&model, &x, &qs, &wrenches, &mut rng);
    (setup, text)
}

/// The job's request on `text` with `gravity` and `maps`.
fn request<'a>(
    setup: &'a Setup,
    text: &'a str,
    (gravity, maps): (GravitySpec, Spec),
) -> Request<'a> {
    Request {
        readings: Readings {
            setup,
            setup_name: "bench".into(),
            name: "bench.csv".into(),
            text,
            force: false,
        },
        geometry: Geometry::Full,
        gravity,
        gravity_bound: None,
        validate: None,
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps,
        error_motions: motions::Spec::default(),
        level: None,
        update: false,
        refit: Default::default(),
        weight: None,
        urdf: false,
    }
}

/// The model the default picked, as options.
fn picked(report: &Report) -> (GravitySpec, Spec) {
    let maps = match &report.maps.choice {
        Some(c) if !c.maps.is_none() => Spec::Fixed(c.maps),
        _ => Spec::None,
    };
    (GravitySpec::Fixed(report.gravity), maps)
}

/// This process's CPU time (every thread, user + system), s.
fn cpu() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, a)| a);
    let fields: Vec<f64> = after
        .split_whitespace()
        .map(|f| f.parse().unwrap_or(0.0))
        .collect();
    // utime and stime, fields 14 and 15 of stat(5), the 12th and 13th after the name.
    (fields.get(11).unwrap_or(&0.0) + fields.get(12).unwrap_or(&0.0)) / 100.0
}

/// Runs `request` once, printing its CPU and wall time.
fn once(name: &str, request: &Request) -> Report {
    let (c, t) = (cpu(), std::time::Instant::now());
    let report = calibrate::run(request).unwrap().report;
    println!(
        "{name}: {:.2} s CPU, {:.2} s wall; {} {}",
        cpu() - c,
        t.elapsed().as_secs_f64(),
        report.gravity.name(),
        stiffid::internal::metrology::calibration::maps::name(
            &report
                .maps
                .choice
                .as_ref()
                .map_or(Default::default(), |c| c.maps)
        )
    );
    report
}

fn bench(c: &mut Criterion) {
    let auto = (GravitySpec::Auto, Spec::Auto);
    let ur10 = ur10_campaign(100);
    let loaded = loaded_campaign();
    let large = ur10_campaign(1000);
    if let Ok(dir) = std::env::var("STIFFID_BENCH_DATA") {
        for (name, (_, text)) in [
            ("ur10-100", &ur10),
            ("loaded-300", &loaded),
            ("ur10-1000", &large),
        ] {
            std::fs::write(std::path::Path::new(&dir).join(format!("{name}.csv")), text).unwrap();
        }
    }
    let mut group = c.benchmark_group("ladder");
    group.sample_size(10);
    for (name, (setup, text)) in [
        ("ur10 100x1", &ur10),
        ("loaded 100x3x1", &loaded),
        ("ur10 1000x1", &large),
    ] {
        let report = once(&format!("{name} default"), &request(setup, text, auto));
        let model = picked(&report);
        once(&format!("{name} picked"), &request(setup, text, model));
        group.bench_function(format!("{name} default"), |b| {
            b.iter(|| calibrate::run(&request(setup, text, auto)).unwrap())
        });
        group.bench_function(format!("{name} picked"), |b| {
            b.iter(|| calibrate::run(&request(setup, text, model)).unwrap())
        });
        if name == "ur10 1000x1" {
            let cross = Request {
                cross_validate: true,
                ..request(setup, text, auto)
            };
            once(&format!("{name} default --cross-validate"), &cross);
            group.bench_function(format!("{name} default --cross-validate"), |b| {
                b.iter(|| calibrate::run(&cross).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
