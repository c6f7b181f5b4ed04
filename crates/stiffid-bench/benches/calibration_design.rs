//! Design for calibration on the FANUC R-2000iC/165F preset, 12 postures x 3 measuring points
//! (20 test postures): one evaluation of every calibration criterion (O1, O3, O4, O5,
//! D-optimality, the predicted error) with full geometry and lumped gravity terms (55 kept
//! parameters), without a gradient; one value of the default criterion (the predicted error)
//! with its exact gradient, with the lumped terms (55) and with full geometry, the six
//! compliances under known masses and a fourth measuring point (41 kept parameters); a
//! campaign's step (12 postures scored after 12 fixed) on a fixed base and on a 6 m track (its
//! direction and error motions of order 3 designed for); and the default global search for
//! calibration (12 postures) in the guide's tracker cell.
//!
//! Measured in CPU time, not wall time: the evaluations in the calling thread's, the search in
//! the whole process's (its worker threads too), so that a machine shared with other work
//! gives the time the computation takes rather than the other programs' turns.

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::app::purpose::{self, CalibrationOptions};
use stiffid::internal::design::observability::{CalibrationCriterion, CalibrationDesign, Placed};
use stiffid::internal::design::{self, CalibrationGoal, Goal, SearchOptions};
use stiffid::internal::metrology::calibration::error_model::MeasuredIn;
use stiffid::internal::metrology::calibration::{gravity, ErrorModel, Geometry};
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis};
use stiffid::internal::robot::{presets, LinkMass};
use stiffid::internal::study::observability::postures;
use stiffid::Robot;

/// The design on the preset with the gravity model `g`, and a group of 12 postures.
fn fanuc(
    g: impl Fn(&Robot) -> gravity::Terms,
    points: &[Vector3<f64>],
) -> (CalibrationDesign, Vec<nalgebra::Vector6<f64>>) {
    let (model, reference, test, group) = fanuc_model(g, points);
    let design = CalibrationDesign::new(model, 1.0, &reference, &test, 5e-5).unwrap();
    (design, group)
}

/// The same on a 6 m track along x, its error motions of order 3 designed for: the reference
/// and test postures dealt over six stations, the group scored at the first after 12 postures
/// fixed at the others (so 24 in the criterion).
fn fanuc_on_track(
    g: impl Fn(&Robot) -> gravity::Terms,
    points: &[Vector3<f64>],
) -> (CalibrationDesign, Vec<nalgebra::Vector6<f64>>) {
    let (arm, reference, test, group) = fanuc_model(g, points);
    let axis = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
    let robot = arm
        .robot()
        .clone()
        .with_external(Some(ExternalAxes::new(vec![axis]).unwrap()));
    let model = ErrorModel::new(
        &robot,
        points,
        MeasuredIn::Tracker,
        Geometry::Full,
        arm.gravity().clone(),
    )
    .unwrap()
    .with_external(&[3], 0)
    .unwrap();
    let stations = robot.external().unwrap().stations(6);
    let placed = |qs: &[nalgebra::Vector6<f64>]| -> Vec<Placed> {
        (qs.iter().enumerate())
            .map(|(i, q)| (*q, stations[i % 6]))
            .collect()
    };
    let design =
        CalibrationDesign::new_placed(model, 1.0, &placed(&reference), &placed(&test), 5e-5)
            .unwrap();
    let fixed: Vec<Placed> = (group.iter().enumerate())
        .map(|(i, q)| (*q, stations[1 + i % 5]))
        .collect();
    (design.on_station(stations[0], &fixed).unwrap(), group)
}

/// Postures, rad.
type Group = Vec<nalgebra::Vector6<f64>>;

/// The model, reference (60), test (20) and group (12) postures of [`fanuc`].
fn fanuc_model(
    g: impl Fn(&Robot) -> gravity::Terms,
    points: &[Vector3<f64>],
) -> (ErrorModel, Group, Group, Group) {
    let masses: [LinkMass; 6] = std::array::from_fn(|l| LinkMass {
        mass: 200.0 - 30.0 * l as f64,
        centre: Vector3::new(0.05 * l as f64, -0.03, 0.1 + 0.02 * l as f64),
        ..LinkMass::default()
    });
    let robot = presets::get("fanuc-r2000ic-165f")
        .unwrap()
        .with_masses(Some(masses));
    let model = ErrorModel::new(
        &robot,
        points,
        MeasuredIn::Tracker,
        Geometry::Full,
        g(&robot),
    )
    .unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let reference = postures(&robot, 60, &mut rng);
    let test = postures(&robot, 20, &mut rng);
    let group = postures(&robot, 12, &mut rng);
    (model, reference, test, group)
}

