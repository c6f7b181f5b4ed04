//! Joint stiffness identification from measured displacements (Zhang et al. 2021, Eq. 10-14), with
//! its uncertainty.
//!
//! Each [`Measurement`] is one measuring point in one posture: the axis angles, the wrench at the
//! loading point and the measured translation of the point (loaded minus unloaded). It gives three
//! rows of the observation matrix, `Psi[r, j] = J_m[r, j] * tau_j` with `tau = J_f^T W` (Eq. 4, 11,
//! [`crate::observation::point_rows`]), and `Psi h = delta` (Eq. 10) is solved for the compliance
//! `h` by Householder QR ([`Factor`]), never by the normal equations.
//!
//! Row order: measurement-major in the order given, then x, y, z (base frame): row `3 i + a` is
//! measurement `i`, coordinate `a`. (For measurements ordered posture by posture and point by point
//! this is the row order of [`crate::observation`].)
//!
//! ## Uncertainty
//! With `m` rows and `r = delta - Psi h`, the residual variance is `s^2 = |r|^2 / (m - 6)` and the
//! covariance of the compliance `Cov(h) = s^2 (Psi^T Psi)^-1`, computed as `s^2 R^-1 R^-T` from the
//! QR factor. This assumes independent measurement errors of equal variance on every coordinate and
//! a correct model.
//! - Compliance: 95% confidence interval `h_j +- t * se(h_j)`, `t` the 0.975 quantile of Student's
//!   t distribution with `m - 6` degrees of freedom (exact for Gaussian errors).
//! - Stiffness `k = 1/h`, first-order delta method: `se(k_j) = se(h_j) / h_j^2` and the interval
//!   `k_j +- t * se(k_j)`. Symmetric and good while `se(h_j) << h_j`; when the relative standard
//!   error is large it misleads (it can even reach below zero).
//! - Stiffness, by mapping the compliance interval through `k = 1/h`:
//!   `[1 / h_upper, 1 / h_lower]`, exact in coverage and asymmetric; unbounded above (`+inf`) when
//!   the compliance interval reaches zero, i.e. when the data cannot rule out an infinitely stiff
//!   joint.
//!
//! With exactly six rows the fit is exact and there is no uncertainty estimate (`None`).

pub mod adequacy;
pub mod cross_validation;
pub mod frames;
pub mod nonnegative;
pub mod robust;

pub use adequacy::{Adequacy, UnitCheck};
pub use cross_validation::{cross_validate, CrossValidation, Fold};
pub use robust::{Loss, RobustFit};

use crate::kinematics::Frames;
use crate::lsq::Factor;
use crate::observation::point_rows;
use crate::stiffness::joint_torques;
use crate::{Error, MeasurementField, Result, Setup};
use nalgebra::{DMatrix, DVector, Matrix6, Vector3, Vector6};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::cell::Cell;
use std::collections::HashMap;

/// Largest accepted displacement of a measuring point, m: a robot deflects by millimetres, so a
/// larger value is a unit or transcription error.
pub const MAX_DISPLACEMENT: f64 = 1.0;

/// Largest accepted force magnitude, N.
pub const MAX_FORCE: f64 = 1e6;

/// Largest accepted moment magnitude, Nm.
pub const MAX_MOMENT: f64 = 1e6;

/// One measured displacement: a measuring point in a posture under a wrench.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// The posture: any number that identifies it (a file's labels are numbered `0, 1, ...` in
    /// order of first appearance). Measurements of the same posture must have the same axis
    /// angles.
    pub posture: usize,
    /// Index of the measuring point in the setup's tool, 0-based.
    pub point: usize,
    /// Axis angles q, rad (controller convention).
    pub q: Vector6<f64>,
    /// Wrench `[f; m]` at the loading point, base frame, N and Nm (Eq. 1).
    pub wrench: Vector6<f64>,
    /// Translation of the measuring point, loaded minus unloaded, base frame, m.
    pub displacement: Vector3<f64>,
}

