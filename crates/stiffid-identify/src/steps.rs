//! Load steps: displacements from raw tracker readings taken at several loads per posture, and how
//! each posture's deflection follows the load.
//!
//! A campaign with load steps reads every measuring point of a posture unloaded first, then under
//! rising loads and, optionally, falling ones back to zero ([`stiffid_core::io::readings`] with a
//! `load_step` or `load_n` column). [`LoadSteps::new`] takes each reading relative to the first
//! (unloaded) reading of the same posture and point: the displacement is the position minus that
//! reference position, the wrench the wrench minus the reference's. Identification uses every
//! loaded reading ([`LoadSteps::loaded`]); an optional offset per posture and measuring point can
//! be fitted beside the compliances ([`crate::offsets`]).
//!
//! ## Linearity, zero-load offset and hysteresis ([`linearity`])
//! Per posture and measuring point, the rising loaded readings give a straight line per coordinate
//! `d(F) = a F + b` (load `F` in N: the file's `load_n`, or the magnitude of the wrench's force
//! change for `load_step`). Per posture: the slope `sqrt(mean_p |a_p|^2)` and the zero-load offset
//! `sqrt(mean_p |b_p|^2)` over its measuring points `p`, `R^2 = 1 - SS_res / SS_tot` (sums over
//! points and coordinates, `SS_tot` about each coordinate's mean), and the hysteresis, the RMS
//! length of the falling reading minus the rising one at the same step (at zero, minus the
//! reference).
//!
//! Each is tested against the setup's tracker noise `sigma^2` per coordinate of one reading. The
//! reference reading's error is common to every step of a point: it moves the intercept, not the
//! slope nor the residuals. With Gaussian noise and a linear, offset-free, hysteresis-free robot:
//! `SS_res / sigma^2 ~ chi2(sum_p 3 (m_p - 2))` (`m_p` rising readings of point `p`);
//! `sum_p |b_p|^2 / (sigma^2 (1 + 1/m_p + Fbar_p^2 / S_FF,p)) ~ chi2(3 P)` (the `1` is the
//! reference's error); `sum |d_fall - d_rise|^2 / (2 sigma^2) ~ chi2(3 pairs)`. A p-value below
//! [`crate::adequacy::SIGNIFICANCE`] flags the posture: the effect exceeds what the
//! tracker noise explains.
//!
//! ## The shared unloaded reading ([`generalised`])
//! The loaded readings of a point are each taken relative to the same unloaded reading, so their
//! errors are correlated: with `m` loaded readings `d_k = x_k - x_0` of one point and independent
//! reading errors of variance `sigma^2` per coordinate, `Cov(d) = sigma^2 (I + J)` per coordinate
//! (`J` the `m x m` matrix of ones). Least squares on the displacements as if independent gives
//! intervals that ignore it (too narrow for the compliances the common error moves). The fit is
//! instead generalised least squares (Aitken 1935; Seber & Lee, *Linear Regression Analysis*,
//! 2003, sec. 3.10): the rows of each point and coordinate are whitened by
//! `W = (I + J)^(-1/2) = I + a J`, `a = (1/sqrt(1 + m) - 1) / m` (the eigenvalues of `I + J` are
//! `1 + m` along the ones and `1` across them), so that `Cov(W d) = sigma^2 I`, and the whitened
//! system is solved by QR as usual. The residual variance and the model check then refer to one
//! reading's `sigma^2`; the stored residuals are the displacements' (unwhitened).
//!
//! The design side of the steps (`[loading] steps_n`: what they are worth in the criteria and
//! the Monte Carlo) is `stiffid_design`'s.

use crate::adequacy::SIGNIFICANCE;
use crate::Identification;
use crate::Method;
use nalgebra::{DVector, RowDVector, Vector3};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::collections::HashMap;
use stiffid_core::io::readings::{Load, Readings};
use stiffid_core::observation::deflection::Frame;
use stiffid_core::observation::frames::{self, DisplacementFrame};
use stiffid_core::observation::{Measurement, Observations};
use stiffid_core::{Error, Result, Setup};

/// The readings of a load-step campaign, each relative to its point's unloaded reference.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadSteps {
    /// Every reading but the references, in file order: the position and wrench minus the
    /// reference's (SI), in the file's frames until [`LoadSteps::to_base_frame`].
    pub measurements: Vec<Measurement>,
    /// The step of each measurement.
    pub steps: Vec<Load>,
    /// The load of each measurement, N: its `load_n`, or with `load_step` the magnitude of its
    /// force change from the reference.
    pub loads_n: Vec<f64>,
    /// Whether each measurement is on the falling branch (below an earlier step of its point).
    pub falling: Vec<bool>,
    /// The line of each measurement (1-based).
    pub lines: Vec<u64>,
    /// The posture labels: `labels[m.posture]`.
    pub labels: Vec<String>,
    /// The frame of the wrenches.
    pub wrench_frame: Frame,
    /// The frame of the displacements.
    pub displacement_frame: DisplacementFrame,
}

