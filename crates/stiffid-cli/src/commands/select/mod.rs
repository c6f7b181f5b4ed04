//! `stiffid select`: the group of postures that minimises a design criterion (local SQP from a
//! start group, global multistart, or the best of a pool of postures), optionally the smallest
//! group for a target accuracy and a measurement plan (`--report`): the arguments made into a
//! [`stiffid::app::select::Request`], the job run, its report rendered.

mod target;

use super::evaluate::{calibration_text, candidates_text, criteria_text, number, ForArgs};
use crate::commands::common::Common;
use crate::load;
use crate::output::{self, json, OutFile};
use crate::progress::Bars;
use crate::report::{campaign, plan};
use anyhow::{bail, Result};
use std::path::PathBuf;
use stiffid::app::document::mm;
use stiffid::app::select::document::{Document, Free, Pool};
use stiffid::app::select::{self as job, Method, PoolInput, Report, Request};
use stiffid::internal::common::limits::{self, short};
use stiffid::internal::common::words::{as_given, count};
use stiffid::internal::design::distinct::Distinctness;
use stiffid::internal::design::observability::CalibrationCriterion;
use stiffid::internal::design::{Criterion, Gradient, SearchOptions, Solver};
use stiffid::{internal::io::postures, Setup};

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
    #[arg(long)]
    criterion: Option<Criterion>,
    #[command(flatten)]
    purpose: ForArgs,
    /// Start group (posture,q1_deg,...,q6_deg) of a local search.
    #[arg(long, conflicts_with_all = ["start_random", "global"])]
    start: Option<PathBuf>,
    /// Start a local search from a seeded Latin-hypercube group within the bounds.
    #[arg(long, conflicts_with = "global")]
    start_random: bool,
    /// Global search: local searches from --starts seeded start groups, the best kept.
    #[arg(long)]
    global: bool,
    /// Choose the best --count of the postures in this file (posture,q1_deg,...,q6_deg; at
    /// most 10000), e.g. postures taught on the pendant: exact by enumeration when there are at
    /// most 100000 groups, else the best of --restarts seeded exchange runs. Postures outside the
    /// setup's bounds are reported and skipped.
    #[arg(long, conflicts_with_all = ["start", "start_random", "global"])]
    pool: Option<PathBuf>,
    /// Exchange runs of a --pool choice, 1 to 50 [default: 8].
    #[arg(long, requires = "pool", value_parser = clap::value_parser!(u64).range(1..=limits::MAX_POOL_RESTARTS))]
    restarts: Option<u64>,
    /// Forbid postures that are not distinct in a --pool choice: the pool keeps the first of
    /// every pair whose axis angles all lie within --distinct-deg or whose flanges reach the same
    /// pose (origins within --distinct-mm, orientations within --distinct-deg; a wrist flip
    /// counts).
    #[arg(long, requires = "pool")]
    distinct: bool,
    /// The axis-angle and flange-orientation distance of --distinct, 0 to 180 deg [default: 2].
    #[arg(long, requires = "distinct")]
    distinct_deg: Option<f64>,
    /// The flange-origin distance of --distinct, 0 to 10000 mm [default: 10].
    #[arg(long, requires = "distinct")]
    distinct_mm: Option<f64>,
    /// The margin every posture keeps to every constraint of the cell (line of sight, incidence,
    /// floor, obstacles, bodies, rope, [constraints]), 0 to 1000 mm, in a search and in a pool
    /// alike [default: the tracker's registration_uncertainty_mm, else 0].
    #[arg(long)]
    margin_mm: Option<f64>,
    /// Choose the smallest group (2 to 60 postures) whose predicted mean deviation rate at noise
    /// level multiple 1 is at most this many percent on every joint (with --pool or --global);
    /// prints the group size against the worst joint's rate and plots it (into --report, else
    /// beside --out as OUT.target.svg and .png).
    #[arg(long, conflicts_with = "count")]
    target_pct: Option<f64>,
    /// Number of postures (random or global starts, pool) [default: 6, 10 with --for check; 2
    /// to 100].
    #[arg(long, value_parser = clap::value_parser!(u64).range(2..=limits::MAX_SEARCH_POSTURES), conflicts_with = "start")]
    count: Option<u64>,
    /// Seed of the random start group, of the global starts or of the pool's exchange runs.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Local searches of a global search [default: 32; 1 to 10000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_STARTS))]
    starts: Option<u64>,
    /// SQP steps of every global start before the best --polished continue; 0 runs every start
    /// to convergence [default: 60; 0 to 10000000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(0..=limits::MAX_EVALS))]
    screen_steps: Option<u64>,
    /// Global starts that continue after the screening [default: 8; 1 to 10000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_STARTS))]
    polished: Option<u64>,
    /// Most criterion evaluations per local search (a value with its exact gradient counts as one,
    /// each finite-difference probe as one) [default: 6000; 1 to 10000000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=limits::MAX_EVALS))]
    max_evals: Option<u64>,
    /// Gradient of the SQP objective: exact (closed form) or fd (forward finite differences, for
    /// comparison).
    #[arg(long, default_value_t = Gradient::Exact)]
    gradient: Gradient,
    /// SQP of the local searches: auto (per criterion: active-set on relative-a, d-optimal and
    /// test-pose, slsqp on classical, zhang2021 and scaled-cond), slsqp (SLSQP, the slsqp crate)
    /// or active-set (ours: a Goldfarb-Idnani QP per step, damped BFGS; much faster in a cell and
    /// for large groups).
    #[arg(long, default_value_t = Solver::default())]
    solver: Solver,
    /// Design for the model and the candidates of `identify --compare-models` together: the
    /// setup's model with every linear candidate added (each at the drives' geometric-mean
    /// stiffness unless declared with one), with the chosen criterion, search and options; the
    /// lost motion and load-dependent candidates stay out (load steps separate them). Reports how
    /// the group identifies each candidate, as `evaluate` does. Stiffness design only.
    #[arg(long)]
    for_candidates: bool,
    /// With --for-candidates: the candidates, comma-separated, as `identify --compare-models
    /// --candidates` names them (families `tilt`, `bend`, `carriage`, `base`, `tool`, `lost`, `load`,
    /// `declared`, or single candidates); default all of them.
    #[arg(long, value_delimiter = ',')]
    candidates: Option<Vec<String>>,
    /// For a robot with external axes (a track): where the arm stands for the whole group, one
    /// value per axis in the cell's order (mm for a linear axis, deg for a rotary one,
    /// comma-separated: `--station 2500`); repeat it to try several stations (1 to 100): the
    /// group is designed at each and the best kept; with --for calibration on a track, the
    /// group is one campaign over them all (the postures dealt over the stations, at least 2 at
    /// each, designed together with the track's parameters). On a cell whose only external
    /// axes are a positioner's (the arm on a fixed base) it may be left out: the positioner
    /// moves the part, never the arm, and the group is designed with it at zero. --out gets
    /// the external axis columns.
    #[arg(long)]
    station: Vec<String>,
    /// Where to write the postures found (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    out: PathBuf,
    /// Also write a measurement plan into this directory: plan.html, plan.csv and figures/ (side
    /// and top view of every posture; with --target-pct, the group size against accuracy).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Write the --report into a directory that holds other files (without --report it has
    /// nothing to do: --out, a file, is replaced whole anyway).
    #[arg(long)]
    force: bool,
}

