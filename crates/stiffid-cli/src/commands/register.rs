//! `stiffid register`: the laser tracker's transform to the robot base from measuring points read
//! by the tracker at known axis angles ([`stiffid::app::register`]: Umeyama's least-squares rigid
//! transform), its residuals and standard deviation, and the `[tracker]` fragment of the setup
//! file; or, with `--count N`, the registration postures to read
//! ([`stiffid::app::register::propose`]).

use crate::commands::cell_readings::{self, three, Outcome};
use crate::output::print_json_or;
use crate::progress::Bars;
use anyhow::Result;
use stiffid::app::document::{mm, mm3};
use stiffid::app::register as job;
use stiffid::app::register::Report;
use stiffid::internal::design::registration as design;
use stiffid::Progress;

/// Arguments of `stiffid register`: `--data` holds at least 3 points not on one line; `--out`
/// gets the `[tracker] base_from_tracker` fragment. Or `--count N` proposes the postures to
/// read, and `--out` gets the readings CSV to fill in.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("readings").required(true).args(["data", "count"])))]
pub struct Args {
    #[command(flatten)]
    readings: cell_readings::Args,
    /// Propose this many registration postures (1 to 60) inside the setup's bounds that pass the
    /// cell's checks without the load (floor, obstacles, self-collision, line of sight) and
    /// minimise the predicted standard deviation of the transform's rotation (the root of its
    /// three variances at the setup's tracker noise), chosen from --candidates seeded postures.
    #[arg(long, conflicts_with = "data", value_parser = clap::value_parser!(u64).range(1..=design::MAX_POSTURES as u64))]
    count: Option<u64>,
    /// Seed of --count's candidates and exchange runs.
    #[arg(long, default_value_t = 1, requires = "count", conflicts_with = "data")]
    seed: u64,
    /// Candidate postures drawn in the bounds for --count [default: 20000; 1 to 100000].
    #[arg(long, requires = "count", conflicts_with = "data", value_parser = clap::value_parser!(u64).range(1..=design::MAX_CANDIDATES as u64))]
    candidates: Option<u64>,
    /// Exchange runs of --count, 1 to 50 [default: 8].
    #[arg(long, requires = "count", conflicts_with = "data", value_parser = clap::value_parser!(u64).range(1..=stiffid::internal::common::limits::MAX_POOL_RESTARTS))]
    restarts: Option<u64>,
}

/// Runs `stiffid register`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.readings.setup()?;
    if let Some(n) = args.count {
        return propose(args, &setup, n as usize);
    }
    let job = |request: &job::Request<'_>| {
        let report = job::run(request)?.report;
        Ok(Outcome {
            fragment: report.fragment.clone(),
            warnings: report.warnings.clone(),
            document: report,
        })
    };
    args.readings.run(&setup, job, text_of)
}

/// `--count N`: the proposal, and the readings template written with `--out`.
fn propose(args: &Args, setup: &stiffid::Setup, n: usize) -> Result<()> {
    let out = args.readings.prepare_out()?;
    let defaults = design::Options::default();
    let request = job::DesignRequest {
        setup,
        setup_name: args.readings.common.setup.clone(),
        postures: n,
        options: design::Options {
            seed: args.seed,
            candidates: args.candidates.map_or(defaults.candidates, |c| c as usize),
            restarts: args.restarts.map_or(defaults.restarts, |r| r as usize),
        },
        force: args.readings.force,
    };
    // The exchange runs report nothing as they go: a spinner says the choice is running.
    let bars = Bars::new(false);
    bars.begin("registration postures", 0);
    let proposed = job::propose(&request);
    bars.end();
    let report = proposed?.report;
    if let Some(out) = &out {
        out.write(report.document().readings_template.as_bytes())?;
    }
    print_json_or(args.readings.common.json, &report, proposal_text)
}

fn proposal_text(report: &job::DesignReport) -> String {
    let d = report.document();
    let mut text = format!(
        "{} registration postures (setup {}, seed {}): {} measuring points each\n\
         chosen from the {} of {} candidates that pass the checks {} ({}, {} groups evaluated)\n\
         \nposture  q1_deg..q6_deg\n",
        d.postures.len(),
        d.setup,
        d.seed,
        d.measuring_points,
        d.feasible,
        d.candidates,
        d.checks.join(", "),
        d.method,
        d.evaluations,
    );
    for p in &d.postures {
        let q: Vec<String> = (p.q.iter())
            .map(|v| format!("{:9.3}", v.to_degrees()))
            .collect();
        text += &format!("{:<8} {}\n", p.posture, q.join(" "));
    }
    text + &format!(
        "\npredicted at the tracker noise {:.4} mm per coordinate:\n\
         standard deviation: translation [{}] mm, rotation [{}] deg\n\
         rotation, root of the summed variances: {:.6} deg (median of 101 random feasible groups: {:.6} deg)\n",
        mm(d.noise_std),
        three(d.std.translation_std_mm, 4),
        three(d.std.rotation_std_deg, 6),
        d.rotation_std_total.to_degrees(),
        d.random_median_rotation_std_total.to_degrees(),
    )
}

fn text_of(d: &Report) -> String {
    let t = &d.transform;
    let mut text = format!(
        "registration of {} points (setup {})\n\
         base_from_tracker: xyz_mm = [{}], rpy_deg = [{}]\n\
         standard deviation: translation [{}] mm, rotation [{}] deg \
         (the robot model's frames {} mm, {} mrad; the tracker noise alone: [{}] mm, [{}] deg)\n\
         residual RMS {:.4} mm (noise per coordinate {:.4} mm)\n\
         \nposture  point  line  residual_mm\n",
        d.points.len(),
        d.setup,
        three(t.xyz_mm, 4),
        three(t.rpy_deg, 5),
        three(t.std.translation_std_mm, 4),
        three(t.std.rotation_std_deg, 5),
        mm(d.robot_frame_sd),
        d.robot_frame_sd_angle * 1e3,
        three(d.noise_only_std.translation_std_mm, 4),
        three(d.noise_only_std.rotation_std_deg, 5),
        mm(d.residual_rms),
        mm(d.noise_std),
    );
    for p in &d.points {
        text += &format!(
            "{:<8} {:>5} {:>5}  {:.4} [{}]\n",
            stiffid::internal::common::limits::short(&p.posture),
            p.point,
            p.line,
            mm(p.residual_norm),
            three(mm3(&p.residual), 4)
        );
    }
    text + "\n" + &d.fragment
}
