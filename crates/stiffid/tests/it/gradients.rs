//! Exact gradients against central differences, at random postures of every preset robot, in axis
//! and kinematic spring coordinates: the point-Jacobian kernel, the dexterity index, the rope block
//! of the observation matrix, every design criterion, and the cell's constraints of the searches.

use crate::common;

use nalgebra::{DMatrix, Matrix6, MatrixXx6, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::design::{Criterion, Evaluator};
use stiffid::internal::observation::{posture_block, rope_block_gradient};
use stiffid::internal::robot::presets;
use stiffid::internal::setup::{self, Setup};
use stiffid::{dexterity, internal::robot::kinematics, Coordinates, Frames, Robot};

/// Step of the fourth-order central differences, rad: truncation ~ h^4, round-off ~ 1e-16 / h,
/// both far below 1e-6 relative for the smooth functions tested.
const H: f64 = 1e-4;

/// The paper setup on every preset robot, with springs in axis and in kinematic coordinates, and
/// the built-in FANUC setup.
fn setups() -> Vec<Setup> {
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut out = vec![setup::builtin("fanuc-r2000ic-165f").unwrap()];
    for name in presets::names() {
        for springs in [Coordinates::Axis, Coordinates::Kinematic] {
            out.push(common::on_robot(
                &paper,
                presets::get(name).unwrap(),
                springs,
            ));
        }
    }
    out
}

/// A posture drawn uniformly within the joint limits (at most +-180 deg per axis).
fn random_posture(robot: &Robot, rng: &mut ChaCha8Rng) -> Vector6<f64> {
    let limit = std::f64::consts::PI;
    Vector6::from_fn(|i, _| {
        rng.random_range(robot.limits().lower[i].max(-limit)..robot.limits().upper[i].min(limit))
    })
}

/// Fourth-order central differences of `f` at `q`, one axis at a time:
/// `(8 (f(q + h) - f(q - h)) - (f(q + 2h) - f(q - 2h))) / 12h`.
fn central(q: &Vector6<f64>, f: impl Fn(&Vector6<f64>) -> f64) -> Vector6<f64> {
    Vector6::from_fn(|a, _| {
        let mut step = Vector6::zeros();
        step[a] = H;
        let (one, two) = (
            f(&(q + step)) - f(&(q - step)),
            f(&(q + 2.0 * step)) - f(&(q - 2.0 * step)),
        );
        (8.0 * one - two) / (12.0 * H)
    })
}

/// `|exact - approx| / |exact|`.
fn relative_error(exact: &[f64], approx: &[f64]) -> f64 {
    let diff: f64 = exact.iter().zip(approx).map(|(e, a)| (e - a).powi(2)).sum();
    let norm: f64 = exact.iter().map(|e| e * e).sum();
    (diff / norm).sqrt()
}

fn random_matrix(rng: &mut ChaCha8Rng, rows: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows, 6, |_, _| rng.random_range(-1.0..1.0))
}

#[test]
fn point_jacobian_gradient_matches_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    for setup in setups() {
        for _ in 0..5 {
            let q = random_posture(setup.robot(), &mut rng);
            let w: Matrix6<f64> = random_matrix(&mut rng, 6).fixed_view::<6, 6>(0, 0).into();
            let g = Vector3::from_fn(|_, _| rng.random_range(-1.0..1.0));
            let p = setup.tool().measuring_points[0];
            let phi = |q: &Vector6<f64>| {
                let f = setup.robot().frames(q);
                f.jacobian(&p, setup.springs()).dot(&w) + g.dot(&f.point(&p))
            };
            let exact = setup
                .robot()
                .frames(&q)
                .jacobian_gradient(&p, setup.springs(), &w, &g);
            let err = relative_error(exact.as_slice(), central(&q, phi).as_slice());
            assert!(err < 1e-6, "{}: {err:e}", setup.robot().name());
        }
    }
}

#[test]
fn dexterity_gradient_matches_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    for setup in setups() {
        let (tcp, l) = (setup.tool().tcp, setup.characteristic_length().unwrap());
        let ln_k = |f: &Frames| dexterity(&f.jacobian(&tcp, setup.springs()), l).ln();
        for _ in 0..5 {
            let q = random_posture(setup.robot(), &mut rng);
            let frames = setup.robot().frames(&q);
            let jacobian = frames.jacobian(&tcp, setup.springs());
            let w = kinematics::dexterity_log_gradient(&jacobian, l).unwrap();
            let exact = frames.jacobian_gradient(&tcp, setup.springs(), &w, &Vector3::zeros());
            let approx = central(&q, |q| ln_k(&setup.robot().frames(q)));
            let err = relative_error(exact.as_slice(), approx.as_slice());
            assert!(err < 1e-6, "{}: {err:e}", setup.robot().name());
        }
    }
}

