//! The error model: the parameters of a calibration, the reflector positions they predict and
//! the identification Jacobian.
//!
//! # The chain with errors
//! Every robot stiffid reads is a chain of joints `pre_i * Rot(w_i, theta_i + offset_i) * post_i`
//! ([`crate::Joint`]; DH, modified DH and URDF all map to it). The error model inserts, in the
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
//! tool frame: Everett, Driels and Mooring 1987); [`crate::metrology::calibration::identifiability`] keeps
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
//! ([`crate::metrology::calibration::gravity`]), `T` the measurement frame in the base frame (the
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
//! [`crate::Frames::jacobian`]), the frame's columns are `[I, -[b]x]`, a measuring point's the
//! flange rotation, and a gravity term's the point Jacobian times its torque regressor. The
//! residual Jacobian is the same matrix. [`ErrorModel::column_scales`] are the lengths that make
//! the columns comparable (m for lengths, the characteristic length times rad for angles).
//!
//! # Example
//! ```
//! use nalgebra::{Isometry3, Vector3, Vector6};
//! use stiffid::metrology::calibration::{gravity, ErrorModel, Geometry};
//! use stiffid::metrology::calibration::error_model::MeasuredIn;
//! use stiffid::robot::presets;
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
//! # Ok::<(), stiffid::Error>(())
//! ```

use super::gravity;
use crate::{Error, Joint, Result, Robot};
use nalgebra::{
    DMatrix, DVector, Isometry3, Matrix3, Translation3, Unit, UnitQuaternion, Vector3, Vector6,
};
use serde::Serialize;

/// Most measuring points a calibration fits.
pub const MAX_POINTS: usize = 100;

/// The share of the largest regressor RMS of its unit below which a gravity term has no effect.
pub const NO_EFFECT: f64 = 1e-9;

/// One commanded posture: its frames at the deflected posture and its gravity regressors.
struct Posture {
    q: Vector6<f64>,
    frames: crate::Frames,
    regressors: Vec<f64>,
}

/// Which joint errors a calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Geometry {
    /// None: the frame and the measuring points only (the cell calibration).
    None,
    /// The joint angle offsets `theta`.
    Offsets,
    /// Every joint error: `theta`, `d`, `a`, `alpha`, Hayati's `beta` and `b` (the dependent ones
    /// merged).
    #[default]
    Full,
}

impl crate::common::choice::Choice for Geometry {
    const FIELD: &'static str = "geometry";
    const ALL: &'static [Self] = &[Geometry::None, Geometry::Offsets, Geometry::Full];
    fn name(self) -> &'static str {
        match self {
            Geometry::None => "none",
            Geometry::Offsets => "offsets",
            Geometry::Full => "full",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Geometry::None => "The frame and the measuring points only (the cell calibration)",
            Geometry::Offsets => "Also the joint angle offsets",
            Geometry::Full => "Every joint error: theta, d, a, alpha, beta, b (dependent merged)",
        }
    }
}

crate::common::choice::by_name!(Geometry);

/// The frame the readings are in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MeasuredIn {
    /// The tracker's frame: the frame parameters are the tracker's registration.
    Tracker,
    /// The robot base frame (a tracker already registered): the frame parameters are the base
    /// frame's error.
    Base,
}

/// One error of a joint, in its rotation frame's basis `(u, v, w)` ([`Basis`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Component {
    /// The joint angle offset: rotation about the axis `w`, rad.
    Theta,
    /// Translation along the axis `w`, m.
    D,
    /// Translation along `u`, m.
    A,
    /// Rotation about `u`, rad.
    Alpha,
    /// Rotation about `v` (Hayati's beta), rad.
    Beta,
    /// Translation along `v`, m.
    B,
}

impl Component {
    /// All six, in the order of the parameter list.
    pub const ALL: [Component; 6] = [
        Component::Theta,
        Component::D,
        Component::A,
        Component::Alpha,
        Component::Beta,
        Component::B,
    ];

