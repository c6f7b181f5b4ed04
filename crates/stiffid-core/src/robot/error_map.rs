//! Joint error maps: the angle error of an axis as a periodic function of its own angle.
//!
//! Strain-wave gears and encoders turn a joint by a little more or less than its axis angle
//! says, by an error that repeats with every turn of the axis (transmission error, eccentricity
//! of the encoder disc). A map writes it as a Fourier series of the axis angle `q` (rad):
//!
//! ```text
//! e(q) = sum_{h=1..H} a_h cos(h q) + b_h sin(h q)        (rad)
//! ```
//!
//! and the chain turns by `q + e(q)`. Where the approach direction is known (the sign `d` of the
//! joint's last motion, -1 or +1: the readings' `dir1..dir6`), a backlash term adds `b d`, `b`
//! half the backlash (rad): `e(q, d) = e(q) + b d` (`ErrorMap::angle_from`); without a direction
//! the robot stands at the mean of the two approaches, `e(q)`. A map fitted over a range of its
//! axis's angles ([`ErrorMap::with_range`], the calibrated robot file's `range_deg`) holds its
//! series there only: beyond it the series tapers to zero over `TAPER_DEG` by a cosine ramp,
//! `e(q) w(d)` with `d` the distance beyond the range and `w(d) = (1 + cos(pi d / W)) / 2` for
//! `d < W`, 0 beyond ([`taper`]), rather than extrapolating a Fourier series fitted elsewhere
//! (the backlash term, a property of the gear, is kept everywhere). A robot with maps ([`crate::Robot::with_error_maps`])
//! evaluates its kinematic angles as `theta = M (q + e(q)) + c` ([`crate::AxisMap`]), so every
//! computation on its frames (kinematics, prediction, compensation, design) uses them. The
//! calibration identifies the coefficients (`stiffid_metrology::calibration::maps`). Source:
//! docs/model.md, section "Calibration", "Joint error maps".

use crate::{Error, Result};
use nalgebra::Vector6;

/// Most harmonics a map holds.
pub const MAX_HARMONICS: usize = 64;

/// The largest coefficient a map holds, rad (10 deg): an error map is a small correction.
pub(crate) const MAX_COEFFICIENT: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// The width `W` of the ramp over which a map's series tapers to zero beyond its fitted range,
/// deg ([`taper`]).
pub(crate) const TAPER_DEG: f64 = 20.0;

/// The factor `w(d)` of a map's series at the axis angle `q` (rad) with the fitted range
/// `(lo, hi)` (rad): exactly 1 within it, `(1 + cos(pi d / W)) / 2` at the distance `d` beyond it
/// within the ramp `W` (`TAPER_DEG`), exactly 0 past the ramp. Continuous with its slope (0 at
/// both ends of the ramp).
#[inline]
pub fn taper(q: f64, (lo, hi): (f64, f64)) -> f64 {
    let d = (lo - q).max(q - hi);
    let width = TAPER_DEG.to_radians();
    if d <= 0.0 {
        1.0
    } else if d >= width {
        0.0
    } else {
        0.5 * (1.0 + (std::f64::consts::PI * d / width).cos())
    }
}

/// One axis's error map: the coefficients of harmonics `1..=H`, half the backlash, rad, and the
/// range of axis angles it was fitted over (rad), when known.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ErrorMap {
    cos: Vec<f64>,
    sin: Vec<f64>,
    backlash: f64,
    range: Option<(f64, f64)>,
}