impl LoadSteps {
    /// The readings relative to their references (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`load_step`) when the readings have no load steps, or when a
    /// point's first reading in a posture is loaded (naming its line and the posture): each
    /// point's readings start with the unloaded one.
    pub fn new(readings: &Readings) -> Result<Self> {
        if !readings.has_loads {
            return Err(Error::InvalidField {
                field: "load_step".into(),
                message: "the readings have no load steps (a load_step or load_n column and the force columns)".into(),
            });
        }
        let mut references = HashMap::new();
        let mut top: HashMap<(usize, usize), f64> = HashMap::new();
        let mut out = LoadSteps {
            measurements: Vec::new(),
            steps: Vec::new(),
            loads_n: Vec::new(),
            falling: Vec::new(),
            lines: Vec::new(),
            labels: readings.labels.clone(),
            wrench_frame: readings.wrench_frame,
            displacement_frame: readings.frame,
        };
        for (r, &line) in readings.readings.iter().zip(&readings.lines) {
            let key = (r.posture, r.point);
            let load = r.load.unwrap_or(Load::Step(0));
            let Some(reference) = references.get(&key) else {
                if !load.is_zero() {
                    return Err(loaded_first(readings, r.posture, r.point, line));
                }
                references.insert(key, r);
                continue;
            };
            let level = load.level();
            let highest = top.entry(key).or_insert(0.0);
            out.falling.push(level < *highest);
            *highest = highest.max(level);
            let wrench = r.wrench - reference.wrench;
            if let Load::Newtons(n) = load {
                check_force(n, wrench.fixed_rows::<3>(0).norm(), line)?;
            }
            out.loads_n.push(match load {
                Load::Newtons(n) => n,
                Load::Step(_) => wrench.fixed_rows::<3>(0).norm(),
            });
            out.measurements.push(Measurement {
                posture: r.posture,
                point: r.point,
                q: r.q,
                e: r.e,
                wrench,
                displacement: r.position - reference.position,
            });
            out.steps.push(load);
            out.lines.push(line);
        }
        Ok(out)
    }

    /// Turns the wrenches and displacements into the base frame ([`frames::file_to_base`]).
    ///
    /// # Errors
    /// Those of [`frames::file_to_base`].
    pub fn to_base_frame(&mut self, setup: &Setup) -> Result<()> {
        frames::file_to_base(
            setup,
            &mut self.measurements,
            &mut self.wrench_frame,
            &mut self.displacement_frame,
        )
    }

    /// The indices of the loaded measurements (step not zero): what identification uses.
    pub fn loaded(&self) -> Vec<usize> {
        (0..self.steps.len())
            .filter(|&i| !self.steps[i].is_zero())
            .collect()
    }
}

/// Generalised least squares of displacements that share their point's unloaded reading
/// (module docs): `method` on `obs` whitened per posture and measuring point of `measurements`
/// (the measurements of `obs`, in its row order), with the residuals and their RMS of `obs`
/// itself.
///
/// # Errors
/// Those of `method`.
pub fn generalised(
    obs: &Observations,
    measurements: &[Measurement],
    method: Method,
) -> Result<Identification> {
    let mut white = obs.clone();
    let mut groups: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (i, m) in measurements.iter().enumerate() {
        groups.entry((m.posture, m.point)).or_default().push(i);
    }
    for members in groups.values() {
        let m = members.len() as f64;
        let a = ((1.0 + m).sqrt().recip() - 1.0) / m;
        for c in 0..3 {
            let rows = || members.iter().map(move |&i| 3 * i + c);
            let psi_sum = rows().fold(RowDVector::zeros(obs.psi.ncols()), |sum, r| {
                sum + obs.psi.row(r)
            });
            let delta_sum: f64 = rows().map(|r| obs.delta[r]).sum();
            for r in rows() {
                white.psi.set_row(r, &(obs.psi.row(r) + &psi_sum * a));
                white.delta[r] = obs.delta[r] + a * delta_sum;
            }
        }
    }
    let mut id = method.fit(&white)?;
    let h = DVector::from_column_slice(id.compliance.as_slice());
    id.predicted = &obs.psi * h;
    id.residuals = &obs.delta - &id.predicted;
    id.residual_rms = (id.residuals.norm_squared() / id.residuals.len() as f64).sqrt();
    Ok(id)
}

/// How far, as a factor either way, a reading's force change from its reference may lie from
/// its nominal load `load_n`: beyond it the file contradicts itself (a force in kN, a load in
/// kg).
const FORCE_FACTOR: f64 = 10.0;

