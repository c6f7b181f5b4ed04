//! `stiffid calibrate-cell`: the tracker's transform and the measuring points in the flange frame
//! fitted together from unloaded readings ([`stiffid::app::calibrate_cell`]), each point's shift from
//! the setup's value with its standard deviation, and the corrected fragment of the setup file.

use crate::commands::cell_readings::{self, three, Outcome};
use anyhow::Result;
use stiffid::app::calibrate_cell as job;
use stiffid::app::calibrate_cell::Report;
use stiffid::app::document::{mm, mm3};

/// Arguments of `stiffid calibrate-cell`: `--data` is every measuring point read in postures
/// that turn the flange (more coordinates than 6 + 3 per point read); `--out` gets the corrected
/// `[tracker]` fragment and measuring points.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("readings").required(true).args(["data"])))]
pub struct Args {
    #[command(flatten)]
    readings: cell_readings::Args,
}

/// Runs `stiffid calibrate-cell`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.readings.setup()?;
    let job = |request: &job::Request<'_>| {
        let report = job::run(request)?.report;
        Ok(Outcome {
            fragment: report.fragment.clone(),
            warnings: report.warnings.clone(),
            document: report,
        })
    };
    args.readings.run(&setup, job, text_of)
}

fn text_of(d: &Report) -> String {
    let t = &d.transform;
    let mut text = format!(
        "cell calibration from {} unloaded readings (setup {}, {} iterations)\n\
         base_from_tracker: xyz_mm = [{}], rpy_deg = [{}]\n\
         standard deviation: translation [{}] mm, rotation [{}] deg\n\
         robot's unloaded absolute error at these postures: RMS {:.4} mm (noise per coordinate {:.4} mm)\n\
         \npoint  shift_mm (flange frame)          std_mm\n",
        d.readings,
        d.setup,
        d.iterations,
        three(t.xyz_mm, 4),
        three(t.rpy_deg, 5),
        three(t.std.translation_std_mm, 4),
        three(t.std.rotation_std_deg, 5),
        mm(d.absolute_error_rms),
        mm(d.noise_std),
    );
    for p in &d.points {
        let std = p.std.map_or("not read".to_string(), |s| three(mm3(&s), 4));
        text += &format!("{:>5}  [{}]  [{}]\n", p.point, three(mm3(&p.shift), 4), std);
    }
    text + "\n" + &d.fragment
}
