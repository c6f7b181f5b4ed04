//! The error budget of compensated points: its parts against Monte Carlo over the stiffness
//! covariance and over held-out calibration errors, the bound as they combine, the free tool
//! axis minimising it, and the refusal of a path whose bound exceeds the largest error accepted.

use nalgebra::{DMatrix, DVector, Matrix6, Translation3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use stiffid::app::compensate::{run, Input, Request};
use stiffid::internal::common::error::JobOption;
use stiffid::internal::machining::compensate::{
    self, Aggregate, Compliance, Free, FreeVariables, Objective, Options, PathPoint, Target,
};
use stiffid::internal::observation::deflection::{Frame, Points};
use stiffid::internal::robot::ik::tool_pose;
use stiffid::{internal::setup, Error, Setup};

/// The FANUC setup loaded at its TCP, with a correlated covariance of 2% to 12% of each
/// compliance.
fn setup_and_compliance() -> (Setup, Compliance, Matrix6<f64>) {
    let s = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let tcp = s.tool().tcp;
    let s = s
        .to_builder()
        .with_loading_point(tcp)
        .with_tcp(tcp)
        .build()
        .unwrap();
    let mut compliance = s.model_compliance("test").unwrap();
    let h = compliance.drives_h();
    let sd = h.component_mul(&Vector6::new(0.02, 0.05, 0.03, 0.08, 0.12, 0.06));
    let mut corr = Matrix6::identity();
    corr[(1, 2)] = 0.6;
    corr[(2, 1)] = 0.6;
    corr[(3, 5)] = -0.4;
    corr[(5, 3)] = -0.4;
    let cov = Matrix6::from_diagonal(&sd) * corr * Matrix6::from_diagonal(&sd);
    compliance.covariance = Some(DMatrix::from_column_slice(6, 6, cov.as_slice()));
    (s, compliance, cov)
}

fn line_path(s: &Setup, n: usize) -> Vec<PathPoint> {
    let start = tool_pose(&s.robot().frames(&s.test_postures()[0]), &s.tool().tcp);
    (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(
                Translation3::new(0.004 * i as f64, -0.002 * i as f64, 0.0) * start,
            ),
            wrench: Vector6::new(300.0, -100.0, -400.0, 0.0, 0.0, 0.0),
            frame: Frame::Tool,
            external: stiffid::internal::robot::external::ExternalValues::NONE,
        })
        .collect()
}

/// The compensation's part is the 95% quantile of the deflection's error over the stiffness
/// covariance (within 10% of 20 000 Monte Carlo draws), the force part 20% of the deflection,
/// and the bound their sum with the residual (no calibration carried).
#[test]
fn the_budget_parts_agree_with_monte_carlo_over_the_stiffness_covariance() {
    let (s, compliance, cov) = setup_and_compliance();
    let path = line_path(&s, 3);
    let out = compensate::path(s.arm(), &compliance, &path, &Options::for_setup(&s)).unwrap();
    let chol = cov.cholesky().unwrap().l();
    let h = compliance.drives_h();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (i, r) in out.iter().enumerate() {
        let frames = s.robot().frames(&r.q);
        let points = Points {
            arm: s.arm(),
            frames: &frames,
            loaded: &s.tool().tcp,
            observed: &s.tool().tcp,
        };
        let mean = points.deflection(&r.wrench, &DVector::from_column_slice(h.as_slice()));
        let mut lengths: Vec<f64> = (0..20_000)
            .map(|_| {
                let z = Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
                let hs = h + chol * z;
                let d = points.deflection(&r.wrench, &DVector::from_column_slice(hs.as_slice()));
                (d.displacement - mean.displacement)
                    .fixed_rows::<3>(0)
                    .norm()
            })
            .collect();
        lengths.sort_by(f64::total_cmp);
        let monte_carlo = lengths[(0.95 * lengths.len() as f64) as usize];
        let b = &r.budget;
        let part = b.compensation.unwrap();
        assert!(
            (part / monte_carlo - 1.0).abs() < 0.10,
            "point {i}: budget {part} m, Monte Carlo {monte_carlo} m"
        );
        let d = r.deflection.fixed_rows::<3>(0).norm();
        assert!((b.force - 0.2 * d).abs() < 1e-15, "point {i}");
        assert_eq!(b.calibration, None);
        assert_eq!(b.model_form, None);
        assert_eq!(b.left, r.residual_position);
        assert!((b.bound - (b.left + b.force + part)).abs() < 1e-15);
        assert_eq!(
            b.dominant().0,
            if part > b.force {
                "compensation"
            } else {
                "force"
            }
        );
    }
}