/// Nothing when the force change `force_n` (N) of a reading under the nominal load `load_n` (N,
/// at line `line`) agrees with it within [`FORCE_FACTOR`] either way, or the load is 0.
fn check_force(load_n: f64, force_n: f64, line: u64) -> Result<()> {
    if load_n == 0.0 || (load_n / FORCE_FACTOR..=load_n * FORCE_FACTOR).contains(&force_n) {
        return Ok(());
    }
    Err(Error::InvalidField {
        field: "load_n".into(),
        message: format!(
            "line {line}: a load of {} N, but the force change from the point's unloaded reading \
             (fx_n, fy_n, fz_n) is {} N: the file contradicts itself (forces in kN, a load in \
             kg?); give both in N",
            stiffid_core::common::words::number(load_n),
            stiffid_core::common::words::number(force_n)
        ),
    })
}

fn loaded_first(readings: &Readings, posture: usize, point: usize, line: u64) -> Error {
    Error::InvalidField {
        field: "load_step".into(),
        message: format!(
            "line {line}: the first reading of point {} in posture '{}' is loaded: each point's readings start with the unloaded one (load 0), the reference of its displacements",
            point + 1,
            stiffid_core::common::limits::short(&readings.labels[posture])
        ),
    }
}

/// How one posture's deflection follows the load (module docs); lengths in m, loads in N.
#[derive(Debug, Clone, PartialEq)]
pub struct Linearity {
    /// The posture (0-based, [`LoadSteps::labels`]).
    pub posture: usize,
    /// Distinct non-zero loads on the rising branch.
    pub levels: usize,
    /// Readings of the posture, references excepted.
    pub readings: usize,
    /// `sqrt(mean_p |a_p|^2)`, m/N; `None` with fewer than two non-zero loads at a point.
    pub slope_m_per_n: Option<f64>,
    /// `sqrt(mean_p |b_p|^2)`, m: the zero-load offset; `None` with fewer than two non-zero loads.
    pub offset_m: Option<f64>,
    /// `R^2` of the straight lines; `None` with fewer than three rising readings per point.
    pub r_squared: Option<f64>,
    /// RMS length of falling minus rising readings at the same step, m; `None` without falling
    /// readings.
    pub hysteresis_m: Option<f64>,
    /// P-value of the offset against the tracker noise; `None` as `offset_m`.
    pub offset_p_value: Option<f64>,
    /// P-value of the residuals about the lines against the tracker noise; `None` without
    /// degrees of freedom.
    pub linearity_p_value: Option<f64>,
    /// P-value of the hysteresis against the tracker noise; `None` as `hysteresis_m`.
    pub hysteresis_p_value: Option<f64>,
}

impl Linearity {
    /// Whether the zero-load offset exceeds what the tracker noise explains.
    pub fn offset_flagged(&self) -> bool {
        self.offset_p_value.is_some_and(|p| p < SIGNIFICANCE)
    }

    /// Whether the deflection departs from a straight line more than the tracker noise explains.
    pub fn nonlinear(&self) -> bool {
        self.linearity_p_value.is_some_and(|p| p < SIGNIFICANCE)
    }

    /// Whether the hysteresis exceeds what the tracker noise explains.
    pub fn hysteresis_flagged(&self) -> bool {
        self.hysteresis_p_value.is_some_and(|p| p < SIGNIFICANCE)
    }
}

/// The straight line of one measuring point's rising readings, per coordinate.
#[derive(Default)]
struct Line {
    slope: Vector3<f64>,
    intercept: Vector3<f64>,
    ss_res: f64,
    ss_tot: f64,
    count: usize,
    /// `1 + 1/m + Fbar^2 / S_FF`: the intercept's variance per unit noise variance.
    intercept_variance: f64,
}

impl Line {
    /// The fit of `(load, displacement)` pairs; `None` with fewer than two distinct loads.
    fn fit(points: &[(f64, Vector3<f64>)]) -> Option<Line> {
        let m = points.len() as f64;
        let mean_f = points.iter().map(|p| p.0).sum::<f64>() / m;
        let mean_d = points.iter().map(|p| p.1).sum::<Vector3<f64>>() / m;
        let sff: f64 = points.iter().map(|p| (p.0 - mean_f).powi(2)).sum();
        if sff.is_nan() || sff <= 0.0 {
            return None;
        }
        let sfd: Vector3<f64> = points.iter().map(|p| (p.1 - mean_d) * (p.0 - mean_f)).sum();
        let slope = sfd / sff;
        let intercept = mean_d - slope * mean_f;
        let ss_res = points
            .iter()
            .map(|p| (p.1 - intercept - slope * p.0).norm_squared())
            .sum();
        let ss_tot = points.iter().map(|p| (p.1 - mean_d).norm_squared()).sum();
        Some(Line {
            slope,
            intercept,
            ss_res,
            ss_tot,
            count: points.len(),
            intercept_variance: 1.0 + 1.0 / m + mean_f * mean_f / sff,
        })
    }
}

