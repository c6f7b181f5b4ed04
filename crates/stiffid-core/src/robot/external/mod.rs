//! The cell's external axes: a carrier under the arm and a positioner under the workpiece.
//!
//! A robot that machines large parts often stands on a linear track (a 7th axis; up to three
//! linear axes make a gantry), and the part often sits on a positioner (a turntable, a
//! tilt-rotate table: one or two revolute axes). [`ExternalAxes`] holds both, in the cell's
//! order: the carrier's axes first, then the positioner's. Their values `e` are metres for a
//! linear axis and radians for a rotary one inside; millimetres and degrees at the edges
//! ([`ExternalAxes::to_si`], [`ExternalAxes::to_display`], columns named `e1_mm`, `e2_deg`).
//!
//! ## The carrier
//! Linear axis `i` moves its carriage by `s_i + offset_i` along `direction_i` (given in the
//! frame of the carriage below it; the first in the cell frame) and, with its
//! [`ErrorMotions`], by the six error motions of ISO 230-1 at `s_i`:
//!
//! ```text
//! C(e) = prod_i  Trans(d_i (s_i + offset_i)) E_i(s_i)
//! ```
//!
//! The arm's base frame in the cell at `e` is `C(e) * robot.base()` ([`crate::Robot::frames_at`]);
//! without a carrier `C = I` and the arm stands where it always did.
//!
//! ## The positioner
//! Rotary axis `j` turns about the line through `point_j` along `direction_j`, both given in the
//! cell frame at `e = 0` (the second axis carried by the first), by `e_j + offset_j`; the part's
//! frame moves with the product of exponentials (Brockett 1984; Lynch and Park, *Modern
//! Robotics*, 2017, Eq. 4.14):
//!
//! ```text
//! P(e) = prod_j  Trans(p_j) Rot(d_j, e_j + offset_j) Trans(-p_j)
//! ```
//!
//! A point of the part `x` (in the part's frame at `e = 0`, cell coordinates) is at `P(e) x` in
//! the cell. Paths and programs give points of the part, never of the moving base or of the floor.

mod error_motions;
pub mod file;
pub use error_motions::{ErrorMotions, MAX_ORDER};

use crate::common::limits;
use crate::{Error, Result};
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

/// Most linear axes of a carrier (a gantry).
pub(crate) const MAX_CARRIER_AXES: usize = 3;

/// Most rotary axes of a positioner (a tilt-rotate table).
pub(crate) const MAX_POSITIONER_AXES: usize = 2;

/// Most external axes of a cell: a carrier's and a positioner's.
pub const MAX_AXES: usize = MAX_CARRIER_AXES + MAX_POSITIONER_AXES;

/// The values of a cell's external axes at one posture, in the cell's order (SI: m for a linear
/// axis, rad for a rotary one); empty for a cell without external axes. A small copyable array
/// of at most [`MAX_AXES`] values, so a measurement or a posture carries it without allocating.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ExternalValues {
    values: [f64; MAX_AXES],
    len: usize,
}

impl ExternalValues {
    /// No values: a cell without external axes.
    pub const NONE: ExternalValues = ExternalValues {
        values: [0.0; MAX_AXES],
        len: 0,
    };

    /// These values (SI, the cell's order).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`external axis values`) when there are more than [`MAX_AXES`].
    pub fn new(values: &[f64]) -> Result<Self> {
        if values.len() > MAX_AXES {
            return Err(invalid(
                "external axis values",
                format!("expected at most {MAX_AXES}, got {}", values.len()),
            ));
        }
        let mut out = Self::NONE;
        out.values[..values.len()].copy_from_slice(values);
        out.len = values.len();
        Ok(out)
    }

    /// The values, SI, the cell's order.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// How an external axis moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisKind {
    /// Prismatic: values in m inside, mm at the edges.
    Linear,
    /// Revolute: values in rad inside, deg at the edges.
    Rotary,
}

/// What an external axis carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// It carries the arm (a track or a gantry: linear axes).
    Carrier,
    /// It carries the workpiece (a turntable or a tilt-rotate table: rotary axes).
    Positioner,
}

