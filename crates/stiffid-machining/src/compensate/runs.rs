//! One configuration per run: a program's cuts, each with the rapid (joint) moves that lead to
//! it, given each its own configuration of the arm (module docs of [`super`], "The free
//! configuration").

use super::configuration::{better, choose_one, evaluate_branch, Branch, Configurations, Run};
use super::stream::nominal_postures;
use super::{Aggregate, Compensated, Compliance, Options, PathPoint};
use std::ops::Range;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::setup::Arm;
use stiffid_core::Result;

/// The 0-based indices of the points that start a run, given whether each point is reached by
/// a joint move (a G-code rapid `G0`, a robot program's `PTP`, `MoveJ`, `MoveAbsJ`, `J`,
/// `MOVJ`): the first point, and each point reached by a joint move right after a point
/// reached by a cutting (linear) move, when a cutting move follows it. So a run is one cut and
/// the joint moves that lead to it (retract, traverse, approach); the joint moves after the
/// last cut end the last run, and a program without a cutting move is one run.
pub fn starts(joint: &[bool]) -> Vec<usize> {
    if joint.is_empty() {
        return Vec::new();
    }
    let last_cut = joint.iter().rposition(|j| !j).unwrap_or(0);
    let later = (1..joint.len()).filter(|&i| joint[i] && !joint[i - 1] && i < last_cut);
    std::iter::once(0).chain(later).collect()
}

/// Compensates `placed`, a path file's points in the arm's frame (on its carriage at their own
/// external values), in every configuration of the arm and keeps the best (module docs of
/// [`super`], "The free configuration"), each configuration with the other free variables of
/// `options` ([`super::path_on_track`]'s dynamic programming): [`path_runs`] with one run.
///
/// # Errors
/// [`Error::InvalidOption`](stiffid_core::Error::InvalidOption) for more than 100 000 points; [`Error::InvalidField`](stiffid_core::Error::InvalidField) (`free_configuration`)
/// without [`super::FreeVariables::configuration`]; when no configuration takes the path, the error of
/// the path's own (those of [`super::path`] and [`super::path_on_track`]).
pub fn path_configurations(
    arm: &Arm,
    compliance: &Compliance,
    placed: &[PathPoint],
    options: &Options,
) -> Result<(Vec<Compensated>, Configurations)> {
    path_runs(arm, compliance, (placed, &[0]), options)
}

/// [`path_configurations`] of a path whose runs start at the 0-based indices `starts`
/// ([`super::starts`]; the first run starts at 0 whatever they say): with
/// [`super::Scope::Run`] each run takes its own configuration, compensated alone.
///
/// # Errors
/// Those of [`path_configurations`], for the first run no configuration takes.
pub fn path_runs(
    arm: &Arm,
    compliance: &Compliance,
    (placed, starts): (&[PathPoint], &[usize]),
    options: &Options,
) -> Result<(Vec<Compensated>, Configurations)> {
    let own: Vec<ExternalValues> = placed.iter().map(|p| p.external).collect();
    let cones = match &options.free.lead_tilt() {
        Some(l) => super::lead_tilt::cones(l, placed.len(), None)?,
        None => Vec::new(),
    };
    let at = (placed, starts);
    choose(arm, compliance, at, options, |first, points, o| {
        let n = first..first + points.len();
        let cones = cones.get(n.clone()).unwrap_or(&[]);
        super::on_track(arm, compliance, points, (&own[n], false, cones), o)
    })
}

