//! The virtual springs' columns of a posture's compact block, and their gradient with respect to
//! the axis angles.
//!
//! **Compact columns.** Spring s (axis `u` through `o`, or direction `u`, fixed in link k,
//! [`stiffid_core::model`]) has the Jacobian column `j_s = [u x (p - o); u]` (rotation) or `[u; 0]`
//! (translation) at a point p, and the generalised load `L_s = J_f,s^T W` of the rope wrench W at
//! the loading point. Its rows in a posture's block are `v_s(p_m) L_s` for each measuring point
//! p_m, the velocity of p_m under the spring's unit twist: `R_f [I_3, -[p_m]x] b_s` with `b_s` the
//! twist at the flange origin t in the flange frame, `b_s = [R_f^T v_s(t); R_f^T w_s]`, exactly as a
//! drive column ([`stiffid_core::observation`]'s `points_factor`). Its compact column is therefore
//! `R_P b_s L_s`.
//!
//! **Gradient.** For a weight `G_m` (3-vector per measuring point) on spring s's rows, the scalar
//! `phi_s = sum_m G_m . v_s(p_m) L_s` depends on `u`, `o` (which move with the joints `j <= k`),
//! the measuring points and the loading point (which move with every joint), and, through the rope
//! force `f(p_f)`, on the loading point again. With `a = sum_m G_m . v_s(p_m)`:
//! - rotation, `v_s(p) = u x (p - o)`, `L_s = f . (u x (p_f - o))`:
//!   `d phi / d p_m = L (G_m x u)`, `d phi / d u = L sum_m (p_m - o) x G_m + a (p_f - o) x f`,
//!   `d phi / d o = -sum_m d phi / d p_m - a f x u`,
//!   `d phi / d p_f = a (f x u + df^T (u x (p_f - o)))`;
//! - translation, `v_s = u`, `L_s = f . u`: `d phi / d u = L sum_m G_m + a f`,
//!   `d phi / d p_f = a df^T u`.
//!
//! Kinematic joint j (axis `z_j` through `o_j`, moment `m_j = z_j x o_j`) moves a point x of a body
//! beyond it by `z_j x x - m_j` and turns a direction d by `z_j x d`, so with `g_x` the point
//! gradients and `g_u`, `g_o`:
//! `d phi / d theta_j = z_j . A - m_j . b`, `A = sum_x x x g_x + [j <= k] (u x g_u + o x g_o)`,
//! `b = sum_x g_x + [j <= k] g_o`: two running sums over the links. Axis angles by the chain rule
//! `d / dq = M^T d / d theta` ([`Frames::kinematic_to_axis`]).

use nalgebra::{Matrix6, Vector3, Vector6};
use stiffid_core::model::{Kind, Placed};
use stiffid_core::robot::kinematics::Frames;
use stiffid_core::setup::Setup;

/// Writes the compact columns `R_P b_s L_s` of the setup's virtual springs at the posture `frames`
/// into `out` (column-major, six rows per spring; rows `min(3p, 6)..6` are zero).
pub(super) fn write_compact_columns(
    setup: &Setup,
    frames: &Frames,
    points_factor: &Matrix6<f64>,
    out: &mut [f64],
) {
    let wrench = setup.rope_wrench(frames);
    let loading = frames.point(&setup.tool().loading_point);
    let t = frames.flange.translation.vector;
    let rt = frames.flange.rotation.inverse();
    for (spring, col) in setup.model().springs().iter().zip(out.chunks_exact_mut(6)) {
        let placed = spring.placed(frames);
        let load = placed.load(&loading, &wrench);
        let v = rt * placed.velocity(&t);
        let w = match placed.kind {
            Kind::Rotation => rt * placed.u,
            Kind::Translation => Vector3::zeros(),
        };
        let b = [v.x, v.y, v.z, w.x, w.y, w.z];
        // R_P is upper triangular: row i starts at column i.
        for (i, c) in col.iter_mut().enumerate() {
            *c = load * (i..6).map(|k| points_factor[(i, k)] * b[k]).sum::<f64>();
        }
    }
}

