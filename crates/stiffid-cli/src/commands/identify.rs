//! `stiffid identify`: joint stiffness from a measurement file (Zhang et al. 2021, Eq. 10-14), with
//! standard errors, 95% confidence intervals, the model check against the tracker noise,
//! residuals, and optionally a robust or non-negative fit and cross-validation.

use crate::commands::common::Common;
use crate::load;
use crate::output::{self, json, OutFile};
use anyhow::{Context, Result};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::formats::measurements::{Labels, MeasurementFile};
use stiffid::identify::streamed::Rows;
use stiffid::identify::{
    cross_validate, Adequacy, CrossValidation, Identification, Loss, Uncertainty, UnitCheck,
};
use stiffid::kinematics::Coordinates;
use stiffid::observation::Observations;
use stiffid::Setup;

mod models;
mod text;

/// Arguments of `stiffid identify`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Measurements CSV: posture,point,q1_deg..q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm.
    #[arg(long)]
    data: PathBuf,
    /// Down-weight outliers by iteratively reweighted least squares (`--robust` alone: huber).
    #[arg(long, value_enum, num_args = 0..=1, default_missing_value = "huber", conflicts_with = "nonnegative")]
    robust: Option<Robust>,
    /// Bound every compliance at >= 0 (Lawson-Hanson non-negative least squares) and report the
    /// active bounds.
    #[arg(long)]
    nonnegative: bool,
    /// Cross-validate over postures: leave one posture out (or `--folds K`), refit, predict it.
    #[arg(long)]
    cross_validate: bool,
    /// Number of cross-validation folds, 2 to the number of postures (implies --cross-validate).
    #[arg(long)]
    folds: Option<usize>,
    /// Also write the JSON result to this file (for `predict --stiffness`, `validate --stiffness`);
    /// with `--compare-models`, the recommended model's `[model]` fragment for the setup.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Compare models: add candidate virtual springs to the setup's model by forward selection on
    /// the leave-one-posture-out error, nested in an outer cross-validation; recommend the
    /// smallest model within one standard error of the best.
    #[arg(long)]
    compare_models: bool,
    /// The candidates of `--compare-models`, comma-separated: family springs (`tilt3_x`,
    /// `tool_y`, `base_rz`) or families (`tilt`, `tool`, `base`); default the tilt springs of
    /// joints 1-6 and the tool translations.
    #[arg(long, value_delimiter = ',', requires = "compare_models")]
    candidates: Option<Vec<String>>,
}

/// The robust weight functions.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Robust {
    /// Huber weights (c = 1.345 MAD scales): outliers keep a small weight.
    Huber,
    /// Tukey's biweight (c = 4.685 MAD scales): far outliers get weight 0.
    Tukey,
}

/// Everything one run found, for the JSON and the text.
pub struct Run<'a> {
    setup_name: &'a str,
    data_name: String,
    setup: &'a Setup,
    /// Where each measurement came from.
    rows: Rows,
    id: Identification,
    adequacy: Option<Adequacy>,
    unit: Option<UnitCheck>,
    cross_validation: Option<CrossValidation>,
    /// The postures' dense numbers -> their first measurement (with cross-validation only).
    first_of_posture: Vec<usize>,
}

