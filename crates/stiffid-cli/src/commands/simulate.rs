//! `stiffid simulate`: Monte Carlo identification with groups of postures from files
//! (Zhang et al. 2021, Section IV-A).

use crate::output::{json, write_atomic};
use crate::{load, postures};
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::{Path, PathBuf};
use stiffid::simulate::{simulate, GroupSimulation, Options};

/// Arguments of `stiffid simulate`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// Postures files (posture,q1_deg,...,q6_deg), one group of postures each.
    #[arg(long, num_args = 1.., required = true)]
    postures: Vec<PathBuf>,
    /// Monte Carlo runs per group and noise level.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..))]
    runs: u64,
    /// Seed of the measurement noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Directory to write deviation_rates.csv and simulation.json into (created if missing).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
}

/// One group's simulation in files: deviation rates in percent, per level then joint.
#[derive(Serialize)]
pub struct GroupJson<'a> {
    /// Name of the group.
    pub name: &'a str,
    /// Mean deviation rate, percent, [levels][6].
    pub mean_deviation_pct: &'a [[f64; 6]],
    /// Standard deviation of the deviation rate, percent, [levels][6].
    pub std_deviation_pct: &'a [[f64; 6]],
    /// First-order predicted mean deviation rate, percent, [levels][6].
    pub predicted_deviation_pct: &'a [[f64; 6]],
    /// Mean identified stiffness, Nm/rad, [levels][6].
    pub mean_stiffness_nm_per_rad: Vec<[f64; 6]>,
}

impl<'a> GroupJson<'a> {
    /// The JSON view of a group's simulation.
    pub fn new(name: &'a str, sim: &'a GroupSimulation) -> Self {
        Self {
            name,
            mean_deviation_pct: &sim.mean_deviation_pct,
            std_deviation_pct: &sim.std_deviation_pct,
            predicted_deviation_pct: &sim.predicted_deviation_pct,
            mean_stiffness_nm_per_rad: sim.mean_stiffness.iter().map(|k| (*k).into()).collect(),
        }
    }
}

#[derive(Serialize)]
struct SimulationJson<'a> {
    setup: &'a str,
    seed: u64,
    runs: usize,
    levels: &'a [f64],
    groups: Vec<GroupJson<'a>>,
}

/// Runs the simulation and prints or writes the deviation rates.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    let groups = args
        .postures
        .iter()
        .map(|p| postures::read(p, &setup.robot))
        .collect::<Result<Vec<_>>>()?;
    let names: Vec<String> = args.postures.iter().map(|p| group_name(p)).collect();
    let options = Options {
        runs: args.runs as usize,
        seed: args.seed,
    };
    let sims = simulate(&setup, &groups, &options)?;
    let doc = SimulationJson {
        setup: &setup.name,
        seed: args.seed,
        runs: options.runs,
        levels: &setup.noise.levels,
        groups: names
            .iter()
            .zip(&sims)
            .map(|(n, s)| GroupJson::new(n, s))
            .collect(),
    };
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create", dir.display()))?;
        let csv = deviation_csv(&names, &sims, &setup.noise.levels);
        write_atomic(&dir.join("deviation_rates.csv"), csv.as_bytes())?;
        write_atomic(&dir.join("simulation.json"), json(&doc)?.as_bytes())?;
    }
    match args.json {
        true => print!("{}", json(&doc)?),
        false => print_tables(&names, &sims, &setup.noise.levels, options.runs),
    }
    Ok(())
}

/// The group name of a postures file: its file stem.
fn group_name(path: &Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// `deviation_rates.csv`: one row per group, noise level and joint.
pub fn deviation_csv(names: &[String], sims: &[GroupSimulation], levels: &[f64]) -> String {
    let mut text = String::from(
        "group,level,variance_multiple,joint,mean_deviation_pct,std_deviation_pct,predicted_deviation_pct,mean_stiffness_nm_per_rad\n",
    );
    for (name, sim) in names.iter().zip(sims) {
        for (l, m) in levels.iter().enumerate() {
            for j in 0..6 {
                text += &format!(
                    "{name},{},{m},{},{:.6},{:.6},{:.6},{:.1}\n",
                    l + 1,
                    j + 1,
                    sim.mean_deviation_pct[l][j],
                    sim.std_deviation_pct[l][j],
                    sim.predicted_deviation_pct[l][j],
                    sim.mean_stiffness[l][j]
                );
            }
        }
    }
    text
}

fn print_tables(names: &[String], sims: &[GroupSimulation], levels: &[f64], runs: usize) {
    println!("mean deviation rate % (+- std over {runs} runs) [first-order prediction]");
    for (name, sim) in names.iter().zip(sims) {
        println!("\n{name}");
        println!("{:>5} {:>5}  {}", "level", "x var", joint_header());
        for (l, m) in levels.iter().enumerate() {
            let cells: Vec<String> = (0..6)
                .map(|j| {
                    format!(
                        "{:>7.3} +-{:<6.3}[{:.3}]",
                        sim.mean_deviation_pct[l][j],
                        sim.std_deviation_pct[l][j],
                        sim.predicted_deviation_pct[l][j]
                    )
                })
                .collect();
            println!("{:>5} {:>5.1}  {}", l + 1, m, cells.join(" "));
        }
    }
}

fn joint_header() -> String {
    (1..=6)
        .map(|j| format!("{:<23}", format!("joint {j}")))
        .collect::<Vec<_>>()
        .join(" ")
}