fn bench(c: &mut Criterion<Cpu>) {
    let mut points = vec![
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let lumped = |r: &Robot| gravity::Terms::lumped(r, stiffid::Coordinates::Axis);
    let (design, group) = fanuc(lumped, &points);
    assert_eq!(design.kept().len(), 55);
    c.bench_function("calibration criteria 12 postures 55 parameters", |b| {
        b.iter(|| design.evaluate(&group).unwrap())
    });
    let test_pose = CalibrationCriterion::TestPose;
    c.bench_function("calibration gradient 12 postures 55 parameters", |b| {
        b.iter(|| design.value_and_log_gradient(test_pose, &group))
    });
    // The same group after 12 fixed, with and without the track's columns: a campaign's step.
    let none = stiffid::internal::robot::external::ExternalValues::NONE;
    let fixed: Vec<Placed> = group.iter().map(|q| (*q, none)).collect();
    let step = design.on_station(none, &fixed).unwrap();
    c.bench_function("calibration gradient 12+12 postures 55 parameters", |b| {
        b.iter(|| step.value_and_log_gradient(test_pose, &group))
    });
    let (track, group) = fanuc_on_track(lumped, &points);
    let kept = track.kept().len();
    c.bench_function(
        &format!("calibration gradient 12+12 postures on a track {kept} parameters"),
        |b| b.iter(|| track.value_and_log_gradient(test_pose, &group)),
    );
    let masses = |r: &Robot| {
        let m = *r.masses().unwrap();
        let nominal = nalgebra::Vector6::repeat(2e-6);
        gravity::Terms::masses(r, m, stiffid::Coordinates::Axis, nominal).unwrap()
    };
    points.push(Vector3::new(0.12, 0.1, 0.15));
    let (design, group) = fanuc(masses, &points);
    assert_eq!(design.kept().len(), 41);
    c.bench_function("calibration gradient 12 postures 41 parameters", |b| {
        b.iter(|| design.value_and_log_gradient(test_pose, &group))
    });
}

/// The paper's setup in the guide's cell (floor, clearance, the tracker at (3000, -2000, 1500)
/// mm, line of sight and incidence).
fn tracker_cell() -> stiffid::Setup {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
        + "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n[tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\n";
    stiffid::internal::setup::parse(&text, "cell.toml", |r, _| presets::get(r)).unwrap()
}

fn search(c: &mut Criterion<Cpu>) {
    let setup = tracker_cell();
    let d = purpose::design(&setup, &CalibrationOptions::default()).unwrap();
    let goal = Goal {
        stiffness: stiffid::internal::design::Criterion::RelativeA,
        calibration: Some(CalibrationGoal {
            design: &d,
            criterion: CalibrationCriterion::TestPose,
            weight: 1.0,
        }),
    };
    let options = SearchOptions::default();
    let mut g = c.benchmark_group("calibration/search");
    g.sample_size(10);
    g.bench_function("global/test-pose/12-postures/tracker-cell", |b| {
        b.iter(|| design::global_for(&setup, &goal, 12, &options, &()).unwrap())
    });
    g.finish();
}

/// CPU time, ns: of the calling thread or of the whole process (`clock_gettime`).
#[derive(Clone, Copy)]
enum Cpu {
    Thread,
    Process,
}

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

unsafe extern "C" {
    fn clock_gettime(clock: i32, time: *mut Timespec) -> i32;
}

impl Cpu {
    fn now(self) -> u64 {
        #[cfg(target_os = "macos")]
        let clock = match self {
            Cpu::Thread => 16,
            Cpu::Process => 12,
        };
        #[cfg(not(target_os = "macos"))]
        let clock = match self {
            Cpu::Thread => 3,
            Cpu::Process => 2,
        };
        let mut t = Timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid, writable timespec; the clock ids are the platform's.
        let status = unsafe { clock_gettime(clock, &mut t) };
        assert_eq!(status, 0, "clock_gettime");
        t.tv_sec as u64 * 1_000_000_000 + t.tv_nsec as u64
    }
}

impl Measurement for Cpu {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        self.now()
    }
    fn end(&self, start: u64) -> u64 {
        self.now() - start
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &Nanoseconds
    }
}

/// Nanoseconds shown as criterion shows wall time.
struct Nanoseconds;

impl ValueFormatter for Nanoseconds {
    fn scale_values(&self, typical: f64, values: &mut [f64]) -> &'static str {
        let (factor, unit) = match typical {
            t if t < 1e3 => (1.0, "ns"),
            t if t < 1e6 => (1e-3, "us"),
            t if t < 1e9 => (1e-6, "ms"),
            _ => (1e-9, "s"),
        };
        values.iter_mut().for_each(|v| *v *= factor);
        unit
    }
    fn scale_throughputs(&self, _: f64, _: &Throughput, _: &mut [f64]) -> &'static str {
        "ns"
    }
    fn scale_for_machines(&self, _: &mut [f64]) -> &'static str {
        "ns"
    }
}

criterion_group! {
    name = evaluations;
    config = Criterion::default().with_measurement(Cpu::Thread);
    targets = bench
}
criterion_group! {
    name = searches;
    config = Criterion::default().with_measurement(Cpu::Process);
    targets = search
}
criterion_main!(evaluations, searches);
