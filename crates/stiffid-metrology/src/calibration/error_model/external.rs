//! The cell's external axes in the error model (module docs of [`super`], "External axes").
//!
//! A linear carrier axis `i` with nominal frame `A0_i` ([`ExternalAxis::frame`]: x along its
//! direction) has the frame `A_i = exp([phi_i]x) A0_i`, `phi_i = delta_y y0 + delta_z z0` (its
//! direction turned about the nominal frame's y and z axes: two parameters), and the six error
//! motions of ISO 230-1 as polynomials of orders `1..K_i` in the normalised position `u`
//! ([`ErrorMotions`]: `6 K_i` coefficients `c_k`, translations `t(u)` and rotation vector `r(u)`
//! in `A_i`):
//!
//! ```text
//! M_i(s) = Trans(A_i (x (s + offset) + t(u))) Rot(A_i r(u)),   C(e) = prod_i M_i(s_i)
//! ```
//!
//! A rotary positioner axis `j` with nominal line `(p0_j, d0_j)` and frame `A0_j` has its line
//! moved across itself, `p_j = p0_j + a_y y0 + a_z z0`, turned, `d_j = exp([phi_j]x) d0_j`, and an
//! angular offset `o_j` (five parameters: ISO 230-7's location and orientation errors of an axis
//! of rotation and its angular positioning error), `P(e) = prod_j Trans(p_j) Rot(d_j, e_j + o_j)
//! Trans(-p_j)`. A reflector fixed on the positioner's table at `x_k` (part frame at `e = 0`,
//! three parameters each) is read at `P(e) x_k`.
//!
//! The Jacobian columns are exact: a turn of a frame by `exp([phi]x)` moves with the left
//! Jacobian of SO(3), `d exp([phi]x) = [J_l(phi) d phi]x exp([phi]x)`, `J_l(phi) = I + (1 - cos
//! t) / t^2 [phi]x + (t - sin t) / t^3 [phi]x^2`, `t = |phi|` (Chirikjian 2011, Eq. 10.86).

use super::{AxisPart, ErrorModel, Kind, Parameter, Target};
use nalgebra::{DVector, Isometry3, Matrix3, Point3, Translation3, Unit, UnitQuaternion, Vector3};
use stiffid_core::robot::external::{
    AxisKind, ErrorMotions, ExternalAxes, ExternalAxis, MAX_ORDER,
};
use stiffid_core::{Error, Result};

/// The motions' names in parameter names, ISO 230-1's six in [`ErrorMotions`] order.
pub(crate) const MOTIONS: [&str; 6] = [
    "positioning",
    "straightness_y",
    "straightness_z",
    "roll",
    "pitch",
    "yaw",
];

/// The external axes of an error model: the nominal axes, each axis's first parameter and the
/// orders of the linear axes' error motions.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct External {
    pub(super) axes: ExternalAxes,
    /// Each axis's nominal frame (x along its direction).
    frames: Vec<UnitQuaternion<f64>>,
    /// The orders `K` of each axis's fitted error motions (0 for a rotary axis).
    pub(super) orders: Vec<usize>,
    /// Each axis's first parameter.
    starts: Vec<usize>,
    /// Whether the axes' parameters are fitted (else the axes stand as the robot gives them and
    /// only the table's reflectors are parameters: [`ErrorModel::with_external_nominal`]).
    fitted: bool,
    /// Each linear axis's zero offset parameter, when the model has one
    /// ([`ErrorModel::with_external_offsets`]).
    pub(super) shifts: Vec<Option<usize>>,
}

/// The left Jacobian of SO(3) at the rotation vector `phi` (module docs).
fn left_jacobian(phi: &Vector3<f64>) -> Matrix3<f64> {
    let t2 = phi.norm_squared();
    let k = phi.cross_matrix();
    let (a, b) = match t2 < 1e-12 {
        true => (0.5 - t2 / 24.0, 1.0 / 6.0 - t2 / 120.0),
        false => {
            let t = t2.sqrt();
            ((1.0 - t.cos()) / t2, (t - t.sin()) / (t2 * t))
        }
    };
    Matrix3::identity() + k * a + k * k * b
}

