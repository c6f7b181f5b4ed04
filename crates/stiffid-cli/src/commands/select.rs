//! `stiffid select`: the group of postures that minimises a design criterion (local SQP from a
//! start group, global multistart, or the best of a pool of postures), optionally the smallest
//! group for a target accuracy ([`target`]) and a measurement plan (`--report`).

mod pool;
mod target;

use super::evaluate::{criteria_text, identifiable, number, CriteriaJson};
use crate::commands::common::Common;
use crate::load;
use crate::output::{self, json, OutFile};
use crate::report::plan;
use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use nalgebra::Vector6;
use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::Serialize;
use std::path::PathBuf;
use std::time::{Duration, Instant};
use stiffid::cell::Checker;
use stiffid::design::{
    self, evaluate, Criterion, Evaluation, Gradient, SearchOptions, SearchOutcome,
};
use stiffid::formats::postures;
use stiffid::limits::{self, short, Range};
use stiffid::Setup;

/// Arguments of `stiffid select`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Design criterion to minimise: classical, zhang2021, scaled-cond, d-optimal, relative-a,
    /// test-pose (or their JSON keys: relative_a, test_pose_mm, ...). The default, relative-a,
    /// ranks groups of postures as their measured accuracy does (in `stiffid reproduce`,
    /// Spearman's rho +1.00 against the simulated deviation rates); the paper's zhang2021 does not
    /// (rho -0.10): see docs/guide.md, "The paper's study".
    #[arg(long, default_value = "relative-a")]
    criterion: Criterion,
    /// Start group (posture,q1_deg,...,q6_deg) of a local search.
    #[arg(long, conflicts_with_all = ["start_random", "global", "target_pct"])]
    start: Option<PathBuf>,
    /// Start a local search from a seeded Latin-hypercube group within the bounds.
    #[arg(long, conflicts_with_all = ["global", "target_pct"])]
    start_random: bool,
    /// Global search: local searches from --starts seeded start groups, the best kept.
    #[arg(long)]
    global: bool,
    /// Choose the best --postures of the postures in this file (posture,q1_deg,...,q6_deg; at
    /// most 10000), e.g. postures taught on the pendant: exact by enumeration when there are at
    /// most 100000 groups, else the best of --restarts seeded exchange runs. Postures outside the
    /// setup's bounds are reported and skipped.
    #[arg(long, conflicts_with_all = ["start", "start_random", "global"])]
    pool: Option<PathBuf>,
    /// Exchange runs of a --pool choice, 1 to 1000 [default: 8].
    #[arg(long, requires = "pool", value_parser = clap::value_parser!(u64).range(1..=limits::MAX_POOL_RESTARTS))]
    restarts: Option<u64>,
    /// Choose the smallest group (2 to 60 postures) whose predicted mean deviation rate at noise
    /// level multiple 1 is at most this many percent on every joint (with --pool or --global);
    /// prints the group size against the worst joint's rate and plots it (into --report, else
    /// beside --out as OUT.target.svg and .png).
    #[arg(long, conflicts_with = "postures")]
    target_pct: Option<f64>,
    /// Number of postures (random or global starts, pool) [default: 6; 2 to 100].
    #[arg(long, value_parser = clap::value_parser!(u64).range(2..=limits::MAX_SEARCH_POSTURES), conflicts_with = "start")]
    postures: Option<u64>,
    /// Seed of the random start group, of the global starts or of the pool's exchange runs.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Local searches of a global search [default: 32; 1 to 10000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_STARTS))]
    starts: Option<u64>,
    /// SQP steps of every global start before the best --polished continue; 0 runs every start
    /// to convergence [default: 60; 0 to 10000000].
    #[arg(long, requires = "global", value_parser = clap::value_parser!(u64).range(0..=limits::MAX_EVALS))]
    screen_steps: Option<u64>,
    /// Global starts that continue after the screening [default: 8; 1 to 10000].
    #[arg(long, requires = "global", value_parser = clap::value_parser!(u64).range(1..=limits::MAX_STARTS))]
    polished: Option<u64>,
    /// Most criterion evaluations per local search (a value with its exact gradient counts as one,
    /// each finite-difference probe as one) [default: 6000; 1 to 10000000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_EVALS))]
    max_evals: Option<u64>,
    /// Gradient of the SQP objective: exact (closed form) or fd (forward finite differences, for
    /// comparison).
    #[arg(long, default_value_t = Gradient::Exact)]
    gradient: Gradient,
    /// Where to write the postures found (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    out: PathBuf,
    /// Also write a measurement plan into this directory: plan.html, plan.csv and figures/ (side
    /// and top view of every posture; with --target-pct, the group size against accuracy).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Write the --report into a directory that holds other files.
    #[arg(long, requires = "report")]
    force: bool,
}

