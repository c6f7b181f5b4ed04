//! What a calibration's fit is told about itself: the reading that fits worst, and the warnings
//! about the fit (convergence, identifiability, misfit).

use super::ladder::Ladder;
use super::{Warning, WarningKind, MIN_DEGREES_OF_FREEDOM, MISFIT_RATIO, WEAK_CONDITION};
use crate::calibration::fit::{self, Fit};
use crate::calibration::gravity::Gravity;
use crate::calibration::ErrorModel;
use nalgebra::DVector;
use stiffid_core::common::choice::Choice;
use stiffid_core::common::limits;
use stiffid_core::io::readings::Readings as Data;

/// The reading with the longest residual (`residuals`: three coordinates per reading of `data`,
/// m), as a clause of the misfit warning: one bad reading raises the noise ratio as a missing
/// model term does.
pub fn largest_residual(data: &Data, residuals: &DVector<f64>) -> String {
    let longest = (residuals.as_slice().chunks_exact(3))
        .map(|r| nalgebra::Vector3::from_column_slice(r).norm())
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let Some((i, length)) = longest else {
        return String::new();
    };
    let (reading, line) = (&data.readings[i], data.lines[i]);
    format!(
        "; or a bad reading: the longest residual is {:.3} mm, line {line} (posture {}, point {})",
        length * 1e3,
        limits::short(&data.labels[reading.posture]),
        stiffid_core::io::readings::point_name(reading.point, reading.table)
    )
}

/// The warnings about the fit; `ladder` the models the calibration chose among, if it chose.
pub fn judge(
    (model, fit, ladder): (&ErrorModel, &Fit, Option<&Ladder>),
    noise_ratio: f64,
    name: &str,
) -> Vec<Warning> {
    let not_converged = fit::stop_warning(fit.stop, fit.iterations);
    let mut w: Vec<Warning> = not_converged.into_iter().collect();
    let id = &fit.identifiability;
    // The priors and the maps' ridge hold part of the fitted parameters: what the readings must
    // determine is the effective count.
    let effective = fit.effective_parameters;
    let dof = (fit.residuals.len() as f64 - effective).max(0.0);
    if dof < MIN_DEGREES_OF_FREEDOM as f64 {
        let held = match fit.fitted.len() as f64 - effective {
            h if h >= 0.5 => {
                format!(" ({effective:.1} effective: the priors and the maps' ridge hold the rest)")
            }
            _ => String::new(),
        };
        w.push(Warning::new(
            WarningKind::Unidentifiable,
            format!(
                "{name}: {} coordinates for {} fitted parameters{held} leave {dof:.1} degrees of freedom (fewer than {MIN_DEGREES_OF_FREEDOM}): the fit explains the readings whatever their errors, and its standard deviations and noise ratio mean little; read more postures",
                fit.residuals.len(),
                fit.fitted.len()
            ),
        ));
    }
    if id.condition > WEAK_CONDITION {
        w.push(Warning::new(
            WarningKind::Unidentifiable,
            format!(
                "the identification Jacobian's condition number is {:.3e} (above {WEAK_CONDITION:e}): some parameters are weakly determined; read more varied postures or give tolerances",
                id.condition
            ),
        ));
    }
    if noise_ratio > MISFIT_RATIO {
        w.push(Warning::new(
            WarningKind::Misfit,
            format!(
                "the residuals are {noise_ratio:.1} times the tracker noise: the model misses part of the robot's error{}",
                match model.gravity().is_empty() {
                    true => untried_hint(model, ladder),
                    false => String::new(),
                }
            ),
        ));
    }
    w
}

/// The gravity models a misfit of the rigid model suggests: those the robot takes (`arm` on an
/// anthropomorphic arm, `masses` with link masses, `lumped`) that `ladder` did not just try and
/// turn down (scored and lost, or skipped); where it tried every one, it says so instead.
fn untried_hint(model: &ErrorModel, ladder: Option<&Ladder>) -> String {
    let robot = model.robot();
    let takes = [Gravity::Arm, Gravity::Lumped, Gravity::Masses];
    let takes: Vec<Gravity> = (takes.into_iter())
        .filter(|&g| match g {
            Gravity::Arm => crate::calibration::gravity::takes_arm(robot),
            Gravity::Masses => robot.masses().is_some(),
            _ => true,
        })
        .collect();
    let tried = |g: Gravity| ladder.is_some_and(|l| l.rungs.iter().any(|r| r.gravity == g));
    let untried: Vec<&str> = (takes.iter().copied())
        .filter(|&g| !tried(g))
        .map(|g| g.name())
        .collect();
    match (untried.is_empty(), ladder.is_some()) {
        (false, _) => format!(" (try --gravity {})", untried.join(" or ")),
        (true, true) => format!(
            " (the ladder's gravity models predict the held-out groups no better: what the model misses is not the weight's sag{})",
            match model.map_start() {
                Some(_) => "",
                None => "; joint error maps (--maps) may hold it",
            }
        ),
        (true, false) => String::new(),
    }
}
