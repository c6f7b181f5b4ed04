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
//! half the backlash (rad): `e(q, d) = e(q) + b d` ([`ErrorMap::angle_from`]); without a direction
//! the robot stands at the mean of the two approaches, `e(q)`. A robot with maps ([`crate::Robot::with_error_maps`])
//! evaluates its kinematic angles as `theta = M (q + e(q)) + c` ([`crate::AxisMap`]), so every
//! computation on its frames (kinematics, prediction, compensation, design) uses them. The
//! calibration identifies the coefficients (`stiffid_metrology::calibration::maps`). Source:
//! docs/model.md, section "Calibration", "Joint error maps".

use crate::{Error, Result};
use nalgebra::Vector6;

/// Most harmonics a map holds.
pub const MAX_HARMONICS: usize = 64;

/// The largest coefficient a map holds, rad (10 deg): an error map is a small correction.
pub const MAX_COEFFICIENT: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// One axis's error map: the coefficients of harmonics `1..=H` and half the backlash, rad.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ErrorMap {
    cos: Vec<f64>,
    sin: Vec<f64>,
    backlash: f64,
}

impl ErrorMap {
    /// The map of the cosine coefficients `cos` (`a_1..a_H`, rad) and the sine coefficients
    /// `sin` (`b_1..b_H`, rad); empty for no map.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_map`) when the two differ in length, hold more than
    /// [`MAX_HARMONICS`], or a coefficient is not finite or beyond [`MAX_COEFFICIENT`].
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
        })
    }

    /// The map with half the backlash `b` (rad): the angle error `+ b d` approached with the
    /// last motion's sign `d` ([`ErrorMap::angle_from`]).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_map`) when `b` is not finite or beyond
    /// [`MAX_COEFFICIENT`].
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

    /// The error `e(q)` (rad) at the axis angle `q` (rad), the harmonics by the angle-addition
    /// recurrence from one `sin_cos`: the harmonics `h` of each residue of `h mod 4` in their own
    /// chain, each turned by `4 q` (a quarter of the dependent steps of one chain turned by
    /// `q`); no `sin_cos` for an axis without harmonics.
    #[inline]
    pub fn angle(&self, q: f64) -> f64 {
        match self.cos.is_empty() {
            true => 0.0,
            false => self.series(q.sin_cos()),
        }
    }

    /// [`ErrorMap::angle`] from `(sin q, cos q)`.
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

    /// The error `e(q) + b d` (rad) at the axis angle `q` (rad) approached with the last
    /// motion's sign `direction` (-1.0 or 1.0).
    #[inline]
    pub fn angle_from(&self, q: f64, direction: f64) -> f64 {
        self.angle(q) + self.backlash * direction
    }

    /// The map whose coefficients and backlash are the sums of this one's and `other`'s (the
    /// longer's count).
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
        }
    }
}

/// The errors `e(q_i)` (rad) of six axes' maps at the axis angles `q` (rad), each
/// [`ErrorMap::angle`] of its own axis's angle: every `sin_cos` taken before the harmonics' sums,
/// so that the axes' independent work overlaps.
#[inline]
pub fn angles(maps: &[ErrorMap; 6], q: &Vector6<f64>) -> [f64; 6] {
    let turns: [Option<(f64, f64)>; 6] =
        std::array::from_fn(|i| (!maps[i].cos.is_empty()).then(|| q[i].sin_cos()));
    std::array::from_fn(|i| turns[i].map_or(0.0, |t| maps[i].series(t)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_recurrence_is_the_series() {
        let map = ErrorMap::new(
            (1..=40).map(|h| 1e-4 / h as f64).collect(),
            (1..=40).map(|h| -2e-4 / (h * h) as f64).collect(),
        )
        .unwrap();
        for q in [-3.0, -0.7, 0.0, 1.3, 6.0] {
            let direct: f64 = (1..=40)
                .map(|h| {
                    let x = h as f64 * q;
                    1e-4 / h as f64 * x.cos() - 2e-4 / (h * h) as f64 * x.sin()
                })
                .sum();
            assert!((map.angle(q) - direct).abs() < 1e-15, "{q}");
        }
        let odd = ErrorMap::new(vec![1e-3, 0.0, 2e-4], vec![0.0, -5e-4, 1e-4]).unwrap();
        let q: f64 = 0.9;
        let direct = 1e-3 * q.cos() + 2e-4 * (3.0 * q).cos() - 5e-4 * (2.0 * q).sin()
            + 1e-4 * (3.0 * q).sin();
        assert!((odd.angle(q) - direct).abs() < 1e-18);
        assert!(ErrorMap::new(vec![0.0], vec![]).is_err());
        assert!(ErrorMap::new(vec![f64::NAN], vec![0.0]).is_err());
        let sum = map.plus(&ErrorMap::new(vec![1e-3], vec![0.0]).unwrap());
        assert_eq!(sum.harmonics(), 40);
        assert_eq!(sum.cos()[0], 1e-4 + 1e-3);
    }

    #[test]
    fn the_recurrence_is_the_series_at_random_angles() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for harmonics in [1, 2, 3, 5, 16, 33, MAX_HARMONICS] {
            let mut coefficient = || MAX_COEFFICIENT * (2.0 * rng.random::<f64>() - 1.0);
            let cos: Vec<f64> = (0..harmonics).map(|_| coefficient()).collect();
            let sin: Vec<f64> = (0..harmonics).map(|_| coefficient()).collect();
            let scale: f64 = cos.iter().chain(&sin).map(|v| v.abs()).sum();
            let map = ErrorMap::new(cos.clone(), sin.clone()).unwrap();
            for _ in 0..200 {
                let q = 4.0 * std::f64::consts::PI * (rng.random::<f64>() - 0.5);
                let direct: f64 = (0..harmonics)
                    .map(|h| {
                        let (s, c) = ((h + 1) as f64 * q).sin_cos();
                        cos[h] * c + sin[h] * s
                    })
                    .sum();
                let got = map.angle(q);
                assert!(got.is_finite());
                assert!((got - direct).abs() <= 1e-12 * scale, "{harmonics} {q}");
            }
        }
        assert_eq!(ErrorMap::default().angle(0.3), 0.0);
        let maps: [ErrorMap; 6] = std::array::from_fn(|i| match i % 2 {
            0 => ErrorMap::default(),
            _ => ErrorMap::new(vec![1e-4; i + 1], vec![-2e-4; i + 1]).unwrap(),
        });
        let q = Vector6::new(0.3, -1.2, 2.5, 0.0, -3.0, 1.0);
        let each: [f64; 6] = std::array::from_fn(|i| maps[i].angle(q[i]));
        assert_eq!(angles(&maps, &q), each);
    }

    #[test]
    fn backlash_adds_half_the_lost_motion_by_direction() {
        let map = ErrorMap::new(vec![1e-3], vec![2e-4])
            .unwrap()
            .with_backlash(5e-4)
            .unwrap();
        let q: f64 = 0.4;
        let mean = 1e-3 * q.cos() + 2e-4 * q.sin();
        assert_eq!(map.angle(q), mean);
        assert!((map.angle_from(q, 1.0) - (mean + 5e-4)).abs() < 1e-18);
        assert!((map.angle_from(q, -1.0) - (mean - 5e-4)).abs() < 1e-18);
        let only = ErrorMap::default().with_backlash(1e-4).unwrap();
        assert!(!only.is_empty());
        assert!((only.plus(&map).backlash() - 6e-4).abs() < 1e-18);
        assert!(ErrorMap::default().with_backlash(f64::NAN).is_err());
        assert!(ErrorMap::default().with_backlash(0.2).is_err());
    }
}
