//! The readings of a cell: what the register and calibrate jobs read.

use crate::app::{in_data, Warning};
use nalgebra::Vector3;
use stiffid_core::io::readings::{self, Readings};
use stiffid_core::setup::plausibility;
use stiffid_core::{Error, Result, Setup};
use stiffid_metrology::register::{self, suspect, Registration, Suspect};

/// Readings of a cell: what the register and calibrate jobs read.
pub struct Request<'a> {
    /// The setup: robot, tool (its measuring points), tracker.
    pub setup: &'a Setup,
    /// The setup as the user named it (a built-in setup's name or a file's path): what the
    /// job's document states.
    pub setup_name: String,
    /// The readings file's name (for errors and the document).
    pub name: String,
    /// Its text: `posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm`
    /// ([`stiffid_core::io::readings`]; with load steps, only the unloaded readings are used), at
    /// most [`readings::MAX_READINGS`] rows.
    pub text: &'a str,
    /// Fit readings that no rigid transform explains ([`stiffid_metrology::register::suspect`]: a
    /// mirror image, a residual beyond [`stiffid_metrology::register::residual_limit`]) instead of
    /// refusing them.
    pub force: bool,
}

/// The readings of `request`, and the warnings about them.
///
/// # Errors
/// Those of [`readings::parse`] and `refuse_other_scale`, as [`stiffid_core::Error::Input`] naming
/// the file.
pub fn read(request: &Request<'_>) -> Result<(Readings, Vec<Warning>)> {
    let Request {
        setup, name, text, ..
    } = request;
    let points = setup.tool().measuring_points.len();
    let data = readings::parse(text, setup.robot(), points).map_err(|e| in_data(name, e))?;
    refuse_other_scale(setup, &data).map_err(|e| in_data(name, e))?;
    let warnings = plausibility::radians_as_degrees(data.readings.iter().map(|r| &r.q))
        .map(|mut w| {
            w.message = format!("{name}: {}", w.message);
            w
        })
        .into_iter()
        .collect();
    Ok((data, warnings))
}

/// Refuses readings (any frame, loaded or not) whose spread is not the robot's: the RMS distance
/// of the readings from their centroid against that of the setup's measuring points through the
/// nominal robot at the same axis angles ([`register::spread_ratio`]), beyond
/// [`register::SPREAD_RATIO_LIMIT`] either way. Readings in metres or centimetres under `_mm`
/// names would otherwise calibrate a robot shrunk to their scale with a residual of zero. Nothing
/// forces them: no robot is a tenth of its model's size.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) with both spreads and the likely unit.
pub(crate) fn refuse_other_scale(setup: &Setup, data: &Readings) -> Result<()> {
    let points = &setup.tool().measuring_points;
    let pairs: Vec<register::Correspondence> = (data.readings.iter())
        .filter(|r| !r.table)
        .map(|r| register::Correspondence {
            base: setup
                .robot()
                .frames_at(&r.q, r.e.as_slice())
                .point(&points[r.point]),
            tracker: r.position,
        })
        .collect();
    let Some((ratio, spread)) = register::spread_ratio(&pairs) else {
        return Ok(());
    };
    let limit = register::SPREAD_RATIO_LIMIT;
    if ratio.is_finite() && ratio <= limit && ratio >= 1.0 / limit {
        return Ok(());
    }
    let units = [
        (1e-3, "metres"),
        (1e-2, "decimetres"),
        (0.1, "centimetres"),
        (1.0 / 25.4, "inches"),
        (1e3, "micrometres"),
    ];
    let (_, unit) = units
        .iter()
        .min_by(|a, b| {
            (a.0 / ratio)
                .ln()
                .abs()
                .total_cmp(&(b.0 / ratio).ln().abs())
        })
        .expect("units");
    Err(Error::InvalidField {
        field: "readings".into(),
        message: format!(
            "the readings spread {:.4} mm about their centroid (RMS) where the robot's measuring points at the same axis angles spread {:.1} mm: {ratio:.4} times the robot's size, readings in {unit}? expected millimetres ({}) of this robot and tool",
            ratio * spread * 1e3,
            spread * 1e3,
            data.columns[1]
        ),
    })
}

/// Refuses, unless `request.force`, readings that no rigid transform explains
/// ([`stiffid_metrology::register::suspect`] at the setup's tracker noise): tracker readings that
/// are a mirror image of the nominal robot's points (by `registration`, or the registration of
/// `data` when `None`), or a fitted residual (`residuals`, m, one per unloaded reading of `data`
/// in file order, or per unloaded reading of the arm's points: the table's reflectors left out) beyond [`stiffid_metrology::register::residual_limit`].
///
/// # Errors
/// [`Error::InvalidField`] in an [`Error::Input`] naming the file: `readings` for a mirror image
/// (both RMS), or the reading's line, posture and point with `residual_norm_mm` (its length and
/// the limit).
pub(crate) fn refuse_implausible(
    request: &Request<'_>,
    data: &Readings,
    registration: Option<&Registration>,
    residuals: &[Vector3<f64>],
) -> Result<()> {
    if request.force {
        return Ok(());
    }
    let sigma = request.setup.noise().reading_sd();
    let registered = match registration {
        Some(r) => Some(r.clone()),
        // Readings in the base frame, or too few: the job says so itself.
        None => register::correspondences(request.setup, data)
            .and_then(|points| register::fit(&points))
            .ok(),
    };
    let mirrored = registered.and_then(|r| suspect(&[], r.rms, r.mirror_rms, sigma));
    let error = match mirrored.or_else(|| suspect(residuals, 0.0, f64::INFINITY, sigma)) {
        None => return Ok(()),
        Some(Suspect::Mirrored { rms, mirror_rms }) => Error::InvalidField {
            field: "readings".into(),
            message: format!(
                "the tracker's readings are a mirror image of the robot's points: the best rotation leaves a residual RMS of {:.3} mm, a reflection {:.3} mm; expected readings in a right-handed tracker frame (an axis flipped, or two coordinate columns swapped?); --force (Python force=True) fits the best rotation anyway",
                rms * 1e3,
                mirror_rms * 1e3
            ),
        },
        Some(Suspect::Residual {
            index,
            length,
            limit,
        }) => {
            // One residual per unloaded reading, or (the tracker's registration) per unloaded
            // reading of the arm's points, the table's reflectors left out.
            let unloaded = data.readings.iter().filter(|r| r.unloaded()).count();
            let (reading, line) = (data.readings.iter().zip(&data.lines))
                .filter(|(r, _)| r.unloaded() && (residuals.len() == unloaded || !r.table))
                .nth(index)
                .expect("one residual per unloaded reading");
            Error::InvalidField {
                field: format!(
                    "line {line} (posture {}, point {}), residual_norm_mm",
                    stiffid_core::common::limits::short(&data.labels[reading.posture]),
                    readings::point_name(reading.point, reading.table)
                ),
                message: format!(
                    "{:.3}: expected at most {:.3} mm (the larger of {} mm, twice a robot's unloaded absolute error, and {} times the tracker noise {:.4} mm): a reading of another point or posture, or axis angles that are not the robot's; --force (Python force=True) fits the readings anyway",
                    length * 1e3,
                    limit * 1e3,
                    register::RESIDUAL_LIMIT * 1e3,
                    register::RESIDUAL_NOISE_MULTIPLE,
                    sigma * 1e3
                ),
            }
        }
    };
    Err(in_data(&request.name, error))
}