/// One linear axis at `values`: its frame `A`, the turn `phi`, its translation `a` (from the
/// carriage below to its mount, in `A`) and rotation vector `A r`, at position `s`.
struct Linear {
    frame: UnitQuaternion<f64>,
    phi: Vector3<f64>,
    /// `A (x (s + offset) + t(u))`.
    shift: Vector3<f64>,
    /// `A r(u)`.
    turn: Vector3<f64>,
    u: f64,
}

impl External {
    /// The frame's y and z axes (of its nominal frame) of axis `i`.
    fn across(&self, i: usize) -> [Vector3<f64>; 2] {
        let f = &self.frames[i];
        [f * Vector3::y(), f * Vector3::z()]
    }

    fn phi(&self, values: &DVector<f64>, i: usize) -> Vector3<f64> {
        if !self.fitted {
            return Vector3::zeros();
        }
        let [y, z] = self.across(i);
        let s = self.starts[i];
        y * values[s] + z * values[s + 1]
    }

    /// Linear axis `i`'s fitted zero offset in `values` (0 without one), m.
    fn shift(&self, values: &DVector<f64>, i: usize) -> f64 {
        self.shifts
            .get(i)
            .copied()
            .flatten()
            .map_or(0.0, |c| values[c])
    }

    fn linear(&self, values: &DVector<f64>, i: usize, s: f64) -> Linear {
        let axis = &self.axes.axes()[i];
        let phi = self.phi(values, i);
        let frame = UnitQuaternion::from_scaled_axis(phi) * self.frames[i];
        let u = axis.travel(s);
        let along = s + axis.offset + self.shift(values, i);
        let (mut t, mut r) = (Vector3::new(along, 0.0, 0.0), Vector3::zeros());
        let mut power = 1.0;
        let start = self.starts[i] + 2;
        for k in 0..self.orders[i] {
            power *= u;
            let c = start + 6 * k;
            t += Vector3::new(values[c], values[c + 1], values[c + 2]) * power;
            r += Vector3::new(values[c + 3], values[c + 4], values[c + 5]) * power;
        }
        // The nominal axis's orders beyond the fitted ones stay as they are.
        for c in axis.errors.coefficients().iter().skip(self.orders[i]) {
            power *= u;
            t += Vector3::new(c[0], c[1], c[2]) * power;
            r += Vector3::new(c[3], c[4], c[5]) * power;
        }
        Linear {
            frame,
            phi,
            shift: frame * t,
            turn: frame * r,
            u,
        }
    }

    /// The carrier's pose `C(e)` at `values` (module docs); a missing value counts as 0.
    pub(super) fn carrier(&self, values: &DVector<f64>, e: &[f64]) -> Isometry3<f64> {
        let mut pose = Isometry3::identity();
        for i in 0..self.axes.carrier_len() {
            let l = self.linear(values, i, e.get(i).copied().unwrap_or(0.0));
            pose *= Isometry3::from_parts(
                Translation3::from(l.shift),
                UnitQuaternion::from_scaled_axis(l.turn),
            );
        }
        pose
    }

    /// Writes the columns of the carrier's parameters for the arm's point at `point` (cell
    /// frame, m) at `e` into `put(parameter, column)`.
    pub(super) fn carrier_columns(
        &self,
        values: &DVector<f64>,
        e: &[f64],
        point: &Vector3<f64>,
        mut put: impl FnMut(usize, Vector3<f64>),
    ) {
        if !self.fitted {
            return;
        }
        let mut carried = Isometry3::identity();
        for i in 0..self.axes.carrier_len() {
            let l = self.linear(values, i, e.get(i).copied().unwrap_or(0.0));
            let turn = UnitQuaternion::from_scaled_axis(l.turn);
            let rc = carried.rotation;
            // The point from the carriage below (`m`) and from this axis's mount (`lever`).
            let m = (carried.inverse() * Point3::from(*point)).coords;
            let lever = m - l.shift;
            let y = turn.inverse() * lever;
            let s = self.starts[i];
            let jl = left_jacobian(&l.phi);
            for (k, n) in self.across(i).iter().enumerate() {
                let w = jl * n;
                put(s + k, rc * (w.cross(&m) - turn * w.cross(&y)));
            }
            if let Some(c) = self.shifts.get(i).copied().flatten() {
                put(c, rc * (l.frame * Vector3::x()));
            }
            let jr = left_jacobian(&l.turn);
            let mut power = 1.0;
            for k in 0..self.orders[i] {
                power *= l.u;
                for motion in 0..6 {
                    let axis = l.frame * Vector3::ith(motion % 3, power);
                    let column = match motion < 3 {
                        true => rc * axis,
                        false => rc * (jr * axis).cross(&lever),
                    };
                    put(s + 2 + 6 * k + motion, column);
                }
            }
            carried *= Isometry3::from_parts(Translation3::from(l.shift), turn);
        }
    }

