//! `select --target-pct X`: the smallest group (2 to 60 postures) whose predicted mean deviation
//! rate at noise level multiple 1 is at most X % on every joint.

use super::{choose, pool, Args, Selection};
use crate::output::write_atomic;
use crate::report::figures::target as figure;
use anyhow::{bail, Result};
use serde::Serialize;
use stiffid::design::target::{smallest_group, TargetOutcome, MAX_POSTURES};
use stiffid::Setup;

/// The `target` object of `select --json`.
#[derive(Serialize)]
pub struct TargetJson {
    target_pct: f64,
    postures: usize,
    steps: Vec<StepJson>,
}

#[derive(Serialize)]
struct StepJson {
    postures: usize,
    worst_joint: usize,
    worst_joint_pct: f64,
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
    if args.report.is_none() {
        let f = figure::figure(&outcome)?;
        let stem = args.out.with_extension("");
        write_atomic(&stem.with_extension("target.svg"), f.svg.as_bytes())?;
        write_atomic(&stem.with_extension("target.png"), &f.png)?;
    }
    Ok((selection, outcome))
}

/// Prints the group sizes tried and their worst joint.
pub fn print(t: &TargetOutcome) {
    println!(
        "smallest group predicting at most {} % on every joint (noise level multiple 1):",
        t.target_pct
    );
    println!("{:>8}  {:>11}  {:>6}", "postures", "worst joint", "rate %");
    for s in &t.steps {
        let (j, w) = s.worst_joint();
        println!("{:>8}  {:>11}  {:>6.3}", s.postures.len(), j + 1, w);
    }
}
