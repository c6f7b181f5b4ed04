//! Point Jacobians against central finite differences of the forward kinematics, for every preset,
//! in axis and kinematic coordinates; the `[v; omega]` row order; the dexterity index.

use nalgebra::{Matrix6, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::robot::presets;
use stiffid::{dexterity, AxisMap, Coordinates, Robot};

/// Finite-difference step, rad: truncation ~ h^2, round-off ~ 1e-16 / h, both far below 1e-6.
const H: f64 = 1e-6;

/// Points in the flange frame, m: the flange origin and tool points off every axis.
const POINTS: [[f64; 3]; 3] = [[0.0, 0.0, 0.0], [0.15, 0.0, 0.2], [-0.08, 0.08, 0.26]];

/// A posture drawn uniformly within the joint limits (at most +-360 deg per axis).
fn random_posture(robot: &Robot, rng: &mut ChaCha8Rng) -> Vector6<f64> {
    let limit = 2.0 * std::f64::consts::PI;
    Vector6::from_fn(|i, _| {
        rng.random_range(robot.limits().lower[i].max(-limit)..robot.limits().upper[i].min(limit))
    })
}

/// The same chain with the identity axis map: its axis angles are the kinematic angles.
fn kinematic_robot(robot: &Robot) -> Robot {
    robot.clone().with_axis_map(AxisMap::default()).unwrap()
}

/// Central differences of `robot`'s kinematics at joint values `x`: translation rows from the
/// point positions, rotation rows from `log(R(x + h e_j) R(x - h e_j)^T) / 2h` of the flange.
fn finite_difference(robot: &Robot, x: &Vector6<f64>, point: &Vector3<f64>) -> Matrix6<f64> {
    let mut j = Matrix6::zeros();
    for c in 0..6 {
        let mut step = Vector6::zeros();
        step[c] = H;
        let plus = robot.frames(&(x + step));
        let minus = robot.frames(&(x - step));
        let v = (plus.point(point) - minus.point(point)) / (2.0 * H);
        let omega =
            (plus.flange.rotation * minus.flange.rotation.inverse()).scaled_axis() / (2.0 * H);
        j.fixed_view_mut::<3, 1>(0, c).copy_from(&v);
        j.fixed_view_mut::<3, 1>(3, c).copy_from(&omega);
    }
    j
}

/// Whether every column of `approx` is within 1e-6 (relative to the column norm) of `exact`.
fn columns_agree(exact: &Matrix6<f64>, approx: &Matrix6<f64>) -> bool {
    (0..6).all(|c| {
        let e = exact.column(c);
        (approx.column(c) - e).norm() <= 1e-6 * e.norm().max(1e-3)
    })
}

/// The blocks swapped: `[omega; v]`.
fn swapped(j: &Matrix6<f64>) -> Matrix6<f64> {
    let mut s = Matrix6::zeros();
    s.fixed_rows_mut::<3>(0).copy_from(&j.fixed_rows::<3>(3));
    s.fixed_rows_mut::<3>(3).copy_from(&j.fixed_rows::<3>(0));
    s
}

#[test]
fn every_preset_jacobian_matches_finite_differences_in_both_coordinates() {
    for (index, name) in presets::names().enumerate() {
        let robot = presets::get(name).unwrap();
        let kinematic = kinematic_robot(&robot);
        let mut rng = ChaCha8Rng::seed_from_u64(0x5eed ^ index as u64);
        for _ in 0..20 {
            let q = random_posture(&robot, &mut rng);
            let theta = robot.axis_map().kinematic(&q);
            let frames = robot.frames(&q);
            for p in POINTS.map(Vector3::from) {
                let j_axis = frames.jacobian(&p, Coordinates::Axis);
                let j_kin = frames.jacobian(&p, Coordinates::Kinematic);
                let fd_axis = finite_difference(&robot, &q, &p);
                let fd_kin = finite_difference(&kinematic, &theta, &p);
                assert!(
                    columns_agree(&j_axis, &fd_axis),
                    "{name}, q = {q}, point {p}: axis Jacobian\n{j_axis}\nfinite differences\n{fd_axis}"
                );
                assert!(
                    columns_agree(&j_kin, &fd_kin),
                    "{name}, theta = {theta}, point {p}: kinematic Jacobian\n{j_kin}\nfinite differences\n{fd_kin}"
                );
                // The comparison is sharp enough to see an [omega; v] row order.
                assert!(!columns_agree(&swapped(&j_axis), &fd_axis));
            }
        }
    }
}

#[test]
fn joint_1_column_is_v_then_omega() {
    // COMAU: theta_1 = -q_1, so turning axis 1 spins everything about the base -z axis through
    // the origin: omega = (0, 0, -1), v = omega x p = (p_y, -p_x, 0).
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    let q = Vector6::from_column_slice(&[10.0, 20.0, -90.0, 30.0, 20.0, 10.0]).map(f64::to_radians);
    let frames = robot.frames(&q);
    let tool = Vector3::new(0.15, 0.0, 0.2);
    let p = frames.point(&tool);
    let j = frames.jacobian(&tool, Coordinates::Axis);
    let expected = [p.y, -p.x, 0.0, 0.0, 0.0, -1.0];
    for (r, e) in expected.iter().enumerate() {
        assert!(
            (j[(r, 0)] - e).abs() < 1e-12,
            "row {r}: {} vs {e}",
            j[(r, 0)]
        );
    }
}

/// A random 6x6 orthogonal matrix (Q of a QR decomposition).
fn orthogonal(rng: &mut ChaCha8Rng) -> Matrix6<f64> {
    Matrix6::from_fn(|_, _| rng.random_range(-1.0..1.0))
        .qr()
        .q()
}

/// `diag(L I, I) J_N`: the Jacobian whose normalised form is `J_N`.
fn denormalised(jn: &Matrix6<f64>, length: f64) -> Matrix6<f64> {
    let mut j = *jn;
    j.fixed_rows_mut::<3>(0).scale_mut(length);
    j
}

#[test]
fn dexterity_is_one_for_an_isotropic_jacobian() {
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    for length in [0.5, 1.2, 3.0] {
        let j = denormalised(&orthogonal(&mut rng), length);
        assert!((dexterity(&j, length) - 1.0).abs() < 1e-12);
    }
}

#[test]
fn dexterity_matches_the_definition_for_a_diagonal_jacobian() {
    // J_N = diag(1, 1, 1, 1, 1, 2): tr(A) = 9, tr(A^-1) = 5.25.
    let jn = Matrix6::from_diagonal(&Vector6::new(1.0, 1.0, 1.0, 1.0, 1.0, 2.0));
    let expected = (9.0f64 * 5.25).sqrt() / 6.0;
    assert!((dexterity(&denormalised(&jn, 1.2), 1.2) - expected).abs() < 1e-12);
}

#[test]
fn dexterity_ignores_row_order_within_blocks_but_not_across() {
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    let q = Vector6::from_column_slice(&[12.81, 33.07, -126.36, 72.81, -67.88, 24.27])
        .map(f64::to_radians);
    let j = robot
        .frames(&q)
        .jacobian(&Vector3::new(0.08, 0.08, 0.26), Coordinates::Axis);
    let k = dexterity(&j, 1.2);
    assert!(k > 1.0 && k.is_finite());
    let permuted =
        Matrix6::from_rows(&[j.row(2), j.row(0), j.row(1), j.row(4), j.row(5), j.row(3)]);
    assert!((dexterity(&permuted, 1.2) - k).abs() < 1e-9 * k);
    // Swapping the blocks scales the wrong rows by 1/L: a different value.
    assert!((dexterity(&swapped(&j), 1.2) - k).abs() > 1e-3 * k);
}

#[test]
fn dexterity_is_infinite_at_a_singularity() {
    let mut j = Matrix6::identity();
    j[(5, 5)] = 0.0;
    assert_eq!(dexterity(&j, 1.0), f64::INFINITY);
}