    /// Rotary axis `i`'s line `(p, d)` and angle at `values` and value `e_i`.
    fn line(&self, values: &DVector<f64>, i: usize, e: f64) -> (Vector3<f64>, Vector3<f64>, f64) {
        let axis = &self.axes.axes()[i];
        if !self.fitted {
            return (axis.point, axis.direction.into_inner(), e + axis.offset);
        }
        let [y, z] = self.across(i);
        let s = self.starts[i];
        let p = axis.point + y * values[s] + z * values[s + 1];
        let phi = y * values[s + 2] + z * values[s + 3];
        let d = UnitQuaternion::from_scaled_axis(phi) * axis.direction.into_inner();
        (p, d, e + axis.offset + values[s + 4])
    }

    fn turn(p: &Vector3<f64>, d: &Vector3<f64>, angle: f64) -> Isometry3<f64> {
        let r = UnitQuaternion::from_axis_angle(&Unit::new_normalize(*d), angle);
        Isometry3::from_parts(Translation3::from(p - r * p), r)
    }

    /// The positioner's pose `P(e)` at `values` (module docs); a missing value counts as 0.
    pub(super) fn positioner(&self, values: &DVector<f64>, e: &[f64]) -> Isometry3<f64> {
        let mut pose = Isometry3::identity();
        for i in self.axes.carrier_len()..self.axes.len() {
            let (p, d, angle) = self.line(values, i, e.get(i).copied().unwrap_or(0.0));
            pose *= Self::turn(&p, &d, angle);
        }
        pose
    }

    /// Writes the columns of the positioner's parameters for the reading of the table
    /// reflector at `x` (part frame at `e = 0`, m) at `e` into `put(parameter, column)`.
    pub(super) fn positioner_columns(
        &self,
        values: &DVector<f64>,
        e: &[f64],
        x: Vector3<f64>,
        mut put: impl FnMut(usize, Vector3<f64>),
    ) {
        if !self.fitted {
            return;
        }
        let start = self.axes.carrier_len();
        let turns: Vec<_> = (start..self.axes.len())
            .map(|i| self.line(values, i, e.get(i).copied().unwrap_or(0.0)))
            .collect();
        let poses: Vec<Isometry3<f64>> =
            turns.iter().map(|(p, d, a)| Self::turn(p, d, *a)).collect();
        // The reflector before each turn: `y_j = T_{j+1} ... T_n x`.
        let mut y = vec![x; poses.len() + 1];
        for j in (0..poses.len()).rev() {
            y[j] = (poses[j] * Point3::from(y[j + 1])).coords;
        }
        let mut before = Isometry3::identity();
        for (j, ((p, d, _), pose)) in turns.iter().zip(&poses).enumerate() {
            let i = start + j;
            let s = self.starts[i];
            let (rb, r) = (before.rotation, pose.rotation);
            let arm = y[j + 1] - p;
            let turned = r * arm;
            let across = self.across(i);
            let phi = across[0] * values[s + 2] + across[1] * values[s + 3];
            let jl = left_jacobian(&phi);
            for (a, n) in across.iter().enumerate() {
                put(s + a, rb * (n - r * n));
                let w = jl * n;
                put(s + 2 + a, rb * (w.cross(&turned) - r * w.cross(&arm)));
            }
            put(s + 4, rb * d.normalize().cross(&turned));
            before *= pose;
        }
    }

