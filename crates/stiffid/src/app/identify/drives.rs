//! The identify job's fast path, the six drive springs by QR: joint stiffness from measurements
//! (Zhang et al. 2021, Eq. 10-14), with its uncertainty, the model check against the tracker noise ([`Adequacy`]), the unit check against
//! the setup's nominal stiffness ([`UnitCheck`]), the physical-sign warnings and, if asked, the
//! cross-validation over postures ([`cross_validate`]).
//!
//! Plain least squares on a file is streamed: the file is read once in chunks and `Psi` reduced in
//! blocks ([`streamed`]), in bounded memory. Every other fit (robust, non-negative) and
//! cross-validation need the whole observation matrix ([`Observations`]).

use super::{Data, Fit, Folds};
use crate::app::in_data;
use crate::identify::prediction::calibrate;
use crate::model::prediction::Calibration;

use crate::common::warning::{joint_list, Warning, WarningKind};
use crate::identify::adequacy::UNIT_FACTOR;
use crate::identify::offsets::{self, Offset};
use crate::identify::steps::{self, linearity, Linearity, LoadSteps};
use crate::identify::{
    cross_validate, least_squares, streamed, Adequacy, CrossValidation, Identification, UnitCheck,
};
use crate::io::measurements::{self, Labels};
use crate::io::read_text;
use crate::io::readings::{self, has_load_column};
use crate::observation::{Measurement, Observations};
use crate::setup::{plausibility, Noise};
use crate::{Error, Result, Setup};
use nalgebra::Vector6;
use std::io::{BufRead, BufReader, Read};

/// What to identify and how (checked together by [`super::Options`]).
pub(super) struct Request<'a, R> {
    /// The setup: robot, tool, tracker noise, nominal stiffness.
    pub setup: &'a Setup,
    /// The measurements.
    pub data: Data<R>,
    /// The fit.
    pub fit: Fit,
    /// Cross-validation over postures: `Some(folds)` (2 to the number of postures; the number of
    /// postures leaves one posture out), `None` for none.
    pub folds: Option<Folds>,
    /// Fit an offset per posture and measuring point beside the compliances
    /// ([`crate::identify::offsets`]; least squares only, without cross-validation; every point
    /// of every posture under at least two different loads).
    pub offsets: bool,
}

/// The tracker noise variance of one row of the fit, m^2, that the model check tests the
/// residuals against: a displacement's (a loaded minus an unloaded reading, twice a reading's);
/// `per_reading` (offsets fitted, or readings under load steps), one reading's: the unloaded
/// reading's error goes into the offset, or the fit is whitened for it
/// ([`crate::identify::steps::generalised`]; docs/model.md, the noise convention).
pub fn row_noise_variance(noise: &Noise, per_reading: bool) -> f64 {
    match per_reading {
        true => noise.reading_variance,
        false => noise.displacement_variance(),
    }
}

/// The noise floor of the prediction intervals' scale: the standard deviation of one
/// displacement coordinate from the tracker noise `noise`, m
/// ([`crate::model::prediction`]).
pub fn noise_floor(noise: &Noise) -> f64 {
    noise.displacement_sd()
}

/// Where each measurement came from: what a report names a measurement by.
#[derive(Debug, Clone, PartialEq)]
pub struct Origin {
    /// The posture labels (a file's; for arrays `1`, `2`, ... in order).
    pub labels: Labels,
    /// The posture of each measurement, numbered in order of first appearance.
    pub postures: Vec<usize>,
    /// The measuring point of each measurement, 0-based.
    pub points: Vec<usize>,
    /// The axis angles of each posture (rad), by posture number.
    pub angles: Vec<Vector6<f64>>,
    /// The line of each measurement in its file (1-based); `None` for arrays.
    pub lines: Option<Vec<u64>>,
    /// The first measurement of each posture (dense number).
    pub first_of_posture: Vec<usize>,
    /// The names of the force and of the displacement columns (a file's header, or the arrays'
    /// argument names), comma-separated.
    pub columns: [String; 2],
}

impl Origin {
    /// The label of measurement `i`'s posture.
    pub fn label(&self, i: usize) -> &str {
        self.labels.get(self.postures[i])
    }

    /// The labels of dense posture numbers.
    pub fn labels_of(&self, postures: &[usize]) -> Vec<String> {
        postures
            .iter()
            .map(|&p| self.label(self.first_of_posture[p]).to_string())
            .collect()
    }