/// The schema of a criterion's name: a string, one of the names of [`Criterion::ALL`].
fn criterion_name(_: &mut SchemaGenerator) -> Schema {
    let names: Vec<&str> = Criterion::ALL.iter().map(|c| c.name()).collect();
    json_schema!({ "type": "string", "enum": names })
}

/// `stiffid select --json`: the group found, how, and its criteria.
#[derive(Serialize, JsonSchema)]
pub struct SelectJson<'a> {
    /// The setup's name.
    setup: &'a str,
    /// The criterion minimised (`relative-a`, ...).
    #[schemars(schema_with = "criterion_name")]
    criterion: &'a str,
    /// `local`, `global` or `pool`.
    search: &'a str,
    /// The SQP objective's gradient (`exact` or `fd`); absent for a pool choice.
    #[serde(skip_serializing_if = "Option::is_none")]
    gradient: Option<&'a str>,
    /// The seed of the random start group, the global starts or the pool's exchange runs.
    seed: u64,
    /// The criterion of the start group; `null` for a pool choice (no start group) or an
    /// infinite value.
    start_value: Option<f64>,
    /// The criterion of the group found (`null` if infinite).
    #[schemars(with = "Option<f64>")]
    value: f64,
    /// Criterion evaluations of the search.
    evaluations: usize,
    /// Wall-clock time of the search, s.
    elapsed_s: f64,
    /// The group found, axis angles q1..q6, deg, one row per posture.
    postures_deg: Vec<[f64; 6]>,
    /// Every criterion of the group found.
    criteria: CriteriaJson,
    /// With `--pool`: the pool and the postures chosen from it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pool: Option<pool::PoolJson>,
    /// With `--target-pct`: every group size tried.
    #[serde(skip_serializing_if = "Option::is_none")]
    target: Option<target::TargetJson>,
    /// With cell checks, for a local or global search: the same search without them.
    #[serde(skip_serializing_if = "Option::is_none")]
    unconstrained: Option<UnconstrainedJson>,
    /// The postures file written (`--out`).
    out: String,
    /// The measurement plan's directory (`--report`).
    #[serde(skip_serializing_if = "Option::is_none")]
    report: Option<String>,
}

/// The unconstrained optimum beside the feasible one: what feasibility costs.
#[derive(Serialize, JsonSchema)]
struct UnconstrainedJson {
    /// Its criterion (`null` if infinite).
    #[schemars(with = "Option<f64>")]
    value: f64,
    /// Axis angles q1..q6, deg, one row per posture.
    postures_deg: Vec<[f64; 6]>,
    /// Every criterion of the unconstrained group.
    criteria: CriteriaJson,
}

/// The group a search or a pool choice found.
pub struct Selection {
    /// `local`, `global` or `pool`.
    search: &'static str,
    /// Axis angles, rad.
    postures: Vec<Vector6<f64>>,
    /// The criterion of the start group (none for a pool choice).
    start_value: Option<f64>,
    value: f64,
    evaluations: usize,
    /// For a pool choice: the chosen postures' numbers in the pool file (1-based) and how.
    pool: Option<pool::Chosen>,
}

