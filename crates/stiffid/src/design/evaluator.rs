//! Fast evaluation of the design criteria, for the posture search.
//!
//! [`Evaluator::new`] precomputes what does not depend on the postures (the nominal compliance,
//! the noise, the observation rows of the test postures). For each posture the forward kinematics
//! is computed once and gives both the TCP dexterity and the posture's rows of `Psi`: with `J_v0`,
//! `J_w` the translation Jacobian of the flange origin `p0` and the rotation Jacobian (springs'
//! coordinates), the translation Jacobian of a tool point p is `J_v0 - [p - p0]x J_w`. The group's
//! `Psi` is reduced to its triangular factor `R` (`Psi = Q R`, Householder, `Q` never formed), and
//! only what the chosen criterion needs is computed from `R`:
//! - `cond_2(Psi)`, `cond_2(S)`: singular values of `R`, `R diag(h) / sigma` (one-sided Jacobi);
//! - `d-optimal`: `prod_k |R_kk h_k / sigma|^(-1/6)`;
//! - `relative-a`, relative standard deviations: row norms of `(R diag(h) / sigma)^-1`;
//! - `test-pose`: `sigma |A R^-1|_F / sqrt(T)`, A the `T` test postures' rows.
//!
//! The rank rule is that of [`crate::lsq::Factor::try_new`]: non-finite entries, a column of `Psi`
//! whose norm is at or below [`RANK_TOLERANCE`] times the largest column norm, or
//! `s_min <= RANK_TOLERANCE s_max` make the group rank deficient (`+infinity`). The singular values are only computed when the bounds
//! `|R|_F |R^-1|_F / 6 <= cond_2(R) <= |R|_F |R^-1|_F` leave the rule undecided.

use super::criteria::{predicted_deviation_pct, Criterion, Evaluation};
use crate::lsq::RANK_TOLERANCE;
use crate::setup::Setup;
use crate::Coordinates;
use nalgebra::{DMatrix, Matrix3x6, Matrix6, UnitQuaternion, Vector3, Vector6};

/// Evaluates design criteria of groups of postures for one setup.
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    setup: &'a Setup,
    /// The nonzero entries `(i, j, M_ij)` of `M` (`J_q = J_theta M`) when the springs sit in the
    /// drives (a few: signs and the parallelogram coupling); `None` on the kinematic joints.
    axis_matrix: Option<Vec<(usize, usize, f64)>>,
    /// `h / sigma` (rad/Nm per m): the column scaling of `S`.
    scaling: Vector6<f64>,
    /// Observation rows of every test posture under its rope-mass load, stacked (`3pT x 6`).
    test_rows: DMatrix<f64>,
}

/// What one posture contributes to a group: its `3p x 6` block of `Psi` and its TCP dexterity.
#[derive(Debug, Clone, PartialEq)]
pub struct PostureTerms {
    /// The block, column-major.
    rows: Vec<f64>,
    /// `k(J_N)` of the TCP (Eq. 21).
    dexterity: f64,
}

impl<'a> Evaluator<'a> {
    /// An evaluator for `setup`.
    pub fn new(setup: &'a Setup) -> Self {
        let mut evaluator = Self {
            setup,
            axis_matrix: match setup.springs {
                Coordinates::Axis => {
                    let m = &setup.robot.axis_map.matrix;
                    let nonzero = (0..6).flat_map(|j| (0..6).map(move |i| (i, j, m[(i, j)])));
                    Some(nonzero.filter(|t| t.2 != 0.0).collect())
                }
                Coordinates::Kinematic => None,
            },
            scaling: setup.nominal_compliance() / setup.noise.sigma(),
            test_rows: DMatrix::zeros(0, 6),
        };
        let p3 = evaluator.block_rows();
        let t = setup.test_postures.len();
        let mut a = vec![0.0; p3 * t * 6];
        for (i, q) in setup.test_postures.iter().enumerate() {
            evaluator.write_block(&evaluator.jacobians(q), &mut a, p3 * t, p3 * i);
        }
        evaluator.test_rows = DMatrix::from_vec(p3 * t, 6, a);
        evaluator
    }

    /// The setup evaluated.
    pub fn setup(&self) -> &Setup {
        self.setup
    }

