//! `stiffid register`: the laser tracker's transform to the robot base from measuring points read
//! by the tracker at known axis angles ([`stiffid::jobs::register`]: Umeyama's least-squares rigid
//! transform), its residuals and standard deviation, and the `[tracker]` fragment of the setup
//! file.

use crate::commands::cell_readings::{self, three, Outcome};
use anyhow::Result;
use stiffid::documents::register::Document;
use stiffid::jobs::register as job;

/// Arguments of `stiffid register`: `--data` holds at least 3 points not on one line; `--out`
/// gets the `[tracker] base_from_tracker` fragment.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("readings").required(true).args(["data"])))]
pub struct Args {
    #[command(flatten)]
    readings: cell_readings::Args,
}

/// Runs `stiffid register`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.readings.setup()?;
    let name = &args.readings.common.setup;
    let job = |request: &job::Request<'_>| {
        let report = job::run(request)?;
        let document = Document::new(&report, name);
        Ok(Outcome {
            fragment: document.fragment.clone(),
            document,
            warnings: report.warnings,
        })
    };
    args.readings.run(&setup, job, text_of)
}

fn text_of(d: &Document) -> String {
    let t = &d.transform;
    let mut text = format!(
        "registration of {} points (setup {})\n\
         base_from_tracker: xyz_mm = [{}], rpy_deg = [{}]\n\
         standard deviation: translation [{}] mm, rotation [{}] deg\n\
         residual RMS {:.4} mm (noise per coordinate {:.4} mm)\n\
         \nposture  point  line  residual_mm\n",
        d.points.len(),
        d.setup,
        three(t.xyz_mm, 4),
        three(t.rpy_deg, 5),
        three(t.translation_std_mm, 4),
        three(t.rotation_std_deg, 5),
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