    /// The external axes at `values`, as a robot file holds them: a linear axis's direction
    /// `A e_x` and its error motions re-expressed in that direction's own frame
    /// ([`ExternalAxis::frame`]); a rotary axis's point (the nominal's foot moved across the
    /// line), direction and offset.
    ///
    /// # Errors
    /// Those of [`ErrorMotions::new`] (a coefficient beyond its limit) and
    /// [`ExternalAxes::new`].
    pub(super) fn axes_at(&self, values: &DVector<f64>) -> Result<ExternalAxes> {
        let mut out = Vec::with_capacity(self.axes.len());
        for (i, axis) in self.axes.axes().iter().enumerate() {
            let mut axis = axis.clone();
            match axis.kind {
                AxisKind::Linear => {
                    let l = self.linear(values, i, axis.lower);
                    axis.direction = Unit::new_normalize(l.frame * Vector3::x());
                    axis.offset += self.shift(values, i);
                    // The file's frame of that direction, and the turn from the model's to it.
                    let to_file = axis.frame().inverse() * l.frame;
                    let s = self.starts[i] + 2;
                    let own = axis.errors.coefficients();
                    // The fitted orders, then the nominal axis's beyond them.
                    let all: Vec<[f64; 6]> = (0..self.orders[i].max(own.len()))
                        .map(|k| {
                            let c = |m: usize| match k < self.orders[i] {
                                true => values[s + 6 * k + m],
                                false => own[k][m],
                            };
                            let t = to_file * Vector3::new(c(0), c(1), c(2));
                            let r = to_file * Vector3::new(c(3), c(4), c(5));
                            [t.x, t.y, t.z, r.x, r.y, r.z]
                        })
                        .collect();
                    axis.errors = ErrorMotions::new(all).map_err(|e| match e {
                        Error::InvalidField { message, .. } => Error::InvalidField {
                            field: format!("external_axis ({}) error_motions", axis.name),
                            message,
                        },
                        e => e,
                    })?;
                }
                AxisKind::Rotary => {
                    let (p, d, _) = self.line(values, i, 0.0);
                    axis.point = p;
                    axis.direction = Unit::new_normalize(d);
                    if self.fitted {
                        axis.offset += values[self.starts[i] + 4];
                    }
                }
            }
            out.push(axis);
        }
        ExternalAxes::new(out)
    }
}

/// The most orders [`ErrorModel::with_external`] fits per linear axis.
pub(crate) const MAX_FITTED_ORDER: usize = MAX_ORDER;

