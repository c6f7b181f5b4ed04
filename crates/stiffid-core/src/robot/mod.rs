//! The robot model: an immutable 6-axis serial chain of revolute joints.
//!
//! A [`Robot`] is built from a DH table ([`dh`]), a URDF file ([`urdf`]), a robot TOML file
//! ([`mod@file`]) or a built-in preset ([`presets`]). Its kinematics are in [`crate::robot::kinematics`].

pub(crate) mod builtin;
pub mod collision;
pub mod configuration;
pub mod dh;
pub mod dynamics;
pub mod error_map;
pub mod external;
pub mod file;
pub mod ik;
pub mod kinematics;
pub mod parts;
pub mod presets;
pub mod urdf;
pub mod urdf_write;
pub mod weight_file;

mod axis_map;
pub use axis_map::AxisMap;
pub use error_map::ErrorMap;
pub use external::ExternalAxes;
pub use weight_file::OwnWeight;

use nalgebra::{Isometry3, Matrix3, Unit, Vector3, Vector6};
use std::sync::Arc;

use crate::common::limits::{self, JointBox};
use crate::{Error, Result};

/// One revolute joint of the chain, in the frame of the previous joint's child link.
///
/// The transform across the joint at kinematic angle `theta` is
/// `pre * Rot(axis, theta + offset) * post`. A modified-DH row gives
/// `pre = RotX(alpha_{i-1}) TransX(a_{i-1})`, `post = TransZ(d_i)`; a standard-DH row gives
/// `pre = I`, `post = TransZ(d_i) TransX(a_i) RotX(alpha_i)`; a URDF joint gives `pre` = its origin
/// (with fixed joints before it folded in) and `post = I`. Lengths in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Fixed transform from the previous joint frame to this joint's rotation frame.
    pub pre: Isometry3<f64>,
    /// Unit rotation axis, in the rotation frame.
    pub axis: Unit<Vector3<f64>>,
    /// Fixed transform after the rotation, to this joint's frame.
    pub post: Isometry3<f64>,
    /// Constant added to the kinematic angle (a DH table's theta offset), rad.
    pub offset: f64,
}

/// An immutable 6-axis serial robot with revolute joints.
///
/// Postures are axis angles `q` (rad, controller convention); [`AxisMap`] turns them into the
/// kinematic angles `theta` of the chain. Joint limits are in axis coordinates. Built by
/// [`Robot::new`] and the `with_*` methods, which check what they are given, or read from a file
/// ([`mod@file`], [`urdf`]) or a preset ([`presets`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    name: String,
    source: String,
    joints: [Joint; 6],
    axis_map: AxisMap,
    limits: JointBox,
    base: Isometry3<f64>,
    flange: Isometry3<f64>,
    /// The controller's world frame in the robot base frame ([`Robot::controller_world`]).
    controller_world: Isometry3<f64>,
    bodies: Bodies,
    masses: Option<[LinkMass; 6]>,
    urdf: Option<std::sync::Arc<urdf::UrdfSource>>,
    /// The axes' error maps ([`ErrorMap`]), when any axis has one.
    error_maps: Option<Arc<[ErrorMap; 6]>>,
    /// The cell's external axes ([`external`]), when it has any.
    external: Option<Arc<ExternalAxes>>,
    /// A calibrated robot's held-out position errors ([`HeldOut`]), when its file carries them.
    held_out: Option<Arc<HeldOut>>,
    /// The mount a calibrated robot was calibrated on, when its file records it (`[mount]`).
    mount: Option<Isometry3<f64>>,
    /// The part's frame a calibration located from the reflectors fixed in the cell (on the
    /// positioner's table or on a fixed part), when its file records it (`[part]`).
    part: Option<Isometry3<f64>>,
    /// A calibrated robot's sag under its own weight ([`OwnWeight`]), when its
    /// file carries it.
    own_weight: Option<Arc<OwnWeight>>,
    /// Each axis's largest speed, rad/s; infinite: no limit.
    max_speeds: Vector6<f64>,
}

/// The held-out position errors of a calibration (`stiffid calibrate --validate` or
/// `--cross-validate`), as the calibrated robot file carries them (`[held_out]`): the length of
/// each held-out reading's error (predicted minus read, m), sorted, and where they come from.
/// A compensation's error budget takes their quantile at its level as the calibration's part
/// ([`HeldOut::quantile`]).
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOut {
    /// `validate` (readings the fit did not see) or `cross-validate` (leave one posture out).
    pub source: String,
    /// The errors' lengths, m, sorted, finite and non-negative (at least one).
    pub errors: Vec<f64>,
}

