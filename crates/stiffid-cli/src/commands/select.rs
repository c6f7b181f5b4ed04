//! `stiffid select`: the group of postures that minimises a design criterion (local SQP from a
//! start group, or global multistart).

use super::evaluate::{number, print_criteria, CriteriaJson};
use crate::output::json;
use crate::{load, postures};
use anyhow::{bail, Result};
use indicatif::{ProgressBar, ProgressStyle};
use nalgebra::Vector6;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use stiffid::design::{self, evaluate, Criterion, Gradient, SearchOptions, SearchOutcome};
use stiffid::Setup;

/// Arguments of `stiffid select`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// Design criterion to minimise: classical, zhang2021, scaled-cond, d-optimal, relative-a,
    /// test-pose.
    #[arg(long)]
    criterion: Criterion,
    /// Start group (posture,q1_deg,...,q6_deg) of a local search.
    #[arg(long, conflicts_with_all = ["start_random", "global"])]
    start: Option<PathBuf>,
    /// Start a local search from a seeded Latin-hypercube group within the bounds.
    #[arg(long, conflicts_with = "global")]
    start_random: bool,
    /// Global search: local searches from --starts seeded start groups, the best kept.
    #[arg(long)]
    global: bool,
    /// Number of postures (random or global starts) [default: 6].
    #[arg(long, value_parser = clap::value_parser!(u64).range(2..), conflicts_with = "start")]
    postures: Option<u64>,
    /// Seed of the random start group or of the global starts.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Local searches of a global search [default: 32].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    starts: Option<u64>,
    /// SQP steps of every global start before the best --polished continue; 0 runs every start
    /// to convergence [default: 60].
    #[arg(long, requires = "global")]
    screen_steps: Option<u64>,
    /// Global starts that continue after the screening [default: 8].
    #[arg(long, requires = "global", value_parser = clap::value_parser!(u64).range(1..))]
    polished: Option<u64>,
    /// Most criterion evaluations per local search (a value with its exact gradient counts as one,
    /// each finite-difference probe as one) [default: 6000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    max_evals: Option<u64>,
    /// Gradient of the SQP objective: exact (closed form) or fd (forward finite differences, for
    /// comparison).
    #[arg(long, default_value_t = Gradient::Exact)]
    gradient: Gradient,
    /// Where to write the postures found (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    out: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct SelectJson<'a> {
    setup: &'a str,
    criterion: &'a str,
    search: &'a str,
    gradient: &'a str,
    seed: u64,
    start_value: f64,
    value: f64,
    evaluations: usize,
    elapsed_s: f64,
    postures_deg: Vec<[f64; 6]>,
    criteria: CriteriaJson,
    out: String,
}

/// Runs the search, writes the postures and prints the result.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    let mut options = SearchOptions {
        seed: args.seed,
        gradient: args.gradient,
        ..SearchOptions::default()
    };
    if let Some(s) = args.starts {
        options.starts = s as usize;
    }
    if let Some(s) = args.screen_steps {
        options.screen_steps = s as usize;
    }
    if let Some(p) = args.polished {
        options.polished = p as usize;
    }
    if let Some(m) = args.max_evals {
        options.max_evals = m as usize;
    }
    let n = args.postures.unwrap_or(6) as usize;
    let started = Instant::now();
    let (search, outcome) = if args.global {
        ("global", global(&setup, args.criterion, n, &options)?)
    } else {
        let start = start_group(args, &setup, n)?;
        let bar = spinner(&format!("local search ({})", args.criterion));
        let outcome = design::local(&setup, args.criterion, &start, &options);
        bar.finish_and_clear();
        ("local", outcome?)
    };
    let elapsed = started.elapsed().as_secs_f64();
    postures::write(&args.out, &outcome.postures)?;
    let e = evaluate(&setup, &outcome.postures);
    if args.json {
        let doc = SelectJson {
            setup: &setup.name,
            criterion: args.criterion.name(),
            search,
            gradient: args.gradient.name(),
            seed: args.seed,
            start_value: outcome.start_value,
            value: outcome.value,
            evaluations: outcome.evaluations,
            elapsed_s: elapsed,
            postures_deg: degrees(&outcome.postures),
            criteria: CriteriaJson::from(&e),
            out: args.out.display().to_string(),
        };
        print!("{}", json(&doc)?);
        return Ok(());
    }
    print_outcome(args, &setup, search, &outcome, elapsed);
    print_criteria(&e);
    println!("postures written to {}", args.out.display());
    Ok(())
}

fn global(
    setup: &Setup,
    criterion: Criterion,
    n: usize,
    options: &SearchOptions,
) -> Result<SearchOutcome> {
    let bar = ProgressBar::new(options.starts as u64).with_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} starts, {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(format!("global search ({criterion})"));
    let outcome = design::global(setup, criterion, n, options, &|done| {
        bar.set_position(done as u64)
    });
    bar.finish_and_clear();
    Ok(outcome?)
}

/// The start group of a local search: the --start file (refusing to overwrite it with --out) or
/// a seeded random group.
fn start_group(args: &Args, setup: &Setup, n: usize) -> Result<Vec<Vector6<f64>>> {
    let Some(path) = &args.start else {
        if !args.start_random {
            bail!("give --start FILE.csv, --start-random or --global");
        }
        return Ok(design::random_group(setup, n, args.seed));
    };
    if same_file(path, &args.out) {
        bail!(
            "--out {}: refusing to overwrite the --start file",
            args.out.display()
        );
    }
    let start = postures::read(path, &setup.robot)?;
    for (i, q) in start.iter().enumerate() {
        let b = &setup.bounds;
        if let Some(a) = (0..6).find(|&a| q[a] < b.lower[a] || q[a] > b.upper[a]) {
            bail!(
                "{}: posture {} (line {}): q{}_deg = {} is outside the setup's bounds [{}, {}]",
                path.display(),
                i + 1,
                i + 2,
                a + 1,
                q[a].to_degrees(),
                b.lower[a].to_degrees(),
                b.upper[a].to_degrees()
            );
        }
    }
    if start.len() < 2 {
        bail!("{}: a search needs at least 2 postures", path.display());
    }
    Ok(start)
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

fn spinner(message: &str) -> ProgressBar {
    let bar = ProgressBar::new_spinner().with_message(message.to_string());
    bar.enable_steady_tick(Duration::from_millis(100));
    bar
}

fn degrees(postures: &[Vector6<f64>]) -> Vec<[f64; 6]> {
    postures
        .iter()
        .map(|q| std::array::from_fn(|a| q[a].to_degrees()))
        .collect()
}

fn print_outcome(args: &Args, setup: &Setup, search: &str, o: &SearchOutcome, elapsed: f64) {
    println!(
        "{search} search of {} postures on setup {} (seed {})",
        o.postures.len(),
        setup.name,
        args.seed
    );
    let factor = o.start_value / o.value;
    println!(
        "{}: {} -> {} ({} lower)",
        args.criterion,
        number(o.start_value),
        number(o.value),
        match factor.is_finite() {
            true => format!("{factor:.3}x"),
            false => "from a rank-deficient start".into(),
        }
    );
    println!("{} evaluations in {elapsed:.2} s", o.evaluations);
    println!("criteria of the result (smaller is better):");
}
