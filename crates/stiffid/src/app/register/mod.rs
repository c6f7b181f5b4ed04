//! The register job: the laser tracker's transform to the robot base from measuring points read
//! by the tracker at known axis angles ([`stiffid_metrology::register`]: Umeyama's least-squares rigid
//! transform), its residuals and standard deviation (the tracker noise's and the robot model's own
//! error's, [`register::robot_covariance`]); or the postures to register in
//! ([`propose`], [`stiffid_design::registration`]).

pub mod document;

use crate::app::in_data;
use crate::app::readings::refuse_implausible;
pub use crate::app::readings::{read, Request};
use crate::app::Warning;
use stiffid_core::cell::{CheckKind, Checker};
use stiffid_core::common::error::JobOption;
use stiffid_core::io::readings::Readings;
use stiffid_core::{Result, Setup};
use stiffid_design::registration::{self as design, Design};
use stiffid_metrology::register::{self, Registration};

/// What the register job found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The readings file's name.
    pub data_name: String,
    /// The readings (their labels and lines name the residuals).
    pub readings: Readings,
    /// The transform, its residuals (one per unloaded reading, in file order) and covariance.
    pub registration: Registration,
    /// Inputs to look at before trusting the result (angles that look like radians).
    pub warnings: Vec<Warning>,
    /// The robot model's frame standard deviations the covariance holds, m and rad
    /// ([`stiffid_core::setup::Arm::frame_sd`]).
    pub frame_sd: (f64, f64),
}

/// The register job's report and its document.
pub type Outcome = crate::app::Outcome<Report, document::Document>;

/// Runs the register job.
///
/// # Errors
/// Those of [`read`]; of [`register::correspondences`] and [`register::fit`] (readings in the
/// base frame, fewer than [`register::MIN_POINTS`] unloaded readings, collinear points), as
/// [`stiffid_core::Error::Input`] naming the file; unless [`Request::force`], readings that are a
/// mirror image or leave a residual beyond [`register::residual_limit`] ([`register::suspect`]),
/// naming the reading.
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    let report = find(request)?;
    let document = document::Document::new(&report, &request.setup_name);
    Ok(Outcome { report, document })
}

/// What [`run`] finds, before its document.
fn find(request: &Request<'_>) -> Result<Report> {
    let (data, warnings) = read(request)?;
    let name = &request.name;
    let points = register::correspondences(request.setup, &data).map_err(|e| in_data(name, e))?;
    let registration = register::fit(&points).map_err(|e| in_data(name, e))?;
    let robot = register::robot_covariance(request.setup, &data, &registration);
    let registration = registration.with_robot(robot.map_err(|e| in_data(name, e))?);
    let fit = &registration;
    refuse_implausible(request, &data, Some(fit), &fit.residuals)?;
    Ok(Report {
        data_name: name.clone(),
        readings: data,
        registration,
        warnings,
        frame_sd: request.setup.arm().frame_sd(),
    })
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
#[derive(Debug, Clone)]
pub struct DesignReport {
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

/// The postures proposed and their document.
pub type Proposed = crate::app::Outcome<DesignReport, document::Proposal>;

/// Proposes the registration postures that minimise the rotation's standard deviation
/// ([`design::design`]).
///
/// # Errors
/// [`stiffid_core::Error::InvalidOption`] ([`JobOption::Force`]) with [`DesignRequest::force`]; those
/// of [`design::design`].
pub fn propose(request: &DesignRequest<'_>) -> Result<Proposed> {
    let report = find_proposal(request)?;
    let document = document::Proposal::new(&report, &request.setup_name);
    Ok(Proposed { report, document })
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