/// The path compensated in the configuration of least objective: one for the whole path
/// ([`super::Scope::Program`]), else one per run starting at `starts` ([`super::Scope::Run`]), each run
/// compensated alone by `evaluate(first, points, options)` (`first`: the 0-based index of
/// `points[0]` in the path) from the posture the path's own configuration reaches at its first
/// point. For the max, each run minimises its peak, then, its peak floored at the worst run's,
/// its sum (so the program's max is least and, for it, its sum); for the sum, each its sum.
///
/// # Errors
/// Those of [`super::path_configurations`], for the first run no configuration takes.
pub(crate) fn choose(
    arm: &Arm,
    compliance: &Compliance,
    (points, starts): (&[PathPoint], &[usize]),
    options: &Options,
    evaluate: impl Fn(usize, &[PathPoint], &Options) -> Result<Vec<Compensated>>,
) -> Result<(Vec<Compensated>, Configurations)> {
    let free = super::configuration::free_configuration(options, points.len())?;
    if free.configuration() == Some(super::Scope::Program) {
        return choose_one(arm, compliance, points, (options, 0.0), |p, o| {
            evaluate(0, p, o)
        });
    }
    let ranges = ranges(starts, points.len());
    let mut start = options.q0;
    let mut chosen = Vec::with_capacity(ranges.len());
    for r in &ranges {
        let mut at = Options {
            q0: start,
            ..options.clone()
        };
        // The run's own move times (the speed limits' clock starts again after the rapid).
        at.feasible.move_times = (options.feasible.move_times.as_deref())
            .and_then(|t| t.get(r.clone()))
            .map(|t| {
                (t.iter().enumerate())
                    .map(|(i, &d)| d.filter(|_| i > 0))
                    .collect()
            });
        let run = &points[r.clone()];
        let one = choose_one(arm, compliance, run, (&at, 0.0), |p, o| {
            evaluate(r.start, p, o)
        })?;
        // The next run starts where the path's own postures end this one.
        let own = nominal_postures(arm, run, start, &at).ok();
        start = own.and_then(|q| q.last().copied()).unwrap_or(start);
        chosen.push((at, one));
    }
    if free.aggregate == Aggregate::Max {
        let floor = (chosen.iter())
            .filter_map(|(_, (_, c))| c.branches[c.chosen].peak)
            .fold(0.0, f64::max);
        for ((at, (results, c)), r) in chosen.iter_mut().zip(&ranges) {
            let Some(k) = pick(&c.branches, floor).filter(|&k| k != c.chosen) else {
                continue;
            };
            let run = &points[r.clone()];
            *results = evaluate_branch(arm, run, (at, &c.branches[k]), |p, o| {
                evaluate(r.start, p, o)
            })?;
            c.chosen = k;
        }
    }
    Ok(combine(points, &ranges, chosen.into_iter().map(|c| c.1)))
}

/// The runs' point ranges from their starts (the first run starts at 0 whatever `starts`
/// says; a start repeated or beyond the path is none), none empty: `starts` point indices,
/// `n` the path's points.
pub(crate) fn ranges(starts: &[usize], n: usize) -> Vec<Range<usize>> {
    let mut bounds: Vec<usize> = starts.iter().copied().filter(|&s| s > 0 && s < n).collect();
    bounds.sort_unstable();
    bounds.dedup();
    bounds.insert(0, 0);
    bounds.push(n);
    bounds.windows(2).map(|w| w[0]..w[1]).collect()
}

/// The branch of least objective for the max with peaks floored at `floor`
/// ([`choose_one`]'s order).
fn pick(branches: &[Branch], floor: f64) -> Option<usize> {
    (branches.iter().enumerate())
        .filter(|(_, b)| b.takes())
        .fold(None, |best, (k, b)| match best {
            Some(j) if !better(b, &branches[j], Aggregate::Max, floor) => Some(j),
            _ => Some(k),
        })
}

/// The runs' results in path order and their configurations: the first run's branches, every
/// run, the runs' warnings each said once with the runs it concerns.
fn combine(
    points: &[PathPoint],
    ranges: &[Range<usize>],
    chosen: impl Iterator<Item = (Vec<Compensated>, Configurations)>,
) -> (Vec<Compensated>, Configurations) {
    let mut results = Vec::with_capacity(points.len());
    let mut runs = Vec::with_capacity(ranges.len());
    let mut said: Vec<(String, Vec<usize>)> = Vec::new();
    let mut first: Option<Configurations> = None;
    for (k, ((r, c), range)) in chosen.zip(ranges).enumerate() {
        results.extend(r);
        for w in &c.warnings {
            match said.iter_mut().find(|s| &s.0 == w) {
                Some(s) => s.1.push(k + 1),
                None => said.push((w.clone(), vec![k + 1])),
            }
        }
        runs.push(Run {
            points: range.clone(),
            first_line: points[range.start].line,
            last_line: points[range.end - 1].line,
            branches: c.branches.clone(),
            chosen: c.chosen,
        });
        first.get_or_insert(c);
    }
    let mut c = first.expect("a path has a point, so a run");
    c.warnings = (said.into_iter())
        .map(|(w, k)| format!("{w} (run{} {})", plural(k.len()), list(&k)))
        .collect();
    c.runs = runs;
    (results, c)
}

/// `s` after a noun for more than one.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// Run numbers, at most ten and a count of the others.
fn list(k: &[usize]) -> String {
    let shown: Vec<String> = k.iter().take(10).map(usize::to_string).collect();
    match k.len() > 10 {
        true => format!("{} and {} more", shown.join(", "), k.len() - 10),
        false => shown.join(", "),
    }
}
