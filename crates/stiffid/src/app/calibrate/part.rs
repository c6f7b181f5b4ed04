//! The part's frame a calibration locates from the reflectors fixed in the cell: on the
//! positioner's table, or, in a cell without a positioner (a fixed base or a track), on the part
//! or its fixture. The setup gives them in the part's frame (`[workpiece] reflectors_mm`), the
//! calibration fits where they are in the calibrated cell (every external axis at 0; a fixed
//! reflector is a free point of the cell, read through the tracker's registration), and the
//! rigid transform between the two (Umeyama's least squares,
//! [`stiffid_metrology::register::fit`]) is the part's frame in the calibrated cell, which the
//! calibrated robot file records (`[part]`, [`stiffid_core::Robot::part`]) for every setup
//! pointing at it. The setup's own
//! `[workpiece] base_from_part` places the part in the nominal cell; after a calibration that
//! moved the cell frame (its registration, the base's errors) it misses the part by as much.

use super::{Warning, WarningKind};
use nalgebra::{Isometry3, Point3};
use stiffid_core::common::words::number;
use stiffid_core::{Result, Setup};
use stiffid_metrology::calibration::error_model::{ErrorModel, Estimate, MeasuredIn};
use stiffid_metrology::register::{fit, Correspondence, Registration};

/// The part's frame in the calibrated cell (m), located from the setup's reflectors and
/// the model's fitted ones (paired by number, `T1` with the first): `None` without reflectors in
/// both. A location that fails (fewer than three reflectors, or on one line), one far from
/// the setup's `[workpiece] base_from_part`, reflectors read in a cell without a positioner
/// that the setup does not place (they locate nothing) and reflectors placed that were not read
/// add a warning to `warnings`. An update (`update`) that locates no part keeps the one its
/// calibrated robot file records, with a warning.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`workpiece.reflectors_mm`) when no rigid transform
/// explains the reflectors as the setup places them and as the calibration fitted them: a mirror
/// image, or a reflector farther from its place than the registration's residual limit
/// (`stiffid_metrology::register`'s check), naming it and how far.
pub(super) fn located(
    setup: &Setup,
    (model, estimate): (&ErrorModel, &Estimate),
    update: bool,
    warnings: &mut Vec<Warning>,
) -> Result<Option<Isometry3<f64>>> {
    let found = locate(setup, (model, estimate), warnings)?;
    match (found, setup.robot().part()) {
        (None, Some(kept)) if update => {
            warnings.push(Warning::new(
                WarningKind::Calibrated,
                "the update locates no part (no reflectors read and placed): the calibrated robot file keeps the part the calibration located ([part]); if the part or the robot moved since, read the reflectors in the check campaign ([workpiece] reflectors_mm and their T rows) to locate it again",
            ));
            Ok(Some(*kept))
        }
        (found, _) => Ok(found),
    }
}

fn locate(
    setup: &Setup,
    (model, estimate): (&ErrorModel, &Estimate),
    warnings: &mut Vec<Warning>,
) -> Result<Option<Isometry3<f64>>> {
    let given = setup.table_reflectors();
    warnings.extend(unplaced(setup, model.tables(), given.len()));
    let Some(part) = setup.workpiece() else {
        return Ok(None);
    };
    let n = given.len().min(model.tables());
    if n == 0 {
        return Ok(None);
    }
    warnings.extend(unread(given.len(), model.tables()));
    // Readings in the base frame: the calibrated robot's base is `T^-1 base`, so its cell too.
    let cell = match model.measured_in() {
        MeasuredIn::Tracker => Isometry3::identity(),
        MeasuredIn::Base => estimate.frame.inverse(),
    };
    let pairs: Vec<Correspondence> = (0..n)
        .map(|k| Correspondence {
            base: (cell * Point3::from(model.table(&estimate.values, k))).coords,
            tracker: (part.inverse() * Point3::from(given[k])).coords,
        })
        .collect();
    match fit(&pairs) {
        Ok(r) => {
            stiffid_metrology::register::refuse_unlocated(&r, setup.noise().reading_sd())?;
            warnings.extend(moved(part, &r.base_from_tracker, n).map(|mut w| {
                w.message += &format!(" (the fit's {})", residuals(&r));
                w
            }));
            warnings.extend(misfit(&r, setup.noise().reading_sd(), n));
            Ok(Some(r.base_from_tracker))
        }
        Err(e) => {
            warnings.push(Warning::new(
                WarningKind::Calibrated,
                format!("the part's frame is not located from the reflectors T1..T{n} ({e}): the calibrated robot file records none, and a setup pointing at it needs [workpiece] base_from_part"),
            ));
            Ok(None)
        }
    }
}

