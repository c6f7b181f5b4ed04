//! The deflection of the joints under the robot's own weight (and the tool's).
//!
//! Link `l` (0-based: the body turned by joints `0..=l`, its frame the joint frame
//! [`stiffid_core::Frames::joints`]`[l]`, the tool part of link 5) of mass `m_l` with its centre `s_l`
//! (link frame) weighs `m_l g`, `g = (0, 0, -`[`G`]`)` m/s^2 in the robot base frame (the base's
//! z axis points up). The joint torques it exerts, in the springs' coordinates, are
//! `tau = J_l(p)^T m_l g` with `J_l` the translational Jacobian of the centre `p` (base frame) as
//! a point of link `l`, and the springs deflect by `dq_j = c_j tau_j(q)` (Klimchik, Pashkevich et
//! al.: the compliance error of heavy robots under gravity). The torques are evaluated on the
//! nominal chain at the commanded posture: the geometric errors change them by a relative
//! amount of their own size, far below what a fit resolves, and so the deflection is linear in
//! the unknowns.
//!
//! - [`Gravity::Masses`]: masses and centres known (URDF `<inertial>`, robot files' `mass_kg`,
//!   `com_mm`), the six compliances `c_j` unknown: one term per joint, regressor `tau_j(q)` (N m).
//! - [`Gravity::LumpedLinks`]: masses unknown. Writing `m_l s_l = (m_l s_x, m_l s_y, m_l s_z)`, the
//!   torque is linear in the four mass moments `(m_l, m_l s_l)` of every link:
//!   `tau_j = sum_l [m_l Y_jl0(q) + sum_k (m_l s_l)_k Y_jlk(q)]`, `Y_jl0 = J_l(o_l)[:, j] . g` (the
//!   unit mass at the link origin `o_l`), `Y_jlk = (J_l(o_l + R_l e_k) - J_l(o_l))[:, j] . g`. The
//!   unknowns are the products `c_j m_l` and `c_j (m_l s_l)_k`, one term per joint `j` and link
//!   `l` it carries and moment `k`. Only combinations are separable: a compliance and a mass
//!   never apart (scaling every mass and dividing every compliance leaves the deflection), a
//!   vertical joint's terms not at all (gravity exerts no torque about it), a moment along a joint
//!   axis not by that joint; [`crate::calibration::identifiability`] keeps the independent terms
//!   and names the merged.
//! - [`Gravity::Lumped`]: the same for three bodies: the upper arm (link 1), the
//!   forearm (link 2, with link 3, the forearm tube that joint 4 rolls, lumped in) and the wrist
//!   (link 4, with the flange and the tool, link 5, lumped in). A lumped link's mass moments are
//!   taken as fixed in its body's frame: exact for a centre on the rolling axis (joints 4 and 6
//!   of a spherical wrist), an approximation otherwise. On an anthropomorphic arm (joint 1
//!   vertical, 2 and 3 horizontal and parallel) the separable products are, in the absolute
//!   angles `phi_2` of the upper arm and `phi_23` of the forearm: `c_2` times `A, B, C, D` of
//!   `tau_2 = A cos phi_2 + B sin phi_2 + C cos phi_23 + D sin phi_23 + (the wrist's)`, `c_3`
//!   times `C, D` of `tau_3`, and the wrist's first moments with `c_2`, `c_3`, `c_4` and `c_5`:
//!   17 terms on the FANUC R-2000iC/165F (kinematic springs) against 30 for every link.
//! - [`Gravity::Arm`]: masses unknown, three physical terms ([`Terms::arm`]) for a heavy
//!   robot and thin data: the weight of the upper arm and of the forearm (with the wrist and the
//!   tool) on the springs of joints 2 and 3, their centres on the links' axes. The upper arm's
//!   axis runs from joint 2's axis to joint 3's (link 1, 0-based), the forearm's from
//!   joint 3's axis to the wrist point (on joint 4's axis, nearest joint 5's: link 2), both
//!   across the joints' axes; with `phi_2` and `phi_23` their angles above the horizontal,
//!   `dq_2 = a cos phi_2 + b cos phi_23` and `dq_3 = c cos phi_23`, each a compliance times a
//!   mass moment along the axis (`b` and `c` the forearm's, through the compliances of joints 2
//!   and 3). The regressor of a term is the lumped one ([`Gravity::Lumped`]) of its link's first
//!   moment along the axis: a sub-model of `lumped`, its `A` and `C` terms with the centres
//!   on the axes (`B = D = 0` in the axes' angles). It holds on an anthropomorphic arm only
//!   (joint 1 vertical, joints 2 and 3 horizontal and parallel within `ARM_TOLERANCE`); any
//!   other robot is refused, naming the joint.

