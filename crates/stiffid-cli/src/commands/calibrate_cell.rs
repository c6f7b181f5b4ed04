//! `stiffid calibrate-cell`: the tracker's transform and the measuring points in the flange frame
//! fitted together from unloaded readings ([`stiffid::calibrate`]), each point's shift from the
//! setup's value with its standard deviation, and the corrected fragment of the setup file.

use crate::commands::common::Common;
use crate::load;
use crate::output::{print_json_or, OutFile};
use anyhow::{Context, Result};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::calibrate::{self, Calibration};
use stiffid::formats::readings;

/// Arguments of `stiffid calibrate-cell`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Readings CSV (as for `register`; with load steps, the unloaded readings): every measuring
    /// point read in postures that turn the flange; more coordinates than 6 + 3 per point read.
    #[arg(long)]
    data: PathBuf,
    /// Write the corrected `[tracker]` fragment and measuring points here (TOML; never over an
    /// input).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// `stiffid calibrate-cell --json`: the transform, the measuring points and the robot's unloaded
/// absolute error.
#[derive(Serialize, JsonSchema)]
pub struct CalibrateJson {
    /// The setup as given (`--setup`).
    setup: String,
    /// The tracker frame in the robot base frame: translation, mm.
    xyz_mm: [f64; 3],
    /// ... and fixed-axis roll, pitch, yaw, deg (as the setup's `base_from_tracker`).
    rpy_deg: [f64; 3],
    /// Standard deviation of the translation, base frame, mm.
    translation_std_mm: [f64; 3],
    /// Standard deviation of the rotation about the base x, y, z axes, deg.
    rotation_std_deg: [f64; 3],
    /// Every measuring point of the setup.
    points: Vec<PointJson>,
    /// RMS of the residual lengths, mm: the robot's unloaded absolute positioning error at these
    /// postures (with the tracker noise).
    absolute_error_rms_mm: f64,
    /// Noise per coordinate estimated from the residuals, mm.
    noise_std_mm: f64,
    /// Unloaded readings used.
    readings: usize,
    /// Gauss-Newton iterations.
    iterations: usize,
    /// The corrected fragment of the setup file.
    fragment: String,
}

/// One measuring point: the setup's, the fitted, the shift and its standard deviation.
#[derive(Serialize, JsonSchema)]
struct PointJson {
    /// The measuring point (1-based).
    point: usize,
    /// The setup's value, flange frame, mm.
    setup_mm: [f64; 3],
    /// The fitted value, flange frame, mm.
    fitted_mm: [f64; 3],
    /// Fitted minus setup, mm.
    shift_mm: [f64; 3],
    /// Standard deviation of the fitted coordinates, mm; `null` for a point never read.
    std_mm: Option<[f64; 3]>,
}

/// Runs `stiffid calibrate-cell`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let name = args.data.display().to_string();
    let text = load::read(&args.data)?;
    let points = setup.tool().measuring_points.len();
    let data = readings::parse(&text, setup.robot(), points).with_context(|| name.clone())?;
    let out = args
        .out
        .as_ref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let observations = calibrate::observations(&setup, &data).with_context(|| name.clone())?;
    let fit =
        calibrate::fit(&observations, &setup.tool().measuring_points).with_context(|| name)?;
    let doc = document(
        &args.common.setup,
        &setup.tool().measuring_points,
        observations.len(),
        &fit,
    );
    if let Some(out) = &out {
        out.write(doc.fragment.as_bytes())?;
    }
    print_json_or(args.common.json, &doc, text_of)
}

fn mm(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v.x * 1e3, v.y * 1e3, v.z * 1e3]
}

fn document(
    setup: &str,
    setup_points: &[nalgebra::Vector3<f64>],
    readings: usize,
    fit: &Calibration,
) -> CalibrateJson {
    let t = fit.base_from_tracker.translation.vector;
    let (r, p, y) = fit.base_from_tracker.rotation.euler_angles();
    let s = fit.transform_std;
    let points: Vec<PointJson> = (0..setup_points.len())
        .map(|k| PointJson {
            point: k + 1,
            setup_mm: mm(&setup_points[k]),
            fitted_mm: mm(&fit.points[k]),
            shift_mm: mm(&fit.shifts[k]),
            std_mm: fit.point_std[k].as_ref().map(mm),
        })
        .collect();
    let list = |v: [f64; 3]| format!("[{:.6}, {:.6}, {:.6}]", v[0], v[1], v[2]);
    let measuring: Vec<String> = points.iter().map(|p| list(p.fitted_mm)).collect();
    let fragment = format!(
        "# cell calibration from {readings} unloaded readings: unloaded absolute error RMS {:.4} mm\n\
         [tracker]\nbase_from_tracker = {{ xyz_mm = {}, rpy_deg = {} }}\n\
         # in [tool]:\n# measuring_points_mm = [{}]\n",
        fit.rms * 1e3,
        list(mm(&t)),
        list([r, p, y].map(f64::to_degrees)),
        measuring.join(", ")
    );
    CalibrateJson {
        setup: setup.to_string(),
        xyz_mm: mm(&t),
        rpy_deg: [r, p, y].map(f64::to_degrees),
        translation_std_mm: [s[0] * 1e3, s[1] * 1e3, s[2] * 1e3],
        rotation_std_deg: [s[3], s[4], s[5]].map(f64::to_degrees),
        points,
        absolute_error_rms_mm: fit.rms * 1e3,
        noise_std_mm: fit.sigma * 1e3,
        readings,
        iterations: fit.iterations,
        fragment,
    }
}

fn text_of(d: &CalibrateJson) -> String {
    let three = |v: [f64; 3], digits: usize| {
        format!("{:.digits$}, {:.digits$}, {:.digits$}", v[0], v[1], v[2])
    };
    let mut text = format!(
        "cell calibration from {} unloaded readings (setup {}, {} Gauss-Newton iterations)\n\
         base_from_tracker: xyz_mm = [{}], rpy_deg = [{}]\n\
         standard deviation: translation [{}] mm, rotation [{}] deg\n\
         robot's unloaded absolute error at these postures: RMS {:.4} mm (noise per coordinate {:.4} mm)\n\
         \npoint  shift_mm (flange frame)          std_mm\n",
        d.readings,
        d.setup,
        d.iterations,
        three(d.xyz_mm, 4),
        three(d.rpy_deg, 5),
        three(d.translation_std_mm, 4),
        three(d.rotation_std_deg, 5),
        d.absolute_error_rms_mm,
        d.noise_std_mm,
    );
    for p in &d.points {
        let std = p.std_mm.map_or("not read".to_string(), |s| three(s, 4));
        text += &format!("{:>5}  [{}]  [{}]\n", p.point, three(p.shift_mm, 4), std);
    }
    text + "\n" + &d.fragment
}