impl ErrorModel {
    /// The model with the robot's external axes ([`stiffid_core::Robot::external`]): per linear carrier
    /// axis its direction (2 parameters, `<axis>.direction.ry`, `.rz`: turns about its frame's
    /// y and z axes, rad) and error motions of orders `1..orders[i]` (`6 K` parameters,
    /// `<axis>.<motion>.u<k>`, the coefficient of `u^k`, m or rad, nominal the axis's own);
    /// per rotary positioner axis its line's location (`<axis>.location.y`, `.z`, m),
    /// direction (`<axis>.direction.ry`, `.rz`, rad) and angular offset (`<axis>.offset`,
    /// rad); then `tables` reflectors fixed in the cell ([`ErrorModel::with_tables`]: on the
    /// positioner's table, or fixed points of a cell with a track alone). Priorities: the
    /// reflectors, a carrier's directions and a positioner's lines 0 (kept before joint 1's
    /// errors, which then merge into them and the tracker's registration: the cell's frame is
    /// the tracker's, the track's and the positioner's), the error motions and offsets 2.
    /// `orders` has one entry per axis (a rotary axis's is ignored).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`external_axis`) when the robot has no external axes, the model has
    /// reflectors, loads or maps already, `orders` has another length, an order exceeds
    /// [`stiffid_core::robot::external::MAX_ORDER`], or `tables` exceeds [`super::MAX_POINTS`].
    pub fn with_external(mut self, orders: &[usize], tables: usize) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "external_axis".into(),
            message,
        };
        let Some(axes) = self.robot.external().cloned() else {
            return Err(invalid("the robot has no external axes".into()));
        };
        if orders.len() != axes.len() || orders.iter().any(|&k| k > MAX_FITTED_ORDER) {
            return Err(invalid(format!(
                "expected {} orders of 0 to {MAX_FITTED_ORDER}, got {orders:?}",
                axes.len()
            )));
        }
        self.check_tables(tables)?;
        let mut starts = Vec::with_capacity(axes.len());
        let mut fitted_orders = Vec::with_capacity(axes.len());
        for (i, axis) in axes.axes().iter().enumerate() {
            starts.push(self.parameters.len());
            let mut push = |name: String, kind: Kind, part: AxisPart, nominal: f64, priority| {
                self.parameters.push(Parameter {
                    name: format!("{}.{name}", axis.name),
                    kind,
                    target: Target::External { axis: i, part },
                    nominal,
                    priority,
                })
            };
            match axis.kind {
                AxisKind::Linear => {
                    for (a, n) in ["ry", "rz"].iter().enumerate() {
                        push(
                            format!("direction.{n}"),
                            Kind::Carrier,
                            AxisPart::Direction(a),
                            0.0,
                            0,
                        );
                    }
                    for order in 1..=orders[i] {
                        let own = axis.errors.coefficients().get(order - 1);
                        for (motion, m) in MOTIONS.iter().enumerate() {
                            let nominal = own.map_or(0.0, |c| c[motion]);
                            let part = AxisPart::Motion { order, motion };
                            push(format!("{m}.u{order}"), Kind::Carrier, part, nominal, 2);
                        }
                    }
                    fitted_orders.push(orders[i]);
                }
                AxisKind::Rotary => {
                    for (a, n) in ["y", "z"].iter().enumerate() {
                        push(
                            format!("location.{n}"),
                            Kind::Positioner,
                            AxisPart::Location(a),
                            0.0,
                            0,
                        );
                    }
                    for (a, n) in ["ry", "rz"].iter().enumerate() {
                        push(
                            format!("direction.{n}"),
                            Kind::Positioner,
                            AxisPart::Direction(a),
                            0.0,
                            0,
                        );
                    }
                    push("offset".into(), Kind::Positioner, AxisPart::Offset, 0.0, 2);
                    fitted_orders.push(0);
                }
            }
        }
        self.push_axes(axes, fitted_orders, starts, true);
        self.with_tables(tables)
    }

    /// The model with the robot's external axes as it gives them (no parameter of theirs
    /// fitted) and `tables` reflectors fixed in the cell ([`ErrorModel::with_tables`]): the
    /// nominal cell, or the cell calibration.
    ///
    /// # Errors
    /// As [`ErrorModel::with_external`].
    pub fn with_external_nominal(mut self, tables: usize) -> Result<Self> {
        let Some(axes) = self.robot.external().cloned() else {
            return Err(Error::InvalidField {
                field: "external_axis".into(),
                message: "the robot has no external axes".into(),
            });
        };
        self.check_tables(tables)?;
        let n = axes.len();
        self.push_axes(axes, vec![0; n], vec![0; n], false);
        self.with_tables(tables)
    }

    /// Refuses external axes added again or after the loads, the maps or the reflectors, and
    /// more than [`super::MAX_POINTS`] reflectors.
    fn check_tables(&self, tables: usize) -> Result<()> {
        let invalid = |message: String| Error::InvalidField {
            field: "external_axis".into(),
            message,
        };
        if self.loads.is_some()
            || self.maps.is_some()
            || self.external.is_some()
            || self.tables() > 0
        {
            return Err(invalid(
                "add the external axes before the reflectors, the loads and the error maps, once"
                    .into(),
            ));
        }
        if tables > super::MAX_POINTS {
            return Err(invalid(format!(
                "expected 0 to {} reflectors fixed in the cell, got {tables}",
                super::MAX_POINTS
            )));
        }
        Ok(())
    }

    fn push_axes(
        &mut self,
        axes: ExternalAxes,
        orders: Vec<usize>,
        starts: Vec<usize>,
        fitted: bool,
    ) {
        self.external = Some(External {
            frames: axes.axes().iter().map(ExternalAxis::frame).collect(),
            shifts: vec![None; axes.len()],
            axes,
            orders,
            starts,
            fitted,
        });
    }

    /// The external axes at `values` as a robot file holds them (the directions, error motions,
    /// lines and offsets fitted), or `None` without external axes.
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a fitted error motion is beyond
    /// [`stiffid_core::robot::external::ErrorMotions::new`]'s limits.
    pub fn external_at(&self, values: &DVector<f64>) -> Result<Option<ExternalAxes>> {
        self.external
            .as_ref()
            .map(|x| x.axes_at(values))
            .transpose()
    }

    /// The carrier's pose `C(e)` (cell frame from the arm's mount) at `values` and external axis
    /// values `e` (SI, the cell's order); the identity without a carrier.
    pub fn carrier_pose(&self, values: &DVector<f64>, e: &[f64]) -> Isometry3<f64> {
        match &self.external {
            Some(x) if x.axes.carrier_len() > 0 => x.carrier(values, e),
            _ => Isometry3::identity(),
        }
    }

    /// The columns of the carrier's fitted parameters for the arm's point `point` (cell frame,
    /// m) at external axis values `e` (SI, the cell's order) and `values`, as
    /// `put(parameter, column)` (m per unit of the parameter); nothing without a carrier. Each
    /// column is affine in the point: a translation, or a turn about an axis fixed in the cell.
    pub fn carrier_columns(
        &self,
        values: &DVector<f64>,
        e: &[f64],
        point: &Vector3<f64>,
        put: impl FnMut(usize, Vector3<f64>),
    ) {
        if let Some(x) = (self.external.as_ref()).filter(|x| x.axes.carrier_len() > 0) {
            x.carrier_columns(values, e, point, put);
        }
    }

    /// The positioner's pose `P(e)` (cell frame from the part's frame at `e = 0`) at `values`;
    /// the identity without a positioner.
    pub fn positioner_pose(&self, values: &DVector<f64>, e: &[f64]) -> Isometry3<f64> {
        match &self.external {
            Some(x) => x.positioner(values, e),
            None => Isometry3::identity(),
        }
    }
}