    /// The value of `criterion` for `postures` (axis angles, rad), equal to
    /// [`Evaluation::value`] of [`Evaluator::evaluation`]: `+infinity` for a group whose observation
    /// matrix is rank deficient, never NaN.
    pub fn value(&self, criterion: Criterion, postures: &[Vector6<f64>]) -> f64 {
        if criterion == Criterion::Classical {
            return postures
                .iter()
                .map(|q| self.dexterity(&self.jacobians(q)))
                .fold(0.0, f64::max);
        }
        let needs_dexterity = criterion == Criterion::Zhang2021;
        let (psi, classical) = self.observation(postures, needs_dexterity);
        self.value_from(criterion, psi, postures.len(), classical)
    }

    /// The terms of one posture (axis angles, rad), to reuse across groups that share it (finite
    /// differences change one posture at a time).
    pub fn posture(&self, q: &Vector6<f64>) -> PostureTerms {
        let jacobians = self.jacobians(q);
        let p3 = self.block_rows();
        let mut rows = vec![0.0; p3 * 6];
        self.write_block(&jacobians, &mut rows, p3, 0);
        PostureTerms {
            rows,
            dexterity: self.dexterity(&jacobians),
        }
    }

    /// The value of `criterion` for the group of postures whose terms are given: the same as
    /// [`Evaluator::value`] of those postures.
    pub fn value_of(&self, criterion: Criterion, terms: &[&PostureTerms]) -> f64 {
        let classical = terms.iter().map(|t| t.dexterity).fold(0.0, f64::max);
        if criterion == Criterion::Classical {
            return classical;
        }
        let p3 = self.block_rows();
        let m = p3 * terms.len();
        let mut psi = vec![0.0; m * 6];
        for (i, t) in terms.iter().enumerate() {
            for j in 0..6 {
                psi[j * m + p3 * i..j * m + p3 * (i + 1)]
                    .copy_from_slice(&t.rows[j * p3..(j + 1) * p3]);
            }
        }
        self.value_from(criterion, psi, terms.len(), classical)
    }

    /// Every criterion and the predicted deviation rates of `postures` (axis angles, rad).
    pub fn evaluation(&self, postures: &[Vector6<f64>]) -> Evaluation {
        let (psi, classical) = self.observation(postures, true);
        let levels = &self.setup.noise.levels;
        let Some(group) = self.group(psi, postures.len()) else {
            let inf = f64::INFINITY;
            return Evaluation {
                classical,
                zhang2021: inf,
                scaled_cond: inf,
                d_optimal: inf,
                relative_a: inf,
                test_pose: inf,
                cond_psi: inf,
                relative_std: Vector6::repeat(inf),
                predicted_deviation_pct: vec![[inf; 6]; levels.len()],
            };
        };
        let cond_psi = finite(cond(&group.r));
        let relative_std = group.relative_std();
        Evaluation {
            classical,
            zhang2021: finite(classical * cond_psi),
            scaled_cond: finite(cond(&group.rs)),
            d_optimal: group.d_optimal(),
            relative_a: group.relative_a(),
            test_pose: self.test_pose(&group),
            cond_psi,
            relative_std,
            predicted_deviation_pct: levels
                .iter()
                .map(|&m| predicted_deviation_pct(&relative_std, m))
                .collect(),
        }
    }

    /// `3p`: the rows of one posture's block.
    fn block_rows(&self) -> usize {
        3 * self.setup.tool.measuring_points.len()
    }

    /// `Psi` of the group (column-major) and its classical index (0 unless `dexterity`).
    fn observation(&self, postures: &[Vector6<f64>], dexterity: bool) -> (Vec<f64>, f64) {
        let p3 = self.block_rows();
        let m = p3 * postures.len();
        let mut psi = vec![0.0; m * 6];
        let mut classical: f64 = 0.0;
        for (i, q) in postures.iter().enumerate() {
            let jacobians = self.jacobians(q);
            self.write_block(&jacobians, &mut psi, m, p3 * i);
            if dexterity {
                classical = classical.max(self.dexterity(&jacobians));
            }
        }
        (psi, classical)
    }

