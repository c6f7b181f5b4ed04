//! `stiffid place`: where to clamp the part so that a program's error bound is least
//! ([`stiffid::app::place`]); writes the setup with that `[workpiece]`.

use crate::commands::common::{choice, Stiffness};
use crate::load;
use crate::output::{print_json_or, OutFile};
use crate::progress::Bars;
use anyhow::{anyhow, bail, Context, Result};
use std::path::{Path, PathBuf};
use stiffid::app::document::{mm, mm3};
use stiffid::app::place::document::{Document, Placement};
use stiffid::app::place::Effort;
use stiffid::app::place::{self, Region, Request, Work};
use stiffid::internal::machining::compensate::{Aggregate, Options};
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::Language;
use stiffid::internal::observation::deflection::Frame;
use stiffid::Progress;

/// Arguments of `stiffid place`.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("input").required(true).args(["path", "program"])))]
pub struct Args {
    /// Setup file (.toml) or built-in setup name (`stiffid setups`) with the part's own
    /// placement, `[workpiece] base_from_part`, and the tool's `[tool] tcp_mm`; its text written
    /// to --out with the placement chosen.
    #[arg(long)]
    setup: String,
    #[command(flatten)]
    stiffness: Stiffness,
    /// The G-code program (its points in the part frame), or a KUKA KRL, ABB RAPID or FANUC LS
    /// program of Cartesian targets in the part frame ($BASE or work object equal to the
    /// setup's [workpiece], LS user frame UF n >= 1 that a remark `! stiffid: user_frame = n ;`
    /// names). Joint targets are refused: they do not move with the part.
    #[arg(long, requires = "process")]
    program: Option<PathBuf>,
    /// With --program: the process file (TOML) that gives every point its cutting force.
    #[arg(long, requires = "program")]
    process: Option<PathBuf>,
    /// With a robot --program: files of the controller's backup that hold what the program
    /// declares elsewhere, or folders whose files of the program's language are read (KUKA the
    /// module's .dat and $config.dat; ABB the task's modules, .mod and .sys), as compensate
    /// reads them.
    #[arg(long, num_args = 1.., value_name = "PATH", requires = "program")]
    backup: Vec<PathBuf>,
    /// A path CSV instead of a program, as compensate reads it but each TCP pose (x_mm, y_mm,
    /// z_mm, rx_deg, ry_deg, rz_deg) in the part frame and a `base` wrench in the part frame
    /// (turning with it); rows of axis angles are refused.
    #[arg(long)]
    path: Option<PathBuf>,
    /// With --path: the frame of the wrench in rows without a `frame` value (`base`: the part
    /// frame).
    #[arg(long, value_parser = choice::<Frame>(), default_value = "base")]
    frame: Frame,
    /// Where the part frame's origin may go in the robot base frame: X0,X1,Y0,Y1 in mm (each
    /// range at most +-20000 mm).
    #[arg(long, allow_hyphen_values = true)]
    region_mm: String,
    /// The part's rotation about the base z axis (the table's normal) from its own: A0,A1 in deg,
    /// within +-180.
    #[arg(long, allow_hyphen_values = true, default_value = "-180,180")]
    rotation_deg: String,
    /// A free variable besides x, y and the rotation (repeatable, one of each; both: the six
    /// degrees of freedom), in the grammar of `compensate --free`: `z=LO..HI` (the part origin's
    /// height, mm from its own; `z` alone: -100..100) or `tilt=-T..T` (the tilt about the base x
    /// and y axes, deg, 0 < T <= 45; `tilt` alone: -10..10). A variable not given stays at its
    /// own (the height, no tilt).
    #[arg(long, value_name = "VARIABLE=LO..HI", allow_hyphen_values = true)]
    free: Vec<String>,
    /// What the placement minimises: the path's largest error bound, or their sum.
    #[arg(long, value_parser = choice::<Aggregate>(), default_value = "max")]
    objective: Aggregate,
    /// Every axis angle keeps at least this distance to its joint limits, deg (0 to 90).
    #[arg(long, default_value_t = 5.0)]
    margin_deg: f64,
    /// The TCP Jacobian's condition number stays below this everywhere (>= 1): away from
    /// singularities.
    #[arg(long, default_value_t = 1000.0)]
    max_condition: f64,
    /// The seed of the search's random samples: the same seed, the same placement.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Grid values per coordinate of x, y and the rotation (2 to 21).
    #[arg(long, default_value_t = 5)]
    grid: usize,
    /// Seeded random placements besides the grid (0 to 10000).
    #[arg(long, default_value_t = 32)]
    samples: usize,
    /// Local searches from the best placements found (1 to 16).
    #[arg(long, default_value_t = 3)]
    starts: usize,
    /// G-code arcs are split into chords of at most this sagitta, mm (1e-6 <= value <= 10).
    #[arg(long, default_value_t = 0.01)]
    chord_tolerance_mm: f64,
    /// The level of the error bound (0.5 to 0.999).
    #[arg(long, default_value_t = stiffid::internal::model::prediction::DEFAULT_LEVEL)]
    level: f64,
    /// The process force model's relative error in the error budget, percent (0 to 100).
    #[arg(long, default_value_t = 20.0)]
    force_tolerance_pct: f64,
    /// Where inverse kinematics starts for the first point, axis angles q1..q6, deg; default
    /// the setup's first test posture.
    #[arg(long, allow_hyphen_values = true)]
    q0_deg: Option<String>,
    /// The setup written with the placement chosen (a new setup file; never one of the inputs).
    #[arg(long)]
    out: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Parses, runs the place job, writes the setup, prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    // A built-in setup is written from its own text (`stiffid setups show NAME`).
    let setup_path = Path::new(&args.setup);
    let setup_text = match setup_path.is_file() {
        true => load::read(setup_path)?,
        false => stiffid::internal::setup::builtin_text(&args.setup)?.to_string(),
    };
    let compliance = args.stiffness.load(&setup)?;
    let (program, process, path, backup);
    let work = match (&args.program, &args.process, &args.path) {
        (Some(_), Some(_), None) if args.frame != Frame::Base => bail!(
            "--frame: {}",
            crate::commands::compensate::FRAME_WITHOUT_PATH
        ),
        (Some(program_path), Some(process_path), None) => {
            let name = program_path.display().to_string();
            let language = Language::of_file(&name).map_err(|e| anyhow!("--program {e}"))?;
            // A KRL program's .dat beside it, read with it as compensate does.
            let (text, data, _) = load::read_program(program_path)?;
            backup = load::read_backup(&args.backup, &name)?;
            let tolerance = args.chord_tolerance_mm * 1e-3;
            let process_name = process_path.display().to_string();
            process = file::parse(&load::read(process_path)?, &process_name)?;
            let how = (tolerance, &process);
            program = place::read_program_with(
                &setup,
                &name,
                (&text, data.as_deref(), &backup),
                language,
                how,
            )
            .map_err(option_error)?;
            Work::Program {
                program: &program,
                process: &process,
            }
        }
        (None, None, Some(p)) => {
            let text = load::read(p)?;
            path = place::read_path(&setup, &p.display().to_string(), &text, args.frame)
                .map_err(option_error)?;
            Work::Path(&path)
        }
        (None, Some(_), Some(_)) => bail!(
            "--process: only with --program: a path CSV gives each row its own wrench (--path)"
        ),
        _ => bail!("expected --program and --process, or --path"),
    };
    let mut options = Options::for_setup(&setup);
    stiffid::internal::model::prediction::check_level("--level", args.level)?;
    options.level = args.level;
    options.force_tolerance = args.force_tolerance_pct / 100.0;
    if let Some(text) = &args.q0_deg {
        options.q0 = load::posture(text, "--q0-deg", setup.robot())?.1;
    }
    let own = setup.workpiece().copied();
    let region = region(args, own.map_or(0.0, |o| o.translation.vector.z))?;
    let out = OutFile::prepare(&args.out, "--out")?;
    let request = Request {
        setup: &setup,
        setup_text: &setup_text,
        compliance: &compliance,
        work,
        options: &options,
        region,
        objective: args.objective,
        margin: args.margin_deg.to_radians(),
        max_condition: args.max_condition,
        effort: Effort {
            grid: args.grid,
            samples: args.samples,
            starts: args.starts,
            seed: args.seed,
        },
    };
    let bars = Bars::new(false);
    bars.begin("placements", 0);
    let outcome = place::run(&request);
    bars.end();
    let report = outcome.map_err(option_error)?.report;
    check_loads(&report.setup_text, &args.out)?;
    out.write(report.setup_text.as_bytes())?;
    crate::output::warnings(&report.warnings);
    print_json_or(args.json, &report.document(), |d| human(d, &args.out))
}