/// The calibration's part is the conformal quantile of the held-out errors a calibrated robot
/// file carries: within 10% of the true 95% quantile of the errors' distribution.
#[test]
fn the_calibration_part_is_the_quantile_of_the_held_out_errors() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    // Errors of 0.02 mm per coordinate: |e| / 0.02 mm is chi with 3 degrees of freedom, whose 95%
    // quantile is sqrt(7.8147) = 2.7955.
    let errors: Vec<String> = (0..600)
        .map(|_| {
            let e = Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal) * 0.02);
            format!("{}", e.fixed_rows::<3>(0).norm())
        })
        .collect();
    let joints: String = [(0.0, 0.0, 830.0), (400.0, -90.0, 0.0), (1175.0, 0.0, 0.0), (250.0, -90.0, 1444.0), (0.0, 90.0, 0.0), (0.0, -90.0, 230.0)]
        .iter()
        .map(|(a, alpha, d)| format!("[[joint]]\na_mm = {a}\nalpha_deg = {alpha}\nd_mm = {d}\nlower_deg = -180.0\nupper_deg = 180.0\n"))
        .collect();
    let text = format!(
        "name = \"arm (calibrated)\"\nconvention = \"modified-dh\"\n{joints}\n[held_out]\nsource = \"validate\"\nerrors_mm = [{}]\n",
        errors.join(", ")
    );
    let robot = stiffid::internal::robot::file::parse(&text, "robot.toml").unwrap();
    let q = robot.held_out().unwrap().quantile(0.95);
    let truth = 0.02e-3 * 7.8147f64.sqrt();
    assert!((q / truth - 1.0).abs() < 0.10, "{q} vs {truth}");
    // Too few errors for the level: infinite, never a smaller number.
    let few = text.replace(&format!("[{}]", errors.join(", ")), "[0.01, 0.02]");
    let robot = stiffid::internal::robot::file::parse(&few, "robot.toml").unwrap();
    assert_eq!(robot.held_out().unwrap().quantile(0.95), f64::INFINITY);
    // A negative length is refused naming the field.
    let bad = text.replace(&format!("[{}]", errors.join(", ")), "[-0.01]");
    let e = stiffid::internal::robot::file::parse(&bad, "robot.toml").unwrap_err();
    assert!(e.to_string().contains("held_out.errors_mm"), "{e}");
}

/// The free tool axis minimising the bound raises no point's bound above its value at the
/// path's own rotation, and lowers the sum (`sum`) or the worst point's (`max`).
#[test]
fn the_free_tool_axis_minimising_the_bound_raises_no_point() {
    let (s, compliance, _) = setup_and_compliance();
    let path = line_path(&s, 20);
    for aggregate in [Aggregate::Sum, Aggregate::Max] {
        let free = FreeVariables {
            free: vec![Free::ToolRotation(crate::compensate::rotation(60.0, 5.0))],
            minimise: Objective::Bound,
            aggregate,
        };
        let options = Options {
            free,
            ..Options::for_setup(&s)
        };
        let out = compensate::path(s.arm(), &compliance, &path, &options).unwrap();
        let (mut before, mut after, mut worst_before, mut worst_after) = (0.0, 0.0, 0.0f64, 0.0f64);
        for (i, r) in out.iter().enumerate() {
            let b0 = r.bound_before.unwrap();
            assert!(
                r.budget.bound <= b0 * (1.0 + 1e-9),
                "{aggregate:?} point {i}"
            );
            before += b0;
            after += r.budget.bound;
            worst_before = worst_before.max(b0);
            worst_after = worst_after.max(r.budget.bound);
        }
        match aggregate {
            Aggregate::Sum => assert!(after < before, "{after} vs {before}"),
            Aggregate::Max => assert!(
                worst_after <= worst_before,
                "{worst_after} vs {worst_before}"
            ),
        }
    }
}

