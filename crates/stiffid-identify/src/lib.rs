//! Joint stiffness identification from measured displacements (Zhang et al. 2021, Eq. 10-14), with
//! its uncertainty.
//!
//! Each [`Measurement`] is one measuring point in one posture: the axis angles, the wrench at the
//! loading point and the measured translation of the point (loaded minus unloaded). It gives three
//! rows of the observation matrix, `Psi[r, j] = J_m[r, j] * tau_j` with `tau = J_f^T W` (Eq. 4, 11,
//! [`stiffid_core::observation::point_rows`]), and `Psi h = delta` (Eq. 10) is solved for the compliance
//! `h` by Householder QR ([`Factor`]), never by the normal equations.
//!
//! Rows in the order of [`stiffid_core::observation`]: row `3 i + a` is measurement `i`, coordinate `a`.
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
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub mod adequacy;
pub mod compare;
pub mod cross_validation;
pub mod nonnegative;
pub mod offsets;
pub mod prediction;
pub mod robust;
pub mod steps;
pub mod streamed;
pub mod svd;
mod uncertainty;
pub mod validate;

pub use adequacy::{Adequacy, UnitCheck};
pub use cross_validation::{cross_validate, CrossValidation, Fold};
pub use robust::{Loss, RobustFit};
pub use uncertainty::Uncertainty;

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};
use rayon::prelude::*;
use stiffid_core::math::lsq::{Factor, Reduced, Solution};
use stiffid_core::observation::{assemble, Check, Measurement, Observations};
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result};

/// How a model is fitted to the data: the full fit, which every fold of a cross-validation
/// repeats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Least squares ([`Observations::least_squares`]).
    LeastSquares,
    /// Non-negative least squares ([`Observations::nonnegative`]).
    Nonnegative,
    /// Robust, with this loss ([`Observations::robust`]).
    Robust(Loss),
}

impl Method {
    /// Fits `obs` with this method.
    ///
    /// # Errors
    /// Those of the fit.
    pub fn fit(self, obs: &Observations) -> Result<Identification> {
        match self {
            Method::LeastSquares => obs.least_squares(),
            Method::Nonnegative => obs.nonnegative(),
            Method::Robust(loss) => obs.robust(loss),
        }
    }
}

/// The held-out explained share `1 - sqrt(A / B)` and its standard error over the postures, from
/// each posture's `[a_p, b_p]`: the sums of its squared prediction errors `delta_b^2` and of its
/// squared measured displacements `|delta_m|^2` (`A`, `B` their sums over the `n` postures).
/// The postures are the independent units: the ratio `r = A / B` has the variance `n / (n - 1)
/// sum_p (a_p - r b_p)^2 / B^2` (the delta method of a ratio estimator; Cochran, *Sampling
/// Techniques*, 3rd ed., 1977, ch. 6), and `1 - sqrt(r)` the standard error `se(r) / (2 sqrt(r))`;
/// `NaN` for one posture.
pub(crate) fn explained_share(per_posture: &[[f64; 2]]) -> [f64; 2] {
    let n = per_posture.len() as f64;
    let [a, b] = per_posture
        .iter()
        .fold([0.0, 0.0], |[a, b], p| [a + p[0], b + p[1]]);
    let r = a / b;
    let var = per_posture
        .iter()
        .map(|p| (p[0] - r * p[1]).powi(2))
        .sum::<f64>()
        * n
        / ((n - 1.0) * b * b);
    [1.0 - r.sqrt(), var.sqrt() / (2.0 * r.sqrt())]
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
    /// The displacement the fit predicts for each measurement, m, three per measurement in the
    /// order of `residuals`: the measured displacement is `predicted + residuals` (with fitted
    /// offsets, the prediction includes its point's offset).
    pub predicted: DVector<f64>,
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
    /// The compliances held at their bound `h_j = 0` by [`Observations::nonnegative`]
    /// (the active constraints); `None` for an unbounded fit.
    pub active_bounds: Option<[bool; 6]>,
    /// Why the active-set steps of [`Observations::nonnegative`] stopped: converged (the
    /// bounded minimum) or at their limit ([`nonnegative::warning`]); `None` for an unbounded
    /// fit.
    pub nonnegative_stop: Option<stiffid_core::common::stop::Stop>,
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

/// Identifies the joint compliance and stiffness by linear least squares (Eq. 13-14), with
/// standard errors and 95% confidence intervals (module docs), in bounded memory: `InBlocks`
/// over all the measurements, then their residuals (`residuals`). The result is the same
/// whatever the number of threads, and equal to [`Observations::least_squares`] to rounding
/// (the same QR, in another order). The other fits ([`Observations::robust`],
/// [`Observations::nonnegative`]) and cross-validation need the whole [`Observations`].
///
/// # Examples
/// Measurements simulated without noise on the paper's setup (8 seeded postures, the setup's
/// nominal stiffness) give that stiffness back.
/// ```
/// use rand::SeedableRng;
/// use stiffid_core::observation::Measurement;
/// use stiffid_core::robot::ik::random_posture;
/// use stiffid_core::observation::stiffness::rope_displacements;
/// let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165")?;
/// let k = setup.try_nominal_stiffness("this example")?;
/// let mut measurements = Vec::new();
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
/// for posture in 0..8 {
///     let q = random_posture(setup.robot(), &mut rng);
///     let frames = setup.robot().frames(&q);
///     let wrench = setup.rope_wrench(&frames);
///     for (point, d) in rope_displacements(&setup, &frames, k).into_iter().enumerate() {
///         let displacement = d;
///         measurements.push(Measurement { posture, point, q, e: Default::default(), wrench, displacement });
///     }
/// }
/// let id = stiffid_identify::least_squares(setup.arm(), &measurements)?;
/// assert!((0..6).all(|j| (id.stiffness[j] / k[j] - 1.0).abs() < 1e-9));
/// # Ok::<(), stiffid_core::Error>(())
/// ```
///
/// # Errors
/// Those of `InBlocks::push` and `InBlocks::solve` (the blocks of rows).
pub fn least_squares(arm: &Arm, measurements: &[Measurement]) -> Result<Identification> {
    let mut blocks = InBlocks::new(arm);
    blocks.push(measurements)?;
    let solved = blocks.solve()?;
    let residuals = residuals(arm, &solved.solution.h, measurements);
    Ok(solved.finish(residuals))
}

/// Measurements per block of `InBlocks`: 3072 rows of `Psi`, 147 kB.
pub(crate) const BLOCK: usize = 1024;

/// Least squares over measurements given a part at a time (a file read in chunks), in bounded
/// memory: the rows of `Psi` are made and reduced by QR in blocks of [`BLOCK`] measurements
/// ([`Reduced`]), in parallel, and merged in block order. Blocks are the measurements
/// `BLOCK k .. BLOCK (k + 1)` whatever the parts, so the result does not depend on how the
/// measurements are cut into parts, nor on the number of threads. Memory: one block, and what
/// [`Check`] keeps per posture.
pub(crate) struct InBlocks<'a> {
    arm: &'a Arm,
    check: Check,
    /// The measurements of the block being filled.
    pending: Vec<Measurement>,
    reduced: Reduced,
    deflected: bool,
}