use nalgebra::{DVectorView, Matrix6, Vector3, Vector6};

mod arm;
mod memo;
use serde::Serialize;
use stiffid_core::common::limits::JointBox;
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::{Error, Result, Robot};

/// Standard gravity, m/s^2.
pub const G: f64 = 9.80665;

/// The bodies of [`Gravity::Lumped`] (links, 0-based): the turret (no term: joint 1 is vertical
/// on every floor robot, and its terms merge), the upper arm, the forearm with link 3 lumped in,
/// the wrist with link 5 and the tool lumped in.
pub(crate) const BODIES: [usize; 4] = [0, 1, 2, 4];

/// Which gravity terms a calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Gravity {
    /// None: the unloaded positions are the rigid robot's.
    #[default]
    None,
    /// Known masses and centres, unknown compliances.
    Masses,
    /// Unknown masses: compliance times mass moment of three bodies, the upper arm, the forearm
    /// and the wrist ([`Terms::of`] builds its terms).
    Lumped,
    /// Unknown masses: compliance times mass moment, for every spring and every link it carries
    /// ([`Terms::lumped`]).
    LumpedLinks,
    /// Unknown masses, three terms: the upper arm's and the forearm's weight on joints 2 and 3,
    /// their centres on the links' axes ([`Terms::arm`]).
    Arm,
}

impl stiffid_core::common::choice::Choice for Gravity {
    const FIELD: &'static str = "gravity";
    const ALL: &'static [Self] = &[
        Gravity::None,
        Gravity::Arm,
        Gravity::Masses,
        Gravity::Lumped,
        Gravity::LumpedLinks,
    ];
    fn name(self) -> &'static str {
        match self {
            Gravity::None => "none",
            Gravity::Masses => "masses",
            Gravity::Lumped => "lumped",
            Gravity::LumpedLinks => "lumped-links",
            Gravity::Arm => "arm",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Gravity::None => "The rigid robot",
            Gravity::Masses => "Known link masses and centres, the joint compliances fitted",
            Gravity::Lumped => {
                "Unknown masses: compliance times mass moment of the upper arm, the forearm and the wrist"
            }
            Gravity::LumpedLinks => {
                "Unknown masses: compliance times mass moment, every joint and every link it carries"
            }
            Gravity::Arm => {
                "Unknown masses, three terms: the upper arm's and the forearm's weight on joints 2 and 3 (an anthropomorphic arm)"
            }
        }
    }
}

stiffid_core::common::choice::by_name!(Gravity);

pub use stiffid_core::robot::LinkMass;

/// Whether [`Gravity::Arm`] holds on `robot`: an anthropomorphic arm (joint 1 vertical, joints 2
/// and 3 horizontal and parallel; the `arm` module's check).
pub(crate) fn takes_arm(robot: &Robot) -> bool {
    arm::axes(robot).is_ok()
}

/// `robot` with `tool` (a body in the flange frame: the setup's [`stiffid_core::setup::Payload::body`])
/// joined to link 6, when the robot gives link masses: the bodies [`Gravity::Masses`] weighs;
/// `robot` itself without a tool or without masses.
pub fn with_tool(robot: &Robot, tool: Option<LinkMass>) -> Robot {
    match (robot.masses(), tool) {
        (Some(m), Some(t)) => {
            let mut m = *m;
            m[5] = m[5].plus(&t.moved(robot.flange()));
            robot.clone().with_masses(Some(m))
        }
        _ => robot.clone(),
    }
}

