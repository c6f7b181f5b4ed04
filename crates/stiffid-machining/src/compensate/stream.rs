//! A whole path compensated: in parallel, in chunks of bounded memory, the failing points named.

use super::feasible::Checks;
use super::fixed_base::optimise_tool_axis;
use super::lead_tilt::{check_cells, check_streaming, cones, Leaning};
use super::tool_axis::Cost;
use super::{
    Compensated, Compliance, Model, Newton, Objective, Options, PathPoint, Target, REQUIRED_M,
    REQUIRED_RAD,
};
use nalgebra::{Isometry3, Vector3, Vector6};
use rayon::prelude::*;
use stiffid_core::common::error::{ColumnProblem, JobOption};
use stiffid_core::observation::deflection::base_wrench;
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::ik::{self, tool_pose};
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result};

/// Compensates every point of a path (module docs), the points in parallel; the result does not
/// depend on the number of threads.
///
/// # Errors
/// [`Error::InvalidField`] for `options` outside their limits ([`Options::validate`]) or a free
/// tool axis grid beyond 5 000 000; [`Error::InvalidOption`] ([`JobOption::Minimise`]) for the
/// surge objective, which needs a drilling program (`path_with_exits`); [`Error::Column`] naming
/// the line of the first point (in path order) that fails: axis angles outside the joint limits
/// ([`ColumnProblem::Outside`], `q1_deg..q6_deg`), a pose inverse kinematics cannot reach
/// ([`ColumnProblem::Uncompensated`] with [`Error::Unreachable`]'s message, `x_mm..rz_deg`), or
/// compensated axis angles outside the joint limits or a residual above 0.1 micrometre / 1
/// microradian (`Uncompensated` with the lines of the other points that fail, `q_compensated`).
pub fn path(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    options: &Options,
) -> Result<Vec<Compensated>> {
    path_with_exits(arm, compliance, points, &[], options)
}

/// [`path`] of a drilling program: `thrusts` holds each point's thrust (N, base frame) released
/// at a drilling exit, `None` elsewhere ([`crate::dynamics::exit_thrusts`]; empty for
/// a path without any), which the free tool axis' [`Objective::Surge`] minimises.
///
/// # Errors
/// Those of [`path`]; [`Error::InvalidOption`] ([`JobOption::Minimise`]) for the
/// surge objective with a robot that gives no masses (or placeholders) or a path without a
/// drilling exit.
///
/// # Panics
/// If `thrusts` is neither empty nor one per point.
pub(crate) fn path_with_exits(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    thrusts: &[Option<Vector3<f64>>],
    options: &Options,
) -> Result<Vec<Compensated>> {
    options.validate()?;
    let cones = match &options.free.lead_tilt() {
        Some(l) => cones(l, points.len(), None)?,
        None => Vec::new(),
    };
    path_in_cones(arm, compliance, points, (thrusts, &cones), options)
}

/// [`path_with_exits`] with each point's cone of the free lead and tilt (rad, one per point
/// with [`super::FreeVariables::lead_tilt`], [`super::lead_tilt::cones`]; a program's from its
/// process).
///
/// # Errors
/// Those of [`path_with_exits`].
pub(crate) fn path_in_cones(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    (thrusts, cones): (&[Option<Vector3<f64>>], &[f64]),
    options: &Options,
) -> Result<Vec<Compensated>> {
    options.validate()?;
    assert!(thrusts.is_empty() || thrusts.len() == points.len());
    if options.free.frees_external() {
        return Err(Error::InvalidOption {
            option: JobOption::StationRange,
            message: "a free station, positioner or tilt is chosen for points with their external values (compensate::path_on_track for a path file's, machining::compensate for a program's); these points have none".into(),
        });
    }
    let (rotation, lean) = (options.free.tool_rotation(), options.free.lead_tilt());
    let (rotation, lean) = (rotation.as_ref(), lean.as_ref());
    let largest = cones.iter().copied().fold(0.0, f64::max);
    check_cells(options, points.len(), largest)?;
    let axes = 2 * usize::from(lean.is_some()) + usize::from(rotation.is_some());
    super::refine::check(options.refine, axes, points.len())?;
    let free = match options.free.frees_tool_axis() {
        true => Some((
            cost(arm, options.free.minimise, thrusts)?,
            options.free.aggregate,
        )),
        false => None,
    };
    let model = Model::new(arm, compliance)?
        .at_level(options.level)
        .with_max_iterations(options.max_iterations)
        .with_force_tolerance(options.force_tolerance);
    let nominal = nominal_postures(arm, points, options.q0, options)?;
    let wrenches: Vec<Vector6<f64>> = points
        .par_iter()
        .zip(&nominal)
        .map(|(p, q)| base_wrench(&arm.robot().frames(q), &p.wrench, p.frame))
        .collect();
    let checks = Checks::new(&model, &options.feasible);
    let own: Vec<ExternalValues> = points.iter().map(|p| p.external).collect();
    let (postures, rotations, leans, removed) = match &free {
        None => (
            nominal.clone(),
            vec![0.0; points.len()],
            Vec::new(),
            Vec::new(),
        ),
        Some((cost, aggregate)) => {
            let poses: Vec<Isometry3<f64>> = (nominal.iter())
                .map(|q| tool_pose(&arm.robot().frames(q), &arm.tool().tcp))
                .collect();
            let leaning = Leaning::new(lean, &poses, cones.to_vec());
            optimise_tool_axis(
                &model,
                (&nominal, &own),
                &wrenches,
                (rotation, &leaning, *aggregate),
                (cost, &checks),
                options,
            )
        }
    };
    let chosen = Chosen {
        nominal: &nominal,
        postures: &postures,
        rotations: &rotations,
        leans: &leans,
        wrenches: &wrenches,
        wrenches_before: &wrenches,
        removed: &removed,
    };
    compensate_chosen(&model, points, &chosen, free.is_some())
}

