//! Forward kinematics, point Jacobians and the dexterity index.
//!
//! All results are in the robot base frame (the world frame of [`Robot::base`]), SI units.

use crate::Robot;
use nalgebra::{
    Isometry3, Matrix3x6, Matrix6, Point3, Quaternion, UnitQuaternion, Vector3, Vector6,
};
use serde::{Deserialize, Serialize};

mod gradient;
pub use gradient::dexterity_log_gradient;

/// Which joint coordinates a Jacobian's columns refer to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum Coordinates {
    /// Controller axis angles q: `J_q = J_theta M` (the springs sit in the drives).
    #[default]
    Axis,
    /// Kinematic angles theta of the DH table or URDF.
    Kinematic,
}

impl Coordinates {
    /// Both, axis first.
    pub(crate) const ALL: [Coordinates; 2] = [Coordinates::Axis, Coordinates::Kinematic];

    /// The name in files, options and documents: `axis` or `kinematic`.
    pub fn name(self) -> &'static str {
        match self {
            Coordinates::Axis => "axis",
            Coordinates::Kinematic => "kinematic",
        }
    }
}

impl crate::common::choice::Choice for Coordinates {
    const FIELD: &'static str = "coordinates";
    const ALL: &'static [Self] = &Coordinates::ALL;
    fn name(self) -> &'static str {
        Coordinates::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Coordinates::Axis => "Controller axis angles q: J_q = J_theta M",
            Coordinates::Kinematic => "Kinematic angles theta of the DH table or URDF",
        }
    }
}

crate::common::choice::by_name!(Coordinates);

/// The forward kinematics of one posture: every joint frame, every joint axis and the flange.
#[derive(Debug, Clone, PartialEq)]
pub struct Frames {
    /// The chain's first frame: the robot's base ([`Robot::base`]), on a carrier moved by it
    /// ([`Robot::frames_at`]), cell frame, m.
    pub base: Isometry3<f64>,
    /// Frame of each joint after its rotation and fixed `post` transform (for a modified-DH robot
    /// the DH frames 1..6), base frame, m.
    pub joints: [Isometry3<f64>; 6],
    /// A point on each joint axis, base frame, m.
    pub axis_points: [Vector3<f64>; 6],
    /// Unit direction of each joint axis, base frame.
    pub axis_directions: [Vector3<f64>; 6],
    /// The flange frame, base frame, m.
    pub flange: Isometry3<f64>,
    /// The joint screws (Pluecker coordinates) of the Jacobian columns, per [`Coordinates`]:
    /// directions `z_j` and moments `z_j x o_j` (m), kinematic columns first, then the axis
    /// columns (both times `M`), so a point Jacobian costs six cross products.
    screws: [Screws; 2],
    /// The axis map's `M` (`theta = M q + c`), for derivatives with respect to q.
    axis_map: Matrix6<f64>,
}

/// Column directions (rad/rad) and moments (m/rad) of the screws of the six Jacobian columns:
/// column j of the point Jacobian is `[d_j x p - m_j; d_j]`.
#[derive(Debug, Clone, PartialEq)]
struct Screws {
    directions: Matrix3x6<f64>,
    moments: Matrix3x6<f64>,
}

impl Robot {
    /// Forward kinematics at axis angles `q` (rad), the error maps applied ([`Robot::mapped`]).
    /// The Jacobians are the chain's at the mapped angles: the maps' slope `e'(q)` (about
    /// `H` times a coefficient, below 1e-3 of a column for maps of a few arc seconds) is left out
    /// of them, as a spring deflects the link whatever its gear's error.
    pub fn frames(&self, q: &Vector6<f64>) -> Frames {
        let mut f = Frames::blank();
        self.update_frames(q, &mut f);
        f
    }

    /// [`Robot::frames`] at `q` written over `f` (every field), so that a loop over postures reuses
    /// one `Frames` instead of copying a new one out of each call.
    pub fn update_frames(&self, q: &Vector6<f64>, f: &mut Frames) {
        self.update_frames_on(self.base(), q, f);
    }