/// `max_error` refuses a path whose bound exceeds it anywhere, naming the worst lines and what
/// dominates their bound; a larger one accepts it.
#[test]
fn a_bound_above_the_largest_error_accepted_is_refused_naming_the_worst_points() {
    let (s, compliance, _) = setup_and_compliance();
    let mut text = String::from("q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n");
    for (i, q) in s.test_postures().iter().take(4).enumerate() {
        let deg: Vec<String> = q.iter().map(|a| a.to_degrees().to_string()).collect();
        text += &format!("{},{},0,{}\n", deg.join(","), 100.0 * i as f64, -300.0);
    }
    let request = |max_error| Request {
        names: Default::default(),
        setup: &s,
        compliance: compliance.clone(),
        input: Input::Path {
            name: "path.csv".into(),
            text: &text,
            frame: Frame::Base,
        },
        options: Options {
            max_error,
            ..Options::for_setup(&s)
        },
    };
    let report = run(request(None), |_, _, _, _| Ok::<(), Error>(())).unwrap();
    let summary = report.summary.document().budget;
    let worst = summary.max_bound_mm.unwrap();
    assert_eq!(summary.worst[0].bound_mm, Some(worst));
    assert_eq!(summary.absent, vec!["calibration", "model_form"]);
    let e = run(request(Some(0.5 * worst * 1e-3)), |_, _, _, _| {
        Ok::<(), Error>(())
    })
    .unwrap_err();
    let Error::Gate { option, message } = &e else {
        panic!("{e}")
    };
    assert_eq!(*option, JobOption::MaxErrorMm);
    let line = summary.worst[0].line;
    assert_eq!(summary.max_bound_line, Some(line));
    assert!(message.contains(&format!("line {line}: ")), "{message}");
    assert!(message.contains("mostly "), "{message}");
    assert!(run(request(Some(2.0 * worst * 1e-3)), |_, _, _, _| Ok::<
        (),
        Error,
    >(()))
    .is_ok());
    // Zero and not-a-number are refused as options.
    for bad in [0.0, f64::NAN] {
        let e = run(request(Some(bad)), |_, _, _, _| Ok::<(), Error>(())).unwrap_err();
        assert!(
            matches!(
                e,
                Error::InvalidOption {
                    option: JobOption::MaxErrorMm,
                    ..
                }
            ),
            "{e}"
        );
    }
}

/// The realised error of `robots` simulated true robots at each compensated point of `out`
/// (`[point][robot]`, m): each robot's compliance drawn from the covariance (Cholesky factor
/// `chol`), its joint zero offsets from N(0, `sigma_q`^2) (the calibration's error) and its
/// process force off by a factor uniform in [0.8, 1.2] (the force model's +-20%); the error is
/// the loaded true tool's distance to the target the unloaded nominal robot reaches.
fn realised_errors(
    s: &Setup,
    compliance: &Compliance,
    chol: &Matrix6<f64>,
    out: &[compensate::Compensated],
    (robots, sigma_q, seed): (usize, f64, u64),
) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut errors = vec![Vec::with_capacity(robots); out.len()];
    let tcp = s.tool().tcp;
    for _ in 0..robots {
        let z = Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
        let h = compliance.drives_h() + chol * z;
        let truth = Compliance {
            h: DVector::from_column_slice(h.as_slice()),
            covariance: None,
            ..compliance.clone()
        };
        let model = compensate::Model::new(s.arm(), &truth).unwrap();
        let offsets = Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal) * sigma_q);
        let force = 1.0 + rng.random_range(-0.2..0.2);
        for (e, r) in errors.iter_mut().zip(out) {
            let target = tool_pose(&s.robot().frames(&r.q), &tcp).translation.vector;
            let pose = model.loaded_pose(&(r.q_compensated + offsets), &(r.wrench * force));
            e.push((pose.translation.vector - target).norm());
        }
    }
    errors
}

