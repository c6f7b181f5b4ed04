//! `stiffid identify`: joint stiffness from a measurement file (Zhang et al. 2021, Eq. 10-14), with
//! standard errors, 95% confidence intervals, the model check against the tracker noise,
//! residuals, and optionally a robust or non-negative fit and cross-validation: the arguments
//! turned into a [`stiffid::app::identify::Request`], the job run, its report rendered.

use crate::commands::common::{choice, Common};
use crate::load;
use crate::output::{self, json, OutFile};
use anyhow::Result;
use std::path::PathBuf;
use stiffid::app::identify::document::Document;
use stiffid::app::identify::{self as job, Data, Fit, Folds, Request};
use stiffid::identify::Loss;

mod models;
mod text;

/// Arguments of `stiffid identify`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Measurements CSV: posture,point,q1_deg..q6_deg,fx_n,fy_n,fz_n\[,mx_nm,my_nm,mz_nm\],dx_mm,dy_mm,dz_mm;
    /// or raw readings under load steps:
    /// posture,point,q1_deg..q6_deg,load_step,fx_n,fy_n,fz_n,x_tracker_mm,y_tracker_mm,z_tracker_mm
    /// (`load_n` instead of `load_step`; `x_mm,y_mm,z_mm` in the base frame).
    #[arg(long)]
    data: PathBuf,
    /// Fit an offset per posture and measuring point beside the compliances (backlash,
    /// friction): needs at least two different loads of every point in every posture; least
    /// squares only.
    #[arg(long, conflicts_with_all = ["robust", "nonnegative", "cross_validate", "folds"])]
    offsets: bool,
    /// Down-weight outliers by iteratively reweighted least squares (`--robust` alone: huber).
    #[arg(long, value_parser = choice::<Loss>(), num_args = 0..=1, default_missing_value = "huber", conflicts_with = "nonnegative")]
    robust: Option<Loss>,
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
    /// The candidates of `--compare-models`, comma-separated: single candidates (`tilt3_z`,
    /// `bend2_y`, `tool_y`, `base_rz`, a declared spring's name) or families (`tilt`, `bend`,
    /// `base`, `tool`, `declared`); default all of them. Those along a joint's own axis or
    /// duplicating another are left out, with the reason.
    #[arg(long, value_delimiter = ',', requires = "compare_models")]
    candidates: Option<Vec<String>>,
    /// With `--compare-models`: N posture bootstrap resamples (1 to 10000), the whole selection
    /// redone on each; reports how often each parameter is chosen and the spread of its
    /// stiffness over the models chosen.
    #[arg(long, value_name = "N", requires = "compare_models")]
    bootstrap: Option<usize>,
    /// The seed of the bootstrap's draws: the same seed gives the same result whatever the
    /// thread count.
    #[arg(long, default_value_t = 1, requires = "bootstrap")]
    seed: u64,
}

/// Identifies, prints, and writes `--out`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    if args.compare_models {
        return models::compare_models(args, &setup);
    }
    // Opened (and so known as an input, never written over) before --out is prepared.
    let reader = load::open(&args.data)?;
    let fit = match (args.robust, args.nonnegative) {
        (Some(loss), _) => Fit::Robust(loss),
        (None, true) => Fit::Nonnegative,
        (None, false) => Fit::LeastSquares,
    };
    let folds = match (args.folds, args.cross_validate) {
        (Some(k), _) => Some(Folds::Count(k)),
        (None, true) => Some(Folds::LeaveOneOut),
        (None, false) => None,
    };
    let request = Request {
        setup: &setup,
        data: Data::File {
            name: args.data.display().to_string(),
            reader,
        },
        fit,
        folds,
        offsets: args.offsets,
    };
    if !setup.model().is_drives_only() {
        return models::identify_model(args, &setup, request);
    }
    let out = args
        .out
        .as_deref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let report = job::run(request)?;
    output::warnings(&report.warnings);
    let doc = Document::new(&report, &args.common.setup, &setup);
    if args.common.json || out.is_some() {
        let text = json(&doc)?;
        if let Some(out) = &out {
            out.write(text.as_bytes())?;
        }
        if args.common.json {
            return output::print(&text);
        }
    }
    output::print(&text::human(&report, &doc, &args.common.setup, &setup))
}