/// The solution of `InBlocks`, before the residuals.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Solved {
    /// The compliance, `(Psi^T Psi)^-1` and `cond_2(Psi)`.
    pub solution: Solution,
    /// The number of distinct postures.
    pub postures: usize,
    /// The number of measurements.
    pub measurements: usize,
}

impl<'a> InBlocks<'a> {
    /// No measurements yet.
    pub(crate) fn new(arm: &'a Arm) -> Self {
        Self {
            arm,
            check: Check::default(),
            pending: Vec::with_capacity(BLOCK),
            reduced: Reduced::default(),
            deflected: false,
        }
    }

    /// Checks the next measurements ([`Check::push`]) and reduces every block they complete.
    ///
    /// # Errors
    /// Those of [`stiffid_core::observation::check`], numbering measurements over all parts.
    pub(crate) fn push(&mut self, measurements: &[Measurement]) -> Result<()> {
        self.check.push(self.arm, measurements, None)?;
        self.deflected |= measurements
            .iter()
            .any(|m| m.displacement.iter().any(|d| *d != 0.0));
        let mut rest = measurements;
        if !self.pending.is_empty() {
            let n = (BLOCK - self.pending.len()).min(rest.len());
            self.pending.extend_from_slice(&rest[..n]);
            rest = &rest[n..];
            if self.pending.len() == BLOCK {
                let pending = std::mem::take(&mut self.pending);
                self.reduce(&pending);
                self.pending = pending;
                self.pending.clear();
            }
        }
        let whole = rest.len() / BLOCK * BLOCK;
        self.reduce(&rest[..whole]);
        self.pending.extend_from_slice(&rest[whole..]);
        Ok(())
    }

    /// Reduces whole blocks (the last one may be partial), in parallel, merged in order.
    fn reduce(&mut self, measurements: &[Measurement]) {
        let blocks: Vec<Reduced> = measurements
            .par_chunks(BLOCK)
            .map(|block| {
                let (psi, delta) = rows(self.arm, block);
                let mut reduced = Reduced::default();
                reduced.push(&psi, &delta);
                reduced
            })
            .collect();
        for b in &blocks {
            self.reduced.merge(b);
        }
    }