    /// The name in parameter names: `theta`, `d`, `a`, `alpha`, `beta`, `b`.
    pub fn name(self) -> &'static str {
        match self {
            Component::Theta => "theta",
            Component::D => "d",
            Component::A => "a",
            Component::Alpha => "alpha",
            Component::Beta => "beta",
            Component::B => "b",
        }
    }

    /// Whether it is an angle (rad) rather than a length (m).
    pub fn is_angle(self) -> bool {
        matches!(self, Component::Theta | Component::Alpha | Component::Beta)
    }
}

/// What a parameter moves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Target {
    /// The measurement frame: 0-2 translation along the base frame's x, y, z (m), 3-5 rotation
    /// about them (rad).
    Frame(usize),
    /// A measuring point's coordinate (0 x, 1 y, 2 z) in the flange frame, m; points 0-based.
    Point {
        /// The measuring point, 0-based.
        point: usize,
        /// The coordinate: 0 x, 1 y, 2 z.
        axis: usize,
    },
    /// A joint error; joints 0-based.
    Joint {
        /// The joint, 0-based.
        joint: usize,
        /// The error.
        component: Component,
    },
    /// A gravity term ([`gravity::Term`]).
    Gravity(gravity::Term),
    /// The compliance of parameter `index` (0-based, drives first) of the setup's stiffness
    /// model under the wrenches of loaded readings ([`ErrorModel::with_loads`]): rad/(N m), m/N
    /// (or a nonlinear law's parameter, [`crate::model::Law`]).
    Compliance {
        /// The parameter of the setup's model, 0-based (drives `0..6`, then the virtual
        /// springs).
        index: usize,
        /// What it is: a drive, a rotational or translational spring, a nonlinear law's.
        kind: crate::model::ParameterKind,
    },
}

/// The kind of a parameter, as documents name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// The tracker's registration.
    Tracker,
    /// The robot base frame's error (readings in the base frame).
    Base,
    /// A measuring point in the flange frame.
    Point,
    /// A joint's geometric error.
    Joint,
    /// A compliance: of a joint under gravity (known masses), or of a parameter of the setup's
    /// stiffness model under the applied wrenches (loaded readings).
    Compliance,
    /// A lumped gravity term: a compliance times a mass moment.
    Gravity,
}

impl Kind {
    /// The name in documents.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Tracker => "tracker",
            Kind::Base => "base",
            Kind::Point => "point",
            Kind::Joint => "joint",
            Kind::Compliance => "compliance",
            Kind::Gravity => "gravity",
        }
    }
}

/// One parameter of the error model.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Its name: `tracker.x`, `point2.z`, `joint3.beta`, `gravity.c2` ... (unique).
    pub name: String,
    /// Its kind.
    pub kind: Kind,
    /// What it moves.
    pub target: Target,
    /// Its nominal value, SI (m, rad, rad/(N m), ...): 0 for an error, the setup's coordinate for
    /// a measuring point, the nominal compliance (or 0) for a compliance.
    pub nominal: f64,
    /// The order in which [`crate::metrology::calibration::identifiability`] keeps parameters: lower first
    /// (0 the frame and the points, 1 the (M)DH errors, 2 `beta`, 3 `b`, 4 the gravity terms).
    pub priority: u8,
}

impl Parameter {
    /// The unit in documents (mm, deg, ...), [`Parameter::to_document`] converts to it.
    pub fn unit(&self) -> &'static str {
        match self.target {
            Target::Frame(i) if i < 3 => "mm",
            Target::Frame(_) => "deg",
            Target::Point { .. } => "mm",
            Target::Joint { component, .. } if component.is_angle() => "deg",
            Target::Joint { .. } => "mm",
            Target::Gravity(term) => term.unit(),
            Target::Compliance { kind, .. } => compliance_unit(kind),
        }
    }

    /// The value (SI) in the document's unit.
    pub fn to_document(&self, si: f64) -> f64 {
        si * self.document_factor()
    }

    /// The factor from SI to the document's unit.
    pub fn document_factor(&self) -> f64 {
        match self.unit() {
            "mm" => 1e3,
            "deg" => 180.0 / std::f64::consts::PI,
            _ => match self.target {
                Target::Gravity(term) => term.document_factor(),
                Target::Compliance { .. } => 1e6,
                _ => 1.0,
            },
        }
    }
}