impl HeldOut {
    /// The split conformal quantile at `level` (Lei et al. 2018, as the stiffness's deflection
    /// intervals take theirs): the `ceil(level (N + 1))`-th smallest of the `N` errors, m;
    /// infinite when `N` is too small for the level.
    pub fn quantile(&self, level: f64) -> f64 {
        let n = self.errors.len();
        let k = (level * (n + 1) as f64 - 1e-9).ceil() as usize;
        match k >= 1 && k <= n {
            true => self.errors[k - 1],
            false => f64::INFINITY,
        }
    }
}

/// What a calibrated robot's name ends with (the robot files `stiffid calibrate` writes).
pub const CALIBRATED: &str = " (calibrated)";

/// A link's rigid-body inertia: its mass, centre of mass and inertia tensor (the gravity model of
/// `stiffid_metrology::calibration::gravity` uses the first two, the mass matrix of
/// [`dynamics`] all three).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LinkMass {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass in the link frame (the joint frame [`crate::Frames::joints`]), m.
    pub centre: Vector3<f64>,
    /// Inertia tensor about the centre of mass, axes of the link frame, kg m^2 (symmetric;
    /// zero when the description gives none).
    pub inertia: Matrix3<f64>,
}

impl Robot {
    /// The robot of six joints (base to flange, lengths in m) within `limits` (axis coordinates,
    /// rad; an infinite end is an unbounded axis), with the identity axis map, base and flange and
    /// [`Bodies::Scaled`]. `name` is human-readable ("COMAU SMART5 NJ 165-3.0"), `source` says
    /// where the numbers come from (datasheet, paper, repository).
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a joint's transforms, axis or offset are not finite, or as
    /// [`Robot::with_limits`].
    ///
    /// # Examples
    /// ```
    /// use nalgebra::Vector6;
    /// use stiffid_core::{common::limits::JointBox, robot::dh, Robot};
    /// let row = dh::Row { a: 0.5, alpha: 0.0, d: 0.1, theta_offset: 0.0 };
    /// let joints = std::array::from_fn(|_| dh::joint(dh::Convention::StandardDh, &row));
    /// let limits = JointBox::new(Vector6::repeat(-3.0), Vector6::repeat(3.0));
    /// let robot = Robot::new("planar", "example", joints.clone(), limits)?;
    /// assert_eq!(robot.limits().upper[0], 3.0);
    /// let reversed = JointBox::new(Vector6::repeat(3.0), Vector6::repeat(-3.0));
    /// assert!(Robot::new("planar", "example", joints, reversed).is_err());
    /// # Ok::<(), stiffid_core::Error>(())
    /// ```
    pub fn new(
        name: impl Into<String>,
        source: impl Into<String>,
        joints: [Joint; 6],
        limits: JointBox,
    ) -> Result<Self> {
        for (i, j) in joints.iter().enumerate() {
            let finite = finite(&j.pre)
                && finite(&j.post)
                && j.axis.iter().all(|v| v.is_finite())
                && j.offset.is_finite();
            if !finite {
                return Err(invalid(
                    format!("joint[{}]", i + 1),
                    "expected finite numbers",
                ));
            }
        }
        Self {
            name: name.into(),
            source: source.into(),
            joints,
            axis_map: AxisMap::default(),
            limits,
            base: Isometry3::identity(),
            flange: Isometry3::identity(),
            controller_world: Isometry3::identity(),
            bodies: Bodies::Scaled,
            masses: None,
            urdf: None,
            error_maps: None,
            external: None,
            held_out: None,
            mount: None,
            part: None,
            own_weight: None,
            max_speeds: Vector6::repeat(f64::INFINITY),
        }
        .with_limits(limits)
    }

    /// The robot with these joint limits (axis coordinates, rad; an infinite end is an unbounded
    /// axis).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`joint[i] limits`) when an end is NaN or a lower end is not below
    /// its upper end.
    pub fn with_limits(self, limits: JointBox) -> Result<Self> {
        for i in 0..6 {
            let (lower, upper) = (limits.lower[i], limits.upper[i]);
            if lower.is_nan() || upper.is_nan() || lower >= upper {
                return Err(invalid(
                    format!("joint[{}] limits", i + 1),
                    "expected a lower end below the upper end",
                ));
            }
        }
        Ok(Self { limits, ..self })
    }