impl ErrorMap {
    /// The map of the cosine coefficients `cos` (`a_1..a_H`, rad) and the sine coefficients
    /// `sin` (`b_1..b_H`, rad); empty for no map.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_map`) when the two differ in length, hold more than
    /// [`MAX_HARMONICS`], or a coefficient is not finite or beyond 10 deg.
    pub fn new(cos: Vec<f64>, sin: Vec<f64>) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "error_map".into(),
            message,
        };
        if cos.len() != sin.len() {
            return Err(invalid(format!(
                "expected as many sine as cosine coefficients, got {} and {}",
                sin.len(),
                cos.len()
            )));
        }
        if cos.len() > MAX_HARMONICS {
            return Err(invalid(format!(
                "expected at most {MAX_HARMONICS} harmonics, got {}",
                cos.len()
            )));
        }
        if !(cos.iter().chain(&sin)).all(|v| v.is_finite() && v.abs() <= MAX_COEFFICIENT) {
            return Err(invalid(format!(
                "expected finite coefficients within {:.0} deg",
                MAX_COEFFICIENT.to_degrees()
            )));
        }
        Ok(ErrorMap {
            cos,
            sin,
            backlash: 0.0,
            range: None,
        })
    }

    /// The map fitted over the axis angles `lo..=hi` (rad): its series tapers to zero beyond
    /// them ([`taper`]).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_map.range_deg`) when a bound is not finite or `lo > hi`.
    pub fn with_range(self, lo: f64, hi: f64) -> Result<Self> {
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(Error::InvalidField {
                field: "error_map.range_deg".into(),
                message: format!(
                    "expected two finite angles, the lower first, got {} and {} deg",
                    lo.to_degrees(),
                    hi.to_degrees()
                ),
            });
        }
        Ok(ErrorMap {
            range: Some((lo, hi)),
            ..self
        })
    }

    /// The range of axis angles the map was fitted over (rad), when known: beyond it the series
    /// tapers to zero ([`taper`]); `None` for a series that holds at every angle.
    pub fn range(&self) -> Option<(f64, f64)> {
        self.range
    }

    /// The map with half the backlash `b` (rad): the angle error `+ b d` approached with the
    /// last motion's sign `d` (`ErrorMap::angle_from`).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_map`) when `b` is not finite or beyond 10 deg.
    pub fn with_backlash(self, b: f64) -> Result<Self> {
        if !(b.is_finite() && b.abs() <= MAX_COEFFICIENT) {
            return Err(Error::InvalidField {
                field: "error_map".into(),
                message: format!(
                    "expected a finite half backlash within {:.0} deg",
                    MAX_COEFFICIENT.to_degrees()
                ),
            });
        }
        Ok(ErrorMap {
            backlash: b,
            ..self
        })
    }

    /// Half the backlash `b`, rad (0: no backlash term).
    pub fn backlash(&self) -> f64 {
        self.backlash
    }

    /// The number of harmonics `H` (0: no map).
    pub fn harmonics(&self) -> usize {
        self.cos.len()
    }

    /// Whether the map is empty (no harmonic and no backlash).
    pub fn is_empty(&self) -> bool {
        self.cos.is_empty() && self.backlash == 0.0
    }

    /// The cosine coefficients `a_1..a_H`, rad.
    pub fn cos(&self) -> &[f64] {
        &self.cos
    }

    /// The sine coefficients `b_1..b_H`, rad.
    pub fn sin(&self) -> &[f64] {
        &self.sin
    }

    /// The factor [`taper`] of the map's series at the axis angle `q` (rad): 1 without a range.
    #[inline]
    pub(crate) fn taper(&self, q: f64) -> f64 {
        self.range.map_or(1.0, |r| taper(q, r))
    }

    /// The series at `q` (rad) from `(sin q, cos q)`, tapered beyond the fitted range: the
    /// series itself, untouched, within it.
    #[inline]
    fn tapered(&self, q: f64, turn: (f64, f64)) -> f64 {
        match self.taper(q) {
            1.0 => self.series(turn),
            0.0 => 0.0,
            w => w * self.series(turn),
        }
    }

    /// `ErrorMap::angle` from `(sin q, cos q)`.
    #[inline]
    fn series(&self, (s1, c1): (f64, f64)) -> f64 {
        let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
        let (s3, c3) = (s2 * c1 + c2 * s1, c2 * c1 - s2 * s1);
        let (s4, c4) = (2.0 * s2 * c2, c2 * c2 - s2 * s2);
        let (mut s, mut c) = ([s1, s2, s3, s4], [c1, c2, c3, c4]);
        let mut sum = [0.0; 4];
        let (a, b) = (self.cos.chunks_exact(4), self.sin.chunks_exact(4));
        let (a_tail, b_tail) = (a.remainder(), b.remainder());
        for (a, b) in a.zip(b) {
            for i in 0..4 {
                sum[i] += a[i] * c[i] + b[i] * s[i];
                (s[i], c[i]) = (s[i] * c4 + c[i] * s4, c[i] * c4 - s[i] * s4);
            }
        }
        for (i, (a, b)) in a_tail.iter().zip(b_tail).enumerate() {
            sum[i] += a * c[i] + b * s[i];
        }
        (sum[0] + sum[1]) + (sum[2] + sum[3])
    }

    /// The map whose coefficients and backlash are the sums of this one's and `other`'s (the
    /// longer's count), with this one's range (`other`'s without one).
    pub fn plus(&self, other: &ErrorMap) -> ErrorMap {
        let n = self.harmonics().max(other.harmonics());
        let at = |v: &[f64], h: usize| v.get(h).copied().unwrap_or(0.0);
        ErrorMap {
            cos: (0..n)
                .map(|h| at(&self.cos, h) + at(&other.cos, h))
                .collect(),
            sin: (0..n)
                .map(|h| at(&self.sin, h) + at(&other.sin, h))
                .collect(),
            backlash: self.backlash + other.backlash,
            range: self.range.or(other.range),
        }
    }
}

/// The errors `e(q_i)` (rad) of six axes' maps at the axis angles `q` (rad), each
/// `ErrorMap::angle` of its own axis's angle (tapered beyond its range): every `sin_cos` taken
/// before the harmonics' sums, so that the axes' independent work overlaps.
#[inline]
pub(crate) fn angles(maps: &[ErrorMap; 6], q: &Vector6<f64>) -> [f64; 6] {
    let turns: [Option<(f64, f64)>; 6] =
        std::array::from_fn(|i| (!maps[i].cos.is_empty()).then(|| q[i].sin_cos()));
    std::array::from_fn(|i| turns[i].map_or(0.0, |t| maps[i].tapered(q[i], t)))
}

#[cfg(test)]
impl ErrorMap {
    /// The error `e(q)` (rad) at the axis angle `q` (rad), the harmonics by the angle-addition
    /// recurrence from one `sin_cos`: the harmonics `h` of each residue of `h mod 4` in their own
    /// chain, each turned by `4 q` (a quarter of the dependent steps of one chain turned by
    /// `q`); no `sin_cos` for an axis without harmonics. Beyond the fitted range it tapers
    /// ([`taper`]).
    #[inline]
    pub(crate) fn angle(&self, q: f64) -> f64 {
        match self.cos.is_empty() {
            true => 0.0,
            false => self.tapered(q, q.sin_cos()),
        }
    }

    /// The error `e(q) + b d` (rad) at the axis angle `q` (rad) approached with the last
    /// motion's sign `direction` (-1.0 or 1.0).
    #[inline]
    pub(crate) fn angle_from(&self, q: f64, direction: f64) -> f64 {
        self.angle(q) + self.backlash * direction
    }
}
