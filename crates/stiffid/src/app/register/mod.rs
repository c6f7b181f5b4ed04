//! The register job: the laser tracker's transform to the robot base from measuring points read
//! by the tracker at known axis angles ([`stiffid_metrology::register`]: Umeyama's least-squares rigid
//! transform), its residuals and standard deviation (the tracker noise's and the robot model's own
//! error's, [`register::register`]); or the postures to register in
//! ([`propose`], [`stiffid_design::registration`]).

pub mod document;

use crate::app::document::transform::{Transform, TransformStd};
use crate::app::document::units;
use crate::app::in_data;
use crate::app::readings::refuse_implausible;
pub use crate::app::readings::{read, Request};
use crate::app::Warning;
use nalgebra::Vector3;
use serde::Serialize;
use stiffid_core::cell::{CheckKind, Checker};
use stiffid_core::common::error::JobOption;
use stiffid_core::io::readings::Readings;
use stiffid_core::{Result, Setup};
use stiffid_design::registration::{self as design, Design};
use stiffid_metrology::register::{self, Registration};

/// The register document: the tracker's transform, its quality and uncertainty.
///
/// The report is its own document (`stiffid register --json`, Python's `register(...)`): SI
/// lengths and angles written in mm and mrad by the unit adapters
/// ([`crate::app::document::units`]); the transform as a setup file writes it.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "register")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The register document: the tracker's transform, its quality and uncertainty."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("register")))]
pub struct Report {
    /// The setup as given.
    pub setup: String,
    /// The readings file.
    #[serde(rename = "data")]
    pub data_name: String,
    /// The tracker frame in the robot base frame.
    #[serde(flatten)]
    pub transform: Transform,
    /// RMS of the residual lengths: m, written in mm.
    #[serde(rename = "residual_rms_mm", serialize_with = "units::mm")]
    pub residual_rms: f64,
    /// Noise per coordinate estimated from the residuals: m, written in mm.
    #[serde(rename = "noise_std_mm", serialize_with = "units::mm")]
    pub noise_std: f64,
    /// How far each frame of the robot model may be from the true robot's, per coordinate of its
    /// position (the setup's `[robot_accuracy] frame_sd_mm`): m, written in mm; its part is in
    /// `std`.
    #[serde(rename = "robot_frame_sd_mm", serialize_with = "units::mm")]
    pub robot_frame_sd: f64,
    /// The same of its orientation (`frame_sd_mrad`): rad, written in mrad.
    #[serde(rename = "robot_frame_sd_mrad", serialize_with = "units::mrad")]
    pub robot_frame_sd_angle: f64,
    /// The standard deviations the tracker noise alone gives (`std` without the robot's part).
    pub noise_only_std: TransformStd,
    /// Every unloaded reading's residual, in file order.
    pub points: Vec<Residual>,
    /// The `[tracker]` fragment of the setup file.
    pub fragment: String,
    /// Inputs to look at before trusting the result (angles that look like radians): printed
    /// and raised, not written.
    #[serde(skip)]
    pub warnings: Vec<Warning>,
    /// The fit in SI (the transform, its residuals and covariance), for a library user: its
    /// numbers are written in the fields above.
    #[serde(skip)]
    pub registration: Registration,
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
    /// Base-frame point minus the transformed tracker reading: m, written in mm.
    #[serde(rename = "residual_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub residual: Vector3<f64>,
    /// Its length: m, written in mm.
    #[serde(rename = "residual_norm_mm", serialize_with = "units::mm")]
    pub residual_norm: f64,
}

/// The register job's report, which is its document.
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the register job.
///
/// # Errors
/// Those of [`read`]; of [`register::register`] (readings in the
/// base frame, fewer than [`register::MIN_POINTS`] unloaded readings, collinear points), as
/// [`stiffid_core::Error::Input`] naming the file; unless [`Request::force`], readings that are a
/// mirror image or leave a residual beyond [`register::residual_limit`] (the registration's check),
/// naming the reading.
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// The report of `fit` from `data`, with the robot model's frame standard deviations
/// `frame_sd` (m, rad).
fn report(
    request: &Request<'_>,
    data: &Readings,
    fit: Registration,
    frame_sd: (f64, f64),
    warnings: Vec<Warning>,
) -> Report {
    let unloaded =
        (data.readings.iter().zip(&data.lines)).filter(|(r, _)| r.unloaded() && !r.table);
    let points = unloaded
        .zip(&fit.residuals)
        .map(|((r, line), residual)| Residual {
            posture: data.labels[r.posture].clone(),
            point: r.point + 1,
            line: *line,
            residual: *residual,
            residual_norm: residual.norm(),
        })
        .collect();
    let noise_only = (fit.covariance - fit.robot_covariance).diagonal();
    Report {
        setup: request.setup_name.clone(),
        data_name: request.name.clone(),
        transform: Transform::new(&fit.base_from_tracker, fit.std().into()),
        residual_rms: fit.rms,
        noise_std: fit.sigma,
        robot_frame_sd: frame_sd.0,
        robot_frame_sd_angle: frame_sd.1,
        noise_only_std: TransformStd::new(noise_only.map(|v| v.max(0.0).sqrt()).into()),
        points,
        fragment: fit.fragment(),
        warnings,
        registration: fit,
    }
}