/// Runs the selection, writes the postures (and the plan) and prints the result.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let pool = match &args.pool {
        Some(path) => Some(PoolInput {
            name: path.display().to_string(),
            postures: load::arm_postures(path, setup.robot(), None)?,
        }),
        None => None,
    };
    // Read (an input from now on, which --out cannot overwrite) and checked before searching.
    let start = match &args.start {
        Some(path) => Some(load::arm_postures(
            path,
            setup.robot(),
            Some(setup.bounds()),
        )?),
        None => None,
    };
    if let Some(pct) = args.target_pct {
        limits::check("--target-pct", &[pct], &limits::TARGET_PCT)?;
    }
    let out = OutFile::prepare(&args.out, "--out")?;
    let target_files = match (args.target_pct, &args.report) {
        (Some(_), None) => Some(target::files(&args.out)?),
        _ => None,
    };
    let campaign = args.purpose.purpose.calibration_only();
    let report_dir = args
        .report
        .as_deref()
        .map(|dir| match campaign {
            true => plan::open(dir, args.force),
            false => plan::stiffness(&setup).and_then(|_| plan::open(dir, args.force)),
        })
        .transpose()?;
    let method = method(args, pool.is_some())?;
    let given = job::Given {
        criterion: args.criterion.is_some(),
        starts: args.starts.is_some(),
        screen_steps: args.screen_steps.is_some(),
        polished: args.polished.is_some(),
        search: job::Given::search_of(args.max_evals.is_some(), args.gradient, args.solver),
        start: args.start.is_some(),
        seed: job::Given::seed_of(args.seed),
    };
    job::check_given(args.purpose.purpose, method, given)?;
    let bars = Bars::new(false);
    let request = Request {
        setup: &setup,
        criterion: criterion(args),
        purpose: args.purpose.purpose,
        calibration: args.purpose.options(),
        method,
        start,
        pool,
        postures: (args.count).map_or(args.purpose.purpose.default_postures(), |n| n as usize),
        target_pct: args.target_pct,
        options: options(args),
        restarts: args.restarts.map(|r| r as usize),
        distinct: args.distinct.then(|| distinctness(args)).transpose()?,
        for_candidates: args.for_candidates,
        candidates: args.candidates.clone(),
        stations: stations(&args.station, &setup)?,
        progress: &bars,
        out: Some(args.out.display().to_string()),
        report_dir: args.report.as_ref().map(|d| d.display().to_string()),
    };
    let report = job::run(&request)?.report;
    output::warnings(&report.warnings);
    let placed: Vec<Vec<f64>> = report
        .placed
        .iter()
        .map(|e| e.as_slice().to_vec())
        .collect();
    let csv = match (setup.robot().external(), &report.station) {
        (axes, _) if !placed.is_empty() => postures::to_csv_cell(&report.postures, &placed, axes),
        (Some(axes), Some(e)) => postures::to_csv_at(&report.postures, axes, e),
        _ => postures::to_csv(&report.postures),
    };
    out.write(csv.as_bytes())?;
    if let (Some(files), Some(t)) = (&target_files, &report.target) {
        target::write_figure(files, t)?;
    }
    let report_dir = match (report_dir, campaign) {
        (Some(dir), true) => {
            let command = crate::commands::common::command_line();
            campaign::write(dir, &setup, &report, &csv, &command)?;
            None
        }
        (dir, _) => dir,
    };
    if let Some(dir) = report_dir {
        write_plan(dir, args, &setup, &report, placed)?;
    }
    match args.common.json {
        true => output::print(&json(&report)?),
        false => output::print(&text(args, &setup, &report, &report.document())),
    }
}

