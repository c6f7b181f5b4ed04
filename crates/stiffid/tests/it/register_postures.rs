//! Registration postures (`stiffid register --postures N`): better than random feasible
//! postures, feasible, the same for a seed whatever the thread count, and their predicted
//! standard deviation equal to a Monte Carlo of the Umeyama fit.

use crate::common::{paper_with, PAPER_CELL};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::cell::Checker;
use stiffid::internal::design::registration::{design, Options, LOAD_CHECKS};
use stiffid::internal::metrology::register::{self, Correspondence};
use stiffid::Setup;

fn cell() -> Setup {
    paper_with(PAPER_CELL).unwrap()
}

fn base_points(setup: &Setup, postures: &[Vector6<f64>]) -> Vec<Vector3<f64>> {
    let tool = &setup.tool().measuring_points;
    (postures.iter())
        .flat_map(|q| {
            let frames = setup.robot().frames(q);
            tool.iter().map(move |p| frames.point(p))
        })
        .collect()
}

#[test]
fn proposed_postures_beat_random_feasible_ones_and_pass_the_checks() {
    let setup = cell();
    let d = design(&setup, 5, &Options::default()).unwrap();
    assert_eq!(d.postures.len(), 5);
    let checker = Checker::new(&setup);
    for q in &d.postures {
        let f = checker.feasibility(q);
        let failing: Vec<_> = f.violations().map(|c| c.kind).collect();
        assert!(
            failing.iter().all(|k| LOAD_CHECKS.contains(k)),
            "{failing:?}"
        );
    }
    let sigma = setup.noise().reading_sd();
    // Twenty random feasible groups of five (Latin hypercube, redrawn until they pass the cell).
    let random: Vec<f64> = (1..=20)
        .map(|seed| {
            let group = stiffid::internal::design::random_group(&setup, 5, 100 + seed);
            sigma * register::rotation_std_per_noise(&base_points(&setup, &group))
        })
        .collect();
    let best_random = random.iter().copied().fold(f64::INFINITY, f64::min);
    let mut sorted = random.clone();
    sorted.sort_by(f64::total_cmp);
    println!(
        "rotation sd: proposed {:.3e} deg, random median {:.3e} deg (best {:.3e}), the design's own random median {:.3e} deg",
        d.rotation_std.to_degrees(),
        sorted[10].to_degrees(),
        best_random.to_degrees(),
        d.random_median_rotation_std.to_degrees()
    );
    assert!(d.rotation_std < best_random, "{random:?}");
    assert!(d.rotation_std < 0.6 * d.random_median_rotation_std);
    let by_svd = sigma * register::rotation_std_per_noise(&base_points(&setup, &d.postures));
    assert!((by_svd - d.rotation_std).abs() < 1e-9 * by_svd);
}

#[test]
fn the_same_seed_gives_the_same_postures_on_one_thread() {
    let setup = cell();
    let options = Options {
        candidates: 400,
        seed: 7,
        restarts: 4,
    };
    let many = design(&setup, 4, &options).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| design(&setup, 4, &options).unwrap());
    assert_eq!(many, one);
    let other = design(&setup, 4, &Options { seed: 8, ..options }).unwrap();
    assert_ne!(other.postures, many.postures);
}

#[test]
fn the_predicted_deviation_matches_a_monte_carlo_of_the_fit() {
    let setup = cell();
    let d = design(&setup, 5, &Options::default()).unwrap();
    // The tracker at the cell's position_mm: the predicted translation is of its origin.
    let truth = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.01, -0.02, 2.4));
    let base = base_points(&setup, &d.postures);
    let normal = Normal::new(0.0, setup.noise().reading_sd()).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let runs = 1000;
    let mut sum_sq = Vector6::zeros();
    for _ in 0..runs {
        let points: Vec<Correspondence> = (base.iter())
            .map(|b| Correspondence {
                base: *b,
                tracker: (truth.inverse() * Point3::from(*b)).coords
                    + Vector3::from_fn(|_, _| normal.sample(&mut rng)),
            })
            .collect();
        let fit = register::fit(&points).unwrap().base_from_tracker;
        let dp = fit.translation.vector - truth.translation.vector;
        let dr = (fit.rotation * truth.rotation.inverse()).scaled_axis();
        let x = Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z);
        sum_sq += x.component_mul(&x);
    }
    let monte_carlo = (sum_sq / runs as f64).map(f64::sqrt);
    let predicted = d.std();
    for k in 0..6 {
        let ratio = predicted[k] / monte_carlo[k];
        assert!((ratio - 1.0).abs() < 0.1, "parameter {k}: ratio {ratio}");
    }
}