    /// The least-squares solution of all the measurements pushed.
    ///
    /// # Errors
    /// [`Error::InvalidField`] when every displacement is zero; those of [`Reduced::try_solve`]
    /// ([`Error::TooFewRows`], [`Error::Unidentifiable`], [`Error::NotFinite`]).
    pub(crate) fn solve(&mut self) -> Result<Solved> {
        if !self.arm.model().is_drives_only() {
            return Err(six_parameters_only());
        }
        let pending = std::mem::take(&mut self.pending);
        self.reduce(&pending);
        if !self.deflected {
            check_deflection(std::iter::empty())?;
        }
        Ok(Solved {
            solution: self.reduced.try_solve()?,
            postures: self.check.postures(),
            measurements: self.reduced.rows() / 3,
        })
    }

    /// The axis angles of `posture` (those of its first measurement), if it was pushed.
    pub(crate) fn angles(&self, posture: usize) -> Option<&Vector6<f64>> {
        self.check.angles(posture)
    }

    /// The external axis values of `posture` (those of its first measurement), if it was
    /// pushed.
    pub(crate) fn external(
        &self,
        posture: usize,
    ) -> Option<&stiffid_core::robot::external::ExternalValues> {
        self.check.external(posture)
    }
}

impl Solved {
    /// The identification with `residuals` and `predicted` (`delta - Psi h` and `Psi h` of every
    /// measurement, `residuals`).
    ///
    /// # Panics
    /// Unless there are three residuals and three predictions per measurement.
    pub(crate) fn finish(self, (residuals, predicted): (Vec<f64>, Vec<f64>)) -> Identification {
        assert_eq!(residuals.len(), 3 * self.measurements);
        assert_eq!(predicted.len(), 3 * self.measurements);
        finish(
            self.postures,
            self.solution.h,
            (DVector::from_vec(residuals), DVector::from_vec(predicted)),
            self.solution.unit_covariance,
            6,
            self.solution.cond,
            None,
        )
    }
}

/// `delta - Psi h` and `Psi h` of some measurements (checked), three per measurement in the row
/// order of [`stiffid_core::observation`], computed in parallel blocks of [`BLOCK`] (the same values
/// whatever the blocks).
pub(crate) fn residuals(
    arm: &Arm,
    h: &Vector6<f64>,
    measurements: &[Measurement],
) -> (Vec<f64>, Vec<f64>) {
    let blocks: Vec<(DVector<f64>, DVector<f64>)> = measurements
        .par_chunks(BLOCK)
        .map(|block| {
            let (psi, delta) = rows(arm, block);
            let predicted = psi * h;
            (delta - &predicted, predicted)
        })
        .collect();
    let mut out = (Vec::new(), Vec::new());
    for (r, p) in blocks {
        out.0.extend_from_slice(r.as_slice());
        out.1.extend_from_slice(p.as_slice());
    }
    out
}

/// `Psi` and `delta` of some measurements ([`assemble`]).
fn rows(arm: &Arm, measurements: &[Measurement]) -> (DMatrix<f64>, DVector<f64>) {
    let n = 3 * measurements.len();
    let (mut psi, mut delta) = (DMatrix::zeros(n, 6), DVector::zeros(n));
    assemble(arm, measurements, &mut psi, &mut delta);
    (psi, delta)
}

/// The error of a six-parameter fit asked for a model with virtual springs.
fn six_parameters_only() -> Error {
    Error::InvalidField {
        field: "model".into(),
        message: "this fit takes the six drive springs alone; fit a model with virtual springs with identify::svd".into(),
    }
}

/// [`Error::InvalidField`] when every measured displacement is zero: nothing deflected.
fn check_deflection<'a>(mut displacements: impl Iterator<Item = &'a f64>) -> Result<()> {
    match displacements.any(|d| *d != 0.0) {
        true => Ok(()),
        false => Err(Error::InvalidField {
            field: "displacement".into(),
            message: "every measured displacement is zero: nothing to identify (check the displacement columns)".into(),
        }),
    }
}

/// The fits of the observations (Eq. 13-14): least squares, bounded, robust. Each checks that
/// something deflected and factors `Psi` by QR ([`Factor`]). The observation matrix is the
/// core's ([`Observations`]); its fits are the identification's.
pub trait Identify {
    /// The least-squares compliance and its statistics (the implementation for [`Observations`]).
    ///
    /// # Errors
    /// Too few rows, unidentifiable joints, non-finite entries.
    fn least_squares(&self) -> Result<Identification>;
    /// The least-squares compliance with the bounds `h >= 0`.
    ///
    /// # Errors
    /// Those of [`Identify::least_squares`].
    fn nonnegative(&self) -> Result<Identification>;
    /// Robust identification by iteratively reweighted least squares with `loss`.
    ///
    /// # Errors
    /// Those of [`Identify::least_squares`]; rank deficiency of the weighted rows.
    fn robust(&self, loss: Loss) -> Result<Identification>;
}