/// One external axis.
#[derive(Debug, Clone, PartialEq)]
pub struct ExternalAxis {
    /// Its name, as the file gives it (`track`, `E1`): unique in a cell.
    pub name: String,
    /// Linear or rotary.
    pub kind: AxisKind,
    /// Carrier or positioner.
    pub role: Role,
    /// Unit direction: a linear axis's motion in the frame of the carriage below it (the first
    /// in the cell frame); a rotary axis's line direction, cell frame at `e = 0`.
    pub direction: Unit<Vector3<f64>>,
    /// A point on a rotary axis's line, cell frame at `e = 0`, m (zero for a linear axis).
    pub point: Vector3<f64>,
    /// Added to the axis value: m for a linear axis, rad for a rotary one.
    pub offset: f64,
    /// The lower end of the travel, m or rad.
    pub lower: f64,
    /// The upper end of the travel, m or rad.
    pub upper: f64,
    /// A linear axis's error motions along its travel (empty for none; a rotary axis has none).
    pub errors: ErrorMotions,
    /// The axis's largest speed, m/s or rad/s; infinite: no limit (`max_speed_mm_s`,
    /// `max_speed_deg_s`).
    pub max_speed: f64,
}

impl ExternalAxis {
    /// A linear carrier axis along `direction` with travel `lower..upper` (m), no offset, no
    /// error motions and no speed limit.
    pub fn linear(name: &str, direction: Unit<Vector3<f64>>, lower: f64, upper: f64) -> Self {
        Self {
            name: name.to_string(),
            kind: AxisKind::Linear,
            role: Role::Carrier,
            direction,
            point: Vector3::zeros(),
            offset: 0.0,
            lower,
            upper,
            errors: ErrorMotions::default(),
            max_speed: f64::INFINITY,
        }
    }

    /// A rotary positioner axis about the line through `point` (m) along `direction`, travel
    /// `lower..upper` (rad), no offset and no speed limit.
    pub fn rotary(
        name: &str,
        point: Vector3<f64>,
        direction: Unit<Vector3<f64>>,
        lower: f64,
        upper: f64,
    ) -> Self {
        Self {
            kind: AxisKind::Rotary,
            role: Role::Positioner,
            point,
            ..Self::linear(name, direction, lower, upper)
        }
    }

    /// The unit of its values at the edges: `mm` or `deg`.
    pub fn unit(&self) -> &'static str {
        match self.kind {
            AxisKind::Linear => "mm",
            AxisKind::Rotary => "deg",
        }
    }

    /// One SI value (m or rad) in the edges' unit (mm or deg).
    pub fn to_display(&self, si: f64) -> f64 {
        match self.kind {
            AxisKind::Linear => si * 1e3,
            AxisKind::Rotary => si.to_degrees(),
        }
    }

    /// One value in the edges' unit (mm or deg) in SI (m or rad).
    pub fn to_si(&self, display: f64) -> f64 {
        match self.kind {
            AxisKind::Linear => display * 1e-3,
            AxisKind::Rotary => display.to_radians(),
        }
    }
}

/// The cell's external axes, carrier first, then positioner. Immutable; built by
/// [`ExternalAxes::new`], which checks them.
#[derive(Debug, Clone, PartialEq)]
pub struct ExternalAxes {
    axes: Vec<ExternalAxis>,
}

impl ExternalAxes {
    /// The axes, in any order of roles (kept in the cell's order: carrier, then positioner, each
    /// in the order given).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`external_axis[i]...`, 1-based in the order given) when there are
    /// none or more than [`MAX_AXES`], more than `MAX_CARRIER_AXES` carrier axes or
    /// `MAX_POSITIONER_AXES` positioner axes, a carrier axis is not linear or a positioner axis not
    /// rotary, a name is empty or repeated, a number is not finite, a travel is empty or beyond
    /// [-100, 100] m (linear) or [`limits::ANGLE_RAD`] (rotary), or a rotary axis carries error
    /// motions.
    pub fn new(axes: Vec<ExternalAxis>) -> Result<Self> {
        if axes.is_empty() || axes.len() > MAX_AXES {
            return Err(invalid(
                "external_axis",
                format!("expected 1 to {MAX_AXES} axes, got {}", axes.len()),
            ));
        }
        for (i, axis) in axes.iter().enumerate() {
            check_axis(axis, &format!("external_axis[{}]", i + 1))?;
            if axes[..i].iter().any(|a| a.name == axis.name) {
                return Err(invalid(
                    &format!("external_axis[{}].name", i + 1),
                    format!(
                        "expected a name no other axis has, got {:?} twice",
                        axis.name
                    ),
                ));
            }
        }
        let count = |role| axes.iter().filter(|a| a.role == role).count();
        if count(Role::Carrier) > MAX_CARRIER_AXES || count(Role::Positioner) > MAX_POSITIONER_AXES
        {
            return Err(invalid(
                "external_axis",
                format!(
                    "expected at most {MAX_CARRIER_AXES} carrier and {MAX_POSITIONER_AXES} \
                     positioner axes, got {} and {}",
                    count(Role::Carrier),
                    count(Role::Positioner)
                ),
            ));
        }
        let (mut ordered, positioner): (Vec<_>, Vec<_>) =
            axes.into_iter().partition(|a| a.role == Role::Carrier);
        ordered.extend(positioner);
        Ok(Self { axes: ordered })
    }

