//! The free configuration: the path evaluated in every configuration of the arm (the shoulder,
//! elbow and wrist branches of inverse kinematics, up to eight), the one of least path
//! objective kept (module docs of [`super`], "The free configuration").

use super::feasible::Checks;
use super::{Aggregate, Compensated, Compliance, Free, FreeVariables, Model, Objective, Options};
use super::{PathPoint, Removed, Target};
use nalgebra::{Isometry3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::ops::Range;
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::ik::{self, tool_pose};
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result, Robot};

/// One configuration of the arm evaluated over the path.
#[derive(Debug, Clone, PartialEq)]
pub struct Branch {
    /// The configuration of its posture at the path's first point, whose axis angles start the
    /// path in it.
    pub configuration: Configuration,
    /// Whether it is the path's own (the posture the path gives, or inverse kinematics reaches
    /// from the start posture).
    pub own: bool,
    /// The largest cost of a point (m): the deflection's length or the bound; `None` when
    /// refused.
    pub peak: Option<f64>,
    /// The sum of the points' costs (m); `None` when refused.
    pub sum: Option<f64>,
    /// Why the configuration cannot take the path: the line of the first point that fails
    /// (`None`: no point is to blame) and why; `None` when it can.
    pub refused: Option<(Option<u64>, String)>,
}

impl Branch {
    /// The path's objective in this configuration (the peak or the sum, with the other as the
    /// tie-break), `None` when refused; a peak below `floor` (m) counts as `floor` (a run whose
    /// peak is below the program's worst run's).
    fn value(&self, aggregate: Aggregate, floor: f64) -> Option<(f64, f64)> {
        let (peak, sum) = (self.peak?, self.sum?);
        Some(match aggregate {
            Aggregate::Sum => (sum, peak),
            Aggregate::Max => (peak.max(floor), sum),
        })
    }

    /// Whether it may be chosen: it takes the path, or it is the path's own and reaches every
    /// point (the no-worse rule keeps it whatever the checks say).
    pub(super) fn takes(&self) -> bool {
        self.peak.is_some() && (self.own || self.refused.is_none())
    }
}

/// Every configuration of the arm evaluated over the path, and the one chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct Configurations {
    /// What a point costs.
    pub objective: Objective,
    /// How the costs add up.
    pub aggregate: Aggregate,
    /// The configurations found at the first point, ordered by their shoulder, elbow and wrist
    /// choices (front before back, elbow up before down, axis 5 positive before negative).
    pub branches: Vec<Branch>,
    /// The index in `branches` of the one chosen.
    pub chosen: usize,
    /// What the user should know: the path's own kept for want of another, or refused.
    pub warnings: Vec<String>,
    /// With one configuration per run ([`super::Scope::Run`]): each run's, in path order
    /// (`branches` and `chosen` are then the first run's); empty with one per program.
    pub runs: Vec<Run>,
}

/// One run's configurations, the one chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// Its points: 0-based indices into the path.
    pub points: Range<usize>,
    /// The line of its first point.
    pub first_line: u64,
    /// The line of its last point.
    pub last_line: u64,
    /// The configurations found at its first point ([`Configurations::branches`]).
    pub branches: Vec<Branch>,
    /// The index in `branches` of the one chosen.
    pub chosen: usize,
}

impl Configurations {
    /// The axis angles (rad) that start the path in the configuration chosen (per run, the
    /// first run's), `None` when it is the path's own (its start posture starts it).
    pub fn start(&self) -> Option<Vector6<f64>> {
        let b = &self.branches[self.chosen];
        (!b.own).then(|| Vector6::from(b.configuration.q_deg).map(f64::to_radians))
    }

    /// `points` as the configuration chosen takes them: as they are in the path's own, else
    /// their poses (every posture target replaced by its TCP pose).
    pub fn in_chosen(&self, arm: &Arm, points: &[PathPoint]) -> Vec<PathPoint> {
        match self.branches[self.chosen].own {
            true => points.to_vec(),
            false => posed(arm, points),
        }
    }
}

/// `points` with every posture target replaced by its TCP pose (forward kinematics at the arm's
/// TCP), for inverse kinematics to solve in another configuration.
pub(crate) fn posed(arm: &Arm, points: &[PathPoint]) -> Vec<PathPoint> {
    let pose = |q: &Vector6<f64>| tool_pose(&arm.robot().frames(q), &arm.tool().tcp);
    (points.iter())
        .map(|p| match &p.target {
            Target::Posture(q) => PathPoint {
                target: Target::Pose(pose(q)),
                ..p.clone()
            },
            Target::Pose(_) => p.clone(),
        })
        .collect()
}

