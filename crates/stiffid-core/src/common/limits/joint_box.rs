//! One box of axis angles: a robot's joint limits or a setup's posture bounds.

use nalgebra::Vector6;

use crate::common::error::ColumnProblem;
use crate::{Error, Result};

/// A closed box of axis angles `lower[i] <= q[i] <= upper[i]`, rad: a robot's joint limits
/// ([`crate::Robot::limits`]) or the bounds of a setup's experiment postures
/// ([`crate::Setup::bounds`], Table 1). An infinite end is an unbounded axis (a continuous URDF
/// joint).
///
/// # Examples
/// ```
/// use nalgebra::Vector6;
/// use stiffid_core::common::limits::JointBox;
///
/// let limits = JointBox::new(Vector6::repeat(-1.0), Vector6::repeat(1.0));
/// let q = Vector6::new(0.0, 0.5, 1.5, 0.0, 0.0, 0.0);
/// assert!(!limits.contains(&q));
/// let v = limits.first_violation(&q).unwrap();
/// assert_eq!((v.axis, v.value), (2, 1.5));
/// let e = limits.check(&q, "the robot's limits", |a| format!("q{}_deg", a + 1));
/// assert_eq!(
///     e.unwrap_err().to_string(),
///     "q3_deg = 85.94 deg: expected within the robot's limits [-57.30, 57.30] deg"
/// );
/// assert!(limits.contains(&limits.clamp(&q)));
/// assert_eq!(limits.distance(&q), -0.5); // axis 3 is 0.5 rad beyond its upper end
/// assert_eq!(limits.distance(&Vector6::repeat(0.25)), 0.75);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointBox {
    /// Lower ends, rad.
    pub lower: Vector6<f64>,
    /// Upper ends, rad.
    pub upper: Vector6<f64>,
}

/// The first axis angle of a posture outside a [`JointBox`], with the range it missed, rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Violation {
    /// The axis, 0-based.
    pub axis: usize,
    /// The angle given (may be NaN or infinite), rad.
    pub value: f64,
    /// The lower end of the axis' range, rad.
    pub lower: f64,
    /// The upper end of the axis' range, rad.
    pub upper: f64,
}

impl JointBox {
    /// The box from its lower and upper ends, rad.
    pub fn new(lower: Vector6<f64>, upper: Vector6<f64>) -> Self {
        Self { lower, upper }
    }

    /// Whether every angle of `q` (rad) lies in the box (inclusive; NaN never does).
    pub fn contains(&self, q: &Vector6<f64>) -> bool {
        self.first_violation(q).is_none()
    }

    /// The first axis of `q` (rad) outside the box (NaN is outside), with its value and range.
    pub fn first_violation(&self, q: &Vector6<f64>) -> Option<Violation> {
        (0..6)
            .find(|&i| !(q[i] >= self.lower[i] && q[i] <= self.upper[i]))
            .map(|axis| Violation {
                axis,
                value: q[axis],
                lower: self.lower[axis],
                upper: self.upper[axis],
            })
    }

    /// Checks that `q` (rad) lies in the box, `within` naming the box in messages (e.g. "the
    /// robot's limits") and `field(axis)` naming the angle as the user gave it.
    ///
    /// # Errors
    /// [`Error::OutsideBox`] for the first axis outside, with the value and the range in degrees.
    pub fn check(
        &self,
        q: &Vector6<f64>,
        within: &'static str,
        field: impl FnOnce(usize) -> String,
    ) -> Result<()> {
        match self.first_violation(q) {
            None => Ok(()),
            Some(v) => Err(v.error(field(v.axis), within)),
        }
    }

    /// `q` (rad) with every angle moved to the nearest point of the box.
    pub fn clamp(&self, q: &Vector6<f64>) -> Vector6<f64> {
        Vector6::from_fn(|i, _| q[i].clamp(self.lower[i], self.upper[i]))
    }

    /// The smallest distance of an angle of `q` (rad) to its end of the box, rad: negative
    /// outside the box, NaN for a NaN angle.
    pub fn distance(&self, q: &Vector6<f64>) -> f64 {
        (0..6)
            .map(|i| (q[i] - self.lower[i]).min(self.upper[i] - q[i]))
            .fold(f64::INFINITY, |d, x| if x.is_nan() { x } else { d.min(x) })
    }

    /// The box grown by `margin` (rad) at both ends of every axis, e.g. to accept rounding.
    pub(crate) fn widened(&self, margin: f64) -> Self {
        Self::new(
            self.lower.add_scalar(-margin),
            self.upper.add_scalar(margin),
        )
    }
}

impl Violation {
    /// The error naming `field` (the angle as the user gave it) and `within` (the box), with the
    /// value given and the range in degrees.
    pub(crate) fn error(&self, field: String, within: &'static str) -> Error {
        Error::OutsideBox {
            field,
            value_deg: self.value.to_degrees(),
            within,
            lower_deg: self.lower.to_degrees(),
            upper_deg: self.upper.to_degrees(),
        }
    }

    /// The same in a table file: the column `name` holds the value, in degrees.
    pub fn outside(&self, name: String, within: &'static str) -> ColumnProblem {
        ColumnProblem::Outside {
            name,
            value: self.value.to_degrees(),
            within,
            lower: self.lower.to_degrees(),
            upper: self.upper.to_degrees(),
        }
    }
}