/// The observation matrix and measured displacements of a list of measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Observations {
    /// `Psi`, `3n x 6` for n measurements, m per (rad/Nm) (Eq. 11), rows as in the module docs.
    pub psi: DMatrix<f64>,
    /// `delta`, `3n`, m.
    pub delta: DVector<f64>,
    /// The number of distinct postures.
    pub postures: usize,
    /// The posture of each measurement, numbered `0..postures` in order of first appearance.
    pub posture_index: Vec<usize>,
}

/// Checks every measurement and stacks its three rows of `Psi` and `delta` (Eq. 10-11). Frames are
/// computed once per run of measurements with the same axis angles, torques once per run with the
/// same angles and wrench.
///
/// # Errors
/// [`Error::Measurement`] naming the measurement (1-based) and what is wrong: a measuring point the
/// setup lacks (`point`), a non-finite axis angle or one outside the robot's joint limits (`q1` ..
/// `q6`), a non-finite force or moment or one above [`MAX_FORCE`] / [`MAX_MOMENT`], a non-finite
/// displacement or one above [`MAX_DISPLACEMENT`], or a posture measured at different axis
/// angles (`posture`). Linear in the measurements whatever the number of postures.
pub fn observations(setup: &Setup, measurements: &[Measurement]) -> Result<Observations> {
    let n = measurements.len();
    let mut psi = DMatrix::zeros(3 * n, 6);
    let mut delta = DVector::zeros(3 * n);
    let mut labels = Postures::new(measurements);
    let mut posture_index = Vec::with_capacity(n);
    // The measurement the frames and torques were computed for, the frames and the torques.
    let mut state: Option<(usize, Frames, Vector6<f64>)> = None;
    for (i, meas) in measurements.iter().enumerate() {
        check(setup, i + 1, meas)?;
        posture_index.push(check_label(&mut labels, measurements, i)?);
        if state
            .as_ref()
            .is_some_and(|(j, _, _)| measurements[*j].q != meas.q)
        {
            state = None;
        }
        let (j, frames, tau) = state.get_or_insert_with(|| {
            let frames = setup.robot().frames(&meas.q);
            let tau = joint_torques(setup, &frames, &meas.wrench);
            (i, frames, tau)
        });
        if measurements[*j].wrench != meas.wrench {
            *tau = joint_torques(setup, frames, &meas.wrench);
        }
        *j = i;
        psi.fixed_view_mut::<3, 6>(3 * i, 0)
            .copy_from(&point_rows(setup, frames, meas.point, tau));
        delta
            .fixed_rows_mut::<3>(3 * i)
            .copy_from(&meas.displacement);
    }
    Ok(Observations {
        psi,
        delta,
        postures: labels.count,
        posture_index,
    })
}

fn check(setup: &Setup, number: usize, meas: &Measurement) -> Result<()> {
    let error = |field, message: String| Error::Measurement {
        number,
        field,
        message,
    };
    let points = setup.tool().measuring_points.len();
    if meas.point >= points {
        return Err(error(
            MeasurementField::Point,
            format!(
                "measuring point {} does not exist: the setup has {points} (1 to {points})",
                meas.point + 1
            ),
        ));
    }
    let robot = &setup.robot();
    if let Some(axis) = robot.first_out_of_limits(&meas.q) {
        let message = match meas.q[axis].is_finite() {
            false => "the axis angle is not finite".to_string(),
            true => format!(
                "{:.3} deg is outside the robot's limits [{:.2}, {:.2}] deg",
                meas.q[axis].to_degrees(),
                robot.lower[axis].to_degrees(),
                robot.upper[axis].to_degrees()
            ),
        };
        return Err(error(MeasurementField::Axis(axis), message));
    }
    let force: Vector3<f64> = meas.wrench.fixed_rows::<3>(0).into();
    let moment: Vector3<f64> = meas.wrench.fixed_rows::<3>(3).into();
    let magnitudes = [
        (MeasurementField::Force, force, MAX_FORCE, 1.0, "N"),
        (MeasurementField::Moment, moment, MAX_MOMENT, 1.0, "Nm"),
        (
            MeasurementField::Displacement,
            meas.displacement,
            MAX_DISPLACEMENT,
            1e3,
            "mm",
        ),
    ];
    for (field, v, limit, scale, unit) in magnitudes {
        if !v.iter().all(|x| x.is_finite()) {
            return Err(error(field, "expected finite numbers".into()));
        }
        // The largest component where the norm would overflow.
        let size = Some(v.norm()).filter(|n| n.is_finite()).unwrap_or(v.amax());
        if size > limit {
            return Err(error(
                field,
                format!(
                    "magnitude {:.4e} {unit} is above the limit {:.0e} {unit}: check the unit of the columns",
                    size * scale,
                    limit * scale
                ),
            ));
        }
    }
    Ok(())
}

