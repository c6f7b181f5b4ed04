//! The identify job's fast path, the six drive springs by QR: joint stiffness from measurements
//! (Zhang et al. 2021, Eq. 10-14), with its uncertainty, the model check against the tracker noise ([`Adequacy`]), the unit check against
//! the setup's nominal stiffness ([`UnitCheck`]), the physical-sign warnings and, if asked, the
//! cross-validation over postures ([`cross_validate`]).
//!
//! Plain least squares on a file is streamed: the file is read once in chunks and `Psi` reduced in
//! blocks ([`streamed`]), in bounded memory. Every other fit (robust, non-negative) and
//! cross-validation need the whole observation matrix ([`Observations`]).

use super::{Fit, Folds};
use crate::app::in_data;
use crate::app::measurements::{
    angle_warnings, arrays_origin, header_has_loads, read_file, Data, Loaded, Origin,
};
use stiffid_core::model::prediction::Calibration;
use stiffid_identify::prediction::calibrate;

use std::io::{BufReader, Read};
use stiffid_core::common::warning::{joint_list, Warning, WarningKind};
use stiffid_core::io::read_text;
use stiffid_core::observation::{Measurement, Observations};
use stiffid_core::setup::Noise;
use stiffid_core::{Result, Setup};
use stiffid_identify::adequacy::UNIT_FACTOR;
use stiffid_identify::offsets::{self, Offset};
use stiffid_identify::steps::{self, linearity, Linearity};
use stiffid_identify::{
    cross_validate, least_squares, streamed, Adequacy, CrossValidation, Identification, UnitCheck,
};

/// What to identify and how (checked together by [`super::Options`]).
pub(super) struct Request<'a, R> {
    /// The setup: robot, tool, tracker noise, nominal stiffness.
    pub setup: &'a Setup,
    /// The setup as the user named it ([`super::Request::setup_name`]).
    pub setup_name: String,
    /// The measurements.
    pub data: Data<R>,
    /// The fit.
    pub fit: Fit,
    /// Cross-validation over postures: `Some(folds)` (2 to the number of postures; the number of
    /// postures leaves one posture out), `None` for none.
    pub folds: Option<Folds>,
    /// Fit an offset per posture and measuring point beside the compliances
    /// ([`stiffid_identify::offsets`]; least squares only, without cross-validation; every point
    /// of every posture under at least two different loads).
    pub offsets: bool,
}

/// The tracker noise variance of one row of the fit, m^2, that the model check tests the
/// residuals against: a displacement's (a loaded minus an unloaded reading, twice a reading's);
/// `per_reading` (offsets fitted, or readings under load steps), one reading's: the unloaded
/// reading's error goes into the offset, or the fit is whitened for it
/// ([`stiffid_identify::steps::generalised`]; docs/model.md, the noise convention).
pub(crate) fn row_noise_variance(noise: &Noise, per_reading: bool) -> f64 {
    match per_reading {
        true => noise.reading_variance,
        false => noise.displacement_variance(),
    }
}

/// The noise floor of the prediction intervals' scale: the standard deviation of one
/// displacement coordinate from the tracker noise `noise`, m
/// ([`stiffid_core::model::prediction`]).
pub(crate) fn noise_floor(noise: &Noise) -> f64 {
    noise.displacement_sd()
}