/// `stiffid identify --json` (and `--out`, a stiffness file). Units in the key names; intervals
/// `[lower, upper]`; `null` for a number that is not finite (an unbounded end, an infinite
/// stiffness) or when there are no degrees of freedom.
#[derive(Serialize, JsonSchema)]
pub struct IdentifyJson {
    /// The setup as given (`--setup`).
    setup: String,
    /// The measurements file (`--data`).
    data: String,
    /// Where the springs sit: in the drives (`axis`) or on the kinematic joints.
    springs: Coordinates,
    /// The fit: `least-squares`, `nonnegative-least-squares`, `huber` or `tukey`.
    method: &'static str,
    /// Rows of the stacked system (3 per measurement).
    rows: usize,
    /// Distinct postures in the file.
    postures: usize,
    /// The identified joint stiffness, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    stiffness_nm_per_rad: [f64; 6],
    /// The identified joint compliance (the unknowns of Eq. 14), rad/Nm.
    compliance_rad_per_nm: [f64; 6],
    /// Whether each compliance is positive (a physical spring).
    physical: [bool; 6],
    /// With `--nonnegative`: which compliances sit at their bound 0; else `null`.
    active_bounds: Option<[bool; 6]>,
    /// Where the intervals below come from (`residual variance`).
    intervals_from: &'static str,
    /// Standard error of each stiffness (delta method), Nm/rad.
    #[schemars(with = "Option<[Option<f64>; 6]>")]
    std_error_nm_per_rad: Option<[f64; 6]>,
    /// 95% confidence interval of each stiffness, symmetric in the stiffness, Nm/rad.
    #[schemars(with = "Option<[[Option<f64>; 2]; 6]>")]
    ci95_nm_per_rad: Option<[[f64; 2]; 6]>,
    /// 95% confidence interval of each stiffness, the compliance's interval inverted, Nm/rad.
    #[schemars(with = "Option<[[Option<f64>; 2]; 6]>")]
    ci95_from_compliance_nm_per_rad: Option<[[f64; 2]; 6]>,
    /// Standard error of each compliance, rad/Nm.
    compliance_std_error_rad_per_nm: Option<[f64; 6]>,
    /// 95% confidence interval of each compliance, rad/Nm.
    compliance_ci95_rad_per_nm: Option<[[f64; 2]; 6]>,
    /// `Cov(h)` of the compliance, (rad/Nm)^2, row-major.
    compliance_covariance_rad2_per_nm2: Option<[[f64; 6]; 6]>,
    /// Rows minus unknowns.
    degrees_of_freedom: Option<usize>,
    /// Student's t quantile of the 95% intervals.
    t_quantile: Option<f64>,
    /// Standard deviation of the residuals, mm.
    residual_std_mm: Option<f64>,
    /// The setup's tracker noise (standard deviation per coordinate), mm.
    noise_std_mm: f64,
    /// `residual_std_mm / noise_std_mm`: about 1 if the model is adequate.
    noise_ratio: Option<f64>,
    /// `dof s^2 / sigma^2`: the residual variance against the tracker noise variance.
    chi2_statistic: Option<f64>,
    /// `P(X >= chi2_statistic)` for `X ~ chi2(dof)`: small when the residuals exceed the noise.
    chi2_p_value: Option<f64>,
    /// Whether `chi2_p_value < 0.01`: the model error dominates the tracker noise.
    model_error_dominates: Option<bool>,
    /// The intervals computed from the setup's tracker noise instead of the residuals.
    tracker_noise: Option<IntervalsJson>,
    /// A warning when most joints are far off the setup's nominal stiffness the same way (a unit
    /// mistake?).
    unit_warning: Option<String>,
    /// `cond_2(Psi)` of the observation matrix, SI units.
    cond_psi: f64,
    /// RMS of the residuals, mm.
    residual_rms_mm: f64,
    /// Every measurement's residual (measured - fitted), file order.
    residuals: Vec<ResidualJson>,
    /// With `--robust`: the reweighting.
    robust: Option<RobustJson>,
    /// With `--cross-validate` or `--folds`: the cross-validation over postures.
    cross_validation: Option<CrossValidationJson>,
}

/// Standard errors and intervals computed from a known variance.
#[derive(Serialize, JsonSchema)]
struct IntervalsJson {
    /// Standard error of each stiffness, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    std_error_nm_per_rad: [f64; 6],
    /// 95% confidence interval of each stiffness, Nm/rad.
    #[schemars(with = "[[Option<f64>; 2]; 6]")]
    ci95_nm_per_rad: [[f64; 2]; 6],
    /// 95% confidence interval of each stiffness from the compliance's, Nm/rad.
    #[schemars(with = "[[Option<f64>; 2]; 6]")]
    ci95_from_compliance_nm_per_rad: [[f64; 2]; 6],
    /// Standard error of each compliance, rad/Nm.
    compliance_std_error_rad_per_nm: [f64; 6],
    /// 95% confidence interval of each compliance, rad/Nm.
    compliance_ci95_rad_per_nm: [[f64; 2]; 6],
    /// The normal quantile of these 95% intervals.
    quantile: f64,
}