/// The cost of the free variables' `objective`; for the surge, the arm's mass model and the
/// path's drilling exits (`thrusts`), refused without either.
fn cost<'a>(
    arm: &Arm,
    objective: Objective,
    thrusts: &'a [Option<Vector3<f64>>],
) -> Result<Cost<'a>> {
    match objective {
        Objective::Deflection => return Ok(Cost::Deflection),
        Objective::Bound => return Ok(Cost::Bound),
        Objective::Surge => {}
    }
    let refuse = |message: String| Error::InvalidOption {
        option: JobOption::Minimise,
        message: format!("surge: {message}"),
    };
    let masses = match stiffid_core::observation::dynamics::mass_model(arm) {
        (Some(masses), _) => masses,
        (None, warning) => {
            let why = warning.map_or_else(
                || {
                    format!(
                        "the robot's description gives no link masses: {}",
                        stiffid_core::robot::dynamics::HOW_TO_GIVE
                    )
                },
                |w| w.message,
            );
            return Err(refuse(format!("the surge needs the robot's masses; {why}")));
        }
    };
    if thrusts.iter().all(Option::is_none) {
        return Err(refuse("no point of the path is a drilling exit: the surge is that of a program's drilling exits, which needs the program and a process whose drilling operation covers them".into()));
    }
    Ok(Cost::Surge {
        masses: Box::new(masses),
        thrusts,
    })
}

/// Path points per chunk of [`stream`].
pub const CHUNK: usize = 4096;