/// What the identify job found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup as the user named it ([`super::Request::setup_name`]).
    pub setup: String,
    /// Where the setup's springs sit: in the drives or on the kinematic joints.
    pub springs: stiffid_core::Coordinates,
    /// The setup's tracker noise (SI).
    pub noise: Noise,
    /// The data's name (a file's, or `arrays`).
    pub data_name: String,
    /// The fit asked for.
    pub fit: Fit,
    /// The identification.
    pub identification: Identification,
    /// Where each measurement came from.
    pub origin: Origin,
    /// The residuals against the setup's tracker noise; `None` without degrees of freedom.
    pub adequacy: Option<Adequacy>,
    /// The unit check against the setup's nominal stiffness, when it fails; `None` when the
    /// stiffness is plausible or the setup has no nominal stiffness.
    pub unit: Option<UnitCheck>,
    /// The cross-validation, if asked.
    pub cross_validation: Option<CrossValidation>,
    /// With the cross-validation: what prediction intervals are built from.
    pub prediction: Option<Calibration>,
    /// Fold by fold: the postures left out and the joints (0-based) whose stiffness the removal
    /// moves by more than its standard error in the full fit (influential folds only).
    pub influential: Vec<(Vec<String>, Vec<usize>)>,
    /// With raw readings under load steps ([`stiffid_identify::steps`]): each posture's linearity, offset
    /// and hysteresis; `None` for displacements.
    pub load_steps: Option<Vec<Linearity>>,
    /// The offsets fitted beside the compliances, when asked ([`super::Options::offsets`]).
    pub offsets: Option<Vec<Offset>>,
    /// Results to look at before trusting them (signs, units).
    pub warnings: Vec<Warning>,
}

/// What identification from a file found besides the compliances.
struct Found {
    identification: Identification,
    origin: Origin,
    cross_validation: Option<(CrossValidation, Calibration)>,
    load_steps: Option<Vec<Linearity>>,
    offsets: Option<Vec<Offset>>,
}

/// Identifies the six drive springs.
///
/// # Errors
/// Errors about the data are [`Error::Input`] naming the data (a file's line and column, or the
/// measurement's number): those of [`streamed::least_squares`], [`stiffid_core::io::measurements::parse`],
/// [`Observations::from_measurements`] and of the fits; [`Error::InvalidField`] (`folds`) and
/// those of [`cross_validate`].
pub(super) fn run<R: Read + Send>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
        setup_name,
        data,
        fit: how,
        folds,
        offsets,
    } = request;
    let how_fit = How {
        fit: how,
        folds,
        offsets,
    };
    let (data_name, found) = match data {
        Data::File { name, reader } => {
            let found = from_file(setup, how_fit, &name, reader)?;
            (name, found)
        }
        Data::Measurements(measurements) => {
            let (id, cv, offsets) =
                fit(setup, how_fit, &measurements, false).map_err(|e| in_data("arrays", e))?;
            let found = Found {
                identification: id,
                origin: arrays_origin(&measurements),
                cross_validation: cv,
                load_steps: None,
                offsets,
            };
            ("arrays".to_string(), found)
        }
    };
    let Found {
        identification,
        origin,
        cross_validation,
        load_steps,
        offsets,
    } = found;
    let unit = setup
        .nominal_stiffness()
        .and_then(|k| identification.unit_check(k));
    let (cross_validation, prediction) = cross_validation.unzip();
    let (prediction, folds) = super::folds::carried(
        prediction,
        cross_validation.as_ref(),
        &origin,
        setup.model(),
    );
    let mut report = Report {
        setup: setup_name,
        springs: setup.springs(),
        noise: setup.noise().clone(),
        data_name,
        fit: how,
        adequacy: identification.adequacy(row_noise_variance(
            setup.noise(),
            offsets.is_some() || load_steps.is_some(),
        )),
        unit,
        influential: Vec::new(),
        identification,
        origin,
        cross_validation,
        prediction,
        load_steps,
        offsets,
        warnings: Vec::new(),
    };
    report.influential = influential(&report);
    report.warnings = warnings(&report);
    report.warnings.extend(folds);
    Ok(report)
}

/// How to fit: the fit, the folds, the offsets.
#[derive(Clone, Copy)]
struct How {
    fit: Fit,
    folds: Option<Folds>,
    offsets: bool,
}

impl How {
    /// Whether the fit runs in blocks, without the whole `Psi`.
    fn in_blocks(self) -> bool {
        self.fit == Fit::LeastSquares && self.folds.is_none() && !self.offsets
    }
}

