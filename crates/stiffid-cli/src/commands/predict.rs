//! `stiffid predict`: the forward model (Zhang et al. 2021, Eq. 3-7) for one posture and wrench,
//! with the TCP deflection and the Cartesian compliance and stiffness of the loaded point.

use crate::commands::common::choice;
use crate::commands::common::Common;
use crate::load;
use crate::output::print_json_or;
use anyhow::{bail, Result};
use nalgebra::{Matrix6, Vector3, Vector6};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::cartesian;
use stiffid::deflection::Frame;
use stiffid::deflection::{base_wrench, Points};
use stiffid::limits;
use stiffid::model::Compliance;

/// Arguments of `stiffid predict`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Axis angles q1..q6, deg, comma-separated.
    #[arg(long, allow_hyphen_values = true)]
    q_deg: String,
    /// Wrench at the loading point (or --at-mm): fx,fy,fz (N) or fx,fy,fz,mx,my,mz (N, Nm), in the
    /// frame of --frame; each component within +-1e7.
    #[arg(long, allow_hyphen_values = true)]
    wrench: String,
    /// Where the wrench acts: a tool point x,y,z in the flange frame, mm; default the setup's
    /// loading point.
    #[arg(long, allow_hyphen_values = true)]
    at_mm: Option<String>,
    /// The frame of the wrench: base, or tool (the flange frame, moving with the tool).
    #[arg(long, value_parser = choice::<Frame>(), default_value = "base")]
    frame: Frame,
    /// JSON file with `stiffness_nm_per_rad` (e.g. from `stiffid identify --out`); default: the
    /// setup's nominal stiffness. With `compliance_covariance_rad2_per_nm2` in it, every
    /// displacement also gets its standard deviation.
    #[arg(long)]
    stiffness: Option<PathBuf>,
}

/// `stiffid predict --json`: the forward model for one posture and wrench. `*_std_*` keys are
/// standard deviations from the stiffness file's compliance covariance, `null` without one.
#[derive(Serialize, JsonSchema)]
pub struct PredictJson {
    /// The setup as given (`--setup`).
    setup: String,
    /// Axis angles q1..q6, deg.
    q_deg: [f64; 6],
    /// The wrench as given, fx, fy, fz (N), mx, my, mz (Nm), in `wrench_frame`.
    wrench: [f64; 6],
    /// `base` or `tool`.
    wrench_frame: &'static str,
    /// Where the wrench acts: a tool point in the flange frame, mm.
    wrench_point_mm: [f64; 3],
    /// The wrench in the base frame, N and Nm.
    wrench_base_frame: [f64; 6],
    /// The joint stiffness used, Nm/rad.
    stiffness_nm_per_rad: [f64; 6],
    /// Joint torques, Nm.
    torques_nm: [f64; 6],
    /// Joint deflections, mrad.
    joint_deflections_mrad: [f64; 6],
    /// Rotation of the flange, base frame, mrad.
    flange_rotation_mrad: [f64; 3],
    /// Its standard deviation, mrad.
    flange_rotation_std_mrad: Option<[f64; 3]>,
    /// Every measuring point of the setup's tool.
    measuring_points: Vec<PointJson>,
    /// The TCP's position, base frame, mm.
    tcp_mm: [f64; 3],
    /// The TCP's displacement, base frame, mm.
    tcp_deflection_mm: [f64; 3],
    /// Its standard deviation, mm.
    tcp_deflection_std_mm: Option<[f64; 3]>,
    /// The tool's rotation, base frame, mrad.
    tcp_rotation_mrad: [f64; 3],
    /// Its standard deviation, mrad.
    tcp_rotation_std_mrad: Option<[f64; 3]>,
    /// `C_x` of the loaded point.
    cartesian_compliance: ComplianceJson,
    /// `K_x` of the loaded point; `null` where `C_x` is singular.
    cartesian_stiffness: Option<StiffnessJson>,
}

/// One measuring point's displacement.
#[derive(Serialize, JsonSchema)]
struct PointJson {
    /// The measuring point (1-based).
    point: usize,
    /// Its position, base frame, mm.
    position_mm: [f64; 3],
    /// Its displacement, base frame, mm.
    displacement_mm: [f64; 3],
    /// Its standard deviation, mm.
    displacement_std_mm: Option<[f64; 3]>,
    /// The displacement's length, mm.
    displacement_norm_mm: f64,
}