    /// The robot with this map from axis angles to kinematic angles.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`axis_map.matrix`) when the matrix is not invertible: its condition
    /// number is NaN or above 1e8, or `axis_map.offset` when an offset is not finite.
    pub fn with_axis_map(self, axis_map: AxisMap) -> Result<Self> {
        let cond = crate::math::jacobi::cond(&axis_map.matrix);
        if cond.is_nan() || cond > limits::MAX_AXIS_MAP_COND {
            return Err(invalid(
                "axis_map.matrix".into(),
                &format!(
                    "expected an invertible 6x6 matrix; its condition number is {} (at most {})",
                    crate::common::words::number(cond),
                    crate::common::words::number(limits::MAX_AXIS_MAP_COND)
                ),
            ));
        }
        if !axis_map.offset.iter().all(|v| v.is_finite()) {
            return Err(invalid("axis_map.offset".into(), "expected finite numbers"));
        }
        Ok(Self { axis_map, ..self })
    }

    /// The robot with these joints (base to flange, lengths in m), everything else kept: a
    /// calibrated chain (`stiffid_metrology::calibration`).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`joint[i]`) when a joint's transforms, axis or offset are not
    /// finite.
    pub fn with_joints(self, joints: [Joint; 6]) -> Result<Self> {
        let checked = Robot::new("", "", joints, self.limits)?;
        Ok(Self {
            joints: checked.joints,
            ..self
        })
    }

    /// The robot with this base transform (world to the chain's first frame, m).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`base`) when it is not finite.
    pub fn with_base(self, base: Isometry3<f64>) -> Result<Self> {
        if !finite(&base) {
            return Err(invalid("base".into(), "expected finite numbers"));
        }
        Ok(Self { base, ..self })
    }

    /// The robot whose controller states a program's positions in the frame `world`, given in
    /// the robot base frame (m): a robot file's `[controller_world]`, a URDF's ROS-Industrial
    /// `base` link.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`controller_world`) when it is not finite.
    pub fn with_controller_world(self, world: Isometry3<f64>) -> Result<Self> {
        if !finite(&world) {
            return Err(invalid(
                "controller_world".into(),
                "expected finite numbers",
            ));
        }
        Ok(Self {
            controller_world: world,
            ..self
        })
    }

    /// The robot with this flange transform (last joint frame to the flange, m).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`flange`) when it is not finite.
    pub fn with_flange(self, flange: Isometry3<f64>) -> Result<Self> {
        if !finite(&flange) {
            return Err(invalid("flange".into(), "expected finite numbers"));
        }
        Ok(Self { flange, ..self })
    }

    /// The robot with these bodies (for the cell's checks and drawings).
    pub fn with_bodies(self, bodies: Bodies) -> Self {
        Self { bodies, ..self }
    }

    /// The robot with these link masses and centres (link `i` the body turned by joint `i`, the
    /// tool's mass part of link 6), or none.
    pub fn with_masses(self, masses: Option<[LinkMass; 6]>) -> Self {
        Self { masses, ..self }
    }

    /// The robot with these axis error maps ([`ErrorMap`], one per axis, empty for none): its
    /// frames turn each axis by `q + e(q)` ([`Robot::mapped`]). All empty: no maps.
    pub fn with_error_maps(self, maps: [ErrorMap; 6]) -> Self {
        let error_maps = (!maps.iter().all(ErrorMap::is_empty)).then(|| Arc::new(maps));
        Self { error_maps, ..self }
    }

    /// The robot in a cell with these external axes (a carrier under the arm, a positioner under
    /// the workpiece: [`external`]), or none.
    pub fn with_external(self, axes: Option<ExternalAxes>) -> Self {
        Self {
            external: axes.map(Arc::new),
            ..self
        }
    }

    /// The robot recording the mount it was calibrated on: the pedestal's pose in the cell
    /// (the calibration setup's `[robot_base]`, the controller's world in the base frame; the
    /// identity without one), which its base already holds.
    pub(crate) fn with_mount(self, mount: Option<Isometry3<f64>>) -> Self {
        Self { mount, ..self }
    }

    /// The mount a calibrated robot was calibrated on (`Robot::with_mount`), when its file
    /// records it.
    pub fn mount(&self) -> Option<&Isometry3<f64>> {
        self.mount.as_ref()
    }