/// What [`run`] finds, before its document.
fn find(request: &Request<'_>) -> Result<Report> {
    let (data, warnings) = read(request)?;
    let name = &request.name;
    let registration = register::register(request.setup, &data).map_err(|e| in_data(name, e))?;
    refuse_implausible(request, &data, Some(&registration), &registration.residuals)?;
    let frame_sd = request.setup.arm().frame_sd();
    Ok(report(request, &data, registration, frame_sd, warnings))
}

/// Registration postures to propose: `stiffid register --count N`.
pub struct DesignRequest<'a> {
    /// The setup: robot, tool (its measuring points), bounds, cell, tracker, noise.
    pub setup: &'a Setup,
    /// The setup as the user named it (a built-in setup's name or a file's path): what the
    /// proposal states.
    pub setup_name: String,
    /// How many postures (1 to [`design::MAX_POSTURES`]).
    pub postures: usize,
    /// The seed, the candidates and the exchange runs.
    pub options: design::Options,
    /// Whether the caller asked to fit implausible readings ([`Request::force`]): refused, a
    /// proposal fits none.
    pub force: bool,
}

/// The registration postures proposed.
///
/// The report is its document (`stiffid register --count N --json`, Python's `register(setup,
/// count=N)`), written through the view [`document::Proposal`] ([`DesignReport::document`]).
#[derive(Debug, Clone)]
pub struct DesignReport {
    /// The setup as the user named it ([`DesignRequest::setup_name`]).
    pub setup: String,
    /// The postures and their predicted covariance ([`design::design`]).
    pub design: Design,
    /// The cell's checks the postures pass (those that apply without the load).
    pub checks: Vec<CheckKind>,
    /// Measuring points read per posture.
    pub measuring_points: usize,
    /// The cell's external axes (their readings' columns; the postures are read with them at
    /// [`stiffid_design::registration::Design::external`]).
    pub external: Option<stiffid_core::robot::ExternalAxes>,
    /// The seed.
    pub seed: u64,
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    pub warnings: Vec<Warning>,
}

impl DesignReport {
    /// The document this report is written as (`stiffid register --count N --json`, Python's
    /// `register(setup, count=N)`), to read: what the command's text prints and `--out` writes.
    pub fn document(&self) -> document::Proposal<'_> {
        document::Proposal::new(self)
    }
}

impl Serialize for DesignReport {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// The postures proposed, which are their document (serialised through [`document::Proposal`]).
pub(crate) type Proposed = crate::app::Outcome<DesignReport>;

/// Proposes the registration postures that minimise the rotation's standard deviation
/// ([`design::design`]).
///
/// # Errors
/// [`stiffid_core::Error::InvalidOption`] ([`JobOption::Force`]) with [`DesignRequest::force`]; those
/// of [`design::design`].
pub fn propose(request: &DesignRequest<'_>) -> Result<Proposed> {
    Ok(Proposed {
        report: find_proposal(request)?,
        document: crate::app::Itself,
    })
}

/// What [`propose`] finds, before its document.
fn find_proposal(request: &DesignRequest<'_>) -> Result<DesignReport> {
    if request.force {
        return Err(stiffid_core::Error::InvalidOption {
            option: JobOption::Force,
            message: "only with readings to register from: a proposal of postures fits none".into(),
        });
    }
    request.setup.check_bodies()?;
    let design = design::design(request.setup, request.postures, &request.options)?;
    let checker = Checker::new(request.setup);
    let checks = (checker.kinds().iter())
        .filter(|k| !design::LOAD_CHECKS.contains(k))
        .copied()
        .collect();
    Ok(DesignReport {
        setup: request.setup_name.clone(),
        design,
        checks,
        measuring_points: request.setup.tool().measuring_points.len(),
        external: (request.setup.robot().external())
            .filter(|a| !a.is_empty())
            .cloned(),
        seed: request.options.seed,
        warnings: Vec::new(),
    })
}