/// The noise ratio above which the reflectors' fit is warned of, as the calibration's is
/// (`stiffid_metrology::calibration::judgement`): residuals three times what the tracker's
/// noise leaves.
const MISFIT_RATIO: f64 = 3.0;

/// The fit's residuals in words: their RMS and the longest, naming its reflector.
fn residuals(r: &Registration) -> String {
    let (k, longest) = (r.residuals.iter().map(|v| v.norm()).enumerate())
        .fold((0, 0.0), |w, (i, l)| if l > w.1 { (i, l) } else { w });
    format!(
        "residuals: {:.4} mm RMS, the longest {:.4} mm at T{}",
        r.rms * 1e3,
        longest * 1e3,
        k + 1
    )
}

/// The warning that the reflectors' fit `r` leaves residuals (RMS of their lengths) more than
/// [`MISFIT_RATIO`] times what the tracker noise `sigma` (m per coordinate) leaves on a point,
/// `sqrt(3) sigma`: a reflector placed off in the setup (`[workpiece] reflectors_mm`) or read
/// as another, which moves the located part by a share of it.
fn misfit(r: &Registration, sigma: f64, n: usize) -> Option<Warning> {
    let ratio = r.rms / (3f64.sqrt() * sigma);
    (ratio > MISFIT_RATIO).then(|| {
        Warning::new(
            WarningKind::Misfit,
            format!(
                "the part located from the reflectors T1..T{n} leaves {} ({ratio:.1} times what the tracker noise leaves): a reflector is off its place in [workpiece] reflectors_mm or its T rows read another, and the fit spreads its error over the part's frame; check the reflectors' coordinates and numbers",
                residuals(r)
            ),
        )
    })
}

/// The warning that the setup places `placed` reflectors and the readings read only `read`:
/// the part is located from the first `read`.
fn unread(placed: usize, read: usize) -> Option<Warning> {
    (placed > read && read > 0).then(|| {
        Warning::new(
            WarningKind::Calibrated,
            format!("the setup places {placed} reflectors ([workpiece] reflectors_mm) and the readings read {read} (T rows): the part is located from T1..T{read} only"),
        )
    })
}

/// The warning that the part located at `located` from `n` reflectors lies away from the
/// setup's `part` (beyond 0.001 mm or 0.001 deg), how far.
fn moved(part: &Isometry3<f64>, located: &Isometry3<f64>, n: usize) -> Option<Warning> {
    let origin = (located.translation.vector - part.translation.vector).norm();
    let angle = part.rotation.angle_to(&located.rotation);
    (origin > 1e-6 || angle > 1e-3f64.to_radians()).then(|| {
        Warning::new(
            WarningKind::Calibrated,
            format!(
                "the part located from the reflectors T1..T{} lies {} mm and {} deg from the setup's [workpiece] base_from_part in the calibrated cell: the calibrated robot file records it ([part]); a setup pointing at that file takes it, leave base_from_part out",
                n,
                number(origin * 1e3),
                number(angle.to_degrees())
            ),
        )
    })
}

/// The warning that a cell without a positioner read `read` reflectors (`T` rows) where the
/// setup places `placed` (`[workpiece] reflectors_mm`): the others are fitted and locate nothing.
fn unplaced(setup: &Setup, read: usize, placed: usize) -> Option<Warning> {
    let positioner = (setup.robot().external()).is_some_and(|a| a.len() > a.carrier_len());
    let names = |from: usize| match from == read {
        true => format!("T{read}"),
        false => format!("T{from}..T{read}"),
    };
    (!positioner && read > placed).then(|| {
        Warning::new(
            WarningKind::Calibrated,
            format!(
                "the readings read reflectors {} fixed in the cell and the setup places {placed} ([workpiece] reflectors_mm, in the part's frame): without a positioner, {} locate nothing; give each in reflectors_mm to locate the part from them",
                names(1),
                names(placed + 1)
            ),
        )
    })
}
