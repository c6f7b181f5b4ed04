//! `stiffid identify`: joint stiffness from a measurement file (Zhang et al. 2021, Eq. 10-14), with
//! standard errors, 95% confidence intervals, the model check against the tracker noise,
//! residuals, and optionally a robust or non-negative fit and cross-validation: the arguments
//! turned into a [`stiffid::app::identify::Request`], the job run, its report rendered.

use crate::commands::common::{choice, Common};
use crate::load;
use crate::output::{self, json, OutFile};
use crate::progress::Bars;
use crate::report::identification;
use anyhow::Result;
use std::path::PathBuf;
use stiffid::app::identify::{self as job, Options, Report, Request};
use stiffid::app::measurements::Data;
use stiffid::internal::identify::Loss;
use stiffid::Progress;

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
    #[arg(long)]
    offsets: bool,
    /// Down-weight outliers by iteratively reweighted least squares (`--robust` alone: huber).
    #[arg(long, value_parser = choice::<Loss>(), num_args = 0..=1, default_missing_value = "huber")]
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
    /// with `--compare-models`, the recommended model's `[model]` fragment for the setup. A
    /// stiffness file those would refuse (a negative compliance) is not written: refused with
    /// the way out (--nonnegative, --compare-models).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Compare models: add candidate virtual springs to the setup's model by forward selection on
    /// the leave-one-posture-out error, nested in an outer cross-validation; recommend the
    /// smallest model within one standard error of the best.
    #[arg(long)]
    compare_models: bool,
    /// The candidates of `--compare-models`, comma-separated: single candidates (`tilt3_z`,
    /// `bend2_y`, `tool_y`, `base_rz`, a declared spring's name) or families (`tilt`, `bend`,
    /// `carriage`, `base`, `tool`, `lost`, `load`, `declared`); default all of them. Those along a joint's own axis or
    /// duplicating another are left out, with the reason.
    #[arg(long, value_delimiter = ',')]
    candidates: Option<Vec<String>>,
    /// With `--compare-models`: N posture bootstrap resamples (1 to 2000), the whole selection
    /// redone on each; reports how often each parameter is chosen and the spread of its
    /// stiffness over the models chosen.
    #[arg(long, value_name = "N")]
    bootstrap: Option<usize>,
    /// The seed of the bootstrap's draws: the same seed gives the same result whatever the
    /// thread count (default 1).
    #[arg(long)]
    seed: Option<u64>,
    /// With `--compare-models --bootstrap N`: also write a stiffness file, the setup's model
    /// fitted to every posture with the models the data support and their resampled parameter
    /// sets (`model_form`): `compensate --stiffness` takes their spread as its error budget's
    /// model-form part.
    #[arg(long, requires = "bootstrap")]
    stiffness_out: Option<PathBuf>,
    /// Also write a report into this directory (created; must be missing, empty or hold an
    /// earlier identification report): the residuals' QQ plot against the noise, the folds'
    /// stability, the prediction intervals' held-out scores, the compared models.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// Identifies (or compares models), prints, and writes `--out`: the options checked together
/// by the library ([`Options`]) before any file is opened.
pub fn run(args: &Args) -> Result<()> {
    let options = Options {
        robust: args.robust,
        nonnegative: args.nonnegative,
        cross_validate: args.cross_validate,
        folds: args.folds,
        offsets: args.offsets,
        compare_models: args.compare_models,
        candidates: args.candidates.clone(),
        bootstrap: args.bootstrap,
        seed: args.seed,
    };
    options.check()?;
    let setup = args.common.load_setup()?;
    // Opened (and so known as an input, never written over) before --out is prepared.
    let reader = load::open(&args.data)?;
    let out = args
        .out
        .as_deref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let stiffness_out = (args.stiffness_out.as_deref())
        .map(|p| OutFile::prepare(p, "--stiffness-out"))
        .transpose()?;
    let report_dir = args
        .report
        .as_deref()
        .map(identification::open)
        .transpose()?;
    let bars = Bars::new(false);
    let request = Request {
        setup: &setup,
        setup_name: args.common.setup.clone(),
        data: Data::File {
            name: args.data.display().to_string(),
            reader,
        },
        options,
        progress: &bars,
    };
    // A spinner for the whole job, replaced by the bootstrap's bar when there is one.
    bars.begin("identification", 0);
    let outcome = job::run(request);
    bars.end();
    let report = outcome?.report;
    output::warnings(report.warnings());
    let name = &args.common.setup;
    // The document's JSON is its form's (each form names itself in `kind`).
    let json_text = json(&report)?;
    let text = match &report {
        Report::Comparison(r) => {
            if let Some(out) = &out {
                out.write(r.fragment().as_bytes())?;
            }
            if let Some(out) = &stiffness_out
                && let Some(text) = r.stiffness_file_text(&setup, &output::flag)?
            {
                out.write(text.as_bytes())?;
            }
            if let Some(dir) = report_dir {
                identification::write(dir, &json_text, &setup, None)?;
            }
            return match args.common.json {
                true => output::print(&json_text),
                false => output::print(&models::text(&r.document(), &r.comparison, &setup)),
            };
        }
        Report::Drives(r) => text::human(r, &r.document(), name, &setup),
        Report::Springs(r) => models::model_text(r, &r.document(), &setup),
    };
    if let Some(out) = &out {
        job::check_stiffness_file(&json_text, &setup, &output::flag)?;
        out.write(json_text.as_bytes())?;
    }
    if let Some(dir) = report_dir {
        let postures = report.postures().map(<[_]>::to_vec).zip(report.external());
        identification::write(dir, &json_text, &setup, postures)?;
    }
    match args.common.json {
        true => output::print(&json_text),
        false => output::print(&text),
    }
}