/// The robot of `s` carrying `n` held-out errors of its calibration: the distance its tool
/// moves under joint zero offsets drawn from N(0, `sigma_q`^2), each at a posture within +-10 deg
/// of one of `near`, as a validation of a calibration with that error would find them.
fn with_held_out(s: &Setup, near: &[Vector6<f64>], n: usize, sigma_q: f64, seed: u64) -> Setup {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let tcp = s.tool().tcp;
    let at = |q: &Vector6<f64>| tool_pose(&s.robot().frames(q), &tcp).translation.vector;
    let mut errors: Vec<f64> = (0..n)
        .map(|k| {
            let q = near[k % near.len()]
                + Vector6::from_fn(|_, _| rng.random_range(-10f64..10.0).to_radians());
            let offsets = Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal) * sigma_q);
            (at(&(q + offsets)) - at(&q)).norm()
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    let held = stiffid::internal::robot::HeldOut {
        source: "validate".into(),
        errors,
    };
    let robot = s.robot().clone().with_held_out(Some(held));
    s.to_builder().with_robot(robot).build().unwrap()
}

/// The bound is a promise at its level: over 2000 simulated true robots (compliance drawn from
/// the stiffness covariance, joint zero offsets as the calibration's held-out errors say, the
/// force within the force model's +-20%), the 95% and 99.7% bounds cover at least 95% and 99.7%
/// of the program points' errors, and neither is wider than 3 times the realised quantile at
/// any point.
#[test]
fn the_bound_covers_the_true_robots_errors_at_its_level_and_is_not_wider_than_needed() {
    let (s, compliance, cov) = setup_and_compliance();
    let chol = cov.cholesky().unwrap().l();
    let path = line_path(&s, 12);
    let sigma_q = 0.001f64.to_radians();
    let nominal = compensate::path(s.arm(), &compliance, &path, &Options::for_setup(&s)).unwrap();
    let near: Vec<Vector6<f64>> = nominal.iter().map(|r| r.q).collect();
    let s = with_held_out(&s, &near, 1000, sigma_q, 5);
    for level in [0.95, 0.997] {
        let options = Options {
            level,
            ..Options::for_setup(&s)
        };
        let out = compensate::path(s.arm(), &compliance, &path, &options).unwrap();
        assert!(out.iter().all(|r| r.budget.calibration.is_some()));
        let errors = realised_errors(&s, &compliance, &chol, &out, (2000, sigma_q, 17));
        let (mut covered, mut total) = (0usize, 0usize);
        let (mut narrowest, mut widest) = (f64::INFINITY, 0.0f64);
        for (i, (e, r)) in errors.iter().zip(&out).enumerate() {
            let bound = r.budget.bound;
            covered += e.iter().filter(|&&x| x <= bound).count();
            total += e.len();
            let mut sorted = e.clone();
            sorted.sort_by(f64::total_cmp);
            let k = ((level * sorted.len() as f64).ceil() as usize).min(sorted.len()) - 1;
            let ratio = bound / sorted[k];
            (narrowest, widest) = (narrowest.min(ratio), widest.max(ratio));
            assert!(
                ratio <= 3.0,
                "level {level} point {i}: bound {bound} m, realised quantile {} m",
                sorted[k]
            );
        }
        let coverage = covered as f64 / total as f64;
        eprintln!("level {level}: coverage {coverage:.5} of {total}, bound / realised quantile {narrowest:.2} to {widest:.2}");
        assert!(coverage >= level, "level {level}: coverage {coverage}");
    }
}