    fn value_from(&self, criterion: Criterion, psi: Vec<f64>, n: usize, classical: f64) -> f64 {
        let Some(group) = self.group(psi, n) else {
            return f64::INFINITY;
        };
        finite(match criterion {
            Criterion::Classical => classical,
            Criterion::Zhang2021 => classical * cond(&group.r),
            Criterion::ScaledCond => cond(&group.rs),
            Criterion::DOptimal => group.d_optimal(),
            Criterion::RelativeA => group.relative_a(),
            Criterion::TestPose => self.test_pose(&group),
        })
    }

    /// The forward kinematics of posture q (axis angles, rad) as [`Jacobians`].
    fn jacobians(&self, q: &Vector6<f64>) -> Jacobians {
        let frames = self.setup.robot.frames(q);
        let p0 = frames.flange.translation.vector;
        let mut jv = Matrix3x6::zeros();
        let mut jw = Matrix3x6::zeros();
        for c in 0..6 {
            let z = frames.axis_directions[c];
            jv.set_column(c, &z.cross(&(p0 - frames.axis_points[c])));
            jw.set_column(c, &z);
        }
        let (jv, jw) = match &self.axis_matrix {
            Some(m) => {
                let (mut qv, mut qw) = (Matrix3x6::zeros(), Matrix3x6::zeros());
                for &(i, j, v) in m {
                    for a in 0..3 {
                        qv[(a, j)] += jv[(a, i)] * v;
                        qw[(a, j)] += jw[(a, i)] * v;
                    }
                }
                (qv, qw)
            }
            None => (jv, jw),
        };
        Jacobians {
            jv,
            jw,
            p0,
            rotation: frames.flange.rotation,
        }
    }

    /// Writes the posture's `3p x 6` block of `Psi` (Eq. 11) into the column-major `out` with `ld`
    /// rows, from row `row`.
    fn write_block(&self, kin: &Jacobians, out: &mut [f64], ld: usize, row: usize) {
        let tool = &self.setup.tool;
        let (jv, jw, p0) = (&kin.jv, &kin.jw, kin.p0);
        let point_jacobian = |p: &Vector3<f64>| {
            let d = kin.rotation * p;
            let mut j = *jv;
            for c in 0..6 {
                let w = jw.column(c).into_owned();
                j.set_column(c, &(jv.column(c) + w.cross(&d)));
            }
            (j, p0 + d)
        };
        let (jf, pf) = point_jacobian(&tool.loading_point);
        let wrench = self.setup.load.wrench(&pf);
        let tau = jf.tr_mul(&wrench.fixed_rows::<3>(0));
        for (k, p) in tool.measuring_points.iter().enumerate() {
            let (jm, _) = point_jacobian(p);
            for c in 0..6 {
                for a in 0..3 {
                    out[c * ld + row + 3 * k + a] = jm[(a, c)] * tau[c];
                }
            }
        }
    }

    /// `k(J_N)` of the TCP (Eq. 20-21), as [`crate::dexterity`]: `|J_N|_F |J_N^-1|_F / 6` with
    /// `|J_N^-1|_F = |R^-1|_F` from `J_N = Q R`; `+infinity` at `1 / f64::EPSILON` or beyond.
    fn dexterity(&self, kin: &Jacobians) -> f64 {
        let (jv, jw) = (&kin.jv, &kin.jw);
        let d = kin.rotation * self.setup.tool.tcp;
        let l = self.setup.characteristic_length;
        let mut jn = [[0.0; 6]; 6];
        for (c, col) in jn.iter_mut().enumerate() {
            let v = (jv.column(c) + jw.column(c).into_owned().cross(&d)) / l;
            col[..3].copy_from_slice(v.as_slice());
            col[3..].copy_from_slice(jw.column(c).as_slice());
        }
        let norm = jn.iter().flatten().map(|v| v * v).sum::<f64>().sqrt();
        let r = square_upper_factor(jn);
        let k = match triangular_inverse(&r) {
            Some(inv) => norm * inv.norm() / 6.0,
            None => f64::INFINITY,
        };
        if k < 1.0 / f64::EPSILON {
            k
        } else {
            f64::INFINITY
        }
    }

