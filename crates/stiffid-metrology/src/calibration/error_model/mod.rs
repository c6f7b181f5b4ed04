//! The error model: the parameters of a calibration, the reflector positions they predict and
//! the identification Jacobian.
//!
//! # The chain with errors
//! Every robot stiffid reads is a chain of joints `pre_i * Rot(w_i, theta_i + offset_i) * post_i`
//! ([`stiffid_core::Joint`]; DH, modified DH and URDF all map to it). The error model inserts, in the
//! rotation frame of each joint `i` (after `pre_i`, where its axis is `w_i`), the small transform
//!
//! ```text
//! E_i = Trans(a_i u_i + b_i v_i) * Rot(u_i, alpha_i) * Rot(v_i, beta_i) * Trans(d_i w_i)
//! ```
//!
//! and adds `theta_i` to the joint angle, where `(u_i, v_i, w_i)` is a right-handed basis with
//! `w_i` the joint axis and `u_i` the coordinate axis (x, then y, then z) most perpendicular to it
//! ([`Basis`]). For a z axis `(u, v, w) = (x, y, z)`, and the six errors are exactly the
//! Denavit-Hartenberg ones: in a modified-DH row `RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i)
//! TransZ(d_i)` they are the errors of `a_{i-1}`, `alpha_{i-1}`, `theta_i`, `d_i`, Hayati's
//! `beta_{i-1}` (a rotation about y, for consecutive (nearly) parallel axes, where `d`
//! degenerates) and `b`, a translation along y that a DH table cannot hold; in a standard-DH
//! table, `a`, `alpha` and `beta` of joint `i` are those of row `i - 1` (the common normal to
//! joint `i`'s axis) and `theta`, `d` those of row `i`. For a URDF joint they are the errors of
//! its origin, with the rotation about the joint's own axis its angle offset. Six errors per
//! joint are redundant (a complete minimal model of a 6R arm has four per joint, `4R + 6` with a
//! tool frame: Everett, Driels and Mooring 1987); [`crate::calibration::identifiability`] keeps
//! the independent ones in the priority [`Parameter::priority`] (the four (M)DH errors before
//! `beta` before `b`) and names the merged.
//!
//! # The frame and the measuring points
//! A reading is measuring point `k` (flange frame `c_k`, m) at axis angles `q`, read at `t` in
//! the measurement frame: the tracker's, or the robot base frame when the tracker is already
//! registered. The residual is
//!
//! ```text
//! r = exp([dphi]x) b(x, q) + dp - T t,        b(x, q) = F_x(q + dq_g(x, q)) c_k
//! ```
//!
//! with `F_x` the flange pose of the chain with errors `x`, `dq_g` the deflection under gravity
//! ([`crate::calibration::gravity`]), `T` the measurement frame in the base frame (the
//! registration) and `(dp, dphi)` its six error parameters (kind `tracker`, or `base` for
//! base-frame readings, where they are the base frame's error): a base-frame perturbation of the
//! prediction, re-centred into `T` after every step of the fit ([`Estimate::recentre`]), so the
//! Jacobian is evaluated at `dp = dphi = 0`. The base frame's own errors and the tracker
//! registration are one rigid transform: the registration absorbs them.
//!
//! # The identification Jacobian
//! [`ErrorModel::jacobian`] is `d b / d x` (3 rows per reading, base frame, m per parameter unit:
//! m/m or m/rad), analytic: every parameter is a one-degree-of-freedom virtual joint of the chain
//! (Hollerbach and Wampler 1996), so its column is `s x (b - o)` for a rotation about the unit
//! axis `s` through `o` and `s` for a translation along `s` (joint offsets are the joint screws of
//! [`stiffid_core::Frames::jacobian`]), the frame's columns are `[I, -[b]x]`, a measuring point's the
//! flange rotation, and a gravity term's the point Jacobian times its torque regressor. The
//! residual Jacobian is the same matrix. [`ErrorModel::column_scales`] are the lengths that make
//! the columns comparable (m for lengths, the characteristic length times rad for angles).
//!
//! # Example
//! ```
//! use nalgebra::{Isometry3, Vector3, Vector6};
//! use stiffid_metrology::calibration::{gravity, ErrorModel, Geometry};
//! use stiffid_metrology::calibration::error_model::MeasuredIn;
//! use stiffid_core::robot::presets;
//! let robot = presets::get("fanuc-r2000ic-165f")?;
//! let points = vec![Vector3::new(0.1, 0.0, 0.2), Vector3::new(-0.1, 0.05, 0.2)];
//! let model = ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full,
//!     gravity::Terms::none(&robot))?;
//! let x = model.nominal();                       // SI: m, rad
//! let postures = [(Vector6::new(0.1, 0.2, -0.3, 0.4, 0.5, 0.6), 0)];
//! let j = model.jacobian(&x, &postures)?;       // 3 rows per (posture, point)
//! assert_eq!(j.shape(), (3, model.parameters().len()));
//! let p = &model.parameters()[6 + 3 * 2];       // after the frame and the points
//! assert_eq!((p.name.as_str(), p.unit()), ("joint1.theta", "deg"));
//! # Ok::<(), stiffid_core::Error>(())
//! ```

