//! A program in encoder pulses (a Yaskawa INFORM job) checked against the bound it must keep:
//! rounding each axis to a whole pulse moves the TCP, and a controller whose pulses are coarse
//! (`[controller] pulses_per_deg = [1, ..]`: a whole degree, about 20 mm at the TCP of a
//! GP-sized arm) could not keep a bound of tenths of a mm however well it is compensated.

use nalgebra::{Vector3, Vector6};
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::robot::ik::tool_pose;
use stiffid_core::{Error, Result, Robot, Setup};
use stiffid_machining::compensate::Compensated;
use stiffid_machining::{Language, Program};

/// The TCP motion (m) of writing posture `q` (rad) in whole pulses at `per_deg` pulses per
/// degree: the distance between the TCP `tcp` (flange frame, m) at `q` and at `q` with each axis
/// rounded to its nearest whole pulse, as the job states it. At most the sum over the axes of
/// half a pulse times the TCP's lever about each axis; a controller's own pulses (about 500 to
/// 1500 per degree on a GP-sized arm) move it by hundredths of a mm, one pulse per degree by
/// tens of mm.
pub fn rounding(robot: &Robot, tcp: &Vector3<f64>, q: &Vector6<f64>, per_deg: &[f64; 6]) -> f64 {
    let written = Vector6::from_fn(|k, _| {
        let pulses = stiffid_machining::program::whole_pulses(q[k].to_degrees(), per_deg[k]);
        (pulses as f64 / per_deg[k]).to_radians()
    });
    let at = |q: &Vector6<f64>| tool_pose(&robot.frames(q), tcp).translation.vector;
    (at(&written) - at(q)).norm()
}

/// The pulses per degree a program is written in: a job read in pulses, its own; a G-code
/// program written as a job, the setup's; `None` for a program in decimals.
fn written_pulses(setup: &Setup, program: &Program, output: Language) -> Option<[f64; 6]> {
    match (program, output) {
        (Program::Robot(p), _) => {
            let six: Option<Vec<f64>> = p.pulses().iter().take(6).copied().collect();
            six.filter(|v| v.len() == 6)
                .map(|v| [v[0], v[1], v[2], v[3], v[4], v[5]])
        }
        (Program::GCode(_), Language::Robot(d))
            if (d.controller().generator()).is_some_and(|g| g.needs_pulses()) =>
        {
            setup
                .workcell()
                .controller()
                .pulses
                .as_ref()
                .map(|p| p.per_deg)
        }
        _ => None,
    }
}

/// The most whole pulses may move the TCP and the job still be written, m: a controller's own
/// pulses (about 500 to 1500 per degree on a GP-sized arm) round by hundredths of a mm, one pulse
/// per degree (a slip in the axis parameters) by tens of mm.
const COARSE_M: f64 = 1e-4;

/// A program in pulses whose whole pulses move the TCP, at some target, by more than the most
/// the compensation does or claims anywhere in the program (the largest of the targets' finite
/// bounds and of their corrections, the TCP's motion from each target's posture to its
/// compensated one): refused where the rounding is also more than [`COARSE_M`] (coarser than a
/// controller's resolution: the pulses are wrong); written with a warning stating the rounding
/// otherwise (a light cut on a real controller: the job is as close as its pulses allow).
///
/// # Errors
/// [`Error::InvalidField`] (`controller.pulses_per_deg`) naming the target, both lengths and
/// the pulses.
pub(super) fn check(
    setup: &Setup,
    (program, output): (&Program, Language),
    results: &[Compensated],
) -> Result<Option<Warning>> {
    let Some(per_deg) = written_pulses(setup, program, output) else {
        return Ok(None);
    };
    let (robot, tcp) = (setup.robot(), setup.tool().tcp);
    let at = |q: &Vector6<f64>| tool_pose(&robot.frames(q), &tcp).translation.vector;
    let most = (results.iter())
        .map(|r| (at(&r.q_compensated) - at(&r.q)).norm())
        .chain(
            results
                .iter()
                .map(|r| r.budget.bound)
                .filter(|b| b.is_finite()),
        )
        .fold(0.0, f64::max);
    let rounded = results
        .iter()
        .map(|r| rounding(robot, &tcp, &r.q_compensated, &per_deg));
    let worst = rounded
        .enumerate()
        .fold((0, 0.0), |w, (i, m)| if m > w.1 { (i, m) } else { w });
    if worst.1 <= most {
        return Ok(None);
    }
    let list: Vec<String> = per_deg.iter().map(f64::to_string).collect();
    let what = format!("[{}]: rounding the axes to whole pulses moves the TCP by {:.4} mm at target {} of the program, more than the most the compensation corrects or bounds anywhere in it ({:.4} mm)", list.join(", "), worst.1 * 1e3, worst.0 + 1, most * 1e3);
    if worst.1 <= COARSE_M {
        return Ok(Some(Warning::new(WarningKind::LeftOut, format!("controller.pulses_per_deg {what}, within a controller's resolution ({} mm): the job is written as close to the compensated path as whole pulses go, each position within that rounding of it", COARSE_M * 1e3))));
    }
    Err(Error::InvalidField {
        field: "controller.pulses_per_deg".into(),
        message: format!("{what}, and more than a controller's resolution rounds ({} mm): the job could not keep what it was compensated for; give the controller's pulses per degree (its axis parameters, S to T)", COARSE_M * 1e3),
    })
}