    /// Forward kinematics of the arm on its carrier: axis angles `q` (rad) and external axis
    /// values `e` (SI, the cell's order, [`crate::robot::external`]), in the cell frame. The
    /// arm's base frame is `C(e) * base` (the carrier's pose, [`ExternalAxes::carrier_pose`]);
    /// without external axes, or with a positioner only, [`Robot::frames`] at `q`.
    ///
    /// [`ExternalAxes::carrier_pose`]: crate::robot::external::ExternalAxes::carrier_pose
    pub fn frames_at(&self, q: &Vector6<f64>, e: &[f64]) -> Frames {
        let base = match self.external() {
            Some(axes) if axes.carrier_len() > 0 => axes.carrier_pose(e) * self.base(),
            _ => *self.base(),
        };
        let mut f = Frames::blank();
        self.update_frames_on(&base, q, &mut f);
        f
    }

    /// [`Robot::update_frames`] with the chain's first frame at `base` (cell frame).
    pub(crate) fn update_frames_on(&self, base: &Isometry3<f64>, q: &Vector6<f64>, f: &mut Frames) {
        self.update_chain(base, &self.mapped(q), f);
    }

    /// [`Robot::update_frames`] with the chain's first frame at `base` (cell frame), approached
    /// with the last motions' signs `direction` (-1.0 or 1.0 per axis, 0.0 for the mean of the
    /// two approaches): the axes turn by
    /// `Robot::mapped_from`, their backlash included.
    pub fn update_frames_from(
        &self,
        base: &Isometry3<f64>,
        q: &Vector6<f64>,
        direction: &Vector6<f64>,
        f: &mut Frames,
    ) {
        self.update_chain(base, &self.mapped_from(q, direction), f);
    }

    /// The chain's frames with its axes turned by `mapped` (axis angles with their errors, rad).
    fn update_chain(&self, base: &Isometry3<f64>, mapped: &Vector6<f64>, f: &mut Frames) {
        let theta = self.axis_map().kinematic(mapped);
        // `flange` carries the running transform, base to the current joint, until it reaches the
        // flange.
        f.base = *base;
        f.flange = *base;
        f.axis_map = self.axis_map().matrix;
        let t = &mut f.flange;
        let [kinematic, axis] = &mut f.screws;
        for (i, joint) in self.joints().iter().enumerate() {
            compose(t, &joint.pre);
            let about_z = joint.axis == Vector3::z_axis();
            let z = match about_z {
                true => z_column(&t.rotation),
                false => t.rotation * joint.axis.into_inner(),
            };
            let o = t.translation.vector;
            f.axis_points[i] = o;
            f.axis_directions[i] = z;
            kinematic.directions.set_column(i, &z);
            kinematic.moments.set_column(i, &z.cross(&o));
            let angle = theta[i] + joint.offset;
            match about_z {
                true => turn_about_z(&mut t.rotation, angle),
                false => *t *= UnitQuaternion::from_axis_angle(&joint.axis, angle),
            }
            compose(t, &joint.post);
            f.joints[i] = *t;
        }
        compose(t, self.flange());
        kinematic.times(&self.axis_map().matrix, axis);
    }
}

impl Frames {
    /// Frames to be written over by the kinematics (`Robot::update_frames_on`).
    pub fn blank() -> Self {
        Frames {
            base: Isometry3::identity(),
            joints: [Isometry3::identity(); 6],
            axis_points: [Vector3::zeros(); 6],
            axis_directions: [Vector3::zeros(); 6],
            flange: Isometry3::identity(),
            screws: [Screws::zeros(), Screws::zeros()],
            axis_map: Matrix6::identity(),
        }
    }
}

impl Screws {
    fn zeros() -> Self {
        Self {
            directions: Matrix3x6::zeros(),
            moments: Matrix3x6::zeros(),
        }
    }

    /// Writes into `out` the screws of the columns of `J M`: column c is
    /// `sum_k M[k, c]` times column k. Skips the zeros of `M` (most axis maps are a signed
    /// permutation plus the J2/J3 coupling).
    fn times(&self, m: &Matrix6<f64>, out: &mut Screws) {
        for c in 0..6 {
            let (mut d, mut w) = (Vector3::zeros(), Vector3::zeros());
            for k in 0..6 {
                let f = m[(k, c)];
                if f != 0.0 {
                    d += self.directions.column(k) * f;
                    w += self.moments.column(k) * f;
                }
            }
            out.directions.set_column(c, &d);
            out.moments.set_column(c, &w);
        }
    }
}

