//! The six error motions of a linear axis along its travel (ISO 230-1:2012, 3.4.4): the
//! positioning error along the axis, the two straightness errors across it, and roll, pitch and
//! yaw, each a polynomial in the axis's position normalised over its travel.

use crate::{Error, Result};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// The highest polynomial order of an error motion.
pub const MAX_ORDER: usize = 8;

/// The largest translation coefficient, m (50 mm), and rotation coefficient, rad (0.1): error
/// motions are small corrections.
pub(crate) const MAX_COEFFICIENT: [f64; 2] = [0.05, 0.1];

/// The error motions of a linear axis: for each order `k = 1..=K`, six coefficients
/// `[positioning, straightness y, straightness z, roll, pitch, yaw]` (m, m, m, rad, rad, rad) of
/// `u^k`, `u` the position normalised to `[-1, 1]` over the travel
/// ([`super::ExternalAxis::travel`]); in the axis's frame ([`super::ExternalAxis::frame`]: x
/// along the axis). No constant term: a constant error is the arm's base pose.
///
/// At `u` the carriage is moved by the translation `t(u) = sum_k c_k[0..3] u^k` and turned by
/// the rotation vector `r(u) = sum_k c_k[3..6] u^k`, both in the axis's frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ErrorMotions {
    coefficients: Vec<[f64; 6]>,
}

impl ErrorMotions {
    /// The error motions of these coefficients, order 1 first (empty: none).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_motions`) when there are more than [`MAX_ORDER`] orders or a
    /// coefficient is not finite or beyond 50 mm (a translation) or 0.1 rad (a rotation).
    pub fn new(coefficients: Vec<[f64; 6]>) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "error_motions".into(),
            message,
        };
        if coefficients.len() > MAX_ORDER {
            return Err(invalid(format!(
                "expected at most order {MAX_ORDER}, got {}",
                coefficients.len()
            )));
        }
        let within = |(i, v): (usize, &f64)| v.is_finite() && v.abs() <= MAX_COEFFICIENT[i / 3];
        if !coefficients
            .iter()
            .all(|c| c.iter().enumerate().all(within))
        {
            return Err(invalid(
                "expected finite coefficients within 50 mm and 0.1 rad".into(),
            ));
        }
        let mut coefficients = coefficients;
        while coefficients
            .last()
            .is_some_and(|c| c.iter().all(|v| *v == 0.0))
        {
            coefficients.pop();
        }
        Ok(Self { coefficients })
    }

    /// The coefficients, order 1 first: `[positioning, straightness y, straightness z, roll,
    /// pitch, yaw]`, m and rad.
    pub fn coefficients(&self) -> &[[f64; 6]] {
        &self.coefficients
    }

    /// Whether there are none.
    pub(crate) fn is_empty(&self) -> bool {
        self.coefficients.is_empty()
    }

    /// The six error motions at normalised position `u`: `[t; r]`, m and rad, axis frame.
    pub(crate) fn at(&self, u: f64) -> [f64; 6] {
        let mut out = [0.0; 6];
        let mut power = 1.0;
        for c in &self.coefficients {
            power *= u;
            for (o, v) in out.iter_mut().zip(c) {
                *o += v * power;
            }
        }
        out
    }

    /// The carriage's error transform at normalised position `u`, in the frame whose axes are
    /// the axis's frame `axes` (its rotation in the carriage's frame): `Trans(A t) Rot(A r)`.
    pub(crate) fn pose(&self, axes: &UnitQuaternion<f64>, u: f64) -> Isometry3<f64> {
        let m = self.at(u);
        let t = axes * Vector3::new(m[0], m[1], m[2]);
        let r = axes * Vector3::new(m[3], m[4], m[5]);
        Isometry3::from_parts(Translation3::from(t), UnitQuaternion::from_scaled_axis(r))
    }
}