/// The upper-tail p-value of `chi2` with `dof` degrees of freedom; `None` for zero degrees of
/// freedom or a non-positive variance.
fn p_value(chi2: f64, dof: usize) -> Option<f64> {
    match dof {
        0 => None,
        _ => ChiSquared::new(dof as f64).ok().map(|c| c.sf(chi2)),
    }
}

/// The linearity, zero-load offset and hysteresis of every posture (module docs), the
/// displacements in any one frame, tested against the noise variance `noise_variance` (m^2 per
/// coordinate of one reading).
pub fn linearity(steps: &LoadSteps, noise_variance: f64) -> Vec<Linearity> {
    let mut by_point: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (i, m) in steps.measurements.iter().enumerate() {
        by_point.entry((m.posture, m.point)).or_default().push(i);
    }
    let mut keys: Vec<(usize, usize)> = by_point.keys().copied().collect();
    keys.sort_unstable();
    let mut out: Vec<Linearity> = Vec::new();
    for posture in 0..steps.labels.len() {
        let points: Vec<&Vec<usize>> = keys
            .iter()
            .filter(|k| k.0 == posture)
            .map(|k| &by_point[k])
            .collect();
        if points.is_empty() {
            continue;
        }
        out.push(posture_linearity(steps, posture, &points, noise_variance));
    }
    out
}

fn posture_linearity(
    steps: &LoadSteps,
    posture: usize,
    points: &[&Vec<usize>],
    sigma2: f64,
) -> Linearity {
    let d = |i: usize| steps.measurements[i].displacement;
    let rising_loaded = |i: &&usize| !steps.falling[**i] && !steps.steps[**i].is_zero();
    let mut lines = Vec::new();
    let mut levels: Vec<f64> = Vec::new();
    let (mut pairs, mut hysteresis2) = (0usize, 0.0);
    for rows in points {
        let rising: Vec<(f64, Vector3<f64>)> = rows
            .iter()
            .filter(rising_loaded)
            .map(|&i| (steps.loads_n[i], d(i)))
            .collect();
        for &(f, _) in &rising {
            if !levels.contains(&f) {
                levels.push(f);
            }
        }
        lines.push(Line::fit(&rising));
        for &i in rows.iter().filter(|i| steps.falling[**i]) {
            let step = steps.steps[i];
            let rise = match step.is_zero() {
                true => Some(Vector3::zeros()),
                false => rows
                    .iter()
                    .find(|&&j| !steps.falling[j] && steps.steps[j] == step)
                    .map(|&j| d(j)),
            };
            if let Some(rise) = rise {
                pairs += 1;
                hysteresis2 += (d(i) - rise).norm_squared();
            }
        }
    }
    let fitted: Vec<&Line> = lines.iter().flatten().collect();
    let complete = fitted.len() == lines.len() && !fitted.is_empty();
    let p = fitted.len() as f64;
    let slope =
        complete.then(|| (fitted.iter().map(|l| l.slope.norm_squared()).sum::<f64>() / p).sqrt());
    let offset2: f64 = fitted.iter().map(|l| l.intercept.norm_squared()).sum();
    let offset_chi2: f64 = fitted
        .iter()
        .map(|l| l.intercept.norm_squared() / (sigma2 * l.intercept_variance))
        .sum();
    let ss_res: f64 = fitted.iter().map(|l| l.ss_res).sum();
    let ss_tot: f64 = fitted.iter().map(|l| l.ss_tot).sum();
    let residual_dof: usize = fitted.iter().map(|l| 3 * (l.count - 2)).sum();
    let valid = sigma2 > 0.0 && sigma2.is_finite();
    Linearity {
        posture,
        levels: levels.len(),
        readings: points.iter().map(|r| r.len()).sum(),
        slope_m_per_n: slope,
        offset_m: complete.then(|| (offset2 / p).sqrt()),
        r_squared: (complete && residual_dof > 0 && ss_tot > 0.0).then(|| 1.0 - ss_res / ss_tot),
        hysteresis_m: (pairs > 0).then(|| (hysteresis2 / pairs as f64).sqrt()),
        offset_p_value: (complete && valid)
            .then(|| p_value(offset_chi2, 3 * fitted.len()))
            .flatten(),
        linearity_p_value: (complete && valid)
            .then(|| p_value(ss_res / sigma2, residual_dof))
            .flatten(),
        hysteresis_p_value: (pairs > 0 && valid)
            .then(|| p_value(hysteresis2 / (2.0 * sigma2), 3 * pairs))
            .flatten(),
    }
}
