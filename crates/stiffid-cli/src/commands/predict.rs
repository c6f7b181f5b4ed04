//! `stiffid predict`: the forward model (Zhang et al. 2021, Eq. 3-7) for one posture and wrench,
//! with the TCP deflection and the Cartesian compliance and stiffness of the loaded point.

use crate::commands::common::choice;
use crate::commands::common::Common;
use crate::load;
use crate::output::print_json_or;
use anyhow::{bail, Result};
use nalgebra::Vector6;
use std::path::PathBuf;
use stiffid::app::predict;
use stiffid::app::predict::document::Document;
use stiffid::internal::common::limits;
use stiffid::internal::observation::deflection::Frame;

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
    /// The level of the prediction intervals (0.5 to 0.999), when the stiffness file holds the
    /// held-out residuals of its identification (`identify --cross-validate`).
    /// Only with such a file [default: 0.95].
    #[arg(long)]
    level: Option<f64>,
}

/// Predicts and prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let (_, q) = load::posture(&args.q_deg, "--q-deg", setup.robot())?;
    let w = load::numbers(&args.wrench, "--wrench", &limits::WRENCH)?;
    if w.len() != 3 && w.len() != 6 {
        bail!(
            "--wrench: expected fx,fy,fz or fx,fy,fz,mx,my,mz, got {} numbers",
            w.len()
        );
    }
    let mut wrench = Vector6::zeros();
    wrench.as_mut_slice()[..w.len()].copy_from_slice(&w);
    let at = match &args.at_mm {
        Some(text) => Some(load::vector::<3>(text, "--at-mm", &limits::LENGTH_MM)? * 1e-3),
        None => None,
    };
    let compliance = match &args.stiffness {
        Some(path) => Some(load::stiffness(path, &setup)?),
        None => None,
    };
    let outcome = predict::run(&predict::Request {
        setup_name: args.common.setup.clone(),
        setup: &setup,
        q,
        wrench,
        frame: args.frame,
        at,
        compliance,
        level: args.level,
    })?;
    crate::output::warnings(&outcome.warnings);
    print_json_or(args.common.json, outcome.written(), |r| {
        human(&r.document())
    })
}

fn human(r: &Document<'_>) -> String {
    header(r) + &joints(r) + &points(r) + &tcp(r) + &cartesian(r) + &mass(r)
}

/// `v` in columns 12 wide with `digits` decimals, a wider value a blank apart.
fn row(v: &[f64], digits: usize) -> String {
    v.iter()
        .map(|x| format!(" {x:>11.digits$}"))
        .collect::<Vec<_>>()
        .join("")
}

/// A prediction interval per axis, `[lower, upper]` (mm), an open end as infinity.
fn ranges(i: &[[Option<f64>; 2]; 3]) -> String {
    i.map(|[lo, hi]| {
        let end = |v: Option<f64>, inf: &str| v.map_or(inf.to_string(), |v| format!("{v:.4}"));
        format!("[{}, {}]", end(lo, "-inf"), end(hi, "inf"))
    })
    .join(", ")
}

/// The setup, the posture and the wrench.
fn header(r: &Document<'_>) -> String {
    format!(
        "setup {}, q = ({}) deg\nwrench at ({}) mm (flange frame), {} frame: f = ({}) N, m = ({}) Nm\n\n",
        r.setup,
        r.q_deg.map(angle).join(", "),
        r.wrench_point_mm.map(|v| format!("{v:.1}")).join(", "),
        r.wrench_frame,
        r.wrench_n_nm[..3].iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", "),
        r.wrench_n_nm[3..].iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", ")
    )
}

/// Per joint its stiffness, torque and deflection.
fn joints(r: &Document<'_>) -> String {
    let mut s = String::new();
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
    s
}

/// Each measuring point's position and displacement, the prediction intervals when the
/// stiffness file gives them.
fn points(r: &Document<'_>) -> String {
    let mut s = String::new();
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
    if r.measuring_points
        .iter()
        .any(|p| p.displacement_interval_mm.is_some())
    {
        s += &format!(
            "prediction intervals ({:.0}%, from the held-out residuals of the identification), mm (x, y, z):
",
            100.0 * r.prediction_level
        );
        for p in &r.measuring_points {
            if let Some(i) = &p.displacement_interval_mm {
                s += &format!(
                    "{:>5}   {}
",
                    p.point,
                    ranges(i)
                );
            }
        }
    }
    s
}

/// The flange's rotation and the TCP's deflection and rotation (with their standard deviations
/// and prediction interval when known).
fn tcp(r: &Document<'_>) -> String {
    let mut s = String::new();
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
        r.tcp_deflection_norm_mm,
        pm(&r.tcp_rotation_mrad, &r.tcp_rotation_std_mrad, 5),
        match r.tcp_deflection_std_mm {
            Some(_) => " (+- one standard deviation from the compliance covariance)",
            None => "",
        }
    );
    if let Some(i) = &r.tcp_deflection_interval_mm {
        s += &format!(
            "TCP deflection's {:.0}% prediction interval, mm (x, y, z): {}\n",
            100.0 * r.prediction_level,
            ranges(i)
        );
    }
    s
}

/// The Cartesian compliance and stiffness at the loaded point.
fn cartesian(r: &Document<'_>) -> String {
    let mut s = String::new();
    s += "\nCartesian compliance C_x at the loaded point, base frame, rows dx dy dz (mm) drx dry drz (mrad), per fx fy fz (kN) mx my mz (kNm):\n";
    for line in &r.cartesian_compliance.matrix_mm_mrad_per_kn_knm {
        s += &format!("  {}\n", row(line, 5));
    }
    match &r.cartesian_stiffness {
        None => s += "Cartesian stiffness: none (the Jacobian of the loaded point is singular)\n",
        Some(k) => {
            s += "Cartesian stiffness K_x = C_x^-1, rows fx fy fz (N) mx my mz (Nm), per dx dy dz (um) drx dry drz (urad):\n";
            for line in &k.matrix_n_nm_per_um_urad {
                s += &format!("  {}\n", row(line, 4));
            }
        }
    }
    s
}

/// The mass lines: natural frequencies and the surge, where the robot gives its masses.
fn mass(r: &Document<'_>) -> String {
    let Some(f) = &r.natural_frequencies_hz else {
        return String::new();
    };
    let hz: Vec<String> = f.iter().map(|v| format!("{v:.2}")).collect();
    let mut s = format!("\nnatural frequencies Hz: {}\n", hz.join(", "));
    if let (Some(m), Some(v)) = (r.effective_mass_kg, r.surge_mm_s) {
        let std = r
            .surge_std_mm_s
            .map_or(String::new(), |d| format!(" (std {d:.3})"));
        let mass_std = r
            .effective_mass_std_kg
            .map_or(String::new(), |d| format!(" (std {d:.2})"));
        s += &format!(
            "effective mass along the force, held: {m:.2} kg{mass_std}; breakthrough surge {v:.3} mm/s{std}\n"
        );
    }
    s
}

/// An angle in degrees to 9 decimals, trailing zeros cut (the radian round trip shows as given).
fn angle(v: f64) -> String {
    let s = format!("{v:.9}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