    /// The axes in the cell's order: carrier, then positioner.
    pub fn axes(&self) -> &[ExternalAxis] {
        &self.axes
    }

    /// How many axes.
    pub fn len(&self) -> usize {
        self.axes.len()
    }

    /// Always false: a cell without external axes has no `ExternalAxes`.
    pub fn is_empty(&self) -> bool {
        self.axes.is_empty()
    }

    /// How many carrier axes (they come first).
    pub fn carrier_len(&self) -> usize {
        self.axes.iter().filter(|a| a.role == Role::Carrier).count()
    }

    /// `count` stations over the carriers' travel (at least 1; one alone at its middle): the
    /// carrier axes together at the Chebyshev-Lobatto points `(1 - cos(pi k / (count - 1))) / 2`
    /// of their travels (the ends included, denser towards them, where a polynomial error
    /// motion is least determined), the positioner's axes at 0 (or the end of the travel
    /// nearest it).
    pub fn stations(&self, count: usize) -> Vec<ExternalValues> {
        let count = count.max(1);
        (0..count)
            .map(|k| {
                let t = match count {
                    1 => 0.5,
                    _ => 0.5 * (1.0 - (std::f64::consts::PI * k as f64 / (count - 1) as f64).cos()),
                };
                let values: Vec<f64> = (self.axes.iter())
                    .map(|a| match a.role {
                        Role::Carrier => a.lower + t * (a.upper - a.lower),
                        Role::Positioner => 0.0f64.clamp(a.lower, a.upper),
                    })
                    .collect();
                ExternalValues::new(&values).expect("at most MAX_AXES axes")
            })
            .collect()
    }

    /// The columns of the axes in data files, in the cell's order: `e1_mm`, `e2_deg`, ...
    pub fn column_names(&self) -> Vec<String> {
        (self.axes.iter().enumerate())
            .map(|(i, a)| format!("e{}_{}", i + 1, a.unit()))
            .collect()
    }

    /// SI values (m, rad) of values in the edges' units (mm, deg), in the cell's order.
    pub fn to_si(&self, display: &[f64]) -> Vec<f64> {
        (self.axes.iter().zip(display))
            .map(|(a, v)| a.to_si(*v))
            .collect()
    }

    /// Values in the edges' units (mm, deg) of SI values (m, rad), in the cell's order.
    pub fn to_display(&self, si: &[f64]) -> Vec<f64> {
        (self.axes.iter().zip(si))
            .map(|(a, v)| a.to_display(*v))
            .collect()
    }