/// The path compensated by `evaluate` in every configuration of the arm, the best kept (module
/// docs of [`super`]): the path's own as given, every other from its posture at the first
/// point with the points' poses (each posture target replaced by its TCP pose), refused where a point fails, a posture fails the
/// checks of [`Options::feasible`] or leaves the configuration; a peak below `floor` (m) counts
/// as `floor` ([`Branch::value`]).
///
/// # Errors
/// Those of [`path_configurations`].
pub(super) fn choose_one(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    (options, floor): (&Options, f64),
    evaluate: impl Fn(&[PathPoint], &Options) -> Result<Vec<Compensated>>,
) -> Result<(Vec<Compensated>, Configurations)> {
    let free = free_configuration(options, points.len())?;
    let Some(first) = points.first() else {
        return Err(Error::InvalidField {
            field: "path".into(),
            message: "no path points".into(),
        });
    };
    let mut alone = options.clone();
    alone.free = alone.free.keeping(|f| !matches!(f, Free::Configuration(_)));
    let own_start = own_start(arm, first, options);
    let starts = starts(arm, first, own_start, options);
    let model = Model::new(arm, compliance)?;
    let checks = Checks::new(&model, &options.feasible);
    let moved = posed(arm, points);
    let mut best: Option<(usize, Vec<Compensated>)> = None;
    let mut own_error = None;
    let mut branches: Vec<Branch> = Vec::with_capacity(starts.len());
    for q in &starts {
        let own = own_start == Some(*q);
        let outcome = match own {
            true => evaluate(points, &alone),
            false => evaluate(
                &moved,
                &Options {
                    q0: *q,
                    ..alone.clone()
                },
            ),
        };
        let configuration = Configuration::of(arm.robot(), q);
        let mut branch = Branch {
            configuration,
            own,
            peak: None,
            sum: None,
            refused: None,
        };
        match outcome {
            Err(e) => {
                let before = (points.iter())
                    .position(|p| Some(p.line) == line_of(&e))
                    .filter(|&i| i > 0);
                // A point before the one that fails may fail a check or its compensation (the nominal
                // postures are solved first): evaluated up to it.
                let earlier = before.and_then(|i| {
                    let run = match own {
                        true => evaluate(&points[..i], &alone),
                        false => evaluate(
                            &moved[..i],
                            &Options {
                                q0: *q,
                                ..alone.clone()
                            },
                        ),
                    };
                    match run {
                        Ok(run) => {
                            refusal(arm.robot(), &configuration, (&points[..i], &run), &checks)
                        }
                        Err(e) => Some((line_of(&e), e.to_string())),
                    }
                });
                branch.refused = Some(earlier.unwrap_or((line_of(&e), e.to_string())));
                if own {
                    own_error = Some(e);
                }
            }
            Ok(results) => {
                let costs: Vec<f64> = results.iter().map(|r| cost(free.minimise, r)).collect();
                branch.peak = Some(costs.iter().copied().fold(0.0, f64::max));
                branch.sum = Some(costs.iter().sum());
                branch.refused = refusal(arm.robot(), &configuration, (points, &results), &checks);
                // The path's own is kept whatever the checks say (the no-worse rule).
                if branch.takes()
                    && best
                        .as_ref()
                        .is_none_or(|b| better(&branch, &branches[b.0], free.aggregate, floor))
                {
                    best = Some((branches.len(), results));
                }
            }
        }
        branches.push(branch);
    }
    if best.is_none() && own_error.is_none() {
        // The start posture reaches no posture at the first point: the path's own error.
        own_error = evaluate(points, &alone).err();
    }
    finish(branches, best, own_error, free)
}