/// The document unit of a compliance of `kind` (SI times 1e6): `urad/(N m)` of a drive or a
/// rotational spring, `um/N` of a translational one, `urad` of a lost motion, `urad/(N m)^2` of
/// a load-dependent compliance.
fn compliance_unit(kind: crate::model::ParameterKind) -> &'static str {
    use crate::model::ParameterKind as P;
    match kind {
        P::Drive | P::Rotation => "urad/(N m)",
        P::Translation => "um/N",
        P::LostMotion => "urad",
        P::LoadDependent => "urad/(N m)^2",
    }
}

/// The basis `(u, v, w)` of a joint's rotation frame: `w` its axis, `u` the coordinate axis (x,
/// then y, then z) least aligned with it, made perpendicular, `v = w x u`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basis {
    /// `u`.
    pub u: Vector3<f64>,
    /// `v = w x u`.
    pub v: Vector3<f64>,
    /// `w`, the joint axis.
    pub w: Vector3<f64>,
}

impl Basis {
    /// The basis of the joint axis `w` (unit).
    pub fn of(w: &Unit<Vector3<f64>>) -> Self {
        let w = w.into_inner();
        let pick = (0..3)
            .min_by(|&a, &b| w[a].abs().total_cmp(&w[b].abs()))
            .unwrap_or(0);
        let e = Vector3::ith(pick, 1.0);
        let u = (e - w * w.dot(&e)).normalize();
        Basis {
            u,
            v: w.cross(&u),
            w,
        }
    }

    /// `E = Trans(a u + b v) Rot(u, alpha) Rot(v, beta) Trans(d w)` of the errors
    /// `[theta, d, a, alpha, beta, b]` (theta is not part of it: it adds to the joint angle).
    pub fn error(&self, e: &[f64; 6]) -> Isometry3<f64> {
        let [_, d, a, alpha, beta, b] = *e;
        let shift = Isometry3::from_parts(
            Translation3::from(self.u * a + self.v * b),
            UnitQuaternion::from_axis_angle(&Unit::new_unchecked(self.u), alpha),
        );
        shift
            * UnitQuaternion::from_axis_angle(&Unit::new_unchecked(self.v), beta)
            * Isometry3::translation(self.w.x * d, self.w.y * d, self.w.z * d)
    }
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
}