impl Selection {
    fn from_search(search: &'static str, o: SearchOutcome) -> Self {
        Self {
            search,
            postures: o.postures,
            start_value: Some(o.start_value),
            value: o.value,
            evaluations: o.evaluations,
            pool: None,
        }
    }
}

/// Runs the search, writes the postures (and the plan) and prints the result.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let pool = match &args.pool {
        Some(path) => Some(pool::Input::read(path, &setup)?),
        None => None,
    };
    if args.start.is_some() {
        start_group(args, &setup, 0)?; // read (an input from now on) and checked before searching
    }
    if let Some(pct) = args.target_pct {
        limits::check("--target-pct", &[pct], &TARGET_PCT)?;
    }
    let out = OutFile::prepare(&args.out, "--out")?;
    let target_files = match (args.target_pct, &args.report) {
        (Some(_), None) => Some(target::files(&args.out)?),
        _ => None,
    };
    let report = args
        .report
        .as_deref()
        .map(|dir| plan::stiffness(&setup).and_then(|_| plan::open(dir, args.force)))
        .transpose()?;
    let started = Instant::now();
    let (selection, target) = match args.target_pct {
        None => {
            let n = args.postures.unwrap_or(6) as usize;
            (choose(args, &setup, pool.as_ref(), n)?, None)
        }
        Some(pct) => {
            let (s, t) = target::smallest(args, &setup, pool.as_ref(), pct)?;
            (s, Some(t))
        }
    };
    let elapsed = started.elapsed().as_secs_f64();
    identifiable(&setup, &selection.postures).with_context(|| {
        format!(
            "setup {}: the best group the search found",
            short(setup.name())
        )
    })?;
    out.write(postures::to_csv(&selection.postures).as_bytes())?;
    if let (Some(files), Some(t)) = (&target_files, &target) {
        target::write_figure(files, t)?;
    }
    if let Some(dir) = report {
        plan::write(
            dir,
            &setup,
            args.criterion,
            &selection.postures,
            target.as_ref(),
        )?;
    }
    let e = evaluate(&setup, &selection.postures);
    let free = match pool.is_none() && target.is_none() {
        true => unconstrained(args, &setup, selection.postures.len())?,
        false => None,
    };
    if args.common.json {
        let doc = SelectJson {
            setup: setup.name(),
            criterion: args.criterion.name(),
            search: selection.search,
            gradient: (selection.search != "pool").then(|| args.gradient.name()),
            seed: args.seed,
            start_value: selection.start_value,
            value: selection.value,
            evaluations: selection.evaluations,
            elapsed_s: elapsed,
            postures_deg: degrees(&selection.postures),
            criteria: CriteriaJson::from(&e),
            pool: pool.as_ref().map(|p| p.json(selection.pool.as_ref())),
            target: target.as_ref().map(target::TargetJson::from),
            unconstrained: free.as_ref().map(|(s, e)| UnconstrainedJson {
                value: s.value,
                postures_deg: degrees(&s.postures),
                criteria: CriteriaJson::from(e),
            }),
            out: args.out.display().to_string(),
            report: args.report.as_ref().map(|d| d.display().to_string()),
        };
        return output::print(&json(&doc)?);
    }
    let mut text = String::new();
    if let Some(p) = &pool {
        text += &p.text(selection.pool.as_ref());
    }
    if let Some(t) = &target {
        text += &target::text(t);
    }
    text += &outcome_text(args, &setup, &selection, elapsed);
    text += &criteria_text(&e, &setup);
    if let Some((s, free_e)) = &free {
        text += &cost_text(args.criterion, &selection, &e, s, free_e);
    }
    text += &format!("postures written to {}\n", args.out.display());
    if let Some(dir) = &args.report {
        text += &format!("plan: {}\n", dir.join("plan.html").display());
    }
    output::print(&text)
}

/// The accepted `--target-pct`.
const TARGET_PCT: Range = Range::new(1e-6, 1e4, "%");