    fn new(
        labels: Labels,
        postures: Vec<usize>,
        points: Vec<usize>,
        angles: Vec<Vector6<f64>>,
        lines: Option<Vec<u64>>,
        columns: [String; 2],
    ) -> Self {
        let mut first_of_posture = vec![usize::MAX; labels.len()];
        for (i, &p) in postures.iter().enumerate().rev() {
            first_of_posture[p] = i;
        }
        Origin {
            labels,
            postures,
            points,
            angles,
            lines,
            first_of_posture,
            columns,
        }
    }
}

/// What the identify job found.
#[derive(Debug, Clone)]
pub struct Report {
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
    /// With raw readings under load steps ([`crate::identify::steps`]): each posture's linearity, offset
    /// and hysteresis; `None` for displacements.
    pub load_steps: Option<Vec<Linearity>>,
    /// The offsets fitted beside the compliances, when asked ([`Request::offsets`]).
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
/// measurement's number): those of [`streamed::least_squares`], [`measurements::parse`],
/// [`Observations::from_measurements`] and of the fits; [`Error::InvalidField`] (`folds`) and
/// those of [`cross_validate`].
pub(super) fn run<R: Read + Send>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
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
    let mut report = Report {
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
/// ([`has_load_column`]) through [`from_readings`].
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
            rows.angles,
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

/// A whole measurement file read, parsed and turned into the base frame, and where each
/// measurement came from.
pub(crate) fn read_file<R: Read>(
    setup: &Setup,
    name: &str,
    reader: R,
) -> Result<(measurements::MeasurementFile, Origin)> {
    let text = read_text(name, reader)?;
    let mut file = measurements::parse(&text).map_err(|e| in_data(name, e))?;
    drop(text);
    file.to_base_frame(setup).map_err(|e| in_data(name, e))?;
    let columns = [
        file.layout.force_columns(),
        file.layout.displacement_columns(),
    ];
    let origin = Origin::new(
        Labels::from_iter(&file.labels),
        file.measurements.iter().map(|m| m.posture).collect(),
        file.measurements.iter().map(|m| m.point).collect(),
        posture_angles(&file.measurements),
        Some(file.lines.clone()),
        columns,
    );
    Ok((file, origin))
}

/// Whether the header of the text `source` starts with (its first line that is neither blank nor
/// a `#` comment, within the buffer) names a load column: raw readings under load steps.
fn header_has_loads<R: Read>(source: &mut BufReader<R>) -> bool {
    let Ok(buffer) = source.fill_buf() else {
        return false;
    };
    let text = String::from_utf8_lossy(buffer);
    text.lines()
        .find(|l| !(l.trim().is_empty() || l.starts_with('#')))
        .is_some_and(has_load_column)
}

/// Raw readings under load steps read for a fit ([`crate::identify::steps`]): every loaded
/// reading relative to its point's unloaded one, in the base frame, with its line and where it
/// came from.
struct Loaded {
    readings: readings::Readings,
    steps: LoadSteps,
    /// The loaded readings as displacement measurements.
    measurements: Vec<Measurement>,
    /// The line of each measurement's reading.
    lines: Vec<u64>,
    origin: Origin,
}

impl Loaded {
    /// The readings of `text` (named `name`): refused naming the data when a posture has no
    /// loaded reading.
    fn read(setup: &Setup, name: &str, text: &str) -> Result<Self> {
        let points = setup.tool().measuring_points.len();
        let readings =
            readings::parse(text, setup.robot(), points).map_err(|e| in_data(name, e))?;
        let mut steps = LoadSteps::new(&readings).map_err(|e| in_data(name, e))?;
        steps.to_base_frame(setup).map_err(|e| in_data(name, e))?;
        let loaded = steps.loaded();
        if let Some(p) = (0..steps.labels.len())
            .find(|&p| !loaded.iter().any(|&i| steps.measurements[i].posture == p))
        {
            return Err(in_data(
                name,
                Error::InvalidField {
                    field: "load_step".into(),
                    message: format!(
                        "posture '{}' has no loaded reading: nothing to identify from it",
                        crate::common::limits::short(&steps.labels[p])
                    ),
                },
            ));
        }
        let measurements: Vec<Measurement> = loaded
            .iter()
            .map(|&i| steps.measurements[i].clone())
            .collect();
        let lines: Vec<u64> = loaded.iter().map(|&i| steps.lines[i]).collect();
        let origin = Origin::new(
            Labels::from_iter(&steps.labels),
            measurements.iter().map(|m| m.posture).collect(),
            measurements.iter().map(|m| m.point).collect(),
            posture_angles(&measurements),
            Some(lines.clone()),
            readings.columns.clone(),
        );
        Ok(Loaded {
            readings,
            steps,
            measurements,
            lines,
            origin,
        })
    }

    /// `error` of a fit of the measurements, placed in the data `name`: a measurement's number
    /// as its reading's line.
    fn explain(&self, name: &str, error: Error) -> Error {
        let e = match error {
            Error::Measurement { number, .. } => Error::InvalidField {
                field: "readings".into(),
                message: format!(
                    "line {}: {error}",
                    self.lines.get(number.wrapping_sub(1)).copied().unwrap_or(0)
                ),
            },
            e => e,
        };
        in_data(name, e)
    }

    /// Readings in another unit fit a robot of another size: refused whatever a fit found
    /// (after it, so that a file's own errors come first).
    fn check_scale(&self, setup: &Setup, name: &str) -> Result<()> {
        super::super::readings::refuse_other_scale(setup, &self.readings)
            .map_err(|e| in_data(name, e))
    }
}

/// The identification of raw readings under load steps ([`Loaded`]), and each posture's
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

/// `f` on the measurements of `data` (a measurement file or raw readings under load steps, as
/// `identify` reads them, turned into the base frame; or arrays): the data's name, where each
/// measurement came from and `f`'s result; `f`'s errors as [`Error::Input`] naming the data (a
/// file's line and column).
///
/// # Errors
/// Those of [`read_file`], of the readings ([`crate::io::readings::parse`],
/// [`LoadSteps::new`]) and of `f`.
pub(crate) fn on_measurements<R: Read, T>(
    setup: &Setup,
    data: Data<R>,
    f: impl FnOnce(&[Measurement]) -> Result<T>,
) -> Result<(String, Origin, T)> {
    match data {
        Data::File { name, reader } => {
            let mut source = BufReader::with_capacity(1 << 20, reader);
            if header_has_loads(&mut source) {
                let data = Loaded::read(setup, &name, &read_text(&name, source)?)?;
                let found = f(&data.measurements).map_err(|e| data.explain(&name, e))?;
                data.check_scale(setup, &name)?;
                return Ok((name, data.origin, found));
            }
            let (file, origin) = read_file(setup, &name, source)?;
            let found = f(&file.measurements).map_err(|e| in_data(&name, file.explain(e)))?;
            Ok((name, origin, found))
        }
        Data::Measurements(measurements) => {
            let found = f(&measurements).map_err(|e| in_data("arrays", e))?;
            Ok(("arrays".to_string(), arrays_origin(&measurements), found))
        }
    }
}

/// The warning that the data's angles look like radians under `_deg` names, if they do
/// ([`plausibility::radians_as_degrees`]), naming the data.
pub(crate) fn angle_warnings(data_name: &str, origin: &Origin) -> Vec<Warning> {
    plausibility::radians_as_degrees(&origin.angles)
        .map(|mut w| {
            w.message = format!("{data_name}: {}", w.message);
            w
        })
        .into_iter()
        .collect()
}

/// The origin of measurements given as arrays: postures labelled `1`, `2`, ... in order.
pub(crate) fn arrays_origin(measurements: &[Measurement]) -> Origin {
    let postures = measurements.iter().map(|m| m.posture).collect::<Vec<_>>();
    let count = postures.iter().max().map_or(0, |p| p + 1);
    Origin::new(
        Labels::from_iter((1..=count).map(|p| p.to_string())),
        postures,
        measurements.iter().map(|m| m.point).collect(),
        posture_angles(measurements),
        None,
        ["wrench".into(), "displacement_mm".into()],
    )
}

/// The axis angles of each posture of `measurements` (numbered from 0, each with a measurement).
fn posture_angles(measurements: &[Measurement]) -> Vec<Vector6<f64>> {
    let count = measurements
        .iter()
        .map(|m| m.posture + 1)
        .max()
        .unwrap_or(0);
    let mut angles = vec![Vector6::zeros(); count];
    for m in measurements {
        angles[m.posture] = m.q;
    }
    angles
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
                        crate::common::limits::short(report.origin.labels.get(l.posture))
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