/// One measurement's residual.
#[derive(Serialize, JsonSchema)]
struct ResidualJson {
    /// The posture's label in the file.
    posture: String,
    /// The measuring point (1-based).
    point: usize,
    /// The line in the file.
    line: u64,
    /// Measured minus fitted displacement, x, y, z, mm.
    residual_mm: [f64; 3],
}

/// The robust fit's reweighting.
#[derive(Serialize, JsonSchema)]
struct RobustJson {
    /// `huber` or `tukey`.
    loss: &'static str,
    /// The tuning constant, MAD scales.
    tuning_constant: f64,
    /// The robust residual scale, mm.
    scale_mm: f64,
    /// Reweighting iterations.
    iterations: usize,
    /// Whether the weights converged.
    converged: bool,
    /// Every row with a weight below 1.
    down_weighted: Vec<RowJson>,
}

/// One down-weighted row.
#[derive(Serialize, JsonSchema)]
struct RowJson {
    /// The posture's label in the file.
    posture: String,
    /// The measuring point (1-based).
    point: usize,
    /// The line in the file.
    line: u64,
    /// `x`, `y` or `z`.
    coordinate: char,
    /// Its final weight, 0 to 1.
    weight: f64,
    /// Its residual, mm.
    residual_mm: f64,
}

/// The cross-validation over postures.
#[derive(Serialize, JsonSchema)]
struct CrossValidationJson {
    /// Number of folds.
    folds: usize,
    /// Mean over the folds of each stiffness, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    stiffness_mean_nm_per_rad: [f64; 6],
    /// Standard deviation over the folds, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    stiffness_std_nm_per_rad: [f64; 6],
    /// Smallest over the folds, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    stiffness_min_nm_per_rad: [f64; 6],
    /// Largest over the folds, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    stiffness_max_nm_per_rad: [f64; 6],
    /// RMS prediction error of the left-out measurements (Eq. 22), mm.
    rms_delta_b_mm: f64,
    /// RMS of the measured displacements, mm.
    rms_measured_mm: f64,
    /// `1 - rms_delta_b_mm / rms_measured_mm`.
    explained: f64,
    /// Folds whose removal moves a stiffness by more than its standard error in the full fit.
    influential_postures: Vec<InfluentialJson>,
    /// Every fold.
    per_fold: Vec<FoldJson>,
}

/// One fold.
#[derive(Serialize, JsonSchema)]
struct FoldJson {
    /// The postures left out (labels).
    postures: Vec<String>,
    /// The stiffness fitted without them, Nm/rad.
    #[schemars(with = "[Option<f64>; 6]")]
    stiffness_nm_per_rad: [f64; 6],
    /// RMS prediction error of the left-out measurements, mm.
    rms_delta_b_mm: f64,
    /// Prediction error of each left-out measurement (Eq. 22), mm.
    delta_b_mm: Vec<f64>,
}

/// An influential fold.
#[derive(Serialize, JsonSchema)]
struct InfluentialJson {
    /// The postures left out (labels).
    postures: Vec<String>,
    /// The joints (1-based) it moves.
    joints: Vec<usize>,
}