/// The gradient with respect to the axis angles (per rad) of `sum_s <G_s, B_s>`, `B_s` the rows
/// of virtual spring s in the posture's block (three per measuring point, point-major) and
/// `weights(s, m)` its weight `G_s` at measuring point m (module docs).
pub(super) fn spring_gradient(
    setup: &Setup,
    frames: &Frames,
    weights: impl Fn(usize, usize) -> Vector3<f64>,
) -> Vector6<f64> {
    let wrench = setup.rope_wrench(frames);
    let f: Vector3<f64> = wrench.fixed_rows::<3>(0).into();
    let pf = frames.point(&setup.tool().loading_point);
    let points: Vec<Vector3<f64>> = setup
        .tool()
        .measuring_points
        .iter()
        .map(|p| frames.point(p))
        .collect();
    // Sums over the points (every joint moves them) and per link (joints j <= k move u and o).
    let (mut a_all, mut b_all) = (Vector3::zeros(), Vector3::zeros());
    let mut by_link = [(Vector3::zeros(), Vector3::zeros()); 7];
    for (s, spring) in setup.model().springs().iter().enumerate() {
        let placed = spring.placed(frames);
        let g: Vec<Vector3<f64>> = (0..points.len()).map(|m| weights(s, m)).collect();
        let motion = spring_motion(setup, &placed, &f, &pf, &points, &g);
        for (x, gx) in points
            .iter()
            .zip(&motion.points)
            .chain([(&pf, &motion.loading)])
        {
            a_all += x.cross(gx);
            b_all += gx;
        }
        let link = &mut by_link[spring.link];
        link.0 += placed.u.cross(&motion.u) + placed.o.cross(&motion.o);
        link.1 += motion.o;
    }
    let mut grad = Vector6::zeros();
    let (mut a, mut b) = (a_all, b_all);
    for (k, (ak, bk)) in by_link.iter().enumerate().rev() {
        a += ak;
        b += bk;
        if k >= 1 {
            let j = k - 1;
            let z = frames.axis_directions[j];
            let m = z.cross(&frames.axis_points[j]);
            grad[j] = z.dot(&a) - m.dot(&b);
        }
    }
    frames.kinematic_to_axis(&grad)
}

/// The derivatives of `phi_s` with respect to the spring's axis, point, the measuring points and
/// the loading point (module docs).
struct Motion {
    u: Vector3<f64>,
    o: Vector3<f64>,
    points: Vec<Vector3<f64>>,
    loading: Vector3<f64>,
}

fn spring_motion(
    setup: &Setup,
    placed: &Placed,
    f: &Vector3<f64>,
    pf: &Vector3<f64>,
    points: &[Vector3<f64>],
    g: &[Vector3<f64>],
) -> Motion {
    let u = placed.u;
    match placed.kind {
        Kind::Rotation => {
            let o = placed.o;
            let a: f64 = points
                .iter()
                .zip(g)
                .map(|(p, gm)| gm.dot(&u.cross(&(p - o))))
                .sum();
            let lever = pf - o;
            let load = f.dot(&u.cross(&lever));
            let gp: Vec<Vector3<f64>> = g.iter().map(|gm| gm.cross(&u) * load).collect();
            let gu = points
                .iter()
                .zip(g)
                .map(|(p, gm)| (p - o).cross(gm))
                .sum::<Vector3<f64>>()
                * load
                + lever.cross(f) * a;
            let go = -gp.iter().sum::<Vector3<f64>>() - f.cross(&u) * a;
            let through_force = setup.load().force_gradient(pf, &u.cross(&lever));
            Motion {
                u: gu,
                o: go,
                points: gp,
                loading: (f.cross(&u) + through_force) * a,
            }
        }
        Kind::Translation => {
            let sum_g: Vector3<f64> = g.iter().sum();
            let a = sum_g.dot(&u);
            let load = f.dot(&u);
            Motion {
                u: sum_g * load + f * a,
                o: Vector3::zeros(),
                points: vec![Vector3::zeros(); points.len()],
                loading: setup.load().force_gradient(pf, &u) * a,
            }
        }
    }
}