/// The third column of the rotation matrix of the unit quaternion `r` (the image of the z axis):
/// `(2(xz + wy), 2(yz - wx), 1 - 2(x^2 + y^2))`, a third of the work of `r * z`.
#[inline(always)]
fn z_column(r: &UnitQuaternion<f64>) -> Vector3<f64> {
    let (w, x, y, z) = (r.w, r.i, r.j, r.k);
    Vector3::new(
        2.0 * (x * z + w * y),
        2.0 * (y * z - w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

/// `r <- r (cos(a/2) + sin(a/2) k)`: the rotation by `a` (rad) about the z axis composed on the
/// right, a product with a quaternion of two non-zero components.
#[inline(always)]
fn turn_about_z(r: &mut UnitQuaternion<f64>, a: f64) {
    let (s, c) = (0.5 * a).sin_cos();
    let (w, x, y, z) = (r.w, r.i, r.j, r.k);
    *r = UnitQuaternion::new_unchecked(Quaternion::new(
        w * c - z * s,
        x * c + y * s,
        y * c - x * s,
        z * c + w * s,
    ));
}

/// `t *= a`, skipping the rotation product when `a` is a pure translation (exactly: most DH
/// `pre`/`post` transforms) and everything when `a` is the identity. A translation along z alone
/// (a DH `d`) is `d` times the third column of `t`'s rotation.
#[inline(always)]
fn compose(t: &mut Isometry3<f64>, a: &Isometry3<f64>) {
    let v = a.translation.vector;
    if a.rotation.as_ref().imag() != Vector3::zeros() {
        *t *= a;
    } else if v.x == 0.0 && v.y == 0.0 {
        if v.z != 0.0 {
            t.translation.vector += z_column(&t.rotation) * v.z;
        }
    } else {
        t.translation.vector += t.rotation * v;
    }
}

impl Frames {
    /// Base-frame position (m) of a point given in the flange frame (m).
    pub fn point(&self, in_flange: &Vector3<f64>) -> Vector3<f64> {
        (self.flange * Point3::from(*in_flange)).coords
    }

    /// Geometric Jacobian (6x6, base frame, rows `[v; omega]`, m/rad and rad/rad) of the body point
    /// given in the flange frame (m), with columns in the chosen joint coordinates.
    ///
    /// Column j in kinematic coordinates is `[z_j x (p - o_j); z_j]`, `z_j` the joint axis and `o_j`
    /// a point on it; in axis coordinates the matrix is multiplied by `M` (`J_q = J_theta M`).
    /// Both are computed from the joint screws of [`Robot::frames`]: `[d_j x p - m_j; d_j]`.
    pub fn jacobian(&self, in_flange: &Vector3<f64>, coordinates: Coordinates) -> Matrix6<f64> {
        self.columns(&self.point(in_flange), coordinates, |x| x)
    }

    /// The translational Jacobian (3x6, base frame, m/rad, columns in axis coordinates) of the
    /// base-frame point `p` carried by link `link` (0 the base, which nothing moves; i turns with
    /// joints 1..=i): column c is `sum_{j <= link} M[j, c] (z_j x (p - o_j))`, the velocity of a point
    /// fixed in that link per unit speed of axis c.
    pub(crate) fn link_point_jacobian(&self, p: &Vector3<f64>, link: usize) -> Matrix3x6<f64> {
        let k = &self.screws[0];
        let mut kinematic = Matrix3x6::zeros();
        for j in 0..link.min(6) {
            let v = k.directions.column(j).cross(p) - k.moments.column(j);
            kinematic.set_column(j, &v);
        }
        kinematic * self.axis_map
    }

    /// The rotational Jacobian (3x6, base frame, rad/rad, columns in axis coordinates) of the
    /// flange: the joint axes times `M`.
    pub(crate) fn flange_rotation_jacobian(&self) -> Matrix3x6<f64> {
        self.screws[1].directions
    }

    /// The body Jacobian (6x6, flange frame, rows `[v; omega]`, m/rad and rad/rad) of the flange
    /// origin, columns in the chosen joint coordinates: [`Frames::jacobian`] of the origin with both
    /// 3-row blocks rotated by `R_f^T`, `R_f` the flange's rotation.
    pub(crate) fn body_jacobian(&self, coordinates: Coordinates) -> Matrix6<f64> {
        let rt = self.flange.rotation.to_rotation_matrix().into_inner();
        let rt = rt.transpose();
        self.columns(&self.flange.translation.vector, coordinates, |x| rt * x)
    }

    /// The Jacobian columns `[d_j x p - m_j; d_j]` of the base-frame point `p`, both 3-row blocks
    /// passed through `frame` (the identity for the base frame).
    #[inline(always)]
    fn columns(
        &self,
        p: &Vector3<f64>,
        coordinates: Coordinates,
        frame: impl Fn(Vector3<f64>) -> Vector3<f64>,
    ) -> Matrix6<f64> {
        let screws = match coordinates {
            Coordinates::Kinematic => &self.screws[0],
            Coordinates::Axis => &self.screws[1],
        };
        let mut j = Matrix6::zeros();
        for c in 0..6 {
            let d = screws.directions.column(c).into_owned();
            let v = d.cross(p) - screws.moments.column(c);
            j.fixed_view_mut::<3, 1>(0, c).copy_from(&frame(v));
            j.fixed_view_mut::<3, 1>(3, c).copy_from(&frame(d));
        }
        j
    }
}

/// The dexterity index from which a posture counts as singular: `1e-3 / f64::EPSILON` (about
/// 4.5e12), where the inverse keeps fewer than 3 correct digits. A wrist angle of 1e-6 rad from
/// the singularity still gives a finite index of about 1e6.
pub(crate) const NUMERICALLY_SINGULAR: f64 = 1e-3 / f64::EPSILON;

/// Dexterity index `k(J_N) = (1/6) sqrt(tr(A) tr(A^-1))`, `A = J_N J_N^T`,
/// `J_N = diag(I/L, I) J` (Zhang et al. 2021, Eq. 20-21; the Frobenius-norm condition number of the
/// normalised Jacobian, Paden & Sastry 1988).
///
/// `jacobian` is 6x6 with rows `[v; omega]` (m/rad, rad/rad); `characteristic_length` L in m.
/// 1 for an isotropic Jacobian, larger is worse; `+infinity` at a singularity (also a numerical
/// one: a value of `NUMERICALLY_SINGULAR` or more, where the computed inverse is mostly rounding
/// noise: at an exactly singular posture rounding leaves values near `1 / f64::EPSILON`, 4.5e15)
/// or for non-finite input. Since `tr(A) = |J_N|_F^2` and `tr(A^-1) = |J_N^-1|_F^2`, it is computed as
/// `|J_N|_F |J_N^-1|_F / 6` without forming `A`.
pub fn dexterity(jacobian: &Matrix6<f64>, characteristic_length: f64) -> f64 {
    index(&normalise(jacobian, characteristic_length)).map_or(f64::INFINITY, |(k, _)| k)
}

/// `J_N = diag(I/L, I) J`.
fn normalise(jacobian: &Matrix6<f64>, characteristic_length: f64) -> Matrix6<f64> {
    let mut jn = *jacobian;
    jn.fixed_rows_mut::<3>(0)
        .scale_mut(1.0 / characteristic_length);
    jn
}

/// `k(J_N) = |J_N|_F |J_N^-1|_F / 6` and `J_N^-1`, where the index is finite and below
/// `NUMERICALLY_SINGULAR` (a non-finite entry makes `|J_N|_F` non-finite: no inverse is tried).
fn index(jn: &Matrix6<f64>) -> Option<(f64, Matrix6<f64>)> {
    let norm = jn.norm();
    if !norm.is_finite() {
        return None;
    }
    let inverse = crate::math::linalg::inverse(jn)?;
    let dexterity = norm * inverse.norm() / 6.0;
    (dexterity < NUMERICALLY_SINGULAR).then_some((dexterity, inverse))
}

/// The normalised Jacobian `J_N` and its inverse, where the dexterity is finite.
fn normalised(
    jacobian: &Matrix6<f64>,
    characteristic_length: f64,
) -> Option<(Matrix6<f64>, Matrix6<f64>)> {
    let jn = normalise(jacobian, characteristic_length);
    index(&jn).map(|(_, inverse)| (jn, inverse))
}
