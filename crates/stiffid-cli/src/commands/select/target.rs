//! `select --target-pct X`: the smallest group (2 to 60 postures) whose predicted mean deviation
//! rate at noise level multiple 1 is at most X % on every joint.

use super::{choose, pool, Args, Selection};
use crate::output::OutFile;
use crate::report::figures::target as figure;
use anyhow::{bail, Result};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::Path;
use stiffid::design::target::{smallest_group, TargetOutcome, MAX_POSTURES};
use stiffid::Setup;

/// The `target` object of `select --json`.
#[derive(Serialize, JsonSchema)]
pub struct TargetJson {
    /// The target: predicted mean deviation rate at noise level multiple 1, percent.
    target_pct: f64,
    /// The size of the group chosen.
    postures: usize,
    /// Every group size tried, smallest first.
    steps: Vec<StepJson>,
}

/// One group size tried.
#[derive(Serialize, JsonSchema)]
struct StepJson {
    /// Postures in the group.
    postures: usize,
    /// The joint (1-based) with the largest predicted rate.
    worst_joint: usize,
    /// Its predicted mean deviation rate, percent.
    worst_joint_pct: f64,
    /// Predicted mean deviation rate of each joint, percent.
    deviation_pct: [f64; 6],
}

impl From<&TargetOutcome> for TargetJson {
    fn from(t: &TargetOutcome) -> Self {
        Self {
            target_pct: t.target_pct,
            postures: t.steps.last().map_or(0, |s| s.postures.len()),
            steps: t
                .steps
                .iter()
                .map(|s| StepJson {
                    postures: s.postures.len(),
                    worst_joint: s.worst_joint().0 + 1,
                    worst_joint_pct: s.worst_joint().1,
                    deviation_pct: s.deviation_pct,
                })
                .collect(),
        }
    }
}

/// The smallest group that reaches `pct`, chosen from the pool or by global searches (its
/// evaluations those of every group size tried), and every group size tried. Without `--report`,
/// the figure is written beside `--out`.
///
/// # Errors
/// Neither `--pool` nor `--global`; a target no group size reaches (naming the best rate).
pub fn smallest(
    args: &Args,
    setup: &Setup,
    pool: Option<&pool::Input>,
    pct: f64,
) -> Result<(Selection, TargetOutcome)> {
    if pool.is_none() && !args.global {
        bail!("--target-pct needs --pool FILE.csv or --global to choose each group");
    }
    let max = pool.map_or(MAX_POSTURES, |p| p.usable());
    let (mut last, mut evaluations) = (None, 0);
    let outcome = smallest_group(setup, pct, max, |n| -> Result<_> {
        let s = choose(args, setup, pool, n)?;
        let postures = s.postures.clone();
        evaluations += s.evaluations;
        last = Some(s);
        Ok(postures)
    })?;
    let (Some(mut selection), Some(step)) = (last, outcome.steps.last()) else {
        bail!("--target-pct: no group size was tried");
    };
    // Every group size's search counts.
    selection.evaluations = evaluations;
    if !outcome.reached {
        let (j, worst) = step.worst_joint();
        let tried = match pool {
            Some(_) => format!("the pool's {max} usable postures"),
            None => format!("{max} postures"),
        };
        bail!(
            "--target-pct {pct}: not reachable: with {tried} the predicted mean deviation rate of joint {} is still {worst:.3} % at noise level multiple 1 (add postures to the pool, lower the noise or raise the target)",
            j + 1
        );
    }
    Ok((selection, outcome))
}

/// The figure files beside `--out` without `--report` (`OUT.target.svg`, `OUT.target.png`),
/// checked before the search.
pub fn files(out: &Path) -> Result<[OutFile; 2]> {
    let stem = out.with_extension("");
    Ok([
        OutFile::prepare(&stem.with_extension("target.svg"), "--out (target figure)")?,
        OutFile::prepare(&stem.with_extension("target.png"), "--out (target figure)")?,
    ])
}

/// Writes the figure of the group sizes tried into the [`files`].
pub fn write_figure(files: &[OutFile; 2], outcome: &TargetOutcome) -> Result<()> {
    let f = figure::figure(outcome)?;
    files[0].write(f.svg.as_bytes())?;
    files[1].write(&f.png)
}

/// The group sizes tried and their worst joint, in words.
pub fn text(t: &TargetOutcome) -> String {
    let mut s = format!(
        "smallest group predicting at most {} % on every joint (noise level multiple 1):\n",
        t.target_pct
    );
    s += &format!(
        "{:>8}  {:>11}  {:>6}\n",
        "postures", "worst joint", "rate %"
    );
    for step in &t.steps {
        let (j, w) = step.worst_joint();
        s += &format!("{:>8}  {:>11}  {:>6.3}\n", step.postures.len(), j + 1, w);
    }
    s
}
