//! `stiffid predict`: the forward model (Zhang et al. 2021, Eq. 3-7) for one posture and wrench.

use crate::load;
use crate::output::print_json_or;
use anyhow::{bail, Result};
use nalgebra::Vector6;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::limits;
use stiffid::stiffness::deflection;

/// Arguments of `stiffid predict`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// Axis angles q1..q6, deg, comma-separated.
    #[arg(long, allow_hyphen_values = true)]
    q_deg: String,
    /// Wrench at the loading point, base frame: fx,fy,fz (N) or fx,fy,fz,mx,my,mz (N, Nm); each
    /// component within +-1e7.
    #[arg(long, allow_hyphen_values = true)]
    wrench: String,
    /// JSON file with `stiffness_nm_per_rad` (e.g. from `stiffid identify --out`); default: the
    /// setup's nominal stiffness.
    #[arg(long)]
    stiffness: Option<PathBuf>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct PredictJson {
    setup: String,
    q_deg: [f64; 6],
    wrench: [f64; 6],
    stiffness_nm_per_rad: [f64; 6],
    torques_nm: [f64; 6],
    joint_deflections_mrad: [f64; 6],
    flange_rotation_mrad: [f64; 3],
    measuring_points: Vec<PointJson>,
}

#[derive(Serialize)]
struct PointJson {
    point: usize,
    position_mm: [f64; 3],
    displacement_mm: [f64; 3],
    displacement_norm_mm: f64,
}

/// Predicts and prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    let (q_deg, q) = load::posture(&args.q_deg, &setup.robot)?;
    let w = load::numbers(&args.wrench, "--wrench", &limits::WRENCH)?;
    if w.len() != 3 && w.len() != 6 {
        bail!(
            "--wrench: expected fx,fy,fz or fx,fy,fz,mx,my,mz, got {} numbers",
            w.len()
        );
    }
    let mut wrench = Vector6::zeros();
    wrench.as_mut_slice()[..w.len()].copy_from_slice(&w);
    let stiffness = match &args.stiffness {
        Some(path) => load::stiffness(path)?,
        None => setup.nominal_stiffness,
    };
    let frames = setup.robot.frames(&q);
    let d = deflection(&setup, &frames, &wrench, &stiffness);
    let rotation = d.displacements[0].fixed_rows::<3>(3) * 1e3;
    let result = PredictJson {
        setup: args.setup.clone(),
        q_deg: q_deg.into(),
        wrench: wrench.into(),
        stiffness_nm_per_rad: stiffness.into(),
        torques_nm: d.torques.into(),
        joint_deflections_mrad: (d.joint_deflections * 1e3).into(),
        flange_rotation_mrad: rotation.into(),
        measuring_points: d
            .displacements
            .iter()
            .zip(&setup.tool.measuring_points)
            .enumerate()
            .map(|(k, (disp, p))| {
                let t = disp.fixed_rows::<3>(0) * 1e3;
                PointJson {
                    point: k + 1,
                    position_mm: (frames.point(p) * 1e3).into(),
                    displacement_mm: t.into(),
                    displacement_norm_mm: t.norm(),
                }
            })
            .collect(),
    };
    print_json_or(args.json, &result, human)
}

fn human(r: &PredictJson) -> String {
    let row = |v: &[f64], digits: usize| {
        v.iter()
            .map(|x| format!("{x:>12.digits$}"))
            .collect::<Vec<_>>()
            .join("")
    };
    let mut s = format!(
        "setup {}, q = ({}) deg\nwrench at the loading point, base frame: f = ({}) N, m = ({}) Nm\n\n",
        r.setup,
        r.q_deg.map(|v| v.to_string()).join(", "),
        r.wrench[..3].iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", "),
        r.wrench[3..].iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", ")
    );
    s += &format!(
        "joint                    {}\n",
        row(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 0)
    );
    s += &format!(
        "stiffness Nm/rad         {}\n",
        row(&r.stiffness_nm_per_rad, 0)
    );
    s += &format!("torque Nm                {}\n", row(&r.torques_nm, 2));
    s += &format!(
        "joint deflection mrad    {}\n",
        row(&r.joint_deflections_mrad, 5)
    );
    s += "\npoint   position mm (x, y, z)                displacement mm (x, y, z)            |d| mm\n";
    for p in &r.measuring_points {
        s += &format!(
            "{:>5}   {}   {}   {:.4}\n",
            p.point,
            row(&p.position_mm, 2),
            row(&p.displacement_mm, 4),
            p.displacement_norm_mm
        );
    }
    let [a, b, c] = r.flange_rotation_mrad;
    s += &format!("\nflange rotation (base frame): ({a:.5}, {b:.5}, {c:.5}) mrad\n");
    s
}