/// One gravity term.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Term {
    /// The compliance of spring `joint` (0-based), rad/(N m), regressor `tau_joint(q)`, N m.
    Compliance {
        /// The spring, 0-based.
        joint: usize,
    },
    /// `c_joint` times mass moment `moment` (0 the mass, 1-3 the first moment along the link
    /// frame's x, y, z) of link `link` (0-based).
    Lumped {
        /// The spring, 0-based.
        joint: usize,
        /// The link, 0-based.
        link: usize,
        /// 0 the mass, 1-3 the first moment's x, y, z.
        moment: usize,
    },
    /// `c_joint` times the first moment of link `link` (0-based: 1 the upper arm, 2 the forearm)
    /// along its axis ([`Gravity::Arm`]), regressor the unit torque of a first moment along the
    /// axis (N/kg).
    Arm {
        /// The spring, 0-based.
        joint: usize,
        /// The link, 0-based: 1 the upper arm, 2 the forearm.
        link: usize,
    },
}

impl Term {
    /// The spring it deflects, 0-based.
    pub fn joint(self) -> usize {
        match self {
            Term::Compliance { joint } | Term::Lumped { joint, .. } | Term::Arm { joint, .. } => {
                joint
            }
        }
    }

    /// The unit in documents.
    pub(crate) fn unit(self) -> &'static str {
        match self {
            Term::Compliance { .. } => "urad/(N m)",
            Term::Lumped { moment: 0, .. } => "urad kg/(N m)",
            Term::Lumped { .. } | Term::Arm { .. } => "urad kg/N",
        }
    }

    /// The factor from SI to the document's unit.
    pub(crate) fn document_factor(self) -> f64 {
        1e6
    }

    /// Its parameter name: `gravity.c2` for joint 2's compliance, `gravity.c2.link3.mx` for a
    /// lumped term (the joint, the link, the mass moment `m`, `mx`, `my` or `mz`),
    /// `gravity.c2.upper-arm` or `gravity.c3.forearm` for an arm term.
    pub fn name(self) -> String {
        match self {
            Term::Compliance { joint } => format!("gravity.c{}", joint + 1),
            Term::Lumped {
                joint,
                link,
                moment,
            } => format!(
                "gravity.c{}.link{}.{}",
                joint + 1,
                link + 1,
                ["m", "mx", "my", "mz"][moment]
            ),
            Term::Arm { joint, link } => format!(
                "gravity.c{}.{}",
                joint + 1,
                if link == 1 { "upper-arm" } else { "forearm" }
            ),
        }
    }
}

/// The gravity terms of a calibration and what their regressors need.
#[derive(Debug, Clone, PartialEq)]
pub struct Terms {
    kind: Gravity,
    robot: Robot,
    coordinates: Coordinates,
    masses: Option<[LinkMass; 6]>,
    nominal: Vector6<f64>,
    terms: Vec<Term>,
    /// `M^-1` of the axis map, for kinematic springs.
    inverse_map: Matrix6<f64>,
    /// Per link, the unit axis (link frame) of its [`Term::Arm`] terms; zero for other links.
    axes: [Vector3<f64>; 6],
    /// Each term's largest regressor magnitude over [`spanning`] postures ([`Terms::peaks`]).
    peaks: Vec<f64>,
    /// The regressors of the postures met ([`Terms::regressors`]).
    memo: memo::Memo,
}

impl Terms {
    /// No gravity term.
    pub fn none(robot: &Robot) -> Self {
        Self::with_terms(
            (robot, Gravity::None),
            Coordinates::Axis,
            (None, [Vector3::zeros(); 6]),
            Vector6::zeros(),
            Vec::new(),
        )
    }