/// The postures seen so far: posture -> (its dense number, its first measurement). A table
/// indexed by the posture number when the numbers are small (as a file's are), else a hash map.
struct Postures {
    table: Table,
    count: usize,
}

enum Table {
    /// `usize::MAX` before the posture is seen.
    Dense(Vec<(usize, usize)>),
    Sparse(HashMap<usize, (usize, usize)>),
}

impl Postures {
    fn new(measurements: &[Measurement]) -> Self {
        let n = measurements.len();
        let table = match measurements.iter().all(|m| m.posture < n) {
            true => Table::Dense(vec![(usize::MAX, usize::MAX); n]),
            false => Table::Sparse(HashMap::new()),
        };
        Self { table, count: 0 }
    }

    /// The dense number and the first measurement of `posture`, first seen at measurement `i`
    /// if new.
    fn entry(&mut self, posture: usize, i: usize) -> (usize, usize) {
        let next = (self.count, i);
        let slot = match &mut self.table {
            Table::Dense(v) => &mut v[posture],
            Table::Sparse(m) => m.entry(posture).or_insert((usize::MAX, usize::MAX)),
        };
        if slot.0 == usize::MAX {
            *slot = next;
            self.count += 1;
        }
        *slot
    }
}

/// The dense number of measurement `i`'s posture; an error if it was measured before at other
/// axis angles.
fn check_label(labels: &mut Postures, measurements: &[Measurement], i: usize) -> Result<usize> {
    let meas = &measurements[i];
    let (index, first) = labels.entry(meas.posture, i);
    if measurements[first].q != meas.q {
        return Err(Error::Measurement {
            number: i + 1,
            field: MeasurementField::Posture,
            message: format!(
                "this posture was measured before at other axis angles (measurement {}): give each posture its own label",
                first + 1
            ),
        });
    }
    Ok(index)
}

/// The result of an identification.
#[derive(Debug, Clone, PartialEq)]
pub struct Identification {
    /// The compliance `h` (Eq. 8, 14), rad/Nm.
    pub compliance: Vector6<f64>,
    /// The stiffness `k = 1/h`, Nm/rad.
    pub stiffness: Vector6<f64>,
    /// Standard errors and 95% confidence intervals; `None` with exactly six rows.
    pub uncertainty: Option<Uncertainty>,
    /// `delta - Psi h` of every row, m, rows as in the module docs (unweighted, also in robust mode).
    pub residuals: DVector<f64>,
    /// `sqrt(|r|^2 / m)`, m.
    pub residual_rms: f64,
    /// `cond_2(Psi)` of the (unweighted) observation matrix.
    pub cond_psi: f64,
    /// The number of rows of `Psi` (three per measurement).
    pub rows: usize,
    /// The number of distinct postures.
    pub postures: usize,
    /// The iteratively reweighted fit, in robust mode.
    pub robust: Option<RobustFit>,
    /// `(Psi^T W Psi)^-1` over the free compliances (zero rows and columns for compliances held
    /// at a bound), (rad/Nm)^2 per m^2: the covariance of `h` per unit noise variance.
    pub unit_covariance: Matrix6<f64>,
    /// The compliances held at their bound `h_j = 0` by [`Observations::identify_nonnegative`]
    /// (the active constraints); `None` for an unbounded fit.
    pub active_bounds: Option<[bool; 6]>,
}