/// What the deflection under the applied wrenches needs: the setup (its stiffness model,
/// springs' coordinates, loading and measuring points, nominal robot) and the column of each of
/// its model's parameters.
#[derive(Debug, Clone)]
struct Loads {
    setup: Box<crate::Setup>,
    /// The parameter (index in [`ErrorModel::parameters`]) of each parameter of the setup's
    /// model: a gravity compliance with known masses for a drive, else its own.
    columns: Vec<usize>,
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
        parameters.extend(gravity.parameters());
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
        })
    }

    /// The model with the compliances of `setup`'s stiffness model ([`crate::Setup::model`]:
    /// the drives, then the virtual springs) under the wrenches of loaded readings (module docs,
    /// "Loaded readings"): one parameter per model parameter (kind [`Kind::Compliance`], named
    /// `compliance.<name>`, nominal the setup's nominal compliance or 0), after the gravity
    /// terms; with known masses ([`gravity::Term::Compliance`]) a drive's is its gravity
    /// compliance, one parameter for both. The setup is the one whose robot and measuring
    /// points the model was made of.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`loads`) when the model already has them, when the setup's
    /// measuring points are not the model's count, or when the gravity terms' springs are in
    /// other coordinates than the setup's model.
    pub fn with_loads(mut self, setup: &crate::Setup) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "loads".into(),
            message,
        };
        if self.loads.is_some() {
            return Err(invalid("the model has the loads already".into()));
        }
        if setup.tool().measuring_points.len() != self.points() {
            return Err(invalid(format!(
                "expected a setup with the model's {} measuring points, got {}",
                self.points(),
                setup.tool().measuring_points.len()
            )));
        }
        let shared = |joint: usize| {
            (self.gravity.terms().iter())
                .position(|t| *t == gravity::Term::Compliance { joint })
                .map(|t| self.gravity_start + t)
        };
        if self.gravity.link_masses().is_some() && self.gravity.coordinates() != setup.springs() {
            return Err(invalid(
                "the gravity compliances' springs are in other coordinates than the setup's model"
                    .into(),
            ));
        }
        let nominal = setup.model_nominal_compliance();
        let mut columns = Vec::new();
        for (index, p) in setup.model().parameters().into_iter().enumerate() {
            if let Some(c) = (index < 6).then(|| shared(index)).flatten() {
                columns.push(c);
                continue;
            }
            columns.push(self.parameters.len());
            self.parameters.push(Parameter {
                name: format!("compliance.{}", p.name),
                kind: Kind::Compliance,
                target: Target::Compliance {
                    index,
                    kind: p.kind,
                },
                nominal: nominal.as_ref().map_or(0.0, |h| h[index]),
                priority: 4,
            });
        }
        self.loads = Some(Loads {
            setup: Box::new(setup.clone()),
            columns,
        });
        Ok(self)
    }

    /// Whether the model has the compliances under the applied wrenches
    /// ([`ErrorModel::with_loads`]).
    pub fn has_loads(&self) -> bool {
        self.loads.is_some()
    }

    /// The parameter (index in [`ErrorModel::parameters`]) of each parameter of the setup's
    /// stiffness model, with loads ([`ErrorModel::with_loads`]).
    pub fn compliance_columns(&self) -> Option<&[usize]> {
        self.loads.as_ref().map(|l| l.columns.as_slice())
    }

    /// The `3 x n` observation rows (`n` the setup's model's parameters; base frame, m per unit
    /// of compliance) of measuring point `k` at commanded axis angles `q` (rad) under `wrench`
    /// (base frame, N, N m, at the loading point): the rows of `Psi`
    /// ([`crate::observation::write_posture_block`]) on the nominal chain with the setup's
    /// points; `None` without loads or without a wrench.
    pub fn load_rows(
        &self,
        q: &Vector6<f64>,
        k: usize,
        wrench: &Vector6<f64>,
    ) -> Option<DMatrix<f64>> {
        let loads = self.loads.as_ref()?;
        if *wrench == Vector6::zeros() {
            return None;
        }
        let setup = &loads.setup;
        let frames = setup.robot().frames(q);
        let mut rows = DMatrix::zeros(3, loads.columns.len());
        write_load_rows(setup, &frames, k, wrench, &mut rows, 0);
        Some(rows)
    }

    /// The deflection (base frame, m) of measuring point `k` at commanded `q` under `wrench`
    /// with the compliances of `values` (SI): [`ErrorModel::load_rows`] times them, zero without
    /// loads or wrench.
    pub fn load_deflection(
        &self,
        values: &DVector<f64>,
        q: &Vector6<f64>,
        k: usize,
        wrench: &Vector6<f64>,
    ) -> Vector3<f64> {
        match (self.load_rows(q, k, wrench), &self.loads) {
            (Some(rows), Some(loads)) => {
                let h = DVector::from_iterator(
                    loads.columns.len(),
                    loads.columns.iter().map(|&c| values[c]),
                );
                Vector3::from_iterator((rows * h).iter().copied())
            }
            _ => Vector3::zeros(),
        }
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
    /// its offset gains `theta_i`; module docs). Its `frames` at the deflected posture
    /// ([`ErrorModel::deflected`]) give the predicted positions.
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a value is not finite.
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
        self.robot.clone().with_joints(joints)
    }

    /// The axis angles `q + dq_g` at which the robot stands when commanded `q` (rad), with the
    /// gravity terms of `values`.
    pub fn deflected(&self, values: &DVector<f64>, q: &Vector6<f64>) -> Vector6<f64> {
        q + self
            .gravity
            .deflection(&values.rows(self.gravity_start, self.gravity.len()), q)
    }

    /// The predicted base-frame positions (m) of `(q, point)` pairs (axis angles, rad; points
    /// 0-based) at `values`, the frame's perturbation applied.
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a value is not finite.
    pub fn positions(
        &self,
        values: &DVector<f64>,
        at: &[(Vector6<f64>, usize)],
    ) -> Result<Vec<Vector3<f64>>> {
        let robot = self.robot_at(values)?;
        let delta = Isometry3::from_parts(
            Translation3::new(values[0], values[1], values[2]),
            UnitQuaternion::from_scaled_axis(Vector3::new(values[3], values[4], values[5])),
        );
        let mut last: Option<Posture> = None;
        Ok(at
            .iter()
            .map(|(q, k)| {
                let p = self.posture_of(&mut last, &robot, values, q);
                (delta * nalgebra::Point3::from(p.frames.point(&self.point(values, *k)))).coords
            })
            .collect())
    }

    /// The posture of commanded `q` on `robot` (the chain at `values`), reused from `last` when
    /// it is the same posture: the readings of one posture's points come together.
    fn posture_of<'p>(
        &self,
        last: &'p mut Option<Posture>,
        robot: &Robot,
        values: &DVector<f64>,
        q: &Vector6<f64>,
    ) -> &'p Posture {
        if last.as_ref().is_none_or(|p| p.q != *q) {
            let regressors = self.gravity.regressors(q);
            let g = values.rows(self.gravity_start, self.gravity.len());
            let frames = robot.frames(&(q + self.gravity.deflection_from(&g, &regressors)));
            *last = Some(Posture {
                q: *q,
                frames,
                regressors,
            });
        }
        last.as_ref().expect("set above")
    }

    /// The predicted base-frame positions (m) of `observations` at `values`: those of
    /// [`ErrorModel::positions`] plus, for a loaded reading, the deflection under its wrench
    /// ([`ErrorModel::load_deflection`]), the frame's perturbation applied.
    ///
    /// # Errors
    /// Those of [`ErrorModel::positions`].
    pub fn predict(
        &self,
        values: &DVector<f64>,
        observations: &[Observation],
    ) -> Result<Vec<Vector3<f64>>> {
        let at: Vec<_> = observations.iter().map(|o| (o.q, o.point)).collect();
        let mut b = self.positions(values, &at)?;
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
    pub fn residuals(
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

    /// The identification Jacobian `d b / d x` at `values` (module docs): 3 rows per `(q, point)`
    /// pair (axis angles, rad; points 0-based), one column per parameter, base frame, m per unit
    /// of the parameter (m/m, m/rad, m per gravity-term unit). Exact where the frame's six values
    /// are zero (as the fit keeps them); it is also the Jacobian of
    /// [`ErrorModel::residuals`].
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a value is not finite; [`Error::InvalidField`] (`point`) for a
    /// point beyond the model's.
    pub fn jacobian(
        &self,
        values: &DVector<f64>,
        at: &[(Vector6<f64>, usize)],
    ) -> Result<DMatrix<f64>> {
        let points = self.points();
        if let Some((_, k)) = at.iter().find(|(_, k)| *k >= points) {
            return Err(Error::InvalidField {
                field: "point".into(),
                message: format!("expected a measuring point 1 to {points}, got {}", k + 1),
            });
        }
        let robot = self.robot_at(values)?;
        let mut j = DMatrix::zeros(3 * at.len(), self.parameters.len());
        let springs = self.gravity.coordinates();
        let mut last: Option<Posture> = None;
        for (row, (q, k)) in at.iter().enumerate() {
            let posture = self.posture_of(&mut last, &robot, values, q);
            let f = &posture.frames;
            let c = self.point(values, *k);
            let b = f.point(&c);
            let mut block = j.fixed_rows_mut::<3>(3 * row);
            block
                .fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&Matrix3::identity());
            block
                .fixed_view_mut::<3, 3>(0, 3)
                .copy_from(&(-b.cross_matrix()));
            block
                .fixed_view_mut::<3, 3>(0, 6 + 3 * k)
                .copy_from(f.flange.rotation.to_rotation_matrix().matrix());
            if let Some(s) = self.joint_start {
                for i in 0..6 {
                    let cols = self.joint_columns(f, values, i, &b);
                    for (c, col) in cols.iter().enumerate() {
                        block.column_mut(s + 6 * i + c).copy_from(col);
                    }
                }
            } else if let Some(s) = self.offsets_start {
                for i in 0..6 {
                    let col = f.axis_directions[i].cross(&(b - f.axis_points[i]));
                    block.column_mut(s + i).copy_from(&col);
                }
            }
            if !self.gravity.is_empty() {
                let jp = f.jacobian(&c, springs);
                let regressors = &posture.regressors;
                for (t, (term, y)) in self.gravity.terms().iter().zip(regressors).enumerate() {
                    let col = jp.fixed_view::<3, 1>(0, term.joint()) * *y;
                    block.column_mut(self.gravity_start + t).copy_from(&col);
                }
            }
        }
        if !j.iter().all(|v| v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the identification Jacobian".into(),
            });
        }
        Ok(j)
    }

    /// The Jacobian of [`ErrorModel::residuals`] (and of [`ErrorModel::predict`]) at `values`:
    /// [`ErrorModel::jacobian`] of the observations' postures and points, with, for a loaded
    /// reading, the compliances' columns (its observation rows, [`ErrorModel::load_rows`]) and
    /// the frame's rotation about the deflected point.
    ///
    /// # Errors
    /// Those of [`ErrorModel::jacobian`].
    pub fn jacobian_of(
        &self,
        values: &DVector<f64>,
        observations: &[Observation],
    ) -> Result<DMatrix<f64>> {
        let at: Vec<_> = observations.iter().map(|o| (o.q, o.point)).collect();
        let mut j = self.jacobian(values, &at)?;
        let Some(loads) = &self.loads else {
            return Ok(j);
        };
        for (i, o) in observations.iter().enumerate() {
            let Some(rows) = self.load_rows(&o.q, o.point, &o.wrench) else {
                continue;
            };
            let d = self.load_deflection(values, &o.q, o.point, &o.wrench);
            let mut block = j.fixed_rows_mut::<3>(3 * i);
            let turned = block.fixed_view::<3, 3>(0, 3) - d.cross_matrix();
            block.fixed_view_mut::<3, 3>(0, 3).copy_from(&turned);
            for (m, &c) in loads.columns.iter().enumerate() {
                let col = block.column(c) + rows.column(m);
                block.column_mut(c).copy_from(&col);
            }
        }
        Ok(j)
    }

    /// [`ErrorModel::column_scales`] at the observations' postures, with, for a compliance
    /// under the applied wrenches ([`Target::Compliance`]), `1 / rms`, `rms` the RMS length of
    /// its observation rows ([`ErrorModel::load_rows`]) over the loaded readings: a compliance
    /// that moves a loaded reading by 1 m RMS (0 below [`NO_EFFECT`] times the largest of its
    /// unit's); for a drive's gravity compliance with known masses, the smaller of that and its
    /// gravity scale (either where the other is 0).
    pub fn column_scales_of(&self, length: f64, observations: &[Observation]) -> DVector<f64> {
        let qs: Vec<Vector6<f64>> = observations.iter().map(|o| o.q).collect();
        let mut scales = self.column_scales(length, &qs);
        let Some(loads) = &self.loads else {
            return scales;
        };
        let mut sum = vec![0.0; loads.columns.len()];
        let mut loaded = 0usize;
        for o in observations {
            if let Some(rows) = self.load_rows(&o.q, o.point, &o.wrench) {
                loaded += 1;
                for (s, col) in sum.iter_mut().zip(rows.column_iter()) {
                    *s += col.norm_squared();
                }
            }
        }
        let rms: Vec<f64> = sum
            .iter()
            .map(|s| (s / loaded.max(1) as f64).sqrt())
            .collect();
        for (m, &c) in loads.columns.iter().enumerate() {
            let unit = self.parameters[c].unit();
            let largest = (loads.columns.iter().zip(&rms))
                .filter(|(&c, _)| self.parameters[c].unit() == unit)
                .map(|(_, r)| *r)
                .fold(0.0, f64::max);
            let loaded = match rms[m] > NO_EFFECT * largest {
                true => 1.0 / rms[m],
                false => 0.0,
            };
            // A drive's gravity compliance (known masses): the smaller of its two scales, the
            // larger effect, where both have one.
            scales[c] = match self.parameters[c].target {
                Target::Gravity(_) if scales[c] > 0.0 && loaded > 0.0 => scales[c].min(loaded),
                Target::Gravity(_) if loaded == 0.0 => scales[c],
                _ => loaded,
            };
        }
        scales
    }

    /// The six columns `[theta, d, a, alpha, beta, b]` of joint `i` for the base-frame point `b`.
    fn joint_columns(
        &self,
        f: &crate::Frames,
        values: &DVector<f64>,
        i: usize,
        b: &Vector3<f64>,
    ) -> [Vector3<f64>; 6] {
        let before = if i == 0 {
            *self.robot.base()
        } else {
            f.joints[i - 1]
        };
        let w_frame = before * self.robot.joints()[i].pre;
        let r = w_frame.rotation;
        let e = self.joint_errors(values, i);
        let basis = &self.bases[i];
        let (u, v) = (r * basis.u, r * basis.v);
        let o = (w_frame * nalgebra::Point3::from(basis.u * e[2] + basis.v * e[5])).coords;
        let v_turned =
            r * (UnitQuaternion::from_axis_angle(&Unit::new_unchecked(basis.u), e[3]) * basis.v);
        let (z, oz) = (f.axis_directions[i], f.axis_points[i]);
        [
            z.cross(&(b - oz)),
            z,
            u,
            u.cross(&(b - o)),
            v_turned.cross(&(b - o)),
            v,
        ]
    }

    /// The basis of joint `i`'s rotation frame (0-based).
    pub fn basis(&self, i: usize) -> &Basis {
        &self.bases[i]
    }

    /// Index of the first gravity parameter.
    pub fn gravity_start(&self) -> usize {
        self.gravity_start
    }

    /// The typical size of each parameter, by which the Jacobian's columns are multiplied to make
    /// them comparable (the column scaling of the identifiability analysis and the design
    /// criteria): 1 m for a length or a translation, `1 / length` rad for an angle (`length` the
    /// characteristic length, m: an angle error that moves a point at that distance by as much as
    /// a 1 m length error), and for a gravity term `1 / (length * y_rms)`, `y_rms` the RMS of its
    /// regressor at the postures `qs` (axis angles, rad), the value that deflects the joint by
    /// that angle; 0 (the column then has no effect) for a term whose regressor's RMS is below
    /// [`NO_EFFECT`] times the largest of its unit's (a torque that rounding alone makes
    /// non-zero, such as gravity's about a vertical axis). A scaled column is the position change
    /// (m) of a typical parameter error.
    pub fn column_scales(&self, length: f64, qs: &[Vector6<f64>]) -> DVector<f64> {
        let rms = self.gravity.regressor_rms(qs);
        DVector::from_iterator(
            self.parameters.len(),
            self.parameters
                .iter()
                .enumerate()
                .map(|(i, p)| match p.target {
                    Target::Frame(a) if a >= 3 => 1.0 / length,
                    Target::Joint { component, .. } if component.is_angle() => 1.0 / length,
                    Target::Gravity(term) => {
                        let y = rms[i - self.gravity_start];
                        let largest = (self.gravity.terms().iter().zip(&rms))
                            .filter(|(t, _)| t.unit() == term.unit())
                            .map(|(_, r)| *r)
                            .fold(0.0, f64::max);
                        match y > NO_EFFECT * largest {
                            true => 1.0 / (y * length),
                            false => 0.0,
                        }
                    }
                    _ => 1.0,
                }),
        )
    }
}

/// Writes the three observation rows of measuring point `k` (the setup's) at the posture
/// `frames` under `wrench` (base frame, N, N m, at the loading point) into rows `row..row + 3`
/// of `psi` (one column per parameter of the setup's model): the drives' (Eq. 11) and the
/// virtual springs' ([`crate::observation::SpringLoads`]).
fn write_load_rows(
    setup: &crate::Setup,
    frames: &crate::Frames,
    k: usize,
    wrench: &Vector6<f64>,
    psi: &mut DMatrix<f64>,
    row: usize,
) {
    use crate::observation::{point_rows, stiffness::joint_torques, SpringLoads};
    let point = &setup.tool().measuring_points[k];
    let arm = setup.arm();
    let tau = joint_torques(arm, frames, wrench);
    psi.fixed_view_mut::<3, 6>(row, 0)
        .copy_from(&point_rows(arm, frames, point, &tau));
    SpringLoads::new(arm, frames, wrench, psi.ncols() - 6).write_rows(frames, point, psi, row);
}
