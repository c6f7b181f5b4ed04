//! `stiffid identify`: joint stiffness from a measurement file (Zhang et al. 2021, Eq. 10-14), with
//! standard errors, 95% confidence intervals, residuals and an optional robust fit.

use crate::output::{json, refuse_to_overwrite, write_atomic};
use crate::{data, load};
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::PathBuf;
use stiffid::identify::{observations, Identification, Loss};
use stiffid::kinematics::Coordinates;

/// Arguments of `stiffid identify`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// Measurements CSV: posture,point,q1_deg..q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm.
    #[arg(long)]
    data: PathBuf,
    /// Down-weight outliers by iteratively reweighted least squares (`--robust` alone: huber).
    #[arg(long, value_enum, num_args = 0..=1, default_missing_value = "huber")]
    robust: Option<Robust>,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
    /// Also write the JSON result to this file (for `predict --stiffness`, `validate --stiffness`).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The robust weight functions.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Robust {
    /// Huber weights (c = 1.345 MAD scales): outliers keep a small weight.
    Huber,
    /// Tukey's biweight (c = 4.685 MAD scales): far outliers get weight 0.
    Tukey,
}

/// The JSON result. Units in the key names; intervals `[lower, upper]`; `null` for an unbounded
/// end or when there are no degrees of freedom left.
#[derive(Serialize)]
struct IdentifyJson {
    setup: String,
    data: String,
    springs: Coordinates,
    method: &'static str,
    rows: usize,
    postures: usize,
    stiffness_nm_per_rad: [f64; 6],
    compliance_rad_per_nm: [f64; 6],
    std_error_nm_per_rad: Option<[f64; 6]>,
    ci95_nm_per_rad: Option<[[f64; 2]; 6]>,
    ci95_from_compliance_nm_per_rad: Option<[[Option<f64>; 2]; 6]>,
    compliance_std_error_rad_per_nm: Option<[f64; 6]>,
    compliance_ci95_rad_per_nm: Option<[[f64; 2]; 6]>,
    compliance_covariance_rad2_per_nm2: Option<[[f64; 6]; 6]>,
    degrees_of_freedom: Option<usize>,
    t_quantile: Option<f64>,
    residual_std_mm: Option<f64>,
    cond_psi: f64,
    residual_rms_mm: f64,
    residuals: Vec<ResidualJson>,
    robust: Option<RobustJson>,
}

#[derive(Serialize)]
struct ResidualJson {
    posture: String,
    point: usize,
    line: u64,
    residual_mm: [f64; 3],
}

#[derive(Serialize)]
struct RobustJson {
    loss: &'static str,
    tuning_constant: f64,
    scale_mm: f64,
    iterations: usize,
    converged: bool,
    down_weighted: Vec<RowJson>,
}

#[derive(Serialize)]
struct RowJson {
    posture: String,
    point: usize,
    line: u64,
    coordinate: char,
    weight: f64,
    residual_mm: f64,
}

/// Identifies, prints, and writes `--out`.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    if let Some(out) = &args.out {
        refuse_to_overwrite(out, &[&args.data])?;
    }
    let data = data::read(&args.data)?;
    let name = args.data.display().to_string();
    let obs = observations(&setup, &data.measurements)
        .map_err(|e| data.explain(e))
        .with_context(|| name.clone())?;
    let id = match args.robust {
        None => obs.identify(),
        Some(Robust::Huber) => obs.identify_robust(Loss::Huber),
        Some(Robust::Tukey) => obs.identify_robust(Loss::Tukey),
    }
    .with_context(|| name.clone())?;
    let result = to_json(&args.setup, &name, setup.springs, &data, &id);
    let text = json(&result)?;
    if let Some(out) = &args.out {
        write_atomic(out, text.as_bytes())?;
    }
    match args.json {
        true => print!("{text}"),
        false => print!("{}", human(&result, &id)),
    }
    Ok(())
}

fn mm(v: f64) -> f64 {
    v * 1e3
}

fn to_json(
    setup: &str,
    name: &str,
    springs: Coordinates,
    data: &data::Data,
    id: &Identification,
) -> IdentifyJson {
    let u = id.uncertainty.as_ref();
    let finite = |v: f64| v.is_finite().then_some(v);
    let residual = |i: usize| id.residuals.fixed_rows::<3>(3 * i).map(mm).into();
    let residuals = data
        .measurements
        .iter()
        .enumerate()
        .map(|(i, m)| ResidualJson {
            posture: m.posture.clone(),
            point: m.point + 1,
            line: data.line(i),
            residual_mm: residual(i),
        })
        .collect();
    let robust = id.robust.as_ref().map(|fit| RobustJson {
        loss: fit.loss.name(),
        tuning_constant: fit.loss.tuning_constant(),
        scale_mm: mm(fit.scale),
        iterations: fit.iterations,
        converged: fit.converged,
        down_weighted: fit
            .down_weighted()
            .into_iter()
            .map(|row| {
                let m = &data.measurements[row / 3];
                RowJson {
                    posture: m.posture.clone(),
                    point: m.point + 1,
                    line: data.line(row / 3),
                    coordinate: ['x', 'y', 'z'][row % 3],
                    weight: fit.weights[row],
                    residual_mm: mm(id.residuals[row]),
                }
            })
            .collect(),
    });
    IdentifyJson {
        setup: setup.to_string(),
        data: name.to_string(),
        springs,
        method: id
            .robust
            .as_ref()
            .map_or("least-squares", |f| f.loss.name()),
        rows: id.rows,
        postures: id.postures,
        stiffness_nm_per_rad: id.stiffness.into(),
        compliance_rad_per_nm: id.compliance.into(),
        std_error_nm_per_rad: u.map(|u| u.stiffness_std_error.into()),
        ci95_nm_per_rad: u.map(|u| u.stiffness_ci95),
        ci95_from_compliance_nm_per_rad: u.map(|u| {
            u.stiffness_ci95_from_compliance
                .map(|[a, b]| [finite(a), finite(b)])
        }),
        compliance_std_error_rad_per_nm: u.map(|u| u.compliance_std_error.into()),
        compliance_ci95_rad_per_nm: u.map(|u| u.compliance_ci95),
        compliance_covariance_rad2_per_nm2: u.map(|u| {
            std::array::from_fn(|r| std::array::from_fn(|c| u.compliance_covariance[(r, c)]))
        }),
        degrees_of_freedom: u.map(|u| u.dof),
        t_quantile: u.map(|u| u.t_quantile),
        residual_std_mm: u.map(|u| mm(u.residual_variance.sqrt())),
        cond_psi: id.cond_psi,
        residual_rms_mm: mm(id.residual_rms),
        residuals,
        robust,
    }
}