#[test]
fn impossible_requests_are_refused_with_the_field() {
    let setup = cell();
    let e = design(&setup, 0, &Options::default()).unwrap_err();
    assert!(e.to_string().starts_with("postures:"), "{e}");
    let few = Options {
        candidates: 3,
        ..Options::default()
    };
    let e = design(&setup, 5, &few).unwrap_err().to_string();
    assert!(e.contains("5 asked for, but only"), "{e}");
    let one_point = stiffid::internal::setup::builtin("zhang2021-comau-nj165")
        .unwrap()
        .to_builder()
        .with_measuring_points(vec![Vector3::new(0.08, 0.08, 0.26)])
        .build()
        .unwrap();
    let e = design(&one_point, 2, &Options::default()).unwrap_err();
    assert!(e.to_string().contains("on more than one line"), "{e}");
}

/// On a cell with a track (its travel from 200 mm) and a turntable (from 10 deg), the readings
/// template carries the external axes' columns at the station the postures were chosen at (each
/// axis at the value of its travel nearest zero), and the template filled with noise-free
/// tracker readings registers as it is: the tracker's transform back to 1e-9.
#[test]
fn the_template_of_a_cell_with_external_axes_registers() {
    use stiffid::app::register as job;
    use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis};
    let base = cell();
    let axes = ExternalAxes::new(vec![
        ExternalAxis::linear("track", Vector3::x_axis(), 0.2, 4.0),
        ExternalAxis::rotary(
            "table",
            Vector3::new(2.0, 1.8, 0.0),
            Vector3::z_axis(),
            10f64.to_radians(),
            std::f64::consts::PI,
        ),
    ])
    .unwrap();
    let robot = base.robot().clone().with_external(Some(axes));
    let setup = base.to_builder().with_robot(robot).build().unwrap();
    let request = job::DesignRequest {
        setup: &setup,
        setup_name: "setup.toml".into(),
        postures: 5,
        options: Options::default(),
        force: false,
    };
    let report = job::propose(&request).unwrap();
    assert_eq!(report.design.external, vec![0.2, 10f64.to_radians()]);
    let template = report.document().readings_template;
    let mut lines = template.lines();
    assert_eq!(
        lines.next().unwrap(),
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,e1_mm,e2_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm"
    );
    let truth = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.01, -0.02, 2.4));
    let mut filled = template.lines().next().unwrap().to_string() + "\n";
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), 13, "{line}");
        assert_eq!(&cells[8..10], ["200.000000", "10.000000"]);
        let v: Vec<f64> = cells[2..10].iter().map(|c| c.parse().unwrap()).collect();
        let q = Vector6::from_fn(|i, _| v[i].to_radians());
        let e = [v[6] * 1e-3, v[7].to_radians()];
        let point: usize = cells[1].parse().unwrap();
        let b = setup
            .robot()
            .frames_at(&q, &e)
            .point(&setup.tool().measuring_points[point - 1]);
        let t = truth.inverse() * Point3::from(b) * 1e3;
        filled += &format!("{},{:?},{:?},{:?}\n", cells[..10].join(","), t.x, t.y, t.z);
    }
    let registered = job::run(&job::Request {
        setup_name: "setup".into(),
        setup: &setup,
        name: "registration.csv".into(),
        text: &filled,
        force: false,
    })
    .unwrap();
    let fit = registered.report.registration.base_from_tracker;
    assert!((fit.translation.vector - truth.translation.vector).norm() < 1e-9);
    assert!((fit.rotation * truth.rotation.inverse()).angle() < 1e-9);
}
