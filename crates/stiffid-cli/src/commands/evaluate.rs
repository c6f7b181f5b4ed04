//! `stiffid evaluate`: every design criterion of a group of postures and its predicted deviation
//! rates.

use crate::output::json;
use crate::{feasibility, load, postures};
use anyhow::Result;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::design::{evaluate, Criterion, Evaluation};

/// Arguments of `stiffid evaluate`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// Postures file (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    postures: PathBuf,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// Every criterion of a group under the keys of `stiffid evaluate --json` (`null` for `+infinity`:
/// a rank-deficient group).
#[derive(Debug, Serialize)]
pub struct CriteriaJson {
    /// `max_i k(J_N)_i`.
    pub classical: f64,
    /// `classical * cond(Psi)`: the paper's index.
    pub zhang2021: f64,
    /// `cond(S)`.
    pub scaled_cond: f64,
    /// `det((S^T S)^-1)^(1/12)`.
    pub d_optimal: f64,
    /// `sqrt(mean_j [(S^T S)^-1]_jj)`.
    pub relative_a: f64,
    /// RMS predicted deflection error at the test postures, mm.
    pub test_pose_mm: f64,
    /// `cond_2(Psi)`, SI units.
    pub cond_psi: f64,
    /// Predicted mean deviation rate, percent, [levels][6].
    pub predicted_deviation_pct: Vec<[f64; 6]>,
}

impl From<&Evaluation> for CriteriaJson {
    fn from(e: &Evaluation) -> Self {
        Self {
            classical: e.classical,
            zhang2021: e.zhang2021,
            scaled_cond: e.scaled_cond,
            d_optimal: e.d_optimal,
            relative_a: e.relative_a,
            test_pose_mm: e.test_pose * 1e3,
            cond_psi: e.cond_psi,
            predicted_deviation_pct: e.predicted_deviation_pct.clone(),
        }
    }
}

/// `stiffid evaluate --json`: the criteria, and every posture's feasibility in the cell.
#[derive(Serialize)]
struct EvaluateJson {
    #[serde(flatten)]
    criteria: CriteriaJson,
    feasibility: Vec<feasibility::PostureJson>,
}

/// Evaluates the postures file and prints the criteria and the feasibility of every posture.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    let group = postures::read(&args.postures, &setup.robot)?;
    let e = evaluate(&setup, &group);
    let checks = feasibility::of_group(&setup, &group);
    if args.json {
        let doc = EvaluateJson {
            criteria: CriteriaJson::from(&e),
            feasibility: feasibility::json(&checks),
        };
        print!("{}", json(&doc)?);
        return Ok(());
    }
    println!(
        "{} postures of {} on setup {}",
        group.len(),
        args.postures.display(),
        setup.name
    );
    print_criteria(&e);
    println!("\npredicted mean deviation rate, % (first order)");
    println!("{:>5} {:>6}  {}", "level", "x var", joints_header());
    for (l, (m, row)) in setup
        .noise
        .levels
        .iter()
        .zip(&e.predicted_deviation_pct)
        .enumerate()
    {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:>9.4}")).collect();
        println!("{:>5} {:>6.2}  {}", l + 1, m, cells.join(" "));
    }
    feasibility::print(&checks);
    Ok(())
}

/// Prints every criterion of an evaluation, one per line (smaller is better).
pub fn print_criteria(e: &Evaluation) {
    for c in Criterion::ALL {
        let (value, unit) = match c {
            Criterion::TestPose => (e.test_pose * 1e3, " mm"),
            _ => (e.value(c), ""),
        };
        println!("  {:<12} {}{unit}", c.name(), number(value));
    }
    println!("  {:<12} {}", "cond(Psi)", number(e.cond_psi));
}

/// A criterion value for people: 6 significant digits, `inf (rank deficient)` for `+infinity`.
pub fn number(v: f64) -> String {
    if v.is_infinite() {
        "inf (rank deficient)".into()
    } else if v != 0.0 && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:.5e}")
    } else {
        format!("{v:.6}")
    }
}

fn joints_header() -> String {
    (1..=6)
        .map(|j| format!("{:>9}", format!("joint {j}")))
        .collect::<Vec<_>>()
        .join(" ")
}
