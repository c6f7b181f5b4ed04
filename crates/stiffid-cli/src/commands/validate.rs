//! `stiffid validate`: predicted against measured displacements for an identified stiffness
//! (Zhang et al. 2021, Eq. 22, Table 7).

use crate::commands::common::{Common, Stiffness};
use crate::load;
use crate::output::print_json_or;
use anyhow::{Context, Result};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::validate;

/// Arguments of `stiffid validate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    #[command(flatten)]
    stiffness: Stiffness,
    /// Measurements CSV (same format as for `identify`), ideally postures not used to identify.
    #[arg(long)]
    data: PathBuf,
}

/// `stiffid validate --json`: measured against predicted displacements (Eq. 22).
#[derive(Serialize, JsonSchema)]
pub struct ValidationJson {
    /// The setup as given (`--setup`).
    setup: String,
    /// The measurements file (`--data`).
    data: String,
    /// The stiffness validated (`--stiffness`), Nm/rad.
    stiffness_nm_per_rad: [f64; 6],
    /// Every measurement, file order.
    checks: Vec<CheckJson>,
    /// Mean of `delta_b` over the measurements, mm.
    mean_delta_b_mm: f64,
    /// Largest `delta_b`, mm.
    max_delta_b_mm: f64,
    /// RMS of `delta_b`, mm.
    rms_delta_b_mm: f64,
    /// Mean length of the measured displacements, mm.
    mean_measured_mm: f64,
    /// Largest measured displacement, mm.
    max_measured_mm: f64,
    /// RMS of the measured displacements, mm.
    rms_measured_mm: f64,
    /// `1 - rms_delta_b_mm / rms_measured_mm`.
    explained: f64,
}

/// One measurement against its prediction.
#[derive(Serialize, JsonSchema)]
struct CheckJson {
    /// The posture's label in the file.
    posture: String,
    /// The measuring point (1-based).
    point: usize,
    /// The line in the file.
    line: u64,
    /// Measured displacement x, y, z, base frame, mm.
    measured_mm: [f64; 3],
    /// Predicted displacement x, y, z, base frame, mm.
    predicted_mm: [f64; 3],
    /// `|measured - predicted|` (Eq. 22), mm.
    delta_b_mm: f64,
}

/// Validates and prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let stiffness = args.stiffness.load()?.stiffness();
    let data = load::measurements(&args.data, &setup)?;
    let name = args.data.display().to_string();
    let v = validate::compare(&setup, &stiffness, &data.measurements)
        .map_err(|e| data.explain(e))
        .with_context(|| name.clone())?;
    let result = ValidationJson {
        setup: args.common.setup.clone(),
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
    print_json_or(args.common.json, &result, human)
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