/// [`path`] for a path of any length in bounded memory: the points come from `points` (an iterator,
/// e.g. a file's rows as they are parsed) and are compensated [`CHUNK`] at a time (in parallel
/// within a chunk, inverse kinematics continued from the previous chunk's last posture); `sink`
/// gets each chunk's points and results, in path order, before the next chunk is read. With
/// [`super::FreeVariables::tool_rotation`] or [`super::FreeVariables::lead_tilt`] the whole path is
/// one problem (dynamic programming over the path): its points are collected (at most 5 000 000
/// grid cells) and compensated by [`path`], then given to `sink` chunk by chunk. The results equal
/// [`path`]'s. Returns the number of points.
///
/// # Errors
/// Those of [`path`] (an uncompensated point names the other failing lines of its chunk, not of
/// the whole path), the first error `points` yields, [`Error::InvalidField`] (`path`) for a path
/// without points (all as `E`), and those of `sink`.
pub fn stream<I, F, E>(
    arm: &Arm,
    compliance: &Compliance,
    points: I,
    options: &Options,
    mut sink: F,
) -> std::result::Result<usize, E>
where
    I: IntoIterator<Item = Result<PathPoint>>,
    F: FnMut(&[PathPoint], &[Compensated]) -> std::result::Result<(), E>,
    E: From<Error>,
{
    options.validate()?;
    let mut points = points.into_iter();
    if options.free.tool_rotation().is_some() || options.free.lead_tilt().is_some() {
        let cone = options.free.lead_tilt().and_then(|l| l.cone).unwrap_or(0.0);
        let mut all = Vec::new();
        for p in points {
            all.push(p?);
            check_streaming(options, all.len(), cone)?;
        }
        let results = path(arm, compliance, &all, options)?;
        for (p, r) in all.chunks(CHUNK).zip(results.chunks(CHUNK)) {
            sink(p, r)?;
        }
        return Ok(all.len());
    }
    let model = Model::new(arm, compliance)?
        .at_level(options.level)
        .with_max_iterations(options.max_iterations)
        .with_force_tolerance(options.force_tolerance);
    let (mut previous, mut count) = (options.q0, 0);
    loop {
        let chunk: Vec<PathPoint> = points.by_ref().take(CHUNK).collect::<Result<_>>()?;
        if chunk.is_empty() {
            break;
        }
        let nominal = nominal_postures(arm, &chunk, previous, options)?;
        previous = nominal[nominal.len() - 1];
        let wrenches: Vec<Vector6<f64>> = chunk
            .par_iter()
            .zip(&nominal)
            .map(|(p, q)| base_wrench(&arm.robot().frames(q), &p.wrench, p.frame))
            .collect();
        let rotations = vec![0.0; chunk.len()];
        let chosen = Chosen {
            nominal: &nominal,
            postures: &nominal,
            rotations: &rotations,
            leans: &[],
            wrenches: &wrenches,
            wrenches_before: &wrenches,
            removed: &[],
        };
        sink(&chunk, &compensate_chosen(&model, &chunk, &chosen, false)?)?;
        count += chunk.len();
    }
    match count {
        0 => Err(Error::InvalidField {
            field: "path".into(),
            message: "no path points".into(),
        }
        .into()),
        n => Ok(n),
    }
}

/// The postures chosen for a run of path points: nominal, after the tool-axis rotation (equal
/// without one), the rotations and the base-frame wrenches.
pub(super) struct Chosen<'a> {
    pub nominal: &'a [Vector6<f64>],
    pub postures: &'a [Vector6<f64>],
    pub rotations: &'a [f64],
    /// Each point's `(lead, tilt)`, rad; empty without a free lead and tilt.
    pub leans: &'a [(f64, f64)],
    pub wrenches: &'a [Vector6<f64>],
    /// The wrenches at the path's own values (the arm's frame on the path's own station).
    pub wrenches_before: &'a [Vector6<f64>],
    /// Each point's states the feasibility checks removed; empty without a free variable.
    pub removed: &'a [super::Removed],
}

/// Compensates every point at its chosen posture, in parallel; the first error in path order.
pub(super) fn compensate_chosen(
    model: &Model,
    points: &[PathPoint],
    c: &Chosen,
    free: bool,
) -> Result<Vec<Compensated>> {
    let arm = model.arm;
    let results: Vec<Result<Compensated>> = (0..points.len())
        .into_par_iter()
        .map(|i| {
            let q = &c.postures[i];
            let frames = arm.robot().frames(q);
            let newton = model
                .compensate_from(q, frames.clone(), &c.wrenches[i])
                .map_err(|e| uncompensated(points[i].line, "q_compensated", e.to_string()))?;
            check_compensated(arm, points[i].line, &newton)?;
            let d = model.tcp_deflection(&frames, &c.wrenches[i]);
            let deflection_std = model.std(&d);
            let deflection_interval = model
                .compliance
                .prediction
                .as_ref()
                .map(|p| d.interval(p, &model.compliance.h, model.level));
            let budget = model.budget(&d, newton.residual_position);
            let before = free.then(|| {
                let frames = arm.robot().frames(&c.nominal[i]);
                model.tcp_deflection(&frames, &c.wrenches_before[i])
            });
            let bound_before =
                (before.as_ref()).map(|b| model.budget(b, newton.residual_position).bound);
            let deflection_before = before.map(|b| b.displacement);
            Ok(Compensated {
                q: *q,
                pose: tool_pose(&frames, &arm.tool().tcp),
                wrench: c.wrenches[i],
                deflection: d.displacement,
                deflection_std: deflection_std.map(|s| s.0),
                translation_norm_std: deflection_std.map(|s| s.1),
                deflection_interval,
                q_compensated: newton.q,
                residual_position: newton.residual_position,
                residual_rotation: newton.residual_rotation,
                iterations: newton.iterations,
                stop: newton.stop,
                tool_rotation: c.rotations[i],
                lead: c.leans.get(i).map_or(0.0, |l| l.0),
                tilt: c.leans.get(i).map_or(0.0, |l| l.1),
                deflection_before,
                q_before: free.then_some(c.nominal[i]),
                outside_region: model.compliance.region.outside(q),
                budget,
                bound_before,
                external: points[i].external,
                removed: c.removed.get(i).copied().unwrap_or_default(),
            })
        })
        .collect();
    first_error(results)
}