/// The identification of a measurement file: streamed for plain least squares without
/// cross-validation nor offsets, else parsed whole; a readings file with load steps
/// ([`stiffid_core::io::readings::has_load_column`]) through [`from_readings`].
fn from_file<R: Read + Send>(setup: &Setup, how: How, name: &str, reader: R) -> Result<Found> {
    let mut source = BufReader::with_capacity(1 << 20, reader);
    if header_has_loads(&mut source) {
        let text = read_text(name, source)?;
        return from_readings(setup, how, name, &text);
    }
    if how.in_blocks() {
        let (id, rows) = streamed::least_squares(setup, source).map_err(|e| in_data(name, e))?;
        let columns = [
            rows.layout.force_columns(),
            rows.layout.displacement_columns(),
        ];
        let origin = Origin::new(
            rows.labels,
            rows.postures,
            rows.points,
            (rows.angles, rows.external),
            Some(rows.lines),
            columns,
        );
        return Ok(Found {
            identification: id,
            origin,
            cross_validation: None,
            load_steps: None,
            offsets: None,
        });
    }
    let (file, origin) = read_file(setup, name, source)?;
    let (id, cv, offsets) =
        fit(setup, how, &file.measurements, false).map_err(|e| in_data(name, file.explain(e)))?;
    Ok(Found {
        identification: id,
        origin,
        cross_validation: cv,
        load_steps: None,
        offsets,
    })
}

/// The identification of raw readings under load steps ([`Loaded`](crate::app::measurements::Loaded)), and each posture's
/// linearity.
fn from_readings(setup: &Setup, how: How, name: &str, text: &str) -> Result<Found> {
    let data = Loaded::read(setup, name, text)?;
    let (id, cv, offsets) =
        fit(setup, how, &data.measurements, true).map_err(|e| data.explain(name, e))?;
    data.check_scale(setup, name)?;
    Ok(Found {
        identification: id,
        load_steps: Some(linearity(&data.steps, setup.noise().reading_variance)),
        origin: data.origin,
        cross_validation: cv,
        offsets,
    })
}

/// The fit of measurements in the base frame, the cross-validation (and the calibration of its
/// prediction intervals) and the offsets if asked. Plain least squares without cross-validation
/// nor offsets runs in blocks ([`least_squares`]), without the whole `Psi`. With `shared`, the
/// loaded readings of each point share its unloaded reading: the fit is generalised least
/// squares ([`steps::generalised`]; offsets absorb the shared error, their fit stays ordinary).
#[allow(clippy::type_complexity)]
fn fit(
    setup: &Setup,
    how: How,
    measurements: &[Measurement],
    shared: bool,
) -> Result<(
    Identification,
    Option<(CrossValidation, Calibration)>,
    Option<Vec<Offset>>,
)> {
    if how.offsets {
        let (id, offsets) = offsets::least_squares(setup.arm(), measurements)?;
        return Ok((id, None, Some(offsets)));
    }
    if how.in_blocks() && !shared {
        return Ok((least_squares(setup.arm(), measurements)?, None, None));
    }
    let obs = Observations::from_measurements(setup.arm(), measurements)?;
    // Every fold is fitted as the full fit.
    let method = how.fit.method();
    let id = match shared {
        true => steps::generalised(&obs, measurements, method)?,
        false => method.fit(&obs)?,
    };
    let cross_validation = match how.folds {
        None => None,
        Some(folds) => {
            let cv = cross_validate(&obs, &id, folds.count(obs.postures), method)?;
            let calibration = calibrate(&obs, &cv, noise_floor(setup.noise()));
            Some((cv, calibration))
        }
    };
    Ok((id, cross_validation, None))
}

/// The postures of each influential fold and the joints (0-based) it moves.
fn influential(report: &Report) -> Vec<(Vec<String>, Vec<usize>)> {
    let Some(cv) = &report.cross_validation else {
        return Vec::new();
    };
    cv.folds
        .iter()
        .filter(|f| f.influential.iter().any(|i| *i))
        .map(|f| {
            let joints = (0..f.influential.len())
                .filter(|&j| f.influential[j])
                .collect();
            (report.origin.labels_of(&f.postures), joints)
        })
        .collect()
}