    /// The robot recording the part's frame its calibration located from the reflectors on the
    /// positioner's table or, in a cell without a positioner, on the part: the frame the
    /// setup's `[workpiece] reflectors_mm` are given in, in the calibrated cell frame with
    /// every external axis at 0 (m), the setup's `[workpiece] base_from_part` for every setup
    /// pointing at the robot.
    pub(crate) fn with_part(self, part: Option<Isometry3<f64>>) -> Self {
        Self { part, ..self }
    }

    /// The part's frame a calibrated robot's calibration located (`Robot::with_part`), when
    /// its file records it.
    pub fn part(&self) -> Option<&Isometry3<f64>> {
        self.part.as_ref()
    }

    /// The robot carrying a calibration's held-out position errors ([`HeldOut`]).
    pub fn with_held_out(self, held_out: Option<HeldOut>) -> Self {
        Self {
            held_out: held_out.map(Arc::new),
            ..self
        }
    }

    /// The robot carrying a calibration's gravity terms ([`OwnWeight`]): the sag
    /// under its own weight that compensation adds.
    pub fn with_own_weight(self, own_weight: Option<OwnWeight>) -> Self {
        Self {
            own_weight: own_weight.map(Arc::new),
            ..self
        }
    }

    /// The robot with these largest axis speeds (rad/s, axis coordinates; infinite: no limit),
    /// as a robot file's `max_speed_deg_s` or a URDF's `<limit velocity>` give them.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`max_speed_deg_s`) when a speed is NaN or not above 0.
    pub fn with_max_speeds(self, max_speeds: Vector6<f64>) -> Result<Self> {
        if let Some(i) = max_speeds.iter().position(|v| v.is_nan() || *v <= 0.0) {
            return Err(invalid(
                format!("max_speed_deg_s[{}]", i + 1),
                "expected a speed above 0 (infinite: no limit)",
            ));
        }
        Ok(Self { max_speeds, ..self })
    }

    /// Each axis's largest speed, rad/s (axis coordinates); infinite where the robot's
    /// description gives none. The compensate job keeps every axis within it at the program's
    /// feed (`stiffid_machining::compensate::Feasible::move_times`).
    pub fn max_speeds(&self) -> &Vector6<f64> {
        &self.max_speeds
    }

    /// The cell's external axes, when it has any.
    pub fn external(&self) -> Option<&ExternalAxes> {
        self.external.as_deref()
    }

    /// A calibrated robot's held-out position errors, when its file carries them.
    pub fn held_out(&self) -> Option<&HeldOut> {
        self.held_out.as_deref()
    }

    /// A calibrated robot's sag under its own weight (its file's `[gravity]`), when it carries
    /// one.
    pub fn own_weight(&self) -> Option<&OwnWeight> {
        self.own_weight.as_deref()
    }

    /// The axes' error maps, when any axis has one.
    pub fn error_maps(&self) -> Option<&[ErrorMap; 6]> {
        self.error_maps.as_deref()
    }

    /// The axis angles the chain turns by at axis angles `q` (rad): `q + e(q)` with the error
    /// maps (`ErrorMap::angle` of each axis's own angle), `q` without.
    #[inline]
    pub fn mapped(&self, q: &nalgebra::Vector6<f64>) -> nalgebra::Vector6<f64> {
        match &self.error_maps {
            None => *q,
            Some(maps) => {
                let e = error_map::angles(maps, q);
                nalgebra::Vector6::from_fn(|i, _| q[i] + e[i])
            }
        }
    }

    /// [`Robot::mapped`] approached with the last motions' signs `direction` (-1.0 or 1.0 per
    /// axis, 0.0 for the mean of the two approaches): `q + e(q) + b d`, `b` each axis's half
    /// backlash (`ErrorMap::angle_from`).
    pub(crate) fn mapped_from(
        &self,
        q: &nalgebra::Vector6<f64>,
        direction: &nalgebra::Vector6<f64>,
    ) -> nalgebra::Vector6<f64> {
        match &self.error_maps {
            None => *q,
            Some(maps) => {
                let e = error_map::angles(maps, q);
                nalgebra::Vector6::from_fn(|i, _| q[i] + (e[i] + maps[i].backlash() * direction[i]))
            }
        }
    }

    /// The URDF the robot was read from, when it was ([`urdf::parse`]): a calibrated URDF is that
    /// file with its chain's joint origins corrected.
    pub fn urdf_source(&self) -> Option<&urdf::UrdfSource> {
        self.urdf.as_deref()
    }