impl Identification {
    /// Whether each joint's result is physical: a finite, positive compliance and stiffness.
    /// A negative compliance, a zero one (infinitely stiff) or a non-finite one is not.
    pub fn physical(&self) -> [bool; 6] {
        std::array::from_fn(|j| {
            let (h, k) = (self.compliance[j], self.stiffness[j]);
            h.is_finite() && k.is_finite() && h > 0.0 && k > 0.0
        })
    }
}

/// Standard errors and 95% confidence intervals of an identification (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Uncertainty {
    /// Degrees of freedom `m - 6` (robust mode: rows of non-zero weight minus 6).
    pub dof: usize,
    /// The variance the intervals use, m^2: `s^2`, the residual variance of one coordinate (or,
    /// in [`Adequacy::from_noise`], the setup's tracker noise variance).
    pub residual_variance: f64,
    /// The quantile of the 95% intervals: of Student's t with `dof` degrees of freedom, or of the
    /// normal distribution for a known variance.
    pub t_quantile: f64,
    /// `s^2 (Psi^T Psi)^-1`, (rad/Nm)^2.
    pub compliance_covariance: Matrix6<f64>,
    /// `se(h_j)`, rad/Nm.
    pub compliance_std_error: Vector6<f64>,
    /// `[h_j - t se(h_j), h_j + t se(h_j)]`, rad/Nm.
    pub compliance_ci95: [[f64; 2]; 6],
    /// `se(k_j) = se(h_j) / h_j^2` (delta method), Nm/rad.
    pub stiffness_std_error: Vector6<f64>,
    /// `[k_j - t se(k_j), k_j + t se(k_j)]` (delta method), Nm/rad.
    pub stiffness_ci95: [[f64; 2]; 6],
    /// The positive stiffness values whose compliance lies in the compliance interval:
    /// `[1/h_upper, 1/h_lower]`, the upper end `+inf` when `h_lower <= 0` (both `+inf`, an empty
    /// interval, when even `h_upper <= 0`), Nm/rad.
    pub stiffness_ci95_from_compliance: [[f64; 2]; 6],
}

impl Uncertainty {
    /// The uncertainty of compliance `h` given `Cov(h) / s^2` (`unit_covariance`), `s^2` and the
    /// degrees of freedom; `None` for zero degrees of freedom.
    pub fn new(
        h: &Vector6<f64>,
        unit_covariance: &Matrix6<f64>,
        residual_variance: f64,
        dof: usize,
    ) -> Option<Self> {
        Some(Self::with_quantile(
            h,
            unit_covariance,
            residual_variance,
            dof,
            t975(dof)?,
        ))
    }

    /// As [`Uncertainty::new`] with a given quantile of the 95% intervals (e.g. 1.96 for a known
    /// variance).
    pub fn with_quantile(
        h: &Vector6<f64>,
        unit_covariance: &Matrix6<f64>,
        residual_variance: f64,
        dof: usize,
        t_quantile: f64,
    ) -> Self {
        let compliance_covariance = unit_covariance * residual_variance;
        let se = compliance_covariance.diagonal().map(f64::sqrt);
        let k = h.map(|v| 1.0 / v);
        let se_k = se.component_div(&h.component_mul(h));
        let interval = |c: f64, s: f64| [c - t_quantile * s, c + t_quantile * s];
        let compliance_ci95: [[f64; 2]; 6] = std::array::from_fn(|j| interval(h[j], se[j]));
        Self {
            dof,
            residual_variance,
            t_quantile,
            compliance_covariance,
            compliance_std_error: se,
            compliance_ci95,
            stiffness_std_error: se_k,
            stiffness_ci95: std::array::from_fn(|j| interval(k[j], se_k[j])),
            stiffness_ci95_from_compliance: compliance_ci95.map(invert),
        }
    }
}