/// The plan of `--report` in `dir`: the postures at their external values (the station chosen
/// for every posture, or each posture's own), the criterion, the target and the provenance.
fn write_plan(
    dir: crate::output::ReportDir,
    args: &Args,
    setup: &Setup,
    report: &Report,
    placed: Vec<Vec<f64>>,
) -> Result<()> {
    let t = report.target.as_ref();
    let provenance = plan::Provenance {
        command: crate::commands::common::command_line(),
        seed: report.seed,
        value: report.value,
    };
    let external = match &report.station {
        Some(e) if placed.is_empty() => vec![e.as_slice().to_vec(); report.postures.len()],
        _ => placed,
    };
    plan::write(
        dir,
        setup,
        criterion(args),
        &report.postures,
        &external,
        t,
        &provenance,
    )?;
    Ok(())
}

/// The distances of `--distinct`: the flagging's defaults, overridden by the arguments.
fn distinctness(args: &Args) -> stiffid::Result<Distinctness> {
    Distinctness::try_from_deg_mm(args.distinct_deg, args.distinct_mm)
}

/// The stiffness criterion: the one given, else relative-a.
fn criterion(args: &Args) -> Criterion {
    args.criterion.unwrap_or(Criterion::RelativeA)
}

/// The method the arguments ask for.
fn method(args: &Args, pool: bool) -> Result<Method> {
    Ok(
        match (args.global, pool, args.start.is_some() || args.start_random) {
            (true, _, _) => Method::Global,
            (_, true, _) => Method::Pool,
            (_, _, true) => Method::Local,
            _ => bail!("give --start FILE.csv, --start-random, --global or --pool FILE.csv"),
        },
    )
}