    /// The model `gravity` of `robot` with springs in `coordinates`: [`Terms::none`],
    /// [`Terms::masses`] of the robot's link masses (the compliances' nominal values `nominal`,
    /// rad/(N m)), the lumped terms of three bodies, [`Terms::lumped`] or [`Terms::arm`].
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`gravity`) for [`Gravity::Masses`] with a robot without masses;
    /// those of [`Terms::masses`] and [`Terms::arm`].
    pub fn of(
        robot: &Robot,
        gravity: Gravity,
        coordinates: Coordinates,
        nominal: Vector6<f64>,
    ) -> Result<Self> {
        match gravity {
            Gravity::None => Ok(Self::none(robot)),
            Gravity::Lumped => Ok(Self::lumped_bodies(robot, coordinates)),
            Gravity::LumpedLinks => Ok(Self::lumped(robot, coordinates)),
            Gravity::Arm => Self::arm(robot, coordinates),
            Gravity::Masses => {
                let Some(masses) = robot.masses() else {
                    return Err(Error::InvalidField {
                        field: "gravity".into(),
                        message: format!(
                            "masses: the robot '{}' gives no link masses (mass_kg and com_mm per joint in a robot file, <inertial> in a URDF): give them or use lumped",
                            robot.name()
                        ),
                    });
                };
                Self::masses(robot, *masses, coordinates, nominal)
            }
        }
    }

    /// Known masses and centres, the compliances of the springs (in `coordinates`) unknown, their
    /// nominal values `nominal` (rad/(N m), zeros when unknown).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`mass_kg`, `com_mm`) when a mass is negative or not finite or a
    /// centre not finite, or (`mass_kg`) when every mass is zero.
    pub fn masses(
        robot: &Robot,
        masses: [LinkMass; 6],
        coordinates: Coordinates,
        nominal: Vector6<f64>,
    ) -> Result<Self> {
        for (i, m) in masses.iter().enumerate() {
            if !(m.mass.is_finite() && m.mass >= 0.0) {
                return Err(invalid(i, "mass_kg", "expected a finite mass, 0 or more"));
            }
            if !m.centre.iter().all(|v| v.is_finite()) {
                return Err(invalid(i, "com_mm", "expected finite numbers"));
            }
        }
        if masses.iter().all(|m| m.mass == 0.0) {
            return Err(invalid(0, "mass_kg", "expected a link with mass"));
        }
        let terms = (0..6).map(|joint| Term::Compliance { joint }).collect();
        Ok(Self::with_terms(
            (robot, Gravity::Masses),
            coordinates,
            (Some(masses), [Vector3::zeros(); 6]),
            nominal,
            terms,
        ))
    }

    /// Unknown masses: the lumped terms of every spring (in `coordinates`) and every link it
    /// carries.
    pub fn lumped(robot: &Robot, coordinates: Coordinates) -> Self {
        Self::lumped_links(
            (robot, Gravity::LumpedLinks),
            coordinates,
            &[0, 1, 2, 3, 4, 5],
        )
    }

    /// Unknown masses, three bodies (module docs, [`Gravity::Lumped`]): the lumped terms of every
    /// spring (in `coordinates`) and every body of [`Gravity::Lumped`] it carries.
    pub(crate) fn lumped_bodies(robot: &Robot, coordinates: Coordinates) -> Self {
        Self::lumped_links((robot, Gravity::Lumped), coordinates, &BODIES)
    }

    /// Unknown masses, three terms ([`Gravity::Arm`], module docs): `c_2` times the upper arm's
    /// first moment along its axis, `c_2` and `c_3` times the forearm's, springs in
    /// `coordinates`.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`gravity`) naming the joint when the robot is not an
    /// anthropomorphic arm (`ARM_TOLERANCE`): joint 1 not vertical, joint 2 not horizontal,
    /// joint 3 not parallel to joint 2, or a link without length across its joints' axes.
    pub fn arm(robot: &Robot, coordinates: Coordinates) -> Result<Self> {
        let axes = arm::axes(robot)?;
        let terms = vec![
            Term::Arm { joint: 1, link: 1 },
            Term::Arm { joint: 1, link: 2 },
            Term::Arm { joint: 2, link: 2 },
        ];
        Ok(Self::with_terms(
            (robot, Gravity::Arm),
            coordinates,
            (None, axes),
            Vector6::zeros(),
            terms,
        ))
    }

    /// The unit axis, in link `link`'s frame, of its [`Term::Arm`] terms (module docs); zero
    /// for a link without.
    pub fn arm_axis(&self, link: usize) -> Vector3<f64> {
        self.axes[link]
    }

    /// The lumped terms of every spring and every link of `links` (0-based) it carries.
    fn lumped_links(
        (robot, kind): (&Robot, Gravity),
        coordinates: Coordinates,
        links: &[usize],
    ) -> Self {
        let m = robot.axis_map().matrix;
        let carries = |joint: usize, link: usize| match coordinates {
            Coordinates::Kinematic => joint <= link,
            Coordinates::Axis => (0..=link).any(|i| m[(i, joint)] != 0.0),
        };
        let mut terms = Vec::new();
        for joint in 0..6 {
            for &link in links {
                if carries(joint, link) {
                    terms.extend((0..4).map(|moment| Term::Lumped {
                        joint,
                        link,
                        moment,
                    }));
                }
            }
        }
        Self::with_terms(
            (robot, kind),
            coordinates,
            (None, [Vector3::zeros(); 6]),
            Vector6::zeros(),
            terms,
        )
    }

    /// The terms `terms` of `kind` on `robot` with the known `masses` and the [`Term::Arm`]
    /// terms' `axes` (zero for none), each term's peak over [`spanning`] postures.
    fn with_terms(
        (robot, kind): (&Robot, Gravity),
        coordinates: Coordinates,
        (masses, axes): (Option<[LinkMass; 6]>, [Vector3<f64>; 6]),
        nominal: Vector6<f64>,
        terms: Vec<Term>,
    ) -> Self {
        let mut made = Terms {
            kind,
            inverse_map: robot
                .axis_map()
                .matrix
                .try_inverse()
                .unwrap_or_else(Matrix6::identity),
            robot: robot.clone(),
            coordinates,
            masses,
            nominal,
            terms,
            axes,
            peaks: Vec::new(),
            memo: memo::Memo::default(),
        };
        made.peaks = made.peaks_over(&spanning(robot.limits()));
        made
    }

    /// Which model it is.
    pub fn kind(&self) -> Gravity {
        self.kind
    }

    /// The terms, in parameter order.
    pub fn terms(&self) -> &[Term] {
        &self.terms
    }

    /// How many terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether there is no term.
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// The springs' coordinates.
    pub fn coordinates(&self) -> Coordinates {
        self.coordinates
    }

    /// The known masses, if any.
    pub fn link_masses(&self) -> Option<&[LinkMass; 6]> {
        self.masses.as_ref()
    }

    /// The nominal value (SI) of `term`: its compliance's nominal value (rad/(N m), zero when
    /// unknown), zero for a lumped or arm term.
    pub(crate) fn nominal(&self, term: Term) -> f64 {
        match term {
            Term::Compliance { joint } => self.nominal[joint],
            Term::Lumped { .. } | Term::Arm { .. } => 0.0,
        }
    }

    /// The unit torques `tau[l][k]` (springs' coordinates) of link `l`'s mass moment `k` at
    /// axis angles `q` (rad): module docs, `Y_.lk`.
    fn unit_torques(&self, q: &Vector6<f64>) -> [[Vector6<f64>; 4]; 6] {
        let f = self.robot.frames(q);
        let g = Vector3::new(0.0, 0.0, -G);
        let m = self.robot.axis_map().matrix;
        std::array::from_fn(|l| {
            let frame = f.joints[l];
            let o = frame.translation.vector;
            std::array::from_fn(|k| {
                let mut theta = Vector6::zeros();
                for i in 0..=l {
                    let z = f.axis_directions[i];
                    let arm = match k {
                        0 => o - f.axis_points[i],
                        _ => frame.rotation * Vector3::ith(k - 1, 1.0),
                    };
                    theta[i] = z.cross(&arm).dot(&g);
                }
                match self.coordinates {
                    Coordinates::Kinematic => theta,
                    Coordinates::Axis => m.transpose() * theta,
                }
            })
        })
    }

    /// The regressor of every term at axis angles `q` (rad): the torque (N m) of a compliance
    /// term, the unit torque of a lumped one (module docs).
    pub(crate) fn regressors(&self, q: &Vector6<f64>) -> Vec<f64> {
        if self.terms.is_empty() {
            return Vec::new();
        }
        self.memo.at(q, || self.computed(q))
    }

    /// [`Terms::regressors`] computed.
    fn computed(&self, q: &Vector6<f64>) -> Vec<f64> {
        let unit = self.unit_torques(q);
        let torque = self.masses.map(|masses| {
            let mut tau = Vector6::zeros();
            for (l, lm) in masses.iter().enumerate() {
                tau += unit[l][0] * lm.mass;
                for k in 0..3 {
                    tau += unit[l][k + 1] * (lm.mass * lm.centre[k]);
                }
            }
            tau
        });
        self.terms
            .iter()
            .map(|t| match *t {
                Term::Compliance { joint } => torque.map_or(0.0, |tau| tau[joint]),
                Term::Lumped {
                    joint,
                    link,
                    moment,
                } => unit[link][moment][joint],
                Term::Arm { joint, link } => (0..3)
                    .map(|k| self.axes[link][k] * unit[link][k + 1][joint])
                    .sum(),
            })
            .collect()
    }

    /// The deflection in axis angles (rad) at commanded axis angles `q` (rad) with the term
    /// values `values` (SI, term order).
    pub fn deflection(&self, values: &DVectorView<'_, f64>, q: &Vector6<f64>) -> Vector6<f64> {
        match self.terms.is_empty() {
            true => Vector6::zeros(),
            false => self.deflection_from(values, &self.regressors(q)),
        }
    }

    /// [`Terms::deflection`] from the regressors of the posture ([`Terms::regressors`]).
    pub(crate) fn deflection_from(
        &self,
        values: &DVectorView<'_, f64>,
        regressors: &[f64],
    ) -> Vector6<f64> {
        let mut springs = Vector6::zeros();
        for ((t, y), v) in self.terms.iter().zip(regressors).zip(values.iter()) {
            springs[t.joint()] += v * y;
        }
        match self.coordinates {
            Coordinates::Axis => springs,
            Coordinates::Kinematic => self.inverse_map * springs,
        }
    }

    /// Each term's largest regressor magnitude (N m, or N m per unit mass moment) over
    /// `SPANNING_POSTURES` postures spread over the robot's joint limits ([`spanning`]): the
    /// largest torque through which a term deflects its joint anywhere the robot can go.
    pub(crate) fn peaks(&self) -> &[f64] {
        &self.peaks
    }

    fn peaks_over(&self, qs: &[Vector6<f64>]) -> Vec<f64> {
        let mut peaks = vec![0.0f64; self.terms.len()];
        if self.terms.is_empty() {
            return peaks;
        }
        for q in qs {
            for (p, y) in peaks.iter_mut().zip(self.regressors(q)) {
                *p = p.max(y.abs());
            }
        }
        peaks
    }

    /// The RMS of each term's regressor over the postures `qs` (axis angles, rad).
    pub(crate) fn regressor_rms(&self, qs: &[Vector6<f64>]) -> Vec<f64> {
        let mut sum = vec![0.0; self.terms.len()];
        for q in qs {
            for (s, y) in sum.iter_mut().zip(self.regressors(q)) {
                *s += y * y;
            }
        }
        let n = qs.len().max(1) as f64;
        sum.iter().map(|s| (s / n).sqrt()).collect()
    }
}

