//! `stiffid force`: the mean cutting force of every operation of a process file, feed frame
//! ([`stiffid::process`]).

use crate::load;
use crate::output::print_json_or;
use anyhow::{bail, Result};
use serde::Serialize;
use std::path::PathBuf;
use stiffid::process::{self, file, milling::MIN_RESOLUTION_DEG, OperationForce};

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

/// `stiffid force --json`.
#[derive(Serialize)]
struct Document {
    /// The process file.
    process: String,
    /// The peak's angular resolution, deg, or `null`.
    peak_resolution_deg: Option<f64>,
    /// One entry per operation, in file order.
    operations: Vec<OperationForce>,
}

/// Parses, computes, prints.
pub fn run(args: &Args) -> Result<()> {
    if let Some(r) = args.peak_resolution_deg {
        if !(MIN_RESOLUTION_DEG..=10.0).contains(&r) {
            bail!(
                "--peak-resolution-deg: {r}: expected a number >= {MIN_RESOLUTION_DEG} and <= 10"
            );
        }
    }
    let name = args.process.display().to_string();
    let parsed = file::parse(&load::read(&args.process)?, &name)?;
    let operations = process::forces(&parsed, args.peak_resolution_deg.map(f64::to_radians));
    let document = Document {
        process: name,
        peak_resolution_deg: args.peak_resolution_deg,
        operations,
    };
    print_json_or(args.json, &document, human)
}

fn human(d: &Document) -> String {
    let mut s = format!(
        "mean force on the tool over one revolution, feed frame [feed, normal, axial], N ({}):\n",
        d.process
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