mod basis;
mod external;
mod external_offsets;
mod held;
mod jacobian;
mod loads;
mod maps;
mod parameter;
mod tables;

pub use basis::Basis;
pub(crate) use external::MAX_FITTED_ORDER;
use loads::Loads;
pub use maps::JointMaps;
pub use parameter::{AxisPart, Component, Geometry, Kind, MeasuredIn, Parameter, Target};
use stiffid_core::robot::external::ExternalValues;

use super::gravity;
use nalgebra::{DVector, Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid_core::{Error, Joint, Result, Robot};

/// Most measuring points a calibration fits.
pub const MAX_POINTS: usize = 100;

/// The share of the largest regressor RMS of its unit below which a gravity term has no effect.
pub(crate) const NO_EFFECT: f64 = 1e-9;

/// No direction of approach: the mean of the two ([`Observation::direction`]).
const MEAN: Vector6<f64> = Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);

/// One commanded posture: its frames at the deflected posture and its gravity regressors.
struct Posture {
    q: Vector6<f64>,
    /// The external axes' values (SI, the cell's order; empty without).
    e: ExternalValues,
    /// The last motions' signs ([`Observation::direction`]).
    direction: Vector6<f64>,
    /// The arm's base frame in the cell: the carrier's pose times the robot's base.
    base: Isometry3<f64>,
    /// The axis angles the chain stands at: `q` plus the deflection under gravity.
    at: Vector6<f64>,
    frames: stiffid_core::Frames,
    regressors: Vec<f64>,
}

/// An estimate: the measurement frame and the parameter values.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The measurement frame in the robot base frame: the tracker's registration, or the
    /// identity for base-frame readings.
    pub frame: Isometry3<f64>,
    /// Every parameter's value, SI, in [`ErrorModel::parameters`] order (the frame's six are a
    /// perturbation of `frame`, zero once re-centred).
    pub values: DVector<f64>,
}

impl Estimate {
    /// The estimate with the frame's six perturbation values folded into `frame` (and zeroed):
    /// `T <- (exp([dphi]x), dp)^-1 T`, so that `exp([dphi]x) b + dp = T t` becomes `b = T t`.
    pub fn recentre(&self) -> Self {
        let v = &self.values;
        let delta = Isometry3::from_parts(
            Translation3::new(v[0], v[1], v[2]),
            UnitQuaternion::from_scaled_axis(Vector3::new(v[3], v[4], v[5])),
        );
        let mut values = v.clone();
        values.rows_mut(0, 6).fill(0.0);
        Estimate {
            frame: delta.inverse() * self.frame,
            values,
        }
    }
}

/// A reading as the calibration needs it.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// The posture's index in the readings (0-based, for the report).
    pub posture: usize,
    /// The measuring point, 0-based.
    pub point: usize,
    /// Axis angles, rad.
    pub q: Vector6<f64>,
    /// The reading in the measurement frame, m.
    pub measured: Vector3<f64>,
    /// The wrench `[f; m]` at the setup's loading point, base frame, N and N m: zero for an
    /// unloaded reading ([`ErrorModel::with_loads`] models the others).
    pub wrench: Vector6<f64>,
    /// The external axes' values, SI (m, rad), the cell's order ([`stiffid_core::robot::ExternalAxes`]);
    /// empty without external axes.
    pub e: ExternalValues,
    /// Whether `point` is a reflector fixed in the cell (`T<k>`: on the positioner's table, or a
    /// fixed point of a cell without a positioner, [`ErrorModel::with_tables`]) rather than a
    /// measuring point on the tool.
    pub table: bool,
    /// The sign of each joint's last motion before the reading (-1.0 or 1.0, the readings'
    /// `dir1..dir6`), by which a backlash term moves the joint ([`ErrorModel::with_maps`]); 0.0
    /// where unknown: the mean of the two approaches.
    pub direction: Vector6<f64>,
}