    /// The factor of a group's `Psi` (`m = 3pn` rows, column-major), `None` if rank deficient.
    fn group(&self, mut psi: Vec<f64>, n: usize) -> Option<Group> {
        let m = self.block_rows() * n;
        if m < 6 {
            return None;
        }
        // Column norms (NaN or infinity if an entry is not finite).
        let norms = Vector6::from_fn(|j, _| {
            let c = &psi[j * m..(j + 1) * m];
            dot(c, c).sqrt()
        });
        let scale = norms.max();
        if !norms.iter().all(|v| v.is_finite()) || norms.min() <= scale * RANK_TOLERANCE {
            return None;
        }
        let r = upper_factor(&mut psi, m);
        let r_inv = triangular_inverse(&r)?;
        let bound = r.norm() * r_inv.norm();
        let deficient = match bound {
            b if !b.is_finite() => true,
            b if b * RANK_TOLERANCE < 1.0 => false,
            b if b * RANK_TOLERANCE >= 6.0 => true,
            _ => cond(&r) * RANK_TOLERANCE >= 1.0,
        };
        if deficient {
            return None;
        }
        let rs = r * Matrix6::from_diagonal(&self.scaling);
        let rs_inv = Matrix6::from_diagonal(&self.scaling.map(|s| 1.0 / s)) * r_inv;
        Some(Group {
            r,
            r_inv,
            rs,
            rs_inv,
        })
    }

    /// `sigma sqrt(mean_t tr(A_t (Psi^T Psi)^-1 A_t^T)) = sigma |A R^-1|_F / sqrt(T)`, m; 0 without
    /// test postures.
    fn test_pose(&self, group: &Group) -> f64 {
        let t = self.setup.test_postures.len();
        if t == 0 {
            return 0.0;
        }
        // Row i of A R^-1: a_i R^-1, R^-1 upper triangular.
        let a = &self.test_rows;
        let mut sum = 0.0;
        for i in 0..a.nrows() {
            for j in 0..6 {
                let x: f64 = (0..=j).map(|k| a[(i, k)] * group.r_inv[(k, j)]).sum();
                sum += x * x;
            }
        }
        finite(self.setup.noise.sigma() * (sum / t as f64).sqrt())
    }
}

/// One posture's kinematics in the springs' coordinates: the translation Jacobian `jv` of the
/// flange origin `p0` and the rotation Jacobian `jw` (3x6 each, base frame), and the flange
/// rotation.
struct Jacobians {
    jv: Matrix3x6<f64>,
    jw: Matrix3x6<f64>,
    p0: Vector3<f64>,
    rotation: UnitQuaternion<f64>,
}

/// The triangular factor of a full-rank group: `Psi = Q R` and `S = Q R_s`, `R_s = R diag(h) / sigma`.
struct Group {
    r: Matrix6<f64>,
    r_inv: Matrix6<f64>,
    rs: Matrix6<f64>,
    rs_inv: Matrix6<f64>,
}

impl Group {
    /// `sqrt([(S^T S)^-1]_jj)`: the row norms of `R_s^-1` (`(S^T S)^-1 = R_s^-1 R_s^-T`).
    fn relative_std(&self) -> Vector6<f64> {
        Vector6::from_fn(|j, _| finite(self.rs_inv.row(j).norm()))
    }

    /// `det((S^T S)^-1)^(1/12) = prod_k |R_s,kk|^(-1/6)`.
    fn d_optimal(&self) -> f64 {
        let log_det: f64 = self.rs.diagonal().iter().map(|d| d.abs().ln()).sum();
        finite((-log_det / 6.0).exp())
    }

    /// `sqrt(tr((S^T S)^-1) / 6) = |R_s^-1|_F / sqrt(6)`.
    fn relative_a(&self) -> f64 {
        finite(self.rs_inv.norm() / 6f64.sqrt())
    }
}

/// `v`, or `+infinity` if it is not finite.
fn finite(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        f64::INFINITY
    }
}

