//! `stiffid validate`: predicted against measured displacements for an identified stiffness
//! (Zhang et al. 2021, Eq. 22, Table 7).

use crate::load;
use crate::output::print_json_or;
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::PathBuf;
use stiffid::validate;

/// Arguments of `stiffid validate`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// JSON file with `stiffness_nm_per_rad` (six values), e.g. from `stiffid identify --out`.
    #[arg(long)]
    stiffness: PathBuf,
    /// Measurements CSV (same format as for `identify`), ideally postures not used to identify.
    #[arg(long)]
    data: PathBuf,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct ValidationJson {
    setup: String,
    data: String,
    stiffness_nm_per_rad: [f64; 6],
    checks: Vec<CheckJson>,
    mean_delta_b_mm: f64,
    max_delta_b_mm: f64,
    rms_delta_b_mm: f64,
    mean_measured_mm: f64,
    max_measured_mm: f64,
    rms_measured_mm: f64,
    explained: f64,
}

#[derive(Serialize)]
struct CheckJson {
    posture: String,
    point: usize,
    line: u64,
    measured_mm: [f64; 3],
    predicted_mm: [f64; 3],
    delta_b_mm: f64,
}

/// Validates and prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    let stiffness = load::stiffness(&args.stiffness)?.stiffness();
    let data = load::measurements(&args.data, &setup)?;
    let name = args.data.display().to_string();
    let v = validate::compare(&setup, &stiffness, &data.measurements)
        .map_err(|e| data.explain(e))
        .with_context(|| name.clone())?;
    let result = ValidationJson {
        setup: args.setup.clone(),
        data: name,
        stiffness_nm_per_rad: stiffness.into(),
        checks: v
            .checks
            .iter()
            .enumerate()
            .map(|(i, c)| CheckJson {
                posture: data.labels[c.posture].clone(),
                point: c.point + 1,
                line: data.lines[i],
                measured_mm: (c.measured * 1e3).into(),
                predicted_mm: (c.predicted * 1e3).into(),
                delta_b_mm: c.delta_b * 1e3,
            })
            .collect(),
        mean_delta_b_mm: v.mean * 1e3,
        max_delta_b_mm: v.max * 1e3,
        rms_delta_b_mm: v.rms * 1e3,
        mean_measured_mm: v.measured[0] * 1e3,
        max_measured_mm: v.measured[1] * 1e3,
        rms_measured_mm: v.measured[2] * 1e3,
        explained: v.explained,
    };
    print_json_or(args.json, &result, human)
}

fn human(r: &ValidationJson) -> String {
    let k: Vec<String> = r
        .stiffness_nm_per_rad
        .iter()
        .map(|k| format!("{k:.0}"))
        .collect();
    let mut s = format!(
        "setup {}, data {}\nstiffness Nm/rad: {}\n\n\
         posture  point   measured mm (x, y, z)           predicted mm (x, y, z)          delta_b mm\n",
        r.setup,
        r.data,
        k.join(", ")
    );
    let v3 = |v: &[f64; 3]| format!("({:+.4}, {:+.4}, {:+.4})", v[0], v[1], v[2]);
    for c in &r.checks {
        s += &format!(
            "{:>7}  {:>5}   {:<30}  {:<30}  {:.4}\n",
            c.posture,
            c.point,
            v3(&c.measured_mm),
            v3(&c.predicted_mm),
            c.delta_b_mm
        );
    }
    s += &format!(
        "\ndelta_b (Eq. 22) over {} measurements: mean {:.4} mm, max {:.4} mm, RMS {:.4} mm\n",
        r.checks.len(),
        r.mean_delta_b_mm,
        r.max_delta_b_mm,
        r.rms_delta_b_mm
    );
    s += &format!(
        "measured deflection |delta_m|: mean {:.4} mm, max {:.4} mm, RMS {:.4} mm\n\
         share of the measured deflection the model explains, 1 - RMS(delta_b)/RMS(|delta_m|): {:.1}%\n",
        r.mean_measured_mm,
        r.max_measured_mm,
        r.rms_measured_mm,
        100.0 * r.explained
    );
    s
}