thread_local! {
    /// The last `(dof, t_{0.975, dof})` of this thread: the quantile costs microseconds, and
    /// repeated identifications (Monte Carlo runs, robust iterations) share their degrees of freedom.
    static LAST_T975: Cell<(usize, f64)> = const { Cell::new((0, f64::NAN)) };
}

/// The 0.975 quantile of Student's t with `dof` degrees of freedom (statrs), memoised per thread.
fn t975(dof: usize) -> Option<f64> {
    let (last, t) = LAST_T975.get();
    if last == dof && dof > 0 {
        return Some(t);
    }
    let t = StudentsT::new(0.0, 1.0, dof as f64)
        .ok()?
        .inverse_cdf(0.975);
    LAST_T975.set((dof, t));
    Some(t)
}

fn invert([lower, upper]: [f64; 2]) -> [f64; 2] {
    match (lower > 0.0, upper > 0.0) {
        (true, _) => [1.0 / upper, 1.0 / lower],
        (false, true) => [1.0 / upper, f64::INFINITY],
        (false, false) => [f64::INFINITY, f64::INFINITY],
    }
}

/// Identifies the joint compliance and stiffness by linear least squares (Eq. 13-14, QR), with
/// standard errors and 95% confidence intervals (module docs): [`observations`] then
/// [`Observations::identify`].
///
/// # Errors
/// Those of [`observations`] and [`Observations::identify`].
pub fn identify(setup: &Setup, measurements: &[Measurement]) -> Result<Identification> {
    observations(setup, measurements)?.identify()
}

/// Identifies robustly ([`Observations::identify_robust`]).
///
/// # Errors
/// Those of [`observations`] and [`Observations::identify_robust`].
pub fn identify_robust(
    setup: &Setup,
    measurements: &[Measurement],
    loss: Loss,
) -> Result<Identification> {
    observations(setup, measurements)?.identify_robust(loss)
}

impl Observations {
    /// The least-squares compliance `h = argmin |Psi h - delta|` (Eq. 13-14, by QR) and its
    /// statistics (module docs).
    ///
    /// # Errors
    /// [`Error::TooFewRows`] for fewer than six rows; [`Error::Unidentifiable`] naming the joints
    /// the data cannot identify and why (no measurement loads them, or their columns of `Psi` are
    /// dependent); [`Error::NotFinite`] for non-finite entries.
    pub fn identify(&self) -> Result<Identification> {
        self.check_deflection()?;
        let factor = Factor::try_new(&self.psi)?;
        let h = factor.solve(&self.delta);
        let residuals = &self.delta - &self.psi * h;
        Ok(self.finish(
            h,
            residuals,
            factor.unit_covariance(),
            6,
            factor.cond(),
            None,
        ))
    }

    /// [`Observations::identify`] without a copy of `Psi`: it is factored in place and the
    /// residuals come from the factor ([`Factor::residuals`]). For large data sets (a million
    /// measurements make `Psi` 144 MB).
    ///
    /// # Errors
    /// Those of [`Observations::identify`].
    pub fn into_identification(mut self) -> Result<Identification> {
        self.check_deflection()?;
        let psi = std::mem::replace(&mut self.psi, DMatrix::zeros(0, 6));
        let factor = Factor::try_from_matrix(psi)?;
        let (h, residuals) = factor.solve_with_residuals(&self.delta);
        Ok(self.finish(
            h,
            residuals,
            factor.unit_covariance(),
            6,
            factor.cond(),
            None,
        ))
    }

