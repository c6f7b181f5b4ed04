//! `stiffid simulate`: Monte Carlo identification with groups of postures from files
//! (Zhang et al. 2021, Section IV-A): the files read into a [`stiffid::app::simulate::Request`],
//! the job run, its report rendered.

use crate::commands::common::Common;
use crate::load;
use crate::output::{self, json, ReportDir};
use crate::progress::Bars;
use anyhow::Result;
use std::path::{Path, PathBuf};
use stiffid::app::simulate::document::deviation_csv;
use stiffid::app::simulate::{self as job, Group, Report, Request};
use stiffid::internal::common::limits;
use stiffid::internal::design::study::simulate::Options;

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
    let request = Request {
        setup: &setup,
        groups: names
            .iter()
            .zip(groups)
            .map(|(name, postures)| Group {
                name: name.clone(),
                postures,
            })
            .collect(),
        options: Options {
            runs: args.runs as usize,
            seed: args.seed,
        },
        progress: &Bars::new(false),
    };
    let outcome = job::run(&request)?;
    output::warnings(&outcome.warnings);
    let doc = outcome.written();
    let (sims, levels) = (&doc.simulations, &doc.levels);
    if let Some(dir) = out {
        dir.write(FILES[0], deviation_csv(&names, sims, levels).as_bytes())?;
        dir.write(FILES[1], json(doc)?.as_bytes())?;
        dir.finish()?;
    }
    match args.common.json {
        true => output::print(&json(doc)?),
        false => output::print(&tables(doc)),
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

/// Every group's rates per level and parameter (drives, then virtual springs).
fn tables(doc: &Report) -> String {
    let mut s = format!(
        "mean deviation rate % (+- std over {} runs) [first-order prediction]\n",
        doc.runs
    );
    let header: Vec<String> = doc
        .parameters
        .iter()
        .map(|p| format!("{:<23}", p.name))
        .collect();
    for group in &doc.groups {
        s += &format!("\n{}\n", group.name);
        s += &format!("{:>5} {:>5}  {}\n", "level", "x var", header.join(" "));
        for (l, m) in doc.levels.iter().enumerate() {
            let cells: Vec<String> = (0..doc.parameters.len())
                .map(|j| {
                    format!(
                        "{:>7.3} +-{:<6.3}[{:.3}]",
                        group.mean_deviation_pct[l][j],
                        group.std_deviation_pct[l][j],
                        group.predicted_deviation_pct[l][j]
                    )
                })
                .collect();
            s += &format!("{:>5} {:>5.1}  {}\n", l + 1, m, cells.join(" "));
        }
    }
    s
}