/// The warnings: results that are not physical, a likely unit mix-up.
fn warnings(report: &Report) -> Vec<Warning> {
    let id = &report.identification;
    let physical = id.physical();
    // The likely cause first: radians under `_deg` names make every other result nonsense.
    let mut out = angle_warnings(&report.data_name, &report.origin);
    out.extend(id.robust.as_ref().and_then(|r| r.warning()));
    let n = id.compliance.len();
    out.extend((id.nonnegative_stop).and_then(|s| stiffid_identify::nonnegative::warning(s, n)));
    let negative: Vec<usize> = (0..n).filter(|&j| id.compliance[j] < 0.0).collect();
    let rigid: Vec<usize> = (0..n)
        .filter(|&j| !physical[j] && id.compliance[j] >= 0.0)
        .collect();
    match negative.len() {
        0 => {}
        k if k == n => out.push(Warning::new(
            WarningKind::AllNegative,
            "every compliance is negative (not physical): the displacements or the forces probably have the wrong sign (the wrench is the force on the robot; the displacement is loaded minus unloaded)",
        )),
        _ => out.push(Warning::new(
            WarningKind::Negative,
            format!(
                "{}: negative compliance, not physical: the model or the data are wrong there; a non-negative fit bounds the compliances at 0",
                joint_list(negative)
            ),
        )),
    }
    if !rigid.is_empty() {
        out.push(Warning::new(
            WarningKind::Rigid,
            format!(
                "{}: zero or non-finite compliance (infinitely stiff), not physical: the data cannot tell the joint from a rigid one",
                joint_list(rigid)
            ),
        ));
    }
    if let Some(unit) = &report.unit {
        out.push(Warning::new(WarningKind::Units, unit_message(report, unit)));
    }
    out.extend(load_step_warnings(report));
    out
}

/// The warnings of load steps: postures whose offset, linearity or hysteresis exceeds the
/// tracker noise.
fn load_step_warnings(report: &Report) -> Vec<Warning> {
    let Some(steps) = &report.load_steps else {
        return Vec::new();
    };
    let offset_hint = match report.offsets {
        Some(_) => "fitted beside the compliances",
        None => "backlash or friction; fit it with offsets beside the compliances",
    };
    type Flag = fn(&Linearity) -> bool;
    let checks: [(Flag, String); 3] = [
        (
            Linearity::offset_flagged,
            format!("a zero-load offset beyond the tracker noise ({offset_hint})"),
        ),
        (
            Linearity::nonlinear,
            "a deflection that departs from a straight line in the load beyond the tracker noise"
                .into(),
        ),
        (
            Linearity::hysteresis_flagged,
            "a hysteresis between rising and falling loads beyond the tracker noise".into(),
        ),
    ];
    checks
        .into_iter()
        .filter_map(|(flagged, what)| {
            let labels: Vec<String> = steps
                .iter()
                .filter(|l| flagged(l))
                .map(|l| {
                    format!(
                        "'{}'",
                        stiffid_core::common::limits::short(report.origin.labels.get(l.posture))
                    )
                })
                .collect();
            (!labels.is_empty()).then(|| {
                let noun = match labels.len() {
                    1 => "posture",
                    _ => "postures",
                };
                Warning::new(
                    WarningKind::LoadSteps,
                    format!("{}: {noun} {}: {what}", report.data_name, labels.join(", ")),
                )
            })
        })
        .collect()
}

/// The unit warning, naming the columns.
fn unit_message(report: &Report, unit: &UnitCheck) -> String {
    let [forces, displacements] = &report.origin.columns;
    let cause = match unit.stiffer {
        true => format!(
            "displacements ({displacements}) in m instead of mm, or forces ({forces}) in mN instead of N"
        ),
        false => format!(
            "forces ({forces}) in kN instead of N, or displacements ({displacements}) in um instead of mm"
        ),
    };
    let angles = match report.origin.lines {
        Some(_) => "q1_deg..q6_deg",
        None => "q_deg",
    };
    format!(
        "the identified stiffness is {} times the setup's nominal on {} (more than {UNIT_FACTOR}x off): a unit is the likely cause: {cause}; the axis angles must be in degrees ({angles})",
        match unit.typical_ratio >= 1.0 {
            true => format!("about {:.3e}", unit.typical_ratio),
            false => format!("about 1/{:.3e}", 1.0 / unit.typical_ratio),
        },
        joint_list(unit.joints.iter().copied())
    )
}