    /// The least-squares compliance with the bounds `h >= 0` (a joint cannot be softer than
    /// infinitely stiff): the Lawson-Hanson active-set method ([`nonnegative`]) on the QR-reduced
    /// problem `min |R h - c|`, `c` the first six entries of `Q^T delta`. Equal to
    /// [`Observations::identify`] when that is already non-negative. Joints at their bound have
    /// `h_j = 0` (`k_j = inf`, not physical: the data cannot tell them from rigid) and are listed
    /// in [`Identification::active_bounds`]; the uncertainty is that of the free compliances
    /// with the bound ones fixed, with `m - free` degrees of freedom.
    ///
    /// # Errors
    /// Those of [`Observations::identify`].
    pub fn identify_nonnegative(&self) -> Result<Identification> {
        self.check_deflection()?;
        let factor = Factor::try_new(&self.psi)?;
        let fit = nonnegative::solve(factor.r(), &factor.project(&self.delta));
        let free = fit.active.iter().filter(|a| !**a).count();
        let mut id = self.finish(
            fit.h,
            &self.delta - &self.psi * fit.h,
            nonnegative::unit_covariance(factor.r(), &fit.active),
            free,
            factor.cond(),
            None,
        );
        id.active_bounds = Some(fit.active);
        Ok(id)
    }

    /// [`Error::InvalidField`] when every measured displacement is zero: nothing deflected.
    fn check_deflection(&self) -> Result<()> {
        match self.delta.iter().any(|d| *d != 0.0) {
            true => Ok(()),
            false => Err(Error::InvalidField {
                field: "displacement".into(),
                message: "every measured displacement is zero: nothing to identify (check the displacement columns)".into(),
            }),
        }
    }

    /// Robust identification: iteratively reweighted least squares with `loss` ([`robust`]),
    /// starting from the least-squares fit. The uncertainty treats the final weights as known:
    /// `s^2 = sum w_i r_i^2 / (m_w - 6)` with `m_w` the rows of non-zero weight, and
    /// `Cov(h) = s^2 (Psi^T W Psi)^-1`. `cond_psi` is that of the unweighted `Psi`.
    ///
    /// # Errors
    /// Those of [`Observations::identify`]; [`Error::Unidentifiable`] also when the rows left with
    /// weight make `Psi` rank deficient.
    pub fn identify_robust(&self, loss: Loss) -> Result<Identification> {
        self.check_deflection()?;
        let factor = Factor::try_new(&self.psi)?;
        let start = factor.solve(&self.delta);
        let (h, weighted, fit) = robust::fit(&self.psi, &self.delta, start, loss)?;
        let residuals = &self.delta - &self.psi * h;
        Ok(self.finish(
            h,
            residuals,
            weighted.unit_covariance(),
            6,
            factor.cond(),
            Some(fit),
        ))
    }

    /// The statistics of compliance `h` with residuals `delta - Psi h`,
    /// `(Psi^T W Psi)^-1 = unit_covariance` and `free` estimated compliances.
    fn finish(
        &self,
        h: Vector6<f64>,
        residuals: DVector<f64>,
        unit_covariance: Matrix6<f64>,
        free: usize,
        cond_psi: f64,
        robust: Option<RobustFit>,
    ) -> Identification {
        let rows = residuals.len();
        let (weighted_rss, weighted_rows) = match &robust {
            None => (residuals.norm_squared(), rows),
            Some(fit) => (
                residuals.component_mul(&residuals).dot(&fit.weights),
                fit.weights.iter().filter(|w| **w > 0.0).count(),
            ),
        };
        let dof = weighted_rows.saturating_sub(free);
        let uncertainty = match dof {
            0 => None,
            _ => Uncertainty::new(&h, &unit_covariance, weighted_rss / dof as f64, dof),
        };
        Identification {
            compliance: h,
            stiffness: h.map(|v| 1.0 / v),
            uncertainty,
            residual_rms: (residuals.norm_squared() / rows as f64).sqrt(),
            residuals,
            cond_psi,
            rows,
            postures: self.postures,
            robust,
            unit_covariance,
            active_bounds: None,
        }
    }
}