/// With cell checks: the group of the same search of `n` postures without them, and its
/// criteria (evaluated on the setup: the criteria do not depend on the cell).
fn unconstrained(args: &Args, setup: &Setup, n: usize) -> Result<Option<(Selection, Evaluation)>> {
    if !Checker::new(setup).constrains() {
        return Ok(None);
    }
    let free = choose(args, &setup.without_cell(), None, n)?;
    let e = evaluate(setup, &free.postures);
    Ok(Some((free, e)))
}

/// What the cell's checks cost: the feasible group beside the unconstrained optimum, in words.
fn cost_text(
    criterion: Criterion,
    feasible: &Selection,
    e: &Evaluation,
    free: &Selection,
    free_e: &Evaluation,
) -> String {
    let mean = Evaluation::predicted_average_pct;
    let mut text = format!(
        "what the cell's checks cost (the same search without them):\n  {criterion}: {} feasible vs {} unconstrained ({:+.1}%)\n",
        number(feasible.value),
        number(free.value),
        100.0 * (feasible.value / free.value - 1.0),
    );
    // NaN only for a setup without a nominal stiffness (stiffid::design::Evaluation).
    if !mean(e).is_nan() {
        text += &format!(
            "  predicted mean deviation rate: {:.3}% feasible vs {:.3}% unconstrained ({:+.1}%)\n",
            mean(e),
            mean(free_e),
            100.0 * (mean(e) / mean(free_e) - 1.0)
        );
    }
    text
}

/// The group of `n` postures by the search the arguments ask for.
fn choose(args: &Args, setup: &Setup, pool: Option<&pool::Input>, n: usize) -> Result<Selection> {
    if let Some(p) = pool {
        return p.choose(args, n);
    }
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
    if args.global {
        return Ok(Selection::from_search(
            "global",
            global(setup, args.criterion, n, &options)?,
        ));
    }
    let start = start_group(args, setup, n)?;
    let bar = spinner(&format!("local search ({})", args.criterion));
    let outcome = design::local(setup, args.criterion, &start, &options);
    bar.finish_and_clear();
    Ok(Selection::from_search("local", outcome?))
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
    let outcome = design::global(setup, criterion, n, options, &|done: usize| {
        bar.set_position(done as u64)
    });
    bar.finish_and_clear();
    Ok(outcome?)
}

/// The start group of a local search: the --start file (read as an input, so --out cannot
/// overwrite it; within the setup's bounds) or a seeded random group.
fn start_group(args: &Args, setup: &Setup, n: usize) -> Result<Vec<Vector6<f64>>> {
    let Some(path) = &args.start else {
        if !args.start_random {
            bail!("give --start FILE.csv, --start-random, --global or --pool FILE.csv");
        }
        return Ok(design::random_group(setup, n, args.seed));
    };
    let start = load::postures(path, setup.robot(), Some(setup.bounds()))?;
    let most = limits::MAX_SEARCH_POSTURES as usize;
    if start.len() < 2 || start.len() > most {
        bail!(
            "{}: a search needs 2 to {most} postures, the file holds {}",
            path.display(),
            start.len()
        );
    }
    Ok(start)
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

fn outcome_text(args: &Args, setup: &Setup, s: &Selection, elapsed: f64) -> String {
    let mut text = format!(
        "{} search of {} postures on setup {} (seed {})\n",
        s.search,
        s.postures.len(),
        short(setup.name()),
        args.seed
    );
    text += &match s.start_value {
        Some(start) => {
            let factor = start / s.value;
            format!(
                "{}: {} -> {} ({})\n",
                args.criterion,
                number(start),
                number(s.value),
                match factor.is_finite() {
                    true => format!("{factor:.3}x lower"),
                    false => "the start's criterion was infinite".into(),
                }
            )
        }
        None => format!("{}: {}\n", args.criterion, number(s.value)),
    };
    text += &format!("{} evaluations in {elapsed:.2} s\n", s.evaluations);
    text + "criteria of the result (smaller is better):\n"
}