impl ErrorModel {
    /// `values` with a carrier's fitted error motions at zero: where
    /// [`crate::calibration::identifiability`] judges what the readings determine.
    /// Error motions of a few micrometres and microradians tilt the carriage from station to
    /// station, and would make joint 1's errors differ from the tracker's registration by that
    /// much: identifiable in name, with a condition number of 1e9, and every fit then amplifies
    /// the noise into them.
    pub(crate) fn structural(&self, values: &DVector<f64>) -> DVector<f64> {
        let mut out = values.clone();
        for (c, p) in self.parameters.iter().enumerate() {
            if let Target::External {
                part: AxisPart::Motion { .. },
                ..
            } = p.target
            {
                out[c] = 0.0;
            }
        }
        out
    }

    /// Why parameter `c` of an external axis merges with the kept ones, in words (what it is
    /// the same as); `None` for any other parameter.
    pub fn merged_words(&self, c: usize) -> Option<&'static str> {
        let Target::External { axis, part } = self.parameters.get(c)?.target else {
            return None;
        };
        let linear = self.robot.external()?.axes().get(axis)?.kind == AxisKind::Linear;
        Some(match (part, linear) {
            (AxisPart::Motion { order: 1, motion: 1 | 2 }, _) => {
                "a straightness linear in the position is a turn of the track's direction (its constant part a shift of the tracker's registration): the direction holds it"
            }
            (AxisPart::Motion { .. }, _) => {
                "these readings do not separate this error motion from the kept parameters: read more stations along the travel, several postures at each"
            }
            (AxisPart::Direction(_), true) => {
                "the track's direction is the tracker's registration turned with the arm on its carriage: read postures along the whole travel"
            }
            (AxisPart::Offset, _) => {
                "an angular offset turns the table's zero, and the reflectors' unknown positions on the table take it"
            }
            (AxisPart::Shift, _) => {
                "a track's zero offset moves the arm along the track as a shift of the tracker's registration does: only reflectors on a positioner's table, read at several angles, tell them apart"
            }
            _ => {
                "read the table's reflectors at more angles of each positioner axis, the axes varied independently"
            }
        })
    }
}
