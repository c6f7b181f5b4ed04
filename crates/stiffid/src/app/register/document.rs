//! The documents of the register job ([`crate::app::register`]): `stiffid register --json`,
//! `stiffid register --count N --json`, Python's `register(...)`.

use crate::app::document::transform::{Transform, TransformStd};
use crate::app::document::{degrees, mm, mm3};
use crate::app::register;
use serde::Serialize;

/// The register document: the tracker's transform, its quality and uncertainty.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "register")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("register")))]
pub struct Document {
    /// The setup as given.
    pub setup: String,
    /// The readings file.
    pub data: String,
    /// The tracker frame in the robot base frame.
    #[serde(flatten)]
    pub transform: Transform,
    /// RMS of the residual lengths, mm.
    pub residual_rms_mm: f64,
    /// Noise per coordinate estimated from the residuals, mm.
    pub noise_std_mm: f64,
    /// How far each frame of the robot model may be from the true robot's, per coordinate of
    /// its position, mm (the setup's `[robot_accuracy] frame_sd_mm`): its part is in `std`.
    pub robot_frame_sd_mm: f64,
    /// The same of its orientation, mrad (`frame_sd_mrad`).
    pub robot_frame_sd_mrad: f64,
    /// The standard deviations the tracker noise alone gives (`std` without the robot's part).
    pub noise_only_std: TransformStd,
    /// Every unloaded reading's residual, in file order.
    pub points: Vec<Residual>,
    /// The `[tracker]` fragment of the setup file.
    pub fragment: String,
}

/// One reading's residual.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Residual {
    /// The posture's label.
    pub posture: String,
    /// The measuring point (1-based).
    pub point: usize,
    /// The line of the readings file.
    pub line: u64,
    /// Base-frame point minus the transformed tracker reading, mm.
    pub residual_mm: [f64; 3],
    /// Its length, mm.
    pub residual_norm_mm: f64,
}

impl Document {
    /// The document of `report`, for the setup named `setup_name` (as the user gave it).
    pub fn new(report: &register::Report, setup_name: &str) -> Self {
        let (data, fit) = (&report.readings, &report.registration);
        let unloaded = data
            .readings
            .iter()
            .zip(&data.lines)
            .filter(|(r, _)| r.unloaded() && !r.table);
        let points = unloaded
            .zip(&fit.residuals)
            .map(|((r, line), residual)| Residual {
                posture: data.labels[r.posture].clone(),
                point: r.point + 1,
                line: *line,
                residual_mm: mm3(residual),
                residual_norm_mm: mm(residual.norm()),
            })
            .collect();
        Document {
            setup: setup_name.to_string(),
            data: report.data_name.clone(),
            transform: Transform::new(&fit.base_from_tracker, fit.std().into()),
            residual_rms_mm: mm(fit.rms),
            noise_std_mm: mm(fit.sigma),
            robot_frame_sd_mm: report.frame_sd.0 * 1e3,
            robot_frame_sd_mrad: report.frame_sd.1 * 1e3,
            noise_only_std: TransformStd::new(
                (fit.covariance - fit.robot_covariance)
                    .diagonal()
                    .map(|v| v.max(0.0).sqrt())
                    .into(),
            ),
            points,
            fragment: fit.fragment(),
        }
    }
}

/// The registration postures proposed (`stiffid register --count N --json`, Python's
/// `register(setup, postures=N)`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "register-postures")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("register-postures")))]
pub struct Proposal {
    /// The setup as given.
    pub setup: String,
    /// The seed of the candidates, the exchange runs and the random groups.
    pub seed: u64,
    /// The postures, `R1`, `R2`, ...: axis angles, deg.
    pub postures: Vec<ProposedPosture>,
    /// Measuring points read per posture.
    pub measuring_points: usize,
    /// The tracker noise per coordinate of one reading (the setup's, level multiple 1), mm.
    pub noise_std_mm: f64,
    /// Predicted standard deviations of the transform at that noise (linearised).
    #[serde(flatten)]
    pub std: TransformStd,
    /// The criterion minimised: the root of the summed variances of the three rotation angles,
    /// deg.
    pub rotation_std_total_deg: f64,
    /// The same, median over 101 groups of as many feasible candidates drawn at random, deg.
    pub random_median_rotation_std_total_deg: f64,
    /// Candidate postures drawn in the bounds.
    pub candidates: usize,
    /// Candidates that pass the cell's checks.
    pub feasible: usize,
    /// The cell's checks the postures pass (those that apply without the load).
    pub checks: Vec<&'static str>,
    /// How the group was chosen (`enumeration` or `exchange`).
    pub method: &'static str,
    /// Groups evaluated.
    pub evaluations: usize,
    /// The readings CSV to fill in: one row per posture and measuring point, the external axes'
    /// columns (`e1_mm`, ...) at the station the postures were chosen at, the tracker's columns
    /// empty.
    pub readings_template: String,
}

/// A posture proposed.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ProposedPosture {
    /// Its label, `R1`, `R2`, ...
    pub posture: String,
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
}

impl Proposal {
    /// The document of `report`, for the setup named `setup_name` (as the user gave it).
    pub fn new(report: &register::DesignReport, setup_name: &str) -> Self {
        let d = &report.design;
        let postures: Vec<ProposedPosture> = (degrees(&d.postures).into_iter().enumerate())
            .map(|(i, q_deg)| ProposedPosture {
                posture: format!("R{}", i + 1),
                q_deg,
            })
            .collect();
        let template = template(report, &postures);
        Proposal {
            setup: setup_name.to_string(),
            seed: report.seed,
            postures,
            measuring_points: report.measuring_points,
            noise_std_mm: mm(d.noise_std),
            std: TransformStd::new(d.std().into()),
            rotation_std_total_deg: d.rotation_std.to_degrees(),
            random_median_rotation_std_total_deg: d.random_median_rotation_std.to_degrees(),
            candidates: d.candidates,
            feasible: d.feasible,
            checks: report.checks.iter().map(|k| k.key()).collect(),
            method: d.method.name(),
            evaluations: d.evaluations,
            readings_template: template,
        }
    }
}

/// The readings CSV of `postures` to fill in: one row per posture and measuring point, the
/// external axes' columns (`e1_mm`, ...) at the design's station, the tracker's columns empty.
fn template(report: &register::DesignReport, postures: &[ProposedPosture]) -> String {
    let header = stiffid_core::io::readings::header();
    let (header, external) = match &report.external {
        Some(axes) => {
            let e = &report.design.external;
            let names = axes.column_names().join(",");
            let values: Vec<String> = (axes.to_display(e).iter())
                .map(|v| format!("{v:.6},"))
                .collect();
            let header = header.replace("q6_deg,", &format!("q6_deg,{names},"));
            (header, values.concat())
        }
        None => (header, String::new()),
    };
    let mut text = header + "\n";
    for p in postures {
        let q: Vec<String> = p.q_deg.iter().map(|v| format!("{v:.6}")).collect();
        for point in 1..=report.measuring_points {
            text += &format!("{},{point},{},{external},,\n", p.posture, q.join(","));
        }
    }
    text
}
