//! `stiffid force`: the mean cutting force of every operation of a process file, feed frame
//! ([`stiffid::internal::machining::process`]).

use crate::load;
use crate::output::print_json_or;
use crate::progress::Bars;
use anyhow::Result;
use std::path::PathBuf;
use stiffid::app::force::{self, Report, Request};
use stiffid::internal::machining::process::file;
use stiffid::Progress;

/// Arguments of `stiffid force`.
#[derive(clap::Args)]
pub struct Args {
    /// Process file (TOML): [tool] diameter_mm, flutes, helix_deg; [cut] feed_per_tooth_mm,
    /// axial_depth_mm, radial_depth_mm, mode = "up" | "down"; [coefficients] preset or
    /// k_tc_n_per_mm2 .. k_ae_n_per_mm (or [[operation]] tables of the same).
    #[arg(long)]
    process: PathBuf,
    /// Also the peak force over one revolution, on a grid of spindle angles this far apart, deg
    /// (0.01 <= value <= 10).
    #[arg(long)]
    peak_resolution_deg: Option<f64>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Parses, runs the force job, prints.
pub fn run(args: &Args) -> Result<()> {
    let name = args.process.display().to_string();
    let parsed = file::parse(&load::read(&args.process)?, &name)?;
    let request = Request {
        name,
        process: &parsed,
        peak_resolution_deg: args.peak_resolution_deg,
    };
    // The job reports no count: a spinner while the peaks are searched.
    let bars = Bars::new(false);
    bars.begin("forces", 0);
    let outcome = force::run(&request);
    bars.end();
    let outcome = outcome.map_err(|e| match e {
        stiffid::Error::InvalidField { field, message } => {
            anyhow::anyhow!("--{}: {message}", field.replace('_', "-"))
        }
        e => e.into(),
    })?;
    print_json_or(args.json, outcome.written(), human)
}

fn human(d: &Report) -> String {
    let mut s = format!(
        "mean force on the tool over one revolution, feed frame [feed, normal, axial], N ({}):\n",
        d.name
    );
    let v = |x: &[f64; 3]| format!("[{:.1}, {:.1}, {:.1}]", x[0], x[1], x[2]);
    for o in &d.operations {
        s += &format!("{} ({}): {}", o.name, o.kind, v(&o.mean_force_n));
        if o.mean_moment_nm != [0.0; 3] {
            s += &format!(", moment {} Nm", v(&o.mean_moment_nm));
        }
        if let Some(p) = &o.peak_force_n {
            let norm = p.iter().map(|x| x * x).sum::<f64>().sqrt();
            s += &format!(", peak {} ({norm:.1} N)", v(p));
        }
        s += "\n";
    }
    s
}