/// The library's error, a field that is an option named as the option (`--region-mm`).
fn option_error(e: stiffid::Error) -> anyhow::Error {
    match e {
        stiffid::Error::InvalidField { field, message } if !field.contains('.') => {
            anyhow!("--{}: {message}", field.replace('_', "-"))
        }
        e => e.into(),
    }
}

/// The region from the arguments ([`Region::from_mm_deg`]); `own_z` the part's own height (m).
fn region(args: &Args, own_z: f64) -> Result<Region> {
    let numbers = |text: &str, option: &str| -> Result<Vec<f64>> {
        text.split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|e| anyhow!("{option} {text}: {e}: expected numbers separated by commas"))
    };
    let exactly = |text: &str, option: &str| -> Result<[f64; 2]> {
        let v = numbers(text, option)?;
        v.try_into()
            .map_err(|v: Vec<f64>| anyhow!("{option} {text}: {} numbers, expected 2", v.len()))
    };
    let r: [f64; 4] = numbers(&args.region_mm, "--region-mm")?
        .try_into()
        .map_err(|v: Vec<f64>| {
            anyhow!(
                "--region-mm {}: {} numbers, expected 4 (X0,X1,Y0,Y1)",
                args.region_mm,
                v.len()
            )
        })?;
    let a = exactly(&args.rotation_deg, "--rotation-deg")?;
    Ok(Region::from_mm_deg(r, a, &args.free, own_z)?)
}