    /// Whether `e` (SI, the cell's order) has one finite value per axis within its travel (to
    /// 1e-9 of the travel's width, the rounding of values written in mm or deg).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`field`, or `field` and the axis's column and name) when the
    /// count differs, a value is not finite or outside its travel; the message gives the values
    /// in mm or deg.
    pub fn check(&self, e: &[f64], field: &str) -> Result<()> {
        if e.len() != self.len() {
            return Err(invalid(
                field,
                format!(
                    "expected {} external axis values ({}), got {}",
                    self.len(),
                    self.column_names().join(", "),
                    e.len()
                ),
            ));
        }
        for (i, (axis, value)) in self.axes.iter().zip(e).enumerate() {
            let slack = 1e-9 * (axis.upper - axis.lower);
            if !value.is_finite() || *value < axis.lower - slack || *value > axis.upper + slack {
                let unit = axis.unit();
                return Err(invalid(
                    &format!("{field} e{}_{unit} ({})", i + 1, axis.name),
                    format!(
                        "expected a value within the axis's travel {} to {} {unit}, got {}",
                        short(axis.to_display(axis.lower)),
                        short(axis.to_display(axis.upper)),
                        short(axis.to_display(*value))
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The carrier's pose `C(e)` (cell frame from the arm's mount, m) at `e` (SI, the cell's
    /// order; values past the carrier's are ignored). The identity without carrier axes.
    pub fn carrier_pose(&self, e: &[f64]) -> Isometry3<f64> {
        let mut pose = Isometry3::identity();
        for (axis, s) in self.carrier().zip(e) {
            let along = axis.direction.into_inner() * (s + axis.offset);
            pose *= Translation3::from(along);
            if !axis.errors.is_empty() {
                pose *= axis.errors.pose(&axis.frame(), axis.travel(*s));
            }
        }
        pose
    }

    /// The positioner's pose `P(e)` (cell frame from the part's frame at `e = 0`) at `e` (SI,
    /// the cell's order). The identity without positioner axes.
    pub fn positioner_pose(&self, e: &[f64]) -> Isometry3<f64> {
        let start = self.carrier_len();
        let mut pose = Isometry3::identity();
        for (axis, angle) in self.axes[start..].iter().zip(e.iter().skip(start)) {
            pose *= turn_about_line(&axis.point, &axis.direction, angle + axis.offset);
        }
        pose
    }

    /// The Jacobian columns of the carrier's axes at `e`: per carrier axis, the velocity of any
    /// point of the arm per unit value (m/m), the carriage's direction in the cell frame (the
    /// error motions' slopes left out, as an error map's are, [`crate::Robot::frames`]).
    pub fn carrier_columns(&self, e: &[f64]) -> Vec<Vector3<f64>> {
        let mut carried = Isometry3::identity();
        let mut columns = Vec::with_capacity(self.carrier_len());
        for (axis, s) in self.carrier().zip(e) {
            columns.push(carried.rotation * axis.direction.into_inner());
            carried *= Translation3::from(axis.direction.into_inner() * (s + axis.offset));
            if !axis.errors.is_empty() {
                carried *= axis.errors.pose(&axis.frame(), axis.travel(*s));
            }
        }
        columns
    }

    /// The lines of the positioner's axes at `e` (SI, the cell's order): per positioner axis, its
    /// unit direction and a point on it (m), cell frame. A point `x` of the part moves by
    /// `d x (x - o)` per radian (`ExternalAxes::positioner_columns`) and turns by `d`.
    pub fn positioner_lines(&self, e: &[f64]) -> Vec<(Vector3<f64>, Vector3<f64>)> {
        let start = self.carrier_len();
        let mut turned = Isometry3::identity();
        let mut lines = Vec::with_capacity(self.len() - start);
        for (axis, angle) in self.axes[start..].iter().zip(e.iter().skip(start)) {
            let d = turned.rotation * axis.direction.into_inner();
            let o = turned * nalgebra::Point3::from(axis.point);
            lines.push((d, o.coords));
            turned *= turn_about_line(&axis.point, &axis.direction, angle + axis.offset);
        }
        lines
    }

    fn carrier(&self) -> impl Iterator<Item = &ExternalAxis> {
        self.axes.iter().take_while(|a| a.role == Role::Carrier)
    }
}

impl ExternalAxis {
    /// The axis's frame for its error motions: x along the direction, z the cell's z made
    /// perpendicular to it (the cell's x when the axis is within 25 deg of vertical), y = z x x.
    pub fn frame(&self) -> UnitQuaternion<f64> {
        let x = self.direction.into_inner();
        let up = match x.z.abs() < 0.9 {
            true => Vector3::z(),
            false => Vector3::x(),
        };
        let z = (up - x * x.dot(&up)).normalize();
        let y = z.cross(&x);
        let m = nalgebra::Matrix3::from_columns(&[x, y, z]);
        UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(m))
    }

    /// The position `s` (m) normalised over the travel to `[-1, 1]`, the error motions'
    /// variable.
    pub fn travel(&self, s: f64) -> f64 {
        (2.0 * s - (self.lower + self.upper)) / (self.upper - self.lower)
    }
}

impl crate::Robot {
    /// Whether `e` (SI, the cell's order) are the values of the robot's external axes within
    /// their travel ([`ExternalAxes::check`]), or empty for a robot without.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`field`) when the robot has external axes and `e` is empty (the
    /// message names the axes and their columns) or of another length, a value outside its
    /// travel (naming the axis), or values given for a robot without external axes.
    pub fn check_external(&self, e: &[f64], field: &str) -> Result<()> {
        match self.external() {
        None if e.is_empty() => Ok(()),
        None => Err(Error::InvalidField {
            field: field.to_string(),
            message: format!(
                "the robot has no external axes, got {} value(s): give external axes in the robot or setup file ([[external_axis]])",
                e.len()
            ),
        }),
        Some(axes) if e.is_empty() => Err(Error::InvalidField {
            field: field.to_string(),
            message: format!(
                "the cell has external axes ({}): expected their values, mm for a linear axis and deg for a rotary one, in this order",
                (axes.column_names().iter().zip(axes.axes()))
                    .map(|(c, a)| format!("{c} {}", a.name))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }),
        Some(axes) => axes.check(e, field),
    }
    }
}

/// The rotation by `angle` (rad) about the line through `point` along `direction`.
fn turn_about_line(
    point: &Vector3<f64>,
    direction: &Unit<Vector3<f64>>,
    angle: f64,
) -> Isometry3<f64> {
    let r = UnitQuaternion::from_axis_angle(direction, angle);
    Isometry3::from_parts(Translation3::from(point - r * point), r)
}

fn check_axis(axis: &ExternalAxis, field: &str) -> Result<()> {
    if axis.name.trim().is_empty() {
        return Err(invalid(&format!("{field}.name"), "expected a name".into()));
    }
    let field = format!("{field} ({})", axis.name);
    match (axis.role, axis.kind) {
        (Role::Carrier, AxisKind::Linear) | (Role::Positioner, AxisKind::Rotary) => {}
        (Role::Carrier, _) => {
            return Err(invalid(
                &field,
                "expected a linear carrier axis (a track or a gantry)".into(),
            ))
        }
        (Role::Positioner, _) => {
            return Err(invalid(&field, "expected a rotary positioner axis".into()))
        }
    }
    let numbers = (axis.direction.iter().chain(axis.point.iter())).chain([
        &axis.offset,
        &axis.lower,
        &axis.upper,
    ]);
    if !numbers.into_iter().all(|v| v.is_finite()) {
        return Err(invalid(&field, "expected finite numbers".into()));
    }
    let range = match axis.kind {
        AxisKind::Linear => limits::LENGTH_M,
        AxisKind::Rotary => limits::ANGLE_RAD,
    };
    let within = |v: f64| v >= range.min && v <= range.max;
    if !(axis.lower < axis.upper && within(axis.lower) && within(axis.upper)) {
        let unit = axis.unit();
        return Err(invalid(
            &format!("{field} limits"),
            format!(
                "expected a lower end below the upper end, both finite, got {} to {} {unit}",
                short(axis.to_display(axis.lower)),
                short(axis.to_display(axis.upper))
            ),
        ));
    }
    if axis.kind == AxisKind::Rotary && !axis.errors.is_empty() {
        return Err(invalid(
            &field,
            "expected no error motions on a rotary axis (its line and offset are its errors)"
                .into(),
        ));
    }
    Ok(())
}

fn short(v: f64) -> String {
    crate::common::words::number(v)
}

fn invalid(field: &str, message: String) -> Error {
    Error::InvalidField {
        field: field.to_string(),
        message,
    }
}

#[cfg(test)]
impl ExternalAxes {
    /// The Jacobian columns of the positioner's axes at `e` for a point of the part at `x`
    /// (cell frame, m): per positioner axis, the point's velocity per radian, `d x (x - o)`
    /// with `d` and `o` the axis's line at `e` (m/rad). The tool's velocity over the part is
    /// the arm's minus these.
    pub(crate) fn positioner_columns(&self, e: &[f64], x: &Vector3<f64>) -> Vec<Vector3<f64>> {
        let start = self.carrier_len();
        let mut turned = Isometry3::identity();
        let mut columns = Vec::with_capacity(self.len() - start);
        for (axis, angle) in self.axes[start..].iter().zip(e.iter().skip(start)) {
            let d = turned.rotation * axis.direction.into_inner();
            let o = turned * nalgebra::Point3::from(axis.point);
            columns.push(d.cross(&(x - o.coords)));
            turned *= turn_about_line(&axis.point, &axis.direction, angle + axis.offset);
        }
        columns
    }
}

#[cfg(test)]
mod external_tests;