/// Relative standard error above which a joint is called poorly determined.
const POOR: f64 = 0.25;

fn human(r: &IdentifyJson, id: &Identification) -> String {
    let springs = match r.springs {
        Coordinates::Axis => "axes (drives)",
        Coordinates::Kinematic => "kinematic joints",
    };
    let mut s = format!(
        "setup {}, data {}\nsprings on the {springs}; {} rows of Psi from {} postures; {}\n\
         cond(Psi) {:.4}, residual RMS {:.4} mm",
        r.setup,
        r.data,
        r.rows,
        r.postures,
        match r.method {
            "least-squares" => "least squares (QR)".to_string(),
            loss => format!("robust: iteratively reweighted least squares, {loss} weights"),
        },
        r.cond_psi,
        r.residual_rms_mm
    );
    let Some(u) = &id.uncertainty else {
        s += "\n\njoint  stiffness Nm/rad  compliance rad/Nm\n";
        for j in 0..6 {
            s += &format!(
                "{:>5}  {:>16.0}  {:>17.6e}\n",
                j + 1,
                r.stiffness_nm_per_rad[j],
                r.compliance_rad_per_nm[j]
            );
        }
        s += "exactly six rows: the fit is exact and there is no uncertainty estimate\n";
        return s;
    };
    s += &format!(
        ", residual standard deviation s {:.4} mm ({} degrees of freedom, t = {:.4})\n\n",
        mm(u.residual_variance.sqrt()),
        u.dof,
        u.t_quantile
    );
    s += "joint  stiffness Nm/rad  std error  rel.   95% CI (delta method)    95% CI (1/compliance CI)  compliance rad/Nm\n";
    let mut poor = Vec::new();
    for j in 0..6 {
        let k = id.stiffness[j];
        let rel = u.stiffness_std_error[j] / k.abs();
        if rel > POOR {
            poor.push(j + 1);
        }
        let [a, b] = u.stiffness_ci95[j];
        let [c, d] = u.stiffness_ci95_from_compliance[j];
        let upper = match d.is_finite() {
            true => format!("{d:.0}"),
            false => "unbounded".into(),
        };
        s += &format!(
            "{:>5}  {:>16.0}  {:>9.0}  {:>4.1}%  [{:>10.0}, {:>10.0}]  [{:>10.0}, {:>10}]  {:>17.6e}\n",
            j + 1,
            k,
            u.stiffness_std_error[j],
            100.0 * rel,
            a,
            b,
            c,
            upper,
            id.compliance[j]
        );
    }
    if !poor.is_empty() {
        s += &format!(
            "poorly determined (std error > {:.0}% of the value): joint {}; the delta-method interval \
             is unreliable there, trust the 1/compliance interval and measure postures that load these joints more\n",
            100.0 * POOR,
            poor.iter().map(|j| j.to_string()).collect::<Vec<_>>().join(", ")
        );
    }
    s += &largest_residuals(r);
    if let Some(robust) = &r.robust {
        s += &down_weighted(robust);
    }
    s
}

fn largest_residuals(r: &IdentifyJson) -> String {
    let norm = |v: &[f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let mut order: Vec<&ResidualJson> = r.residuals.iter().collect();
    order.sort_by(|a, b| norm(&b.residual_mm).total_cmp(&norm(&a.residual_mm)));
    let mut s = "\nlargest residuals (measured - fitted), mm (all of them: --json):\n".to_string();
    for res in order.iter().take(5) {
        let [x, y, z] = res.residual_mm;
        s += &format!(
            "  line {:>4}  posture {:>4}  point {}  ({x:+.4}, {y:+.4}, {z:+.4})  |{:.4}|\n",
            res.line,
            res.posture,
            res.point,
            norm(&res.residual_mm)
        );
    }
    s
}

fn down_weighted(robust: &RobustJson) -> String {
    let shown = 10;
    let mut s = format!(
        "\nrobust fit: {} weights, c = {}, scale {:.4} mm (1.4826 x median |residual|), {} iterations{}\n\
         down-weighted rows (weight < {}), lowest weight first:\n",
        robust.loss,
        robust.tuning_constant,
        robust.scale_mm,
        robust.iterations,
        if robust.converged { "" } else { " (not converged)" },
        stiffid::identify::robust::DOWN_WEIGHTED
    );
    for row in robust.down_weighted.iter().take(shown) {
        s += &format!(
            "  line {:>4}  posture {:>4}  point {}  {}: weight {:.3}, residual {:+.4} mm\n",
            row.line, row.posture, row.point, row.coordinate, row.weight, row.residual_mm
        );
    }
    match robust.down_weighted.len() {
        0 => s += "  none\n",
        n if n > shown => s += &format!("  ... and {} more (--json)\n", n - shown),
        _ => {}
    }
    s
}