/// Whether branch `a` is better than `b`: a lower objective (its tie-break next), or equal and
/// the path's own. Values within [`super::TIE_BREAK`] of each other (relative) are equal: a
/// gain below it is not worth another configuration (a spherical wrist's flip gives the same
/// deflections to rounding). A peak below `floor` counts as `floor` ([`Branch::value`]).
pub(super) fn better(a: &Branch, b: &Branch, aggregate: Aggregate, floor: f64) -> bool {
    let below = |x: f64, y: f64| x < y - super::TIE_BREAK * y.abs();
    match (a.value(aggregate, floor), b.value(aggregate, floor)) {
        (Some(v), Some(w)) if below(v.0, w.0) => true,
        (Some(v), Some(w)) if below(w.0, v.0) => false,
        (Some(v), Some(w)) if below(v.1, w.1) => !b.own,
        (Some(v), Some(w)) if below(w.1, v.1) => a.own,
        (Some(_), Some(_)) => a.own && !b.own,
        (Some(_), None) => true,
        _ => false,
    }
}

/// The chosen branch's results and every branch, or the path's own error when no branch takes
/// the path; a warning when the path's own is kept for want of another or was refused.
fn finish(
    branches: Vec<Branch>,
    best: Option<(usize, Vec<Compensated>)>,
    own_error: Option<Error>,
    free: FreeVariables,
) -> Result<(Vec<Compensated>, Configurations)> {
    let Some((chosen, results)) = best else {
        return Err(own_error.unwrap_or_else(|| Error::InvalidField {
            field: "free_configuration".into(),
            message: format!(
                "no configuration of the arm takes the path: {}",
                (branches.iter())
                    .filter_map(|b| b.refused.as_ref().map(|r| r.1.clone()))
                    .collect::<Vec<_>>()
                    .join("; ")
            ),
        }));
    };
    let mut warnings = Vec::new();
    let others = branches.iter().filter(|b| !b.own).count();
    let open = (branches.iter()).any(|b| !b.own && b.refused.is_none());
    if branches[chosen].own && !open {
        warnings.push(format!(
            "no other configuration of the arm takes the path ({others} found at its first point, each refused: see configurations): the path's own kept"
        ));
    }
    if let Some(own) = branches.iter().find(|b| b.own && b.peak.is_none()) {
        warnings.push(format!(
            "the path's own configuration cannot take it ({}): another chosen",
            own.refused.as_ref().map_or("", |r| r.1.as_str())
        ));
    }
    let configurations = Configurations {
        objective: free.minimise,
        aggregate: free.aggregate,
        branches,
        chosen,
        warnings,
        runs: Vec::new(),
    };
    Ok((results, configurations))
}

/// `points` compensated by `evaluate` in `branch`'s configuration, as [`choose_one`] did
/// (the path's own as given, another from its first posture with the points' poses).
///
/// # Errors
/// Those of `evaluate`.
pub(super) fn evaluate_branch(
    arm: &Arm,
    points: &[PathPoint],
    (options, branch): (&Options, &Branch),
    evaluate: impl Fn(&[PathPoint], &Options) -> Result<Vec<Compensated>>,
) -> Result<Vec<Compensated>> {
    let mut alone = options.clone();
    alone.free = alone.free.keeping(|f| !matches!(f, Free::Configuration(_)));
    match branch.own {
        true => evaluate(points, &alone),
        false => evaluate(
            &posed(arm, points),
            &Options {
                q0: Vector6::from(branch.configuration.q_deg).map(f64::to_radians),
                ..alone
            },
        ),
    }
}

/// A point's cost under `objective`: its deflection's length or its bound, m.
fn cost(objective: Objective, r: &Compensated) -> f64 {
    match objective {
        Objective::Deflection => r.deflection.fixed_rows::<3>(0).norm(),
        _ => r.budget.bound,
    }
}

/// The line an error names, if any.
fn line_of(e: &Error) -> Option<u64> {
    match e {
        Error::Column { line, .. } | Error::Program { line, .. } => Some(*line),
        Error::Input { error, .. } => line_of(error),
        _ => None,
    }
}

/// Why a configuration's compensated path is refused: the first point whose posture fails a
/// check of `checks` or is in another configuration than `configuration`.
fn refusal(
    robot: &Robot,
    configuration: &Configuration,
    (points, results): (&[PathPoint], &[Compensated]),
    checks: &Checks,
) -> Option<(Option<u64>, String)> {
    points.iter().zip(results).find_map(|(p, r)| {
        let touching = checks.touching(Some(&r.q), &r.external);
        let why = match checks.fails(&r.q, &r.external, &touching) {
            Some(removed) => failed_check(removed),
            None => {
                let change = Configuration::of(robot, &r.q).change_from(configuration)?;
                format!("the posture leaves the configuration ({change})")
            }
        };
        Some((Some(p.line), why))
    })
}