/// Where a predicted position is: a measuring point at axis angles `q` and external axis values
/// `e`, or a reflector on the positioner's table.
#[derive(Clone, Copy)]
struct At<'a> {
    q: &'a Vector6<f64>,
    e: &'a ExternalValues,
    direction: &'a Vector6<f64>,
    point: usize,
    table: bool,
}

impl<'a> At<'a> {
    fn arm(pairs: &'a [(Vector6<f64>, usize)]) -> impl Iterator<Item = At<'a>> + Clone {
        pairs.iter().map(|(q, k)| At {
            q,
            e: &ExternalValues::NONE,
            direction: &MEAN,
            point: *k,
            table: false,
        })
    }

    fn of(observations: &'a [Observation]) -> impl Iterator<Item = At<'a>> + Clone {
        observations.iter().map(|o| At {
            q: &o.q,
            e: &o.e,
            direction: &o.direction,
            point: o.point,
            table: o.table,
        })
    }
}

impl Observation {
    /// Whether the reading carries a wrench.
    pub fn loaded(&self) -> bool {
        self.wrench != Vector6::zeros()
    }
}

/// The error model of a robot, its measuring points and the frame its readings are in.
#[derive(Debug, Clone)]
pub struct ErrorModel {
    robot: Robot,
    bases: [Basis; 6],
    parameters: Vec<Parameter>,
    measured_in: MeasuredIn,
    /// Index of each joint's first error parameter (the six in [`Component::ALL`] order), if
    /// the model has joint errors.
    joint_start: Option<usize>,
    /// Index of the first offset when only the offsets are modelled.
    offsets_start: Option<usize>,
    gravity: gravity::Terms,
    gravity_start: usize,
    /// The compliances under the applied wrenches, with loaded readings.
    loads: Option<Loads>,
    /// The joints' fitted error maps ([`ErrorModel::with_maps`]).
    maps: Option<maps::Maps>,
    /// The cell's external axes ([`ErrorModel::with_external`]).
    external: Option<external::External>,
    /// The reflectors fixed in the cell ([`ErrorModel::with_tables`]).
    tables: tables::Tables,
    /// The parameters held at their nominal values ([`ErrorModel::with_held`]), ascending.
    held: Vec<usize>,
}

impl ErrorModel {
    /// The error model of `robot` (nominal), its measuring points `points` (flange frame, m: the
    /// setup's, the points' nominal values) and readings in `measured_in`, with the joint errors
    /// of `geometry` and the gravity terms of `gravity`.
    ///
    /// Parameters, in order: the frame's six, three per measuring point, six per joint
    /// ([`Component::ALL`] order; one per joint with [`Geometry::Offsets`]), the gravity terms.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`measuring_points_mm`) with no point or more than [`MAX_POINTS`],
    /// or a non-finite point.
    pub fn new(
        robot: &Robot,
        points: &[Vector3<f64>],
        measured_in: MeasuredIn,
        geometry: Geometry,
        gravity: gravity::Terms,
    ) -> Result<Self> {
        if points.is_empty() || points.len() > MAX_POINTS {
            return Err(Error::InvalidField {
                field: "measuring_points_mm".into(),
                message: format!(
                    "expected 1 to {MAX_POINTS} measuring points, got {}",
                    points.len()
                ),
            });
        }
        if !points.iter().flat_map(|p| p.iter()).all(|v| v.is_finite()) {
            return Err(Error::InvalidField {
                field: "measuring_points_mm".into(),
                message: "expected finite numbers".into(),
            });
        }
        let (kind, prefix) = match measured_in {
            MeasuredIn::Tracker => (Kind::Tracker, "tracker"),
            MeasuredIn::Base => (Kind::Base, "base"),
        };
        let mut parameters: Vec<Parameter> = ["x", "y", "z", "rx", "ry", "rz"]
            .iter()
            .enumerate()
            .map(|(i, n)| Parameter {
                name: format!("{prefix}.{n}"),
                kind,
                target: Target::Frame(i),
                nominal: 0.0,
                priority: 0,
            })
            .collect();
        for (k, p) in points.iter().enumerate() {
            for (axis, n) in ["x", "y", "z"].iter().enumerate() {
                parameters.push(Parameter {
                    name: format!("point{}.{n}", k + 1),
                    kind: Kind::Point,
                    target: Target::Point { point: k, axis },
                    nominal: p[axis],
                    priority: 0,
                });
            }
        }
        let components: &[Component] = match geometry {
            Geometry::None => &[],
            Geometry::Offsets => &[Component::Theta],
            Geometry::Full => &Component::ALL,
        };
        let start = parameters.len();
        for joint in 0..6 {
            for &component in components {
                parameters.push(Parameter {
                    name: format!("joint{}.{}", joint + 1, component.name()),
                    kind: Kind::Joint,
                    target: Target::Joint { joint, component },
                    nominal: 0.0,
                    priority: match component {
                        Component::Beta => 2,
                        Component::B => 3,
                        _ => 1,
                    },
                });
            }
        }
        let gravity_start = parameters.len();
        parameters.extend(parameter::gravity_parameters(&gravity));
        Ok(ErrorModel {
            bases: std::array::from_fn(|i| Basis::of(&robot.joints()[i].axis)),
            robot: robot.clone(),
            parameters,
            measured_in,
            joint_start: (geometry == Geometry::Full).then_some(start),
            offsets_start: (geometry == Geometry::Offsets).then_some(start),
            gravity,
            gravity_start,
            loads: None,
            maps: None,
            external: None,
            tables: tables::Tables::default(),
            held: Vec::new(),
        })
    }

    /// The parameters, in the order of the Jacobian's columns.
    pub fn parameters(&self) -> &[Parameter] {
        &self.parameters
    }

    /// The nominal robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The frame the readings are in.
    pub fn measured_in(&self) -> MeasuredIn {
        self.measured_in
    }

    /// The gravity model.
    pub fn gravity(&self) -> &gravity::Terms {
        &self.gravity
    }

    /// The measuring points' count.
    pub fn points(&self) -> usize {
        (self.parameters.iter())
            .filter(|p| p.kind == Kind::Point)
            .count()
            / 3
    }

    /// The nominal values (SI), in parameter order.
    pub fn nominal(&self) -> DVector<f64> {
        DVector::from_iterator(
            self.parameters.len(),
            self.parameters.iter().map(|p| p.nominal),
        )
    }

    /// The six errors `[theta, d, a, alpha, beta, b]` of joint `i` (0-based) in `values`.
    fn joint_errors(&self, values: &DVector<f64>, i: usize) -> [f64; 6] {
        if let Some(s) = self.joint_start {
            std::array::from_fn(|c| values[s + 6 * i + c])
        } else if let Some(s) = self.offsets_start {
            [values[s + i], 0.0, 0.0, 0.0, 0.0, 0.0]
        } else {
            [0.0; 6]
        }
    }

    /// The measuring point `k` (flange frame, m) in `values`.
    pub fn point(&self, values: &DVector<f64>, k: usize) -> Vector3<f64> {
        values.fixed_rows::<3>(6 + 3 * k).into_owned()
    }

    /// The robot with the joint errors of `values` (joint `i`'s `pre` becomes `pre_i E_i` and
    /// its offset gains `theta_i`; module docs) and the error maps of `values`
    /// ([`ErrorModel::with_maps`]). Its `frames` at the deflected posture (`q + dq_g` at the
    /// commanded `q`, with the gravity terms of `values`) give the predicted positions.
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a value is not finite or a map's coefficient beyond its
    /// limit ([`stiffid_core::robot::ErrorMap::new`]).
    pub fn robot_at(&self, values: &DVector<f64>) -> Result<Robot> {
        let joints: [Joint; 6] = std::array::from_fn(|i| {
            let j = &self.robot.joints()[i];
            let e = self.joint_errors(values, i);
            Joint {
                pre: j.pre * self.bases[i].error(&e),
                axis: j.axis,
                post: j.post,
                offset: j.offset + e[0],
            }
        });
        let robot = self.robot.clone().with_joints(joints)?;
        Ok(match self.maps_at(values)? {
            Some(maps) => robot.with_error_maps(maps),
            None => robot,
        })
    }

    /// The predicted base-frame positions (m) of `(q, point)` pairs (axis angles, rad; points
    /// 0-based) at `values`, the frame's perturbation applied (with external axes: at `e = 0`,
    /// cell frame).
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a value is not finite.
    pub fn positions(
        &self,
        values: &DVector<f64>,
        at: &[(Vector6<f64>, usize)],
    ) -> Result<Vec<Vector3<f64>>> {
        self.positions_at(values, At::arm(at))
    }

    fn positions_at<'a>(
        &self,
        values: &DVector<f64>,
        at: impl Iterator<Item = At<'a>>,
    ) -> Result<Vec<Vector3<f64>>> {
        let robot = self.robot_at(values)?;
        let delta = Isometry3::from_parts(
            Translation3::new(values[0], values[1], values[2]),
            UnitQuaternion::from_scaled_axis(Vector3::new(values[3], values[4], values[5])),
        );
        let mut last: Option<Posture> = None;
        Ok(at
            .map(|a| {
                let b = match a.table {
                    true => self.table_position(values, a.e.as_slice(), a.point),
                    false => {
                        let p = self.posture_of(&mut last, &robot, values, &a);
                        p.frames.point(&self.point(values, a.point))
                    }
                };
                (delta * nalgebra::Point3::from(b)).coords
            })
            .collect())
    }

    /// The posture of commanded `a.q` on `robot` (the chain at `values`) at external axis values
    /// `a.e` approached from `a.direction`, reused from `last` when it is the same posture: the
    /// readings of one posture's points come together.
    fn posture_of<'p>(
        &self,
        last: &'p mut Option<Posture>,
        robot: &Robot,
        values: &DVector<f64>,
        a: &At,
    ) -> &'p Posture {
        let (q, e, direction) = (a.q, a.e, a.direction);
        let same = |p: &Posture| p.q == *q && p.e == *e && p.direction == *direction;
        if !last.as_ref().is_some_and(same) {
            let regressors = self.gravity.regressors(q);
            let g = values.rows(self.gravity_start, self.gravity.len());
            let at = q + self.gravity.deflection_from(&g, &regressors);
            let base = match &self.external {
                Some(x) if x.axes.carrier_len() > 0 => {
                    x.carrier(values, e.as_slice()) * robot.base()
                }
                _ => *robot.base(),
            };
            let mut frames = stiffid_core::Frames::blank();
            robot.update_frames_from(&base, &at, direction, &mut frames);
            *last = Some(Posture {
                q: *q,
                e: *e,
                direction: *direction,
                base,
                at,
                frames,
                regressors,
            });
        }
        last.as_ref().expect("set above")
    }

    /// The predicted base-frame positions (m) of `observations` at `values`: those of
    /// [`ErrorModel::positions`] plus, for a loaded reading, the deflection under its wrench
    /// (`ErrorModel::load_deflection`), the frame's perturbation applied.
    ///
    /// # Errors
    /// Those of [`ErrorModel::positions`].
    pub fn predict(
        &self,
        values: &DVector<f64>,
        observations: &[Observation],
    ) -> Result<Vec<Vector3<f64>>> {
        let mut b = self.positions_at(values, At::of(observations))?;
        if self.loads.is_some() {
            let turn =
                UnitQuaternion::from_scaled_axis(Vector3::new(values[3], values[4], values[5]));
            for (b, o) in b.iter_mut().zip(observations).filter(|(_, o)| o.loaded()) {
                *b += turn * self.load_deflection(values, &o.q, o.point, &o.wrench);
            }
        }
        Ok(b)
    }

    /// The residuals `exp([dphi]x) b + dp - T t` (3 per observation, base frame, m), `b` with
    /// the deflection under a loaded reading's wrench ([`ErrorModel::predict`]).
    ///
    /// # Errors
    /// Those of [`ErrorModel::positions`].
    pub(crate) fn residuals(
        &self,
        estimate: &Estimate,
        observations: &[Observation],
    ) -> Result<DVector<f64>> {
        let b = self.predict(&estimate.values, observations)?;
        let mut r = DVector::zeros(3 * observations.len());
        for (i, (o, b)) in observations.iter().zip(&b).enumerate() {
            let t = estimate.frame * nalgebra::Point3::from(o.measured);
            r.fixed_rows_mut::<3>(3 * i).copy_from(&(b - t.coords));
        }
        Ok(r)
    }

    /// The basis of joint `i`'s rotation frame (0-based).
    pub fn basis(&self, i: usize) -> &Basis {
        &self.bases[i]
    }

    /// Index of the first gravity parameter.
    pub fn gravity_start(&self) -> usize {
        self.gravity_start
    }
}
