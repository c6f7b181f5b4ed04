//! How many encoder pulses make a degree (or a mm) of each axis of a job: the setup's
//! `[controller] pulses_per_deg` and `external_pulses`, or a `'stiffid:` comment of the job, the
//! two never contradicting (module docs of [`super`]).

use super::Context;
use crate::program::at;
use stiffid_core::common::limits::short;
use stiffid_core::{Error, Result};

/// The `'stiffid:` comments of `//INST`: the robot's and the external axes' pulses per unit,
/// with their lines.
#[derive(Default)]
pub(super) struct Directives {
    pub robot: Option<(u64, Vec<f64>)>,
    pub external: Option<(u64, Vec<f64>)>,
}

/// The relative difference within which two statements of one axis's pulses are one.
const SAME: f64 = 1e-9;

/// Whether two lists of pulses per unit are the same within [`SAME`].
fn same(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && (a.iter().zip(b)).all(|(x, y)| (x - y).abs() <= SAME * x.abs().max(y.abs()))
}

/// Reads a `'stiffid: key = numbers` comment on `line` into `directives` (other comments are
/// kept as they are and mean nothing here).
///
/// # Errors
/// [`Error::Program`] naming the line of a malformed comment, and naming both lines of a key
/// stated twice with other values.
pub(super) fn directive(line: u64, comment: &str, directives: &mut Directives) -> Result<()> {
    let Some(rest) = comment.trim().strip_prefix("stiffid:") else {
        return Ok(());
    };
    let (key, value) = rest
        .split_once('=')
        .ok_or_else(|| at(line, "'stiffid: expected 'key = numbers'".into()))?;
    let key = key.trim();
    let numbers: Vec<f64> = value
        .split([' ', ',', '\t'])
        .filter(|w| !w.is_empty())
        .map(str::parse)
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| at(line, format!("'stiffid: {}: expected numbers", short(key))))?;
    if (numbers.iter()).any(|n: &f64| !(n.is_finite() && (1e-6..=1e9).contains(&n.abs()))) {
        return Err(at(
            line,
            format!(
                "'stiffid: {}: expected pulses per unit, from 1e-6 to 1e9 in size",
                short(key)
            ),
        ));
    }
    let slot = match key {
        "pulses_per_deg" if numbers.len() == 6 => &mut directives.robot,
        "pulses_per_deg" => {
            let n = numbers.len();
            return Err(at(
                line,
                format!("'stiffid: pulses_per_deg: expected 6 numbers (S L U R B T), found {n}"),
            ));
        }
        "external_pulses" => &mut directives.external,
        other => {
            return Err(at(
                line,
                format!(
                    "'stiffid: unknown '{}' (expected pulses_per_deg or external_pulses)",
                    short(other)
                ),
            ))
        }
    };
    match slot {
        Some((first, before)) if !same(before, &numbers) => Err(at(line, format!("'stiffid: {key} stated twice with other values (lines {first} and {line}): which the controller uses cannot be known; keep one"))),
        Some(_) => Ok(()),
        None => {
            *slot = Some((line, numbers));
            Ok(())
        }
    }
}

/// The robot's six axes' pulses per degree: the setup's, or the job's comment; refused where
/// neither gives them or they differ. `first` is the line of the job's first motion.
///
/// # Errors
/// [`Error::Program`] naming the line.
pub(super) fn robot(directives: &Directives, context: &Context, first: u64) -> Result<Vec<f64>> {
    let setup = context.pulses.map(|p| p.per_deg.to_vec());
    match (&directives.robot, setup) {
        (Some((line, job)), Some(setup)) if !same(job, &setup) => Err(contradiction(*line, "pulses_per_deg", job, &setup)),
        (Some((_, job)), _) => Ok(job.clone()),
        (None, Some(setup)) => Ok(setup),
        (None, None) => Err(at(first, "the robot's positions are in pulses, and how many make a degree of each axis is the controller's (its axis parameters), which neither the setup nor the job gives: give them in the setup, [controller] pulses_per_deg = [S, L, U, R, B, T]".into())),
    }
}

/// The pulses per unit of external axis `k` (base axes first, then station axes; `count` in
/// all): the setup's `external_pulses`, or the job's comment; refused where neither gives them
/// or they differ.
///
/// # Errors
/// [`Error::Program`] naming the line.
pub(super) fn external(
    directives: &Directives,
    context: &Context,
    (k, count): (usize, usize),
    first: u64,
) -> Result<f64> {
    let setup = (context.pulses).and_then(|p| (!p.external.is_empty()).then_some(&p.external));
    let contradicted = (directives.external.as_ref()).and_then(|(line, job)| {
        let setup = setup.filter(|setup| !same(job, setup))?;
        Some(contradiction(*line, "external_pulses", job, setup))
    });
    if let Some(e) = contradicted {
        return Err(e);
    }
    let (line, list) = match (&directives.external, setup) {
        (Some((line, job)), _) => (*line, job),
        (None, Some(setup)) => (first, setup),
        (None, None) => return Err(at(first, format!("the base or station positions are in pulses, and how many make a mm or a degree is the controller's, which neither the setup nor the job gives: give them in the setup, [controller] external_pulses = [..] ({count} numbers: base axes, then station axes)"))),
    };
    list.get(k).copied().ok_or_else(|| {
        let n = list.len();
        at(
            line,
            format!(
                "external_pulses gives {n} numbers for the job's {count} base and station axes"
            ),
        )
    })
}

/// The error of a job whose `'stiffid:` comment on `line` states other pulses than the setup.
fn contradiction(line: u64, key: &str, job: &[f64], setup: &[f64]) -> Error {
    let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(", ");
    at(line, format!("'stiffid: {key} = {} contradicts the setup's [controller] {key} = [{}]: which the controller uses cannot be known; correct one (or remove the comment: the setup's suffice)", list(job), list(setup)))
}
