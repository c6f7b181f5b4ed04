//! `stiffid simulate`: Monte Carlo identification with groups of postures from files
//! (Zhang et al. 2021, Section IV-A).

use crate::commands::common::Common;
use crate::load;
use crate::output::{self, json, ReportDir};
use anyhow::Result;
use schemars::JsonSchema;
use serde::Serialize;
use std::path::{Path, PathBuf};
use stiffid::limits;
use stiffid::simulate::{monte_carlo, GroupSimulation, Options};

/// Arguments of `stiffid simulate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Postures files (posture,q1_deg,...,q6_deg), one group of postures each [1 to 100 files].
    #[arg(long, num_args = 1..=limits::MAX_GROUPS, required = true)]
    postures: Vec<PathBuf>,
    /// Monte Carlo runs per group and noise level [1 to 100000].
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_RUNS))]
    runs: u64,
    /// Seed of the measurement noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Directory to write deviation_rates.csv and simulation.json into (created if missing; an
    /// existing directory must be empty, unless --force).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write into --out even if it holds other files (never over an input file).
    #[arg(long, requires = "out")]
    force: bool,
}

/// One group's simulation in files: deviation rates in percent, per level then joint.
#[derive(Serialize, JsonSchema)]
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

/// `stiffid simulate --json` (and `--out DIR/simulation.json`).
#[derive(Serialize, JsonSchema)]
pub struct SimulationJson<'a> {
    /// The setup's name.
    setup: &'a str,
    /// The seed of the measurement noise.
    seed: u64,
    /// Monte Carlo runs per group and noise level.
    runs: usize,
    /// The noise level multiples of the setup's variance.
    levels: &'a [f64],
    /// One per postures file, in the order given.
    groups: Vec<GroupJson<'a>>,
}

/// Runs the simulation and prints or writes the deviation rates.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let groups = args
        .postures
        .iter()
        .map(|p| load::postures(p, setup.robot(), Some(setup.bounds())))
        .collect::<Result<Vec<_>>>()?;
    let names = group_names(&args.postures);
    let out = match &args.out {
        None => None,
        Some(dir) => Some(ReportDir::prepare(
            dir,
            "--out",
            Some(args.force),
            &|rel| FILES.iter().any(|f| rel == Path::new(f)),
            &|_| false,
        )?),
    };
    let options = Options {
        runs: args.runs as usize,
        seed: args.seed,
    };
    let sims = monte_carlo(&setup, &groups, &options)?;
    let doc = SimulationJson {
        setup: setup.name(),
        seed: args.seed,
        runs: options.runs,
        levels: &setup.noise().levels,
        groups: names
            .iter()
            .zip(&sims)
            .map(|(n, s)| GroupJson::new(n, s))
            .collect(),
    };
    if let Some(dir) = out {
        let csv = deviation_csv(&names, &sims, &setup.noise().levels);
        dir.write(FILES[0], csv.as_bytes())?;
        dir.write(FILES[1], json(&doc)?.as_bytes())?;
        dir.finish()?;
    }
    match args.common.json {
        true => output::print(&json(&doc)?),
        false => output::print(&tables(&names, &sims, &setup.noise().levels, options.runs)),
    }
}

/// The files of `--out`.
const FILES: [&str; 2] = ["deviation_rates.csv", "simulation.json"];

/// The group name of each postures file: its file stem, or the path as given where two files
/// share a stem (the same path twice gets ` (2)`, ...).
fn group_names(paths: &[PathBuf]) -> Vec<String> {
    let stem = |p: &Path| p.file_stem().map(|s| s.to_string_lossy().into_owned());
    let mut names: Vec<String> = Vec::with_capacity(paths.len());
    for p in paths {
        let shared = paths.iter().filter(|q| stem(q) == stem(p)).count() > 1;
        let base = match (stem(p), shared) {
            (Some(s), false) => s,
            _ => p.display().to_string(),
        };
        let seen = names
            .iter()
            .filter(|n| n.split(" (").next() == Some(base.as_str()))
            .count();
        names.push(match seen {
            0 => base,
            k => format!("{base} ({})", k + 1),
        });
    }
    names
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
                    "{},{},{m},{},{:.6},{:.6},{:.6},{:.1}\n",
                    output::csv_field(name),
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

fn tables(names: &[String], sims: &[GroupSimulation], levels: &[f64], runs: usize) -> String {
    let mut s =
        format!("mean deviation rate % (+- std over {runs} runs) [first-order prediction]\n");
    for (name, sim) in names.iter().zip(sims) {
        s += &format!("\n{name}\n");
        s += &format!("{:>5} {:>5}  {}\n", "level", "x var", joint_header());
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
            s += &format!("{:>5} {:>5.1}  {}\n", l + 1, m, cells.join(" "));
        }
    }
    s
}

fn joint_header() -> String {
    (1..=6)
        .map(|j| format!("{:<23}", format!("joint {j}")))
        .collect::<Vec<_>>()
        .join(" ")
}