/// Identifies, prints, and writes `--out`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    if args.compare_models {
        return models::compare_models(args, &setup);
    }
    if !setup.model().is_drives_only() {
        return models::identify_model(args, &setup);
    }
    // Opened (and so known as an input, never written over) before --out is prepared.
    let data = load::open(&args.data)?;
    let out = args
        .out
        .as_deref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let name = args.data.display().to_string();
    let (id, rows, cross_validation, first_of_posture) = match args.robust.is_some()
        || args.nonnegative
        || args.cross_validate
        || args.folds.is_some()
    {
        // Plain least squares: the file read in chunks, Psi in blocks (bounded memory, parallel).
        false => {
            let (id, rows) = load::identify_streamed(&args.data, data, &setup)?;
            (id, rows, None, Vec::new())
        }
        true => {
            let file = load::measurements(&args.data, &setup)?;
            let obs = Observations::from_measurements(&setup, &file.measurements)
                .map_err(|e| file.explain(e))
                .with_context(|| name.clone())?;
            let mut first_of_posture = vec![usize::MAX; obs.postures];
            for (i, &p) in obs.posture_index.iter().enumerate().rev() {
                first_of_posture[p] = i;
            }
            let (id, cv) = fit(args, &obs).with_context(|| name.clone())?;
            (id, rows_of(file), cv, first_of_posture)
        }
    };
    let run = Run {
        setup_name: &args.common.setup,
        data_name: name,
        setup: &setup,
        rows,
        adequacy: id.adequacy(setup.noise().variance),
        unit: setup.nominal_stiffness().and_then(|k| id.unit_check(k)),
        id,
        cross_validation,
        first_of_posture,
    };
    for warning in text::warnings(&run) {
        output::warn(&warning);
    }
    if args.common.json || out.is_some() {
        let text = json(&to_json(&run))?;
        if let Some(out) = &out {
            out.write(text.as_bytes())?;
        }
        if args.common.json {
            return output::print(&text);
        }
    }
    output::print(&text::human(&run))
}

/// Where each measurement of a parsed file came from.
fn rows_of(file: MeasurementFile) -> Rows {
    Rows {
        postures: file.measurements.iter().map(|m| m.posture).collect(),
        points: file.measurements.iter().map(|m| m.point).collect(),
        lines: file.lines,
        labels: Labels::from_iter(&file.labels),
        layout: file.layout,
    }
}

/// The fit the arguments ask for (robust, bounded or, for cross-validation, least squares on the
/// whole `Psi`), and the cross-validation if asked.
fn fit(args: &Args, obs: &Observations) -> Result<(Identification, Option<CrossValidation>)> {
    let id = match (args.robust, args.nonnegative) {
        (Some(Robust::Huber), _) => obs.robust(Loss::Huber)?,
        (Some(Robust::Tukey), _) => obs.robust(Loss::Tukey)?,
        (None, true) => obs.nonnegative()?,
        (None, false) => obs.least_squares()?,
    };
    let cross_validation = match args.cross_validate || args.folds.is_some() {
        false => None,
        true => {
            Some(cross_validate(obs, &id, args.folds.unwrap_or(obs.postures)).context("--folds")?)
        }
    };
    Ok((id, cross_validation))
}

fn mm(v: f64) -> f64 {
    v * 1e3
}

impl Run<'_> {
    /// The label of measurement `i`'s posture.
    fn label(&self, i: usize) -> &str {
        self.rows.label(i)
    }

    /// The labels of dense posture numbers.
    fn labels(&self, postures: &[usize]) -> Vec<String> {
        postures
            .iter()
            .map(|&p| self.label(self.first_of_posture[p]).to_string())
            .collect()
    }

    /// The postures of each influential fold and the joints (1-based) it moves.
    fn influential(&self) -> Vec<InfluentialJson> {
        let Some(cv) = &self.cross_validation else {
            return Vec::new();
        };
        cv.folds
            .iter()
            .filter(|f| f.influential.iter().any(|i| *i))
            .map(|f| InfluentialJson {
                postures: self.labels(&f.postures),
                joints: (0..6)
                    .filter(|&j| f.influential[j])
                    .map(|j| j + 1)
                    .collect(),
            })
            .collect()
    }
}

fn intervals(u: &Uncertainty) -> IntervalsJson {
    IntervalsJson {
        std_error_nm_per_rad: u.stiffness_std_error.into(),
        ci95_nm_per_rad: u.stiffness_ci95,
        ci95_from_compliance_nm_per_rad: u.stiffness_ci95_from_compliance,
        compliance_std_error_rad_per_nm: u.compliance_std_error.into(),
        compliance_ci95_rad_per_nm: u.compliance_ci95,
        quantile: u.t_quantile,
    }
}