#[test]
fn rope_block_gradient_matches_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(16);
    for setup in setups() {
        let rows = 3 * setup.tool().measuring_points.len();
        for _ in 0..5 {
            let q = random_posture(setup.robot(), &mut rng);
            let g: MatrixXx6<f64> =
                MatrixXx6::from_column_slice(random_matrix(&mut rng, rows).as_slice());
            let phi = |q: &Vector6<f64>| {
                let f = setup.robot().frames(q);
                posture_block(setup.arm(), &f, &setup.rope_wrench(&f)).dot(&g)
            };
            let exact = rope_block_gradient(&setup, &setup.robot().frames(&q), &g);
            let err = relative_error(exact.as_slice(), central(&q, phi).as_slice());
            assert!(err < 1e-6, "{}: {err:e}", setup.robot().name());
        }
    }
}

#[test]
fn every_criterion_gradient_matches_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    for setup in setups() {
        let evaluator = Evaluator::new(&setup);
        for _ in 0..3 {
            let group: Vec<Vector6<f64>> = (0..6)
                .map(|_| random_posture(setup.robot(), &mut rng))
                .collect();
            for criterion in Criterion::ALL {
                let (value, exact) = evaluator.value_and_gradient(criterion, &group);
                assert_eq!(value, evaluator.value(criterion, &group), "{criterion}");
                assert!(value.is_finite(), "{criterion} on {}", setup.robot().name());
                let mut approx = Vec::new();
                for i in 0..group.len() {
                    approx.extend(
                        central(&group[i], |q| {
                            let mut probed = group.clone();
                            probed[i] = *q;
                            evaluator.value(criterion, &probed)
                        })
                        .iter(),
                    );
                }
                let exact: Vec<f64> = exact.iter().flat_map(|g| g.iter().copied()).collect();
                let err = relative_error(&exact, &approx);
                assert!(
                    err < 1e-6,
                    "{criterion} on {} ({:?} springs): {err:e}",
                    setup.robot().name(),
                    setup.springs()
                );
            }
        }
    }
}

#[test]
fn gradient_of_a_rank_deficient_group_is_zero_not_nan() {
    // q5 = 0 in every posture: axes 4 and 6 are collinear, so their columns of Psi are equal.
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let group: Vec<Vector6<f64>> = stiffid::internal::design::random_group(&setup, 6, 5)
        .into_iter()
        .map(|mut q| {
            q[4] = 0.0;
            q
        })
        .collect();
    let evaluator = Evaluator::new(&setup);
    for criterion in [
        Criterion::Zhang2021,
        Criterion::DOptimal,
        Criterion::RelativeA,
    ] {
        let (value, gradient) = evaluator.value_and_gradient(criterion, &group);
        assert_eq!(value, f64::INFINITY);
        assert!(
            gradient.iter().all(|g| *g == Vector6::zeros()),
            "{criterion}"
        );
    }
}

/// The cell's constraints as the searches see them (`design::search::cell_constraints`: smooth
/// minima of the pair margins of floor, obstacle, self-collision, rope, lines of sight, incidence
/// and loading-point height) against two-sided differences, at seeded postures of the paper setup
/// in a cell: every value's gradient, wherever the differences of steps h and h / 2 agree (no
/// broad-phase switch or witness tie within the step).
#[test]
fn cell_constraint_gradients_match_central_differences() {
    use stiffid::internal::cell::Checker;
    use stiffid::internal::design::search::cell_constraints;
    let text = setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
        + "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n[[cell.obstacle]]\nname = \"table\"\nmin_mm = [1800, -500, 0]\nmax_mm = [2600, 500, 900]\n[tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\nmax_incidence_deg = 60.0\n[constraints]\nloading_point_min_z_mm = 300.0\n";
    let setup = setup::parse(&text, "cell.toml", |r, _| presets::get(r)).unwrap();
    let checker = Checker::new(&setup);
    let postures = stiffid::internal::design::random_group(&setup, 40, 5);
    let mut checked = vec![0; checker.kinds().len() - 1];
    for q in &postures {
        let c = cell_constraints(&checker, q);
        for (k, count) in checked.iter_mut().enumerate() {
            let f = |q: &Vector6<f64>| cell_constraints(&checker, q).values[k];
            let two_sided = |h: f64| {
                Vector6::from_fn(|a, _| {
                    let step = Vector6::ith(a, h);
                    (f(&(q + step)) - f(&(q - step))) / (2.0 * h)
                })
            };
            let (d, half) = (two_sided(1e-6), two_sided(5e-7));
            if (d - half).norm() > 1e-6 * (1.0 + d.norm()) {
                continue;
            }
            let err = (c.gradients[k] - d).norm() / d.norm().max(1e-3);
            assert!(
                err < 1e-5,
                "check {k}: {:?} against {:?}",
                c.gradients[k],
                d
            );
            *count += 1;
        }
    }
    assert!(
        checked.iter().all(|&n| n >= 20),
        "postures checked per check: {checked:?}"
    );
}
