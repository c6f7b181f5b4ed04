//! `stiffid reproduce`: the paper's simulation study end to end, with a report.

use crate::progress::Bars;
use crate::report::{self, figures};
use crate::{load, output};
use anyhow::Result;
use std::path::PathBuf;
use std::time::Instant;
use stiffid::app::reproduce::document::{sentences, GENERATOR};
use stiffid::app::reproduce::{self as job, Report, Request};
use stiffid::internal::common::limits;
use stiffid::internal::design::study::{Options, DEFAULT_STARTS, DEFAULT_TRIALS};
use stiffid::internal::design::Solver;
use stiffid::Progress;

/// Arguments of `stiffid reproduce`.
#[derive(clap::Args)]
pub struct Args {
    /// Directory of the report (created if missing; an existing directory must be empty or hold a
    /// previous report, unless --force).
    #[arg(long, default_value = "stiffid-report")]
    out: PathBuf,
    /// Monte Carlo runs per group and noise level (the paper: 200) [1 to 100000].
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_RUNS))]
    runs: u64,
    /// Seed of the start group, the global searches and the noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Setup: a built-in name or a setup .toml file.
    #[arg(long, default_value = "zhang2021-comau-nj165")]
    setup: String,
    /// Local searches per global search (the beyond-the-paper groups) [1 to 10000].
    #[arg(long, default_value_t = DEFAULT_STARTS as u64, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_STARTS))]
    starts: u64,
    /// Start groups of the start-group check (the paper's local searches from other seeded start
    /// groups; 0 skips it) [0 to 2000].
    #[arg(long, default_value_t = DEFAULT_TRIALS as u64, value_parser = clap::value_parser!(u64).range(0..=limits::MAX_TRIALS))]
    trials: u64,
    /// SQP of every search: auto (per criterion: active-set on the global relative-a and d-optimal
    /// searches, slsqp on the paper's classical and zhang2021 searches), slsqp (SLSQP, the slsqp
    /// crate) or active-set (ours: a Goldfarb-Idnani QP per step, damped BFGS).
    #[arg(long, default_value_t = Solver::default())]
    solver: Solver,
    /// Write into --out even if it holds other files.
    #[arg(long)]
    force: bool,
}

/// Runs the study, writes the report, prints the summary.
pub fn run(args: &Args) -> Result<()> {
    let started = Instant::now();
    let setup = load::setup(&args.setup)?;
    let out = report::open(
        &args.out,
        "--out",
        Some(args.force),
        GENERATOR,
        &report::holds,
    )?;
    let options = Options {
        runs: args.runs as usize,
        seed: args.seed,
        starts: args.starts as usize,
        trials: args.trials as usize,
        solver: args.solver,
    };
    let bars = Bars::new(true);
    let request = Request {
        setup: &setup,
        options,
        progress: &bars,
    };
    let mut report = job::run(&request)?.report;
    output::warnings(&report.warnings);
    bars.begin("figures", 1);
    let figures = figures::all(
        &stiffid_figures::reproduce::figures(&report.study),
        figures::Png::Also,
    )?;
    bars.end();
    report.study.elapsed_s = started.elapsed().as_secs_f64();
    report::write(out, &report, &figures)?;
    let html = args.out.join("report.html");
    output::print(&(summary(&report) + &format!("\nreport: {}\n", html.display())))
}

fn summary(report: &Report) -> String {
    let study = &report.study;
    let l = study.validation_level;
    let mut s = format!(
        "\n{} runs per group and level, seed {}, {:.1} s\n\n",
        study.runs, study.seed, study.elapsed_s
    );
    s += &format!(
        "{:<28} {:>10} {:>10} {:>9} {:>9}   mean deviation rate % at level {}, joints 1-6\n",
        "group",
        "classical",
        "zhang2021",
        "rel.-a",
        "avg dev%",
        l + 1
    );
    for g in &study.groups {
        let e = &g.evaluation;
        let rates: Vec<String> = g.simulation.mean_deviation_pct[l]
            .iter()
            .map(|r| format!("{r:6.3}"))
            .collect();
        s += &format!(
            "{:<28} {:>10.4} {:>10.1} {:>9.5} {:>9.3}   {}\n",
            g.title,
            e.classical,
            e.zhang2021,
            e.relative_a,
            g.average_deviation_pct(),
            rates.join(" ")
        );
    }
    s += "\n";
    for sentence in sentences(&report.findings, study) {
        s += &format!("- {sentence}\n");
    }
    s
}