/// `C_x` of the loaded point, base frame, by blocks and whole (rows and columns `[f; m]` and
/// `[translation; rotation]`, SI).
#[derive(Serialize, JsonSchema)]
struct ComplianceJson {
    translation_per_force_m_per_n: [[f64; 3]; 3],
    translation_per_moment_m_per_nm: [[f64; 3]; 3],
    rotation_per_force_rad_per_n: [[f64; 3]; 3],
    rotation_per_moment_rad_per_nm: [[f64; 3]; 3],
    matrix_si: [[f64; 6]; 6],
}

/// `K_x = C_x^-1` of the loaded point, base frame, by blocks and whole (SI).
#[derive(Serialize, JsonSchema)]
struct StiffnessJson {
    force_per_translation_n_per_m: [[f64; 3]; 3],
    force_per_rotation_n_per_rad: [[f64; 3]; 3],
    moment_per_translation_nm_per_m: [[f64; 3]; 3],
    moment_per_rotation_nm_per_rad: [[f64; 3]; 3],
    matrix_si: [[f64; 6]; 6],
}

fn rows<const N: usize>(m: &Matrix6<f64>, r0: usize, c0: usize) -> [[f64; N]; N] {
    std::array::from_fn(|r| std::array::from_fn(|c| m[(r0 + r, c0 + c)]))
}

fn xyz(v: &Vector6<f64>, from: usize, scale: f64) -> [f64; 3] {
    std::array::from_fn(|i| v[from + i] * scale)
}

/// Predicts and prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let (q_deg, q) = load::posture(&args.q_deg, "--q-deg", setup.robot())?;
    let w = load::numbers(&args.wrench, "--wrench", &limits::WRENCH)?;
    if w.len() != 3 && w.len() != 6 {
        bail!(
            "--wrench: expected fx,fy,fz or fx,fy,fz,mx,my,mz, got {} numbers",
            w.len()
        );
    }
    let mut wrench = Vector6::zeros();
    wrench.as_mut_slice()[..w.len()].copy_from_slice(&w);
    let at: Vector3<f64> = match &args.at_mm {
        Some(text) => load::vector::<3>(text, "--at-mm", &limits::LENGTH_MM)? * 1e-3,
        None => setup.tool().loading_point,
    };
    let compliance = match &args.stiffness {
        Some(path) => load::stiffness(path, &setup)?,
        None => Compliance::nominal(&setup, "predict without --stiffness FILE")?,
    };
    let h = &compliance.h;
    let covariance = &compliance.covariance;
    let stiffness = compliance.drives_h().map(|h| 1.0 / h);
    let frames = setup.robot().frames(&q);
    let base = base_wrench(&frames, &wrench, args.frame);
    let at_point = |observed| Points {
        setup: &setup,
        frames: &frames,
        loaded: &at,
        observed,
    };
    let std = |d: &stiffid::deflection::PointDeflection| covariance.as_ref().map(|c| d.std(c));
    let tcp = at_point(&setup.tool().tcp).deflection(&base, h);
    let tcp_std = std(&tcp);
    let c = cartesian::compliance(&setup, &frames, &at, h);
    let k = cartesian::stiffness(&setup, &frames, &at, h);
    let result = PredictJson {
        setup: args.common.setup.clone(),
        q_deg: q_deg.into(),
        wrench: wrench.into(),
        wrench_frame: args.frame.name(),
        wrench_point_mm: (at * 1e3).into(),
        wrench_base_frame: base.into(),
        stiffness_nm_per_rad: stiffness.into(),
        torques_nm: std::array::from_fn(|j| tcp.torques[j]),
        joint_deflections_mrad: std::array::from_fn(|j| tcp.joint_deflections[j] * 1e3),
        flange_rotation_mrad: xyz(&tcp.displacement, 3, 1e3),
        flange_rotation_std_mrad: tcp_std.map(|s| xyz(&s, 3, 1e3)),
        measuring_points: setup
            .tool()
            .measuring_points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let d = at_point(p).deflection(&base, h);
                let t = d.displacement.fixed_rows::<3>(0) * 1e3;
                PointJson {
                    point: i + 1,
                    position_mm: (frames.point(p) * 1e3).into(),
                    displacement_mm: t.into(),
                    displacement_std_mm: std(&d).map(|s| xyz(&s, 0, 1e3)),
                    displacement_norm_mm: t.norm(),
                }
            })
            .collect(),
        tcp_mm: (frames.point(&setup.tool().tcp) * 1e3).into(),
        tcp_deflection_mm: xyz(&tcp.displacement, 0, 1e3),
        tcp_deflection_std_mm: tcp_std.map(|s| xyz(&s, 0, 1e3)),
        tcp_rotation_mrad: xyz(&tcp.displacement, 3, 1e3),
        tcp_rotation_std_mrad: tcp_std.map(|s| xyz(&s, 3, 1e3)),
        cartesian_compliance: ComplianceJson {
            translation_per_force_m_per_n: rows(&c, 0, 0),
            translation_per_moment_m_per_nm: rows(&c, 0, 3),
            rotation_per_force_rad_per_n: rows(&c, 3, 0),
            rotation_per_moment_rad_per_nm: rows(&c, 3, 3),
            matrix_si: rows(&c, 0, 0),
        },
        cartesian_stiffness: k.map(|k| StiffnessJson {
            force_per_translation_n_per_m: rows(&k, 0, 0),
            force_per_rotation_n_per_rad: rows(&k, 0, 3),
            moment_per_translation_nm_per_m: rows(&k, 3, 0),
            moment_per_rotation_nm_per_rad: rows(&k, 3, 3),
            matrix_si: rows(&k, 0, 0),
        }),
    };
    print_json_or(args.common.json, &result, human)
}