/// The upper triangular `R` (6x6) of `a = Q R` by Householder reflections, `a` column-major with
/// `m >= 6` rows and 6 columns (overwritten). `Q` is not formed.
fn upper_factor(a: &mut [f64], m: usize) -> Matrix6<f64> {
    let mut r = Matrix6::zeros();
    for k in 0..6 {
        let (done, rest) = a.split_at_mut((k + 1) * m);
        let v = &mut done[k * m + k..(k + 1) * m];
        let norm = dot(v, v).sqrt();
        let x0 = v[0];
        let alpha = if x0 > 0.0 { -norm } else { norm };
        r[(k, k)] = alpha;
        v[0] -= alpha;
        // v^T v = |x|^2 - x0^2 + (x0 - alpha)^2 = 2 (|x|^2 - x0 alpha), alpha^2 = |x|^2.
        let vv = 2.0 * (norm * norm - x0 * alpha);
        for j in k + 1..6 {
            let col = &mut rest[(j - k - 1) * m + k..(j - k) * m];
            if vv > 0.0 {
                let s = 2.0 * dot(v, col) / vv;
                col.iter_mut().zip(v.iter()).for_each(|(y, x)| *y -= s * x);
            }
            r[(k, j)] = col[0];
        }
    }
    r
}

/// [`upper_factor`] of a 6x6 matrix given by columns (fixed sizes, so the loops unroll).
fn square_upper_factor(mut a: [[f64; 6]; 6]) -> Matrix6<f64> {
    let mut r = Matrix6::zeros();
    for k in 0..6 {
        let norm = (k..6).map(|i| a[k][i] * a[k][i]).sum::<f64>().sqrt();
        let x0 = a[k][k];
        let alpha = if x0 > 0.0 { -norm } else { norm };
        r[(k, k)] = alpha;
        a[k][k] -= alpha;
        let vv = 2.0 * (norm * norm - x0 * alpha);
        let v = a[k];
        for j in k + 1..6 {
            if vv > 0.0 {
                let s = 2.0 * (k..6).map(|i| v[i] * a[j][i]).sum::<f64>() / vv;
                for i in k..6 {
                    a[j][i] -= s * v[i];
                }
            }
            r[(k, j)] = a[j][k];
        }
    }
    r
}

/// `a . b` with four independent partial sums (so the compiler can vectorise it).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// The inverse of an upper triangular 6x6 matrix, `None` if a diagonal entry is 0 or the result is
/// not finite.
fn triangular_inverse(r: &Matrix6<f64>) -> Option<Matrix6<f64>> {
    let r: [[f64; 6]; 6] = (*r).into();
    let mut inv = [[0.0; 6]; 6];
    for j in 0..6 {
        inv[j][j] = 1.0 / r[j][j];
        for i in (0..j).rev() {
            let s: f64 = (i + 1..=j).map(|k| r[k][i] * inv[j][k]).sum();
            inv[j][i] = -s / r[i][i];
        }
    }
    let inv = Matrix6::from(inv);
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// `s_max / s_min` of a 6x6 matrix by one-sided Jacobi (Hestenes) rotations of its columns until
/// every pair is orthogonal to rounding: accurate relative to each singular value (Demmel & Veselic
/// 1992). Column norms are updated with each rotation rather than recomputed.
fn cond(a: &Matrix6<f64>) -> f64 {
    let mut c: [[f64; 6]; 6] = (*a).into();
    let mut norms: [f64; 6] = std::array::from_fn(|j| c[j].iter().map(|v| v * v).sum());
    for _ in 0..60 {
        let mut rotated = false;
        for p in 0..5 {
            for q in p + 1..6 {
                let gamma: f64 = (0..6).map(|k| c[p][k] * c[q][k]).sum();
                if gamma.abs() <= f64::EPSILON * (norms[p] * norms[q]).sqrt() {
                    continue;
                }
                rotated = true;
                let zeta = (norms[q] - norms[p]) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let cs = 1.0 / (1.0 + t * t).sqrt();
                let sn = cs * t;
                let (head, tail) = c.split_at_mut(q);
                for (x, y) in head[p].iter_mut().zip(tail[0].iter_mut()) {
                    (*x, *y) = (cs * *x - sn * *y, sn * *x + cs * *y);
                }
                norms[p] -= t * gamma;
                norms[q] += t * gamma;
            }
        }
        if !rotated {
            break;
        }
    }
    let s: [f64; 6] = std::array::from_fn(|j| c[j].iter().map(|v| v * v).sum::<f64>().sqrt());
    let max = s.iter().fold(0.0, |a: f64, v| a.max(*v));
    let min = s.iter().fold(f64::INFINITY, |a: f64, v| a.min(*v));
    max / min
}