/// Parses the setup written as `--setup` would read it from `--out` (a robot file it names
/// relative to its directory must be found from there).
fn check_loads(text: &str, out: &Path) -> Result<()> {
    let dir = out.parent().unwrap_or(Path::new(""));
    load::setup_text_as_written(text, &out.display().to_string(), dir)
        .context("--out: the setup written would not load from its directory (a robot file named relative to the setup's own directory?): write it beside the setup")?;
    Ok(())
}

fn human(d: &Document, out: &Path) -> String {
    let line = |name: &str, p: &Placement| {
        let xyz_mm = mm3(&p.xyz);
        match (p.peak_bound.map(mm), p.mean_bound.map(mm)) {
        (Some(peak), Some(mean)) => format!(
            "{name:<11} xyz [{:.1}, {:.1}, {:.1}] mm, rpy [{:.2}, {:.2}, {:.2}] deg: peak bound {peak:.4} mm (line {}), mean {mean:.4} mm, joint-limit margin {:.1} deg, condition {:.1}\n",
            xyz_mm[0], xyz_mm[1], xyz_mm[2], p.rpy_deg[0], p.rpy_deg[1], p.rpy_deg[2],
            p.worst_line.unwrap_or(0),
            p.min_limit_margin.map_or(f64::NAN, f64::to_degrees),
            p.max_condition.unwrap_or(f64::NAN),
        ),
        _ => format!(
            "{name:<11} xyz [{:.1}, {:.1}, {:.1}] mm: not feasible ({})\n",
            xyz_mm[0],
            xyz_mm[1],
            xyz_mm[2],
            p.reason.unwrap_or("")
        ),
    }
    };
    let mut s = format!(
        "placement minimising the path's {} error bound ({} placements evaluated)\n",
        if d.objective == "max" {
            "largest"
        } else {
            "summed"
        },
        d.evaluations
    );
    s += &line("placed", &d.placed);
    s += &line("own", &d.own);
    s += &line("reach-only", &d.reach_only);
    if let Some(g) = d.gain_vs_own_pct {
        s += &format!("gain: {g:.1}% against the own placement, ");
    } else {
        s += "gain: ";
    }
    s += &format!(
        "{:.1}% against the reach-only placement\nwritten: {}\n",
        d.gain_vs_reach_only_pct,
        out.display()
    );
    s
}
