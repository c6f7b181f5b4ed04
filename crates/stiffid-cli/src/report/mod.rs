//! The report of `stiffid reproduce`: `report.html` (self-contained, figures inline as SVG),
//! `report.md`, `summary.json`, `deviation_rates.csv`, one postures CSV per group and `figures/`
//! (SVG and PNG).

pub mod compensation;
mod content;
pub mod figures;
pub mod findings;
pub mod html;
mod markdown;
pub mod plan;
pub mod summary;
pub mod tables;

use crate::commands::simulate::deviation_csv;
use crate::output::write_atomic;
use crate::postures;
use anyhow::{bail, Context, Result};
use figures::Figure;
use std::path::Path;
use stiffid::design::Evaluation;
use stiffid::study::{criterion_values, Origin, Study};

/// The design criteria in reports, keyed as in `stiffid evaluate`, with what they measure.
pub const CRITERIA: [(&str, &str); 7] = [
    (
        "classical",
        "max k(J_N) over the postures (the paper's classical index)",
    ),
    (
        "zhang2021",
        "classical x cond(Psi) (the paper's novel index)",
    ),
    ("scaled_cond", "cond(Psi diag(h) / sigma), scale-free"),
    (
        "d_optimal",
        "geometric mean relative std of the compliances at level 1",
    ),
    (
        "relative_a",
        "RMS relative std of the compliances at level 1",
    ),
    (
        "test_pose_mm",
        "RMS error of the deflection predicted at the test postures, mm",
    ),
    ("cond_psi", "cond(Psi) in SI units"),
];

/// The values of [`CRITERIA`] of one group, in that order (the library's [`criterion_values`],
/// `test_pose_mm` in mm).
pub fn criteria_values(e: &Evaluation) -> [(&'static str, f64); 7] {
    let mut v = criterion_values(e);
    v[5] *= 1e3;
    std::array::from_fn(|i| (CRITERIA[i].0, v[i]))
}

/// How a group was obtained, in words.
pub fn search_words(origin: &Origin, seed: u64) -> String {
    match origin {
        Origin::Start => format!(
            "seeded random start group: a Latin hypercube in the bounds (seed {seed}; each axis range cut into 6 equal strata, one posture per stratum of every axis, uniform within it)"
        ),
        Origin::Local(c) => format!("`{c}` minimised by SQP from Group 1 (as the paper)"),
        Origin::Global(c, n) => format!(
            "`{c}` minimised globally: best of {n} SQP searches from seeded Latin-hypercube starts (beyond the paper)"
        ),
    }
}

/// Refuses to write into `dir` if it exists, is not empty and holds no report of ours (no
/// `summary.json` whose `generator` is `generator`), unless `force`.
pub fn check_target(dir: &Path, force: bool, generator: &str) -> Result<()> {
    let hint = match generator == summary::GENERATOR {
        true => " or pass --force",
        false => "",
    };
    check_dir(
        dir,
        force,
        &format!(
            "a stiffid report (no summary.json written by {generator}); choose another directory{hint}"
        ),
        |d| summary::is_ours(&d.join("summary.json"), generator),
    )
}

/// Refuses to write into `dir` if it exists and is not a directory, or is not empty and
/// `is_ours(dir)` is false, unless `force`; `refusal` says what `is_ours` recognises and what to do.
pub fn check_dir(
    dir: &Path,
    force: bool,
    refusal: &str,
    is_ours: impl Fn(&Path) -> bool,
) -> Result<()> {
    if !dir.exists() || force {
        return Ok(());
    }
    if !dir.is_dir() {
        bail!("{}: exists and is not a directory", dir.display());
    }
    let mut entries =
        std::fs::read_dir(dir).with_context(|| format!("{}: cannot read", dir.display()))?;
    if entries.next().is_none() || is_ours(dir) {
        return Ok(());
    }
    bail!("{}: not empty and not {refusal}", dir.display())
}

/// Writes every file of the report into `dir` (created if missing), each file whole;
/// `summary.json` first, so the directory is recognisably ours from then on.
pub fn write(dir: &Path, study: &Study, figures: &[Figure]) -> Result<()> {
    std::fs::create_dir_all(dir.join("figures"))
        .with_context(|| format!("{}: cannot create", dir.display()))?;
    write_atomic(&dir.join("summary.json"), summary::json(study)?.as_bytes())?;
    for f in figures {
        write_atomic(
            &dir.join("figures").join(format!("{}.svg", f.name)),
            f.svg.as_bytes(),
        )?;
        write_atomic(&dir.join("figures").join(format!("{}.png", f.name)), &f.png)?;
    }
    for g in &study.groups {
        postures::write(&dir.join(format!("{}.csv", g.name)), &g.postures)?;
    }
    let names: Vec<String> = study.groups.iter().map(|g| g.name.clone()).collect();
    let sims: Vec<_> = study.groups.iter().map(|g| g.simulation.clone()).collect();
    let csv = deviation_csv(&names, &sims, &study.setup.noise.levels);
    write_atomic(&dir.join("deviation_rates.csv"), csv.as_bytes())?;
    write_atomic(
        &dir.join("report.md"),
        markdown::report(study, figures).as_bytes(),
    )?;
    write_atomic(
        &dir.join("report.html"),
        html::report(study, figures).as_bytes(),
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{check_target, summary};

    #[test]
    fn only_empty_missing_or_own_directories_are_written_without_force() {
        let dir = std::env::temp_dir().join(format!("stiffid-target-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        assert!(
            check_target(&dir, false, summary::GENERATOR).is_ok(),
            "missing"
        );
        std::fs::create_dir_all(&dir).unwrap();
        assert!(
            check_target(&dir, false, summary::GENERATOR).is_ok(),
            "empty"
        );
        std::fs::write(dir.join("summary.json"), r#"{"generator": "someone else"}"#).unwrap();
        assert!(
            check_target(&dir, false, summary::GENERATOR).is_err(),
            "foreign summary.json"
        );
        assert!(
            check_target(&dir, true, summary::GENERATOR).is_ok(),
            "forced"
        );
        std::fs::write(
            dir.join("summary.json"),
            r#"{"generator": "stiffid reproduce"}"#,
        )
        .unwrap();
        assert!(
            check_target(&dir, false, summary::GENERATOR).is_ok(),
            "own report"
        );
        let file = dir.join("summary.json");
        assert!(
            check_target(&file, false, summary::GENERATOR).is_err(),
            "a file"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