    /// The robot with the URDF it was read from.
    pub(crate) fn with_urdf_source(self, source: urdf::UrdfSource) -> Self {
        Self {
            urdf: Some(std::sync::Arc::new(source)),
            ..self
        }
    }

    /// The link masses and centres, when the robot's description gives them (a robot file's
    /// `mass_kg` and `com_mm`, a URDF's `<inertial>`).
    pub fn masses(&self) -> Option<&[LinkMass; 6]> {
        self.masses.as_ref()
    }

    /// Human-readable name, e.g. "COMAU SMART5 NJ 165-3.0".
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether it is a calibrated robot: its name ends with [`CALIBRATED`], as the files of
    /// `stiffid calibrate` name it.
    pub fn is_calibrated(&self) -> bool {
        self.name.ends_with(CALIBRATED)
    }

    /// Where the numbers come from (datasheet, paper, repository).
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The six joints, base to flange.
    pub fn joints(&self) -> &[Joint; 6] {
        &self.joints
    }

    /// Controller axis angles to kinematic angles.
    pub fn axis_map(&self) -> &AxisMap {
        &self.axis_map
    }

    /// Joint limits, axis coordinates, rad.
    pub fn limits(&self) -> &JointBox {
        &self.limits
    }

    /// Base transform: world (robot base frame of all results) to the chain's first frame, m.
    pub fn base(&self) -> &Isometry3<f64> {
        &self.base
    }

    /// The controller's world frame in the robot base frame, m: the frame the robot's
    /// controller states a program's positions in before any base or user frame (FANUC's world,
    /// user frame 0, lies on axis 1 at the height of axis 2; KUKA's and ABB's at the foot, the
    /// identity). A robot file's `[controller_world]`, a URDF's ROS-Industrial `base` link
    /// ("base_link to `<vendor>` World Coordinates"); the identity without one. A setup places
    /// it in the cell after its `[robot_base]` ([`crate::Setup::program_world`]).
    pub fn controller_world(&self) -> &Isometry3<f64> {
        &self.controller_world
    }

    /// Flange transform: last joint frame to the flange frame, m.
    pub fn flange(&self) -> &Isometry3<f64> {
        &self.flange
    }

    /// The robot's own bodies, for the cell's checks and drawings ([`crate::cell::bodies`]).
    pub fn bodies(&self) -> &Bodies {
        &self.bodies
    }

    /// The robot's size (m): the sum of the lengths of its chain's fixed transforms (each joint's
    /// `pre` and `post`, the flange), at least 1 mm. A scale for tolerances of lengths.
    pub fn size(&self) -> f64 {
        let lengths = (self.joints.iter())
            .flat_map(|j| [&j.pre, &j.post])
            .chain([&self.flange])
            .map(|t| t.translation.vector.norm());
        lengths.sum::<f64>().max(1e-3)
    }
}

fn finite(t: &Isometry3<f64>) -> bool {
    t.translation.vector.iter().all(|v| v.is_finite())
        && t.rotation.coords.iter().all(|v| v.is_finite())
}

fn invalid(field: String, message: &str) -> Error {
    Error::InvalidField {
        field,
        message: message.to_string(),
    }
}

/// The bodies of a robot as its description gives them.
#[derive(Debug, Clone, Default)]
pub enum Bodies {
    /// None given: capsules along the chain, radii scaled to the robot's size
    /// ([`crate::setup::default_geometry`]).
    #[default]
    Scaled,
    /// Capsules along the chain with these radii of the base and links 1-6, m (a robot TOML
    /// file's `[robot_geometry] link_radius_mm`).
    Capsules([f64; 7]),
    /// Convex collision shapes: a URDF's `<collision>` elements ([`collision::parse`]).
    Shapes(Arc<collision::CollisionGeometry>),
    /// A URDF whose collision meshes were not found ([`Error::MeshNotFound`], its message): the
    /// robot serves kinematics and identification; the cell's body checks refuse it
    /// ([`crate::Setup::check_bodies`]).
    Missing(Arc<str>),
}

/// Shapes are equal when they are the same read (the same `Arc`).
impl PartialEq for Bodies {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Bodies::Scaled, Bodies::Scaled) => true,
            (Bodies::Capsules(a), Bodies::Capsules(b)) => a == b,
            (Bodies::Shapes(a), Bodies::Shapes(b)) => Arc::ptr_eq(a, b),
            (Bodies::Missing(a), Bodies::Missing(b)) => a == b,
            _ => false,
        }
    }
}

#[cfg(test)]
mod error_map_tests;
