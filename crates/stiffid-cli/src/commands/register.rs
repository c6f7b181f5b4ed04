//! `stiffid register`: the laser tracker's transform to the robot base from measuring points read
//! by the tracker at known axis angles (Umeyama's least-squares rigid transform), its residuals
//! and standard deviation, and the `[tracker]` fragment of the setup file.

use crate::commands::common::Common;
use crate::load;
use crate::output::{print_json_or, OutFile};
use anyhow::{Context, Result};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::formats::readings::{self, Readings};
use stiffid::register::{self, Registration};

/// Arguments of `stiffid register`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Readings CSV: posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm, one row
    /// per posture and measuring point (at least 3 points not on one line; at most 100000 rows;
    /// with load steps, the unloaded readings).
    #[arg(long)]
    data: PathBuf,
    /// Write the `[tracker] base_from_tracker` fragment of the setup file here (TOML; never over
    /// an input).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// `stiffid register --json`: the tracker's transform, its quality and uncertainty.
#[derive(Serialize, JsonSchema)]
pub struct RegisterJson {
    /// The setup as given (`--setup`).
    setup: String,
    /// The tracker frame in the robot base frame: translation, mm.
    xyz_mm: [f64; 3],
    /// ... and fixed-axis roll, pitch, yaw, deg (as the setup's `base_from_tracker`).
    rpy_deg: [f64; 3],
    /// Standard deviation of the translation, base frame, mm (linearised, from the residuals).
    translation_std_mm: [f64; 3],
    /// Standard deviation of the rotation about the base x, y, z axes, deg.
    rotation_std_deg: [f64; 3],
    /// RMS of the residual lengths, mm.
    residual_rms_mm: f64,
    /// Noise per coordinate estimated from the residuals, mm.
    noise_std_mm: f64,
    /// Every reading's residual.
    points: Vec<PointJson>,
    /// The `[tracker]` fragment of the setup file.
    fragment: String,
}

/// One reading's residual.
#[derive(Serialize, JsonSchema)]
struct PointJson {
    /// The posture's label.
    posture: String,
    /// The measuring point (1-based).
    point: usize,
    /// The line of the readings file.
    line: u64,
    /// Base-frame point minus the transformed tracker reading, mm.
    residual_mm: [f64; 3],
    /// Its length, mm.
    residual_norm_mm: f64,
}

/// Runs `stiffid register`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let name = args.data.display().to_string();
    let text = load::read(&args.data)?;
    let points = setup.tool().measuring_points.len();
    let data = readings::parse(&text, setup.robot(), points).with_context(|| name.clone())?;
    let out = args
        .out
        .as_ref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let points = register::correspondences(&setup, &data).with_context(|| name.clone())?;
    let fit = register::fit(&points).with_context(|| name)?;
    let doc = document(&args.common.setup, &data, &fit);
    if let Some(out) = &out {
        out.write(doc.fragment.as_bytes())?;
    }
    print_json_or(args.common.json, &doc, text_of)
}

fn document(setup: &str, data: &Readings, fit: &Registration) -> RegisterJson {
    let (xyz_mm, rpy_deg) = fit.xyz_mm_rpy_deg();
    let s = fit.std();
    let mm = |v: nalgebra::Vector3<f64>| [v.x * 1e3, v.y * 1e3, v.z * 1e3];
    let points = data
        .readings
        .iter()
        .zip(&data.lines)
        .zip(&fit.residuals)
        .map(|((r, line), residual)| PointJson {
            posture: data.labels[r.posture].clone(),
            point: r.point + 1,
            line: *line,
            residual_mm: mm(*residual),
            residual_norm_mm: residual.norm() * 1e3,
        })
        .collect();
    RegisterJson {
        setup: setup.to_string(),
        xyz_mm,
        rpy_deg,
        translation_std_mm: [s[0] * 1e3, s[1] * 1e3, s[2] * 1e3],
        rotation_std_deg: [s[3], s[4], s[5]].map(f64::to_degrees),
        residual_rms_mm: fit.rms * 1e3,
        noise_std_mm: fit.sigma * 1e3,
        points,
        fragment: fit.fragment(),
    }
}

fn text_of(d: &RegisterJson) -> String {
    let three = |v: [f64; 3], digits: usize| {
        format!("{:.digits$}, {:.digits$}, {:.digits$}", v[0], v[1], v[2])
    };
    let mut text = format!(
        "registration of {} points (setup {})\n\
         base_from_tracker: xyz_mm = [{}], rpy_deg = [{}]\n\
         standard deviation: translation [{}] mm, rotation [{}] deg\n\
         residual RMS {:.4} mm (noise per coordinate {:.4} mm)\n\
         \nposture  point  line  residual_mm\n",
        d.points.len(),
        d.setup,
        three(d.xyz_mm, 4),
        three(d.rpy_deg, 5),
        three(d.translation_std_mm, 4),
        three(d.rotation_std_deg, 5),
        d.residual_rms_mm,
        d.noise_std_mm,
    );
    for p in &d.points {
        text += &format!(
            "{:<8} {:>5} {:>5}  {:.4} [{}]\n",
            stiffid::limits::short(&p.posture),
            p.point,
            p.line,
            p.residual_norm_mm,
            three(p.residual_mm, 4)
        );
    }
    text + "\n" + &d.fragment
}