impl Identify for Observations {
    /// The least-squares compliance `h = argmin |Psi h - delta|` (Eq. 13-14, by QR) and its
    /// statistics (module docs).
    ///
    /// # Errors
    /// [`Error::TooFewRows`] for fewer than six rows; [`Error::Unidentifiable`] naming the joints
    /// the data cannot identify and why (no measurement loads them, or their columns of `Psi` are
    /// dependent); [`Error::NotFinite`] for non-finite entries.
    fn least_squares(&self) -> Result<Identification> {
        if self.psi.ncols() != 6 {
            return Err(six_parameters_only());
        }
        check_deflection(self.delta.iter())?;
        let factor = Factor::try_new(self.psi.clone())?;
        let h = factor.solve(&self.delta);
        Ok(finish(
            self.postures,
            h,
            split(self, &h),
            factor.unit_covariance(),
            6,
            factor.cond(),
            None,
        ))
    }

    /// The least-squares compliance with the bounds `h >= 0` (a joint cannot be softer than
    /// infinitely stiff): the Lawson-Hanson active-set method ([`nonnegative`]) on the QR-reduced
    /// problem `min |R h - c|`, `c` the first six entries of `Q^T delta`. Equal to
    /// [`Observations::least_squares`] when that is already non-negative. Joints at their bound have
    /// `h_j = 0` (`k_j = inf`, not physical: the data cannot tell them from rigid) and are listed
    /// in [`Identification::active_bounds`]; the uncertainty is that of the free compliances
    /// with the bound ones fixed, with `m - free` degrees of freedom.
    ///
    /// # Errors
    /// Those of [`Observations::least_squares`].
    fn nonnegative(&self) -> Result<Identification> {
        if self.psi.ncols() != 6 {
            return Err(six_parameters_only());
        }
        check_deflection(self.delta.iter())?;
        let factor = Factor::try_new(self.psi.clone())?;
        let fit = nonnegative::solve(factor.r(), &factor.project(&self.delta));
        let free = fit.active.iter().filter(|a| !**a).count();
        let mut id = finish(
            self.postures,
            fit.h,
            split(self, &fit.h),
            nonnegative::unit_covariance(factor.r(), &fit.active),
            free,
            factor.cond(),
            None,
        );
        id.active_bounds = Some(fit.active);
        id.nonnegative_stop = Some(fit.stop);
        Ok(id)
    }

    /// Robust identification: iteratively reweighted least squares with `loss` ([`robust`]),
    /// starting from the least-squares fit. The uncertainty treats the final weights as known:
    /// `s^2 = sum w_i r_i^2 / (m_w - 6)` with `m_w` the rows of non-zero weight, and
    /// `Cov(h) = s^2 (Psi^T W Psi)^-1`. `cond_psi` is that of the unweighted `Psi`.
    ///
    /// # Errors
    /// Those of [`Observations::least_squares`]; [`Error::Unidentifiable`] also when the rows left with
    /// weight make `Psi` rank deficient.
    fn robust(&self, loss: Loss) -> Result<Identification> {
        if self.psi.ncols() != 6 {
            return Err(six_parameters_only());
        }
        check_deflection(self.delta.iter())?;
        let factor = Factor::try_new(self.psi.clone())?;
        let start = DVector::from_column_slice(factor.solve(&self.delta).as_slice());
        let solve = |a: DMatrix<f64>, b: &DVector<f64>| {
            let f = Factor::try_new(a)?;
            Ok((DVector::from_column_slice(f.solve(b).as_slice()), f))
        };
        let (h, weighted, fit) = robust::fit(&self.psi, &self.delta, start, loss, &solve)?;
        let h = Vector6::from_column_slice(h.as_slice());
        Ok(finish(
            self.postures,
            h,
            split(self, &h),
            weighted.unit_covariance(),
            6,
            factor.cond(),
            Some(fit),
        ))
    }
}

/// The residuals `delta - Psi h` and the predictions `Psi h` of the compliance `h`.
fn split(obs: &Observations, h: &Vector6<f64>) -> (DVector<f64>, DVector<f64>) {
    let predicted = &obs.psi * h;
    (&obs.delta - &predicted, predicted)
}

/// The statistics of compliance `h` with residuals `delta - Psi h` and predictions `Psi h`,
/// `(Psi^T W Psi)^-1 = unit_covariance` and `free` estimated compliances.
fn finish(
    postures: usize,
    h: Vector6<f64>,
    (residuals, predicted): (DVector<f64>, DVector<f64>),
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
        predicted,
        cond_psi,
        rows,
        postures,
        robust,
        unit_covariance,
        active_bounds: None,
        nonnegative_stop: None,
    }
}

#[cfg(test)]
mod nonnegative_tests;

#[cfg(test)]
mod robust_tests;