fn to_json(run: &Run) -> IdentifyJson {
    let (id, rows) = (&run.id, &run.rows);
    let u = id.uncertainty.as_ref();
    let residual = |i: usize| id.residuals.fixed_rows::<3>(3 * i).map(mm).into();
    let residuals = (0..rows.lines.len())
        .map(|i| ResidualJson {
            posture: run.label(i).to_string(),
            point: rows.points[i] + 1,
            line: rows.lines[i],
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
            .map(|row| RowJson {
                posture: run.label(row / 3).to_string(),
                point: rows.points[row / 3] + 1,
                line: rows.lines[row / 3],
                coordinate: ['x', 'y', 'z'][row % 3],
                weight: fit.weights[row],
                residual_mm: mm(id.residuals[row]),
            })
            .collect(),
    });
    let a = run.adequacy.as_ref();
    IdentifyJson {
        setup: run.setup_name.to_string(),
        data: run.data_name.clone(),
        springs: run.setup.springs(),
        method: text::method_key(id),
        rows: id.rows,
        postures: id.postures,
        stiffness_nm_per_rad: id.stiffness.into(),
        compliance_rad_per_nm: id.compliance.into(),
        physical: id.physical(),
        active_bounds: id.active_bounds,
        intervals_from: "residual variance",
        std_error_nm_per_rad: u.map(|u| u.stiffness_std_error.into()),
        ci95_nm_per_rad: u.map(|u| u.stiffness_ci95),
        ci95_from_compliance_nm_per_rad: u.map(|u| u.stiffness_ci95_from_compliance),
        compliance_std_error_rad_per_nm: u.map(|u| u.compliance_std_error.into()),
        compliance_ci95_rad_per_nm: u.map(|u| u.compliance_ci95),
        compliance_covariance_rad2_per_nm2: u.map(|u| {
            std::array::from_fn(|r| std::array::from_fn(|c| u.compliance_covariance[(r, c)]))
        }),
        degrees_of_freedom: u.map(|u| u.dof),
        t_quantile: u.map(|u| u.t_quantile),
        residual_std_mm: u.map(|u| mm(u.residual_variance.sqrt())),
        noise_std_mm: mm(run.setup.noise().sigma()),
        noise_ratio: a.map(|a| a.noise_ratio),
        chi2_statistic: a.map(|a| a.chi2),
        chi2_p_value: a.map(|a| a.p_value),
        model_error_dominates: a.map(Adequacy::model_error_dominates),
        tracker_noise: a.map(|a| intervals(&a.from_noise)),
        unit_warning: run.unit.as_ref().map(|u| text::unit_warning(run, u)),
        cond_psi: id.cond_psi,
        residual_rms_mm: mm(id.residual_rms),
        residuals,
        robust,
        cross_validation: run.cross_validation.as_ref().map(|cv| CrossValidationJson {
            folds: cv.folds.len(),
            stiffness_mean_nm_per_rad: cv.stiffness_mean.into(),
            stiffness_std_nm_per_rad: cv.stiffness_std.into(),
            stiffness_min_nm_per_rad: cv.stiffness_range[0].into(),
            stiffness_max_nm_per_rad: cv.stiffness_range[1].into(),
            rms_delta_b_mm: mm(cv.rms_delta_b),
            rms_measured_mm: mm(cv.rms_measured),
            explained: 1.0 - cv.rms_delta_b / cv.rms_measured,
            influential_postures: run.influential(),
            per_fold: cv
                .folds
                .iter()
                .map(|f| FoldJson {
                    postures: run.labels(&f.postures),
                    stiffness_nm_per_rad: f.stiffness.into(),
                    rms_delta_b_mm: mm(f.rms_delta_b),
                    delta_b_mm: f.delta_b.iter().map(|d| mm(*d)).collect(),
                })
                .collect(),
        }),
    }
}
