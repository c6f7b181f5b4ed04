//! `stiffid validate`: predicted against measured displacements for an identified stiffness
//! (Zhang et al. 2021, Eq. 22, Table 7), over every parameter of the setup's model: the arguments
//! turned into a [`stiffid::app::validate::Request`], the job run, its document rendered.

use crate::commands::common::{Common, Stiffness};
use crate::load;
use crate::output::{self, print_json_or};
use crate::progress::Bars;
use anyhow::Result;
use std::path::PathBuf;
use stiffid::app::measurements::Data;
use stiffid::app::validate::document::Document;
use stiffid::app::validate::{self as job, Request};
use stiffid::internal::common::words::count;
use stiffid::Progress;

/// Arguments of `stiffid validate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    #[command(flatten)]
    stiffness: Stiffness,
    /// Measurements CSV or raw readings under load steps (the formats `identify` reads), ideally
    /// postures not used to identify.
    #[arg(long)]
    data: PathBuf,
    /// The level of the prediction intervals (0.5 to 0.999), built from the held-out residuals
    /// the stiffness file holds (`identify --cross-validate`).
    /// Only with such a file [default: 0.95].
    #[arg(long)]
    level: Option<f64>,
}

/// Validates and prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let compliance = args.stiffness.load(&setup)?;
    let reader = load::open(&args.data)?;
    // The job reports no count: a spinner says it is reading and predicting.
    let bars = Bars::new(false);
    bars.begin("validation", 0);
    let outcome = job::run(Request {
        setup_name: args.common.setup.clone(),
        setup: &setup,
        compliance: &compliance,
        data: Data::File {
            name: args.data.display().to_string(),
            reader,
        },
        level: args.level,
    });
    bars.end();
    let outcome = outcome?;
    output::warnings(&outcome.warnings);
    print_json_or(args.common.json, outcome.written(), |r| {
        human(&r.document())
    })
}

fn human(r: &Document<'_>) -> String {
    let k: Vec<String> = r
        .parameters
        .iter()
        .map(|p| {
            let v = p.stiffness.map_or("inf".into(), |k| format!("{k:.0}"));
            format!("{} {v} {}", p.name, p.unit)
        })
        .collect();
    let mut s = format!(
        "setup {}, data {}\nstiffness: {}\n\n\
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
        "\ndelta_b (Eq. 22) over {}: mean {:.4} mm, max {:.4} mm, RMS {:.4} mm\n",
        count(r.checks.len(), "measurement"),
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
        r.explained_pct
    );
    s += &match &r.prediction_intervals {
        Some(p) => format!(
            "prediction intervals ({}, {:.0}% level, from the held-out residuals of the identification): {:.1}% of {} measured coordinates inside ({} outside)
",
            p.method,
            100.0 * p.level,
            p.coverage_pct,
            p.coordinates,
            p.coordinates - p.covered
        ),
        None => "prediction intervals: none (the stiffness file holds no held-out residuals: identify with --cross-validate)
".into(),
    };
    s
}