/// The postures of `Terms::peaks`.
pub(crate) const SPANNING_POSTURES: usize = 512;

/// `SPANNING_POSTURES` postures spread over `limits` (axis angles, rad): the Halton sequence
/// in the first six primes (Halton 1960), its first point skipped; an axis with an infinite end
/// spans one turn about 0 (the weight's torque repeats every turn).
pub fn spanning(limits: &JointBox) -> Vec<Vector6<f64>> {
    use std::f64::consts::PI;
    const PRIMES: [u64; 6] = [2, 3, 5, 7, 11, 13];
    let span = |i: usize| match limits.lower[i].is_finite() && limits.upper[i].is_finite() {
        true => (limits.lower[i], limits.upper[i]),
        false => (-PI, PI),
    };
    (1..=SPANNING_POSTURES as u64)
        .map(|k| {
            Vector6::from_fn(|i, _| {
                let (lo, hi) = span(i);
                lo + (hi - lo) * radical_inverse(k, PRIMES[i])
            })
        })
        .collect()
}

/// The van der Corput radical inverse of `k` in `base`: its digits mirrored about the point.
fn radical_inverse(mut k: u64, base: u64) -> f64 {
    let (mut value, mut scale) = (0.0, 1.0 / base as f64);
    while k > 0 {
        value += (k % base) as f64 * scale;
        k /= base;
        scale /= base as f64;
    }
    value
}

fn invalid(link: usize, field: &str, message: &str) -> Error {
    Error::InvalidField {
        field: format!("joint[{}].{field}", link + 1),
        message: message.into(),
    }
}

#[cfg(test)]
mod memo_tests;