/// The check a posture failed, in words.
fn failed_check(removed: Removed) -> String {
    match removed {
        Removed {
            limit_margin: 1, ..
        } => "an axis angle within the margin of its joint limit",
        Removed { singularity: 1, .. } => "the TCP Jacobian's condition number above the largest",
        _ => "a collision in the cell",
    }
    .into()
}

/// The path's own posture at its first point: the one it gives, or inverse kinematics' from
/// the start posture; `None` where that fails.
fn own_start(arm: &Arm, first: &PathPoint, options: &Options) -> Option<Vector6<f64>> {
    match &first.target {
        Target::Posture(q) => Some(*q),
        Target::Pose(t) => (ik::solve(arm.robot(), &arm.tool().tcp, t, &options.q0, &options.ik))
            .ok()
            .map(|s| s.q),
    }
}

/// The shoulder, elbow and wrist choices of a configuration, as bits: behind axis 1 (4), elbow
/// down (2), axis 5 negative (1).
fn key(c: &Configuration) -> u8 {
    4 * u8::from(c.behind()) + 2 * u8::from(c.elbow_down()) + u8::from(c.wrist_negative())
}

/// One posture per configuration that reaches the first point's pose, ordered by [`key`]: the
/// path's own, and for each other the solution nearest to it (else to the start posture) among
/// inverse kinematics from [`super::CONFIGURATION_SEEDS`] seeded random starts and the own
/// posture with its wrist turned over.
fn starts(
    arm: &Arm,
    first: &PathPoint,
    own: Option<Vector6<f64>>,
    options: &Options,
) -> Vec<Vector6<f64>> {
    let robot = arm.robot();
    let tcp = &arm.tool().tcp;
    let target: Isometry3<f64> = match &first.target {
        Target::Pose(t) => *t,
        Target::Posture(q) => tool_pose(&robot.frames(q), tcp),
    };
    let near = own.unwrap_or(options.q0);
    let mut rng = ChaCha8Rng::seed_from_u64(options.ik.seed);
    let mut seeds: Vec<Vector6<f64>> = (0..super::CONFIGURATION_SEEDS)
        .map(|_| ik::random_posture(robot, &mut rng))
        .collect();
    let pi = std::f64::consts::PI;
    for (d4, d6) in [(pi, pi), (pi, -pi), (-pi, pi), (-pi, -pi)] {
        seeds.push(near + Vector6::new(0.0, 0.0, 0.0, d4, -2.0 * near[4], d6));
    }
    let single = ik::Options {
        restarts: 0,
        ..options.ik
    };
    let found: Vec<Option<Vector6<f64>>> = (seeds.par_iter())
        .map(|s| ik::solve(robot, tcp, &target, s, &single).ok().map(|s| s.q))
        .collect();
    let mut best: [Option<(f64, Vector6<f64>)>; 8] = [None; 8];
    let candidates = own.into_iter().map(|q| (q, true));
    for (q, is_own) in candidates.chain(found.into_iter().flatten().map(|q| (q, false))) {
        let k = key(&Configuration::of(robot, &q)) as usize;
        let d = if is_own { -1.0 } else { (q - near).norm() };
        if best[k].is_none_or(|(b, _)| d < b) {
            best[k] = Some((d, q));
        }
    }
    best.iter().flatten().map(|b| b.1).collect()
}

/// The free variables of `options` with a free configuration, for a path of `points` points.
///
/// # Errors
/// [`Error::InvalidField`] (`free_configuration`) without one; [`Error::InvalidOption`]
/// ([`JobOption::Configuration`]) for more than [`super::MAX_CONFIGURATION_POINTS`] points.
pub(super) fn free_configuration(options: &Options, points: usize) -> Result<FreeVariables> {
    if options.free.configuration().is_none() {
        return Err(Error::InvalidField {
            field: "free_configuration".into(),
            message: "missing: the configurations are evaluated for a free configuration".into(),
        });
    }
    if points > super::MAX_CONFIGURATION_POINTS {
        return Err(Error::InvalidOption {
            option: JobOption::Configuration,
            message: format!(
                "{points} path points: at most {} (every configuration holds the whole path)",
                super::MAX_CONFIGURATION_POINTS
            ),
        });
    }
    Ok(options.free.clone())
}