fn human(r: &PredictJson) -> String {
    let row = |v: &[f64], digits: usize| {
        v.iter()
            .map(|x| format!("{x:>12.digits$}"))
            .collect::<Vec<_>>()
            .join("")
    };
    let mut s = format!(
        "setup {}, q = ({}) deg\nwrench at ({}) mm (flange frame), {} frame: f = ({}) N, m = ({}) Nm\n\n",
        r.setup,
        r.q_deg.map(|v| v.to_string()).join(", "),
        r.wrench_point_mm.map(|v| format!("{v:.1}")).join(", "),
        r.wrench_frame,
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
    let pm = |v: &[f64; 3], sd: &Option<[f64; 3]>, digits: usize| match sd {
        None => v.map(|x| format!("{x:.digits$}")).join(", "),
        Some(sd) => (0..3)
            .map(|i| format!("{:.digits$} +- {:.digits$}", v[i], sd[i]))
            .collect::<Vec<_>>()
            .join(", "),
    };
    s += &format!(
        "TCP at ({}) mm: deflection ({}) mm, |d| {:.4} mm; rotation ({}) mrad{}\n",
        r.tcp_mm.map(|v| format!("{v:.1}")).join(", "),
        pm(&r.tcp_deflection_mm, &r.tcp_deflection_std_mm, 4),
        r.tcp_deflection_mm
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt(),
        pm(&r.tcp_rotation_mrad, &r.tcp_rotation_std_mrad, 5),
        match r.tcp_deflection_std_mm {
            Some(_) => " (+- one standard deviation from the compliance covariance)",
            None => "",
        }
    );
    s += "\nCartesian compliance C_x at the loaded point, base frame, rows dx dy dz (mm) drx dry drz (mrad), per fx fy fz (kN) mx my mz (kNm):\n";
    let c = &r.cartesian_compliance.matrix_si;
    for line in c {
        let values: Vec<f64> = line.iter().map(|v| v * 1e6).collect();
        s += &format!("  {}\n", row(&values, 5));
    }
    match &r.cartesian_stiffness {
        None => s += "Cartesian stiffness: none (the Jacobian of the loaded point is singular)\n",
        Some(k) => {
            s += "Cartesian stiffness K_x = C_x^-1, rows fx fy fz (N) mx my mz (Nm), per dx dy dz (um) drx dry drz (urad):\n";
            for line in &k.matrix_si {
                let values: Vec<f64> = line.iter().map(|v| v * 1e-6).collect();
                s += &format!("  {}\n", row(&values, 4));
            }
        }
    }
    s
}