/// The search options: the library's defaults, overridden by the arguments.
fn options(args: &Args) -> SearchOptions {
    let mut options = SearchOptions {
        seed: args.seed,
        gradient: args.gradient,
        solver: args.solver,
        margin: args.margin_mm.map(|m| m * 1e-3),
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
    options
}

fn text(args: &Args, setup: &Setup, r: &Report, doc: &Document) -> String {
    let mut text = String::new();
    if let Some(p) = &doc.pool {
        text += &pool_text(p);
    }
    if let Some(t) = &r.target {
        text += &target::text(t);
    }
    text += &outcome_text(setup, r);
    text += &margin_text(doc);
    text += &criteria_text(&doc.criteria, setup);
    if let Some(c) = &doc.calibration {
        text += &calibration_text(c);
    }
    if let (Some(free), Some(doc)) = (&r.unconstrained, &doc.unconstrained) {
        text += &cost_text(&objective(r), r, free.value, doc);
    }
    if let Some(c) = &doc.candidates {
        text += &format!(
            "\ndesigned for the model and {}{}\n",
            count(c.designed.len(), "candidate"),
            match c.nonlinear.is_empty() {
                true => String::new(),
                false => format!(
                    " (not for {}: load steps separate them, not postures)",
                    c.nonlinear.join(", ")
                ),
            }
        );
        text += &candidates_text(&c.identified);
        text += "\n";
    }
    text += &format!("postures written to {}\n", args.out.display());
    if let Some(dir) = &args.report {
        text += &format!("plan: {}\n", dir.join("plan.html").display());
    }
    text
}

/// The margin kept and each posture's smallest margin, in words; empty without the cell's
/// checks of lengths.
fn margin_text(doc: &Document) -> String {
    let smallest: Vec<String> = (doc.min_margins.iter())
        .map(|m| m.map_or("-".into(), |m| format!("{:.1}", mm(m))))
        .collect();
    match doc.min_margins.iter().any(Option::is_some) {
        true => format!(
            "margin kept to every constraint of the cell: {} mm; each posture's smallest: {} mm\n",
            number(as_given(mm(doc.margin))),
            smallest.join(", ")
        ),
        false => String::new(),
    }
}

/// What the pool held and what was chosen, in words.
fn pool_text(p: &Pool) -> String {
    let mut s = format!(
        "pool {}: {}, {} usable\n",
        p.file,
        count(p.postures, "posture"),
        p.usable
    );
    for k in &p.skipped {
        s += &format!("  skipped posture {}: {}\n", k.posture, k.reason);
    }
    let numbers: Vec<String> = p.chosen.iter().map(|n| n.to_string()).collect();
    let how = match p.method {
        "enumeration" => "exact, every group enumerated",
        _ => "exchange algorithm, best of the restarts",
    };
    s + &format!(
        "chosen ({how}): postures {} of the pool\n",
        numbers.join(", ")
    )
}

/// What the cell's checks cost: the feasible group beside the unconstrained optimum (of
/// minimised value `free_value`), in words, its shares from the document's `free`.
fn cost_text(criterion: &str, r: &Report, free_value: f64, free: &Free) -> String {
    let percent = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{v:+.1}"));
    let mut text = format!(
        "what the cell's checks cost (the same search without them):\n  {criterion}: {} feasible vs {} unconstrained ({}%)\n",
        number(shown(r, r.value)),
        number(shown(r, free_value)),
        percent(free.cost_pct),
    );
    // None only for a setup without a nominal stiffness (stiffid::internal::design::Evaluation).
    if let (Some(feasible), Some(unconstrained)) = (
        free.feasible_predicted_average_pct,
        free.predicted_average_pct,
    ) {
        text += &format!(
            "  predicted mean deviation rate: {feasible:.3}% feasible vs {unconstrained:.3}% unconstrained ({}%)\n",
            percent(free.predicted_average_change_pct)
        );
    }
    text
}

/// The value the search minimised, in words: the stiffness criterion, the calibration
/// criterion's loss in the text's units ([`shown`]), or both.
fn objective(r: &Report) -> String {
    use stiffid::internal::common::choice::Choice;
    let loss = |c: CalibrationCriterion| match c {
        CalibrationCriterion::TestPose => "calibration test-pose (predicted RMS error, mm)".into(),
        CalibrationCriterion::DOptimality => "calibration 1/d-optimality (1/mm^2)".into(),
        c => format!("calibration 1/{} (1/mm)", c.name()),
    };
    match &r.calibration {
        None => r.criterion.to_string(),
        Some(c) if c.weight >= 1.0 => loss(c.criterion),
        Some(c) => format!(
            "{}^{:.2} x ({})^{:.2}",
            r.criterion,
            1.0 - c.weight,
            loss(c.criterion),
            c.weight
        ),
    }
}

/// A value the search minimised (the report's SI: the calibration's predicted error in m, its
/// indices' reciprocals in 1/m or 1/m^2) in the units [`objective`] names: mm, 1/mm, 1/mm^2,
/// and for both purposes the calibration's part so scaled.
fn shown(r: &Report, value: f64) -> f64 {
    let Some(c) = &r.calibration else {
        return value;
    };
    let factor: f64 = match c.criterion {
        CalibrationCriterion::TestPose => 1e3,
        CalibrationCriterion::DOptimality => 1e-6,
        _ => 1e-3,
    };
    value * factor.powf(c.weight.min(1.0))
}

fn outcome_text(setup: &Setup, r: &Report) -> String {
    let mut text = format!(
        "{} search of {} postures on setup {} (seed {})\n",
        r.method,
        r.postures.len(),
        short(setup.name()),
        r.seed
    );
    text += &match r.start_value {
        Some(start) => {
            let factor = start / r.value;
            format!(
                "{}: {} -> {} ({})\n",
                objective(r),
                number(shown(r, start)),
                number(shown(r, r.value)),
                match factor.is_finite() {
                    true => format!("{factor:.3}x lower"),
                    false => "the start's criterion was infinite".into(),
                }
            )
        }
        None => format!("{}: {}\n", objective(r), number(shown(r, r.value))),
    };
    text += &format!("{} evaluations in {:.2} s", r.evaluations, r.elapsed_s);
    text += &match r.solver {
        Some(solver) => format!(" ({solver})\n"),
        None => "\n".into(),
    };
    if let Some(t) = r.termination {
        text += &format!("stopped: {}\n", termination_text(t, &r.terminations));
    }
    text + "criteria of the result (smaller is better):\n"
}

/// Why the search stopped: the reason of the search that found the group, and for several
/// searches how many stopped for each reason.
fn termination_text(
    t: stiffid::internal::design::Termination,
    all: &[stiffid::internal::design::Termination],
) -> String {
    let mut s = t.name().to_string();
    if all.len() > 1 {
        let counts: Vec<String> = (stiffid::internal::design::Termination::ALL.iter())
            .filter(|r| r.count(all) > 0)
            .map(|r| format!("{} {r}", r.count(all)))
            .collect();
        s += &format!(" (the {} starts: {})", all.len(), counts.join(", "));
    }
    s
}

/// The `--station` values (mm, deg, the cell's order) in SI.
fn stations(
    given: &[String],
    setup: &stiffid::Setup,
) -> Result<Vec<stiffid::internal::robot::external::ExternalValues>> {
    let Some(axes) = setup.robot().external() else {
        if !given.is_empty() {
            bail!("--station: the robot has no external axes: give no station");
        }
        return Ok(Vec::new());
    };
    given
        .iter()
        .map(|text| {
            let values: Vec<f64> = text
                .split(',')
                .map(|v| v.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .ok()
                .filter(|v: &Vec<f64>| v.len() == axes.len())
                .ok_or_else(|| {
                    anyhow::anyhow!(
                        "--station: '{}': expected {} comma-separated numbers ({})",
                        stiffid::internal::common::limits::short(text),
                        axes.len(),
                        axes.column_names().join(", ")
                    )
                })?;
            Ok(stiffid::internal::robot::external::ExternalValues::new(
                &axes.to_si(&values),
            )?)
        })
        .collect()
}