/// The error of the path point at `line` that cannot be compensated; `columns` names where.
fn uncompensated(line: u64, columns: &str, reason: String) -> Error {
    Error::Column {
        line,
        column: None,
        name: columns.into(),
        problem: ColumnProblem::Uncompensated {
            reason,
            others: Vec::new(),
            failed: 1,
        },
    }
}

/// The results, or the first error (in path order) naming the lines of the other failing points
/// (the first ten).
fn first_error<T>(results: Vec<Result<T>>) -> Result<Vec<T>> {
    let failed: Vec<u64> = results
        .iter()
        .filter_map(|r| match r {
            Err(Error::Column { line, .. }) => Some(*line),
            _ => None,
        })
        .collect();
    let mut out = Vec::with_capacity(results.len());
    for r in results {
        match r {
            Ok(v) => out.push(v),
            Err(Error::Column {
                line,
                column,
                name,
                problem: ColumnProblem::Uncompensated { reason, .. },
            }) => {
                let problem = ColumnProblem::Uncompensated {
                    reason,
                    others: failed[1..].iter().take(10).copied().collect(),
                    failed: failed.len(),
                };
                return Err(Error::Column {
                    line,
                    column,
                    name,
                    problem,
                });
            }
            Err(e) => return Err(e),
        }
    }
    Ok(out)
}

/// Refuses a point compensated outside the joint limits, or whose Newton steps stopped with a
/// residual above [`REQUIRED_M`] or [`REQUIRED_RAD`].
fn check_compensated(arm: &Arm, line: u64, newton: &Newton) -> Result<()> {
    let robot = &arm.robot();
    let (ep, eo) = (newton.residual_position, newton.residual_rotation);
    if let Some(v) = robot.limits().first_violation(&newton.q) {
        return Err(uncompensated(
            line,
            "q_compensated",
            format!(
                "cannot be compensated within the joint limits: axis {} would need {:.4} deg, limits [{:.2}, {:.2}] deg",
                v.axis + 1,
                v.value.to_degrees(),
                v.lower.to_degrees(),
                v.upper.to_degrees()
            ),
        ));
    }
    if !(ep <= REQUIRED_M && eo <= REQUIRED_RAD) {
        return Err(uncompensated(
            line,
            "q_compensated",
            format!(
                "the compensation did not converge: residual {:.3} um and {:.3} urad after {} Newton steps ({}; near a singularity?)",
                ep * 1e6,
                eo * 1e6,
                newton.iterations,
                newton.stop
            ),
        ));
    }
    Ok(())
}

/// The nominal axis angles of every point: given, or by inverse kinematics continued from the
/// previous point (the first from `start`).
pub(super) fn nominal_postures(
    arm: &Arm,
    points: &[PathPoint],
    start: Vector6<f64>,
    options: &Options,
) -> Result<Vec<Vector6<f64>>> {
    let robot = &arm.robot();
    let mut previous = start;
    let mut out = Vec::with_capacity(points.len());
    for p in points {
        let q = match &p.target {
            Target::Posture(q) => {
                if let Some(v) = robot.limits().first_violation(q) {
                    let name = format!("q{}_deg", v.axis + 1);
                    return Err(Error::Column {
                        line: p.line,
                        column: None,
                        problem: v.outside(name.clone(), "the joint limits"),
                        name,
                    });
                }
                *q
            }
            Target::Pose(t) => {
                let q = ik::solve(robot, &arm.tool().tcp, t, &previous, &options.ik)
                    .map_err(|e| uncompensated(p.line, "x_mm..rz_deg", e.to_string()))?
                    .q;
                let from = if out.is_empty() {
                    "the start posture"
                } else {
                    "the previous point"
                };
                if let Some(change) =
                    Configuration::of(robot, &q).change_from(&Configuration::of(robot, &previous))
                {
                    return Err(uncompensated(p.line, "x_mm..rz_deg", format!("inverse kinematics reaches this pose only in another configuration than {from}'s ({change}); refused rather than switched silently: start in the configuration wanted (--q0-deg, q0_deg)")));
                }
                q
            }
        };
        previous = q;
        out.push(q);
    }
    Ok(out)
}
