//! The robot calibration job (`stiffid calibrate`): the robot's geometric errors, the gravity
//! terms, the tracker's registration and the measuring points fitted together from the readings
//! of a campaign ([`stiffid_metrology::calibration`]); with loaded readings (load steps) the
//! compliances of the setup's stiffness model in the same fit ([`ErrorModel::with_loads`]);
//! held-out validation with prediction intervals built from the leave-one-posture-out errors
//! (jackknife+, [`stiffid_metrology::calibration::intervals`]) and their coverage, and
//! leave-one-posture-out cross-validation; the calibrated robot as a
//! robot TOML file and a URDF, the fitted compliances as a stiffness file. `--geometry none
//! --gravity none` is the cell calibration of `calibrate-cell`.
//!
//! With [`Request::update`], a calibrated robot refitted from check readings after their check
//! ([`drift`]). Limits: at most `MAX_READINGS` readings (the readings file's own limit), at most
//! [`stiffid_metrology::calibration::error_model::MAX_POINTS`] measuring points, more coordinates
//! than identifiable parameters, at most 5000 postures with cross-validation (one fit per posture;
//! beyond it, held-out readings get no intervals), at least `MIN_UPDATE_POSTURES` postures with
//! `update`.

mod checks;
mod chosen;
mod compliance;
pub mod document;
pub mod drift;
mod files;
mod held;
mod held_document;
mod ladder_document;
mod maps_document;
mod part;
pub mod scene;
pub(crate) mod update;

use stiffid_metrology::calibration::judgement::judge::{judge, largest_residual};
use stiffid_metrology::calibration::judgement::maps;
pub use stiffid_metrology::calibration::judgement::{
    diverged, extrapolation, fit_bound, ladder, region,
};

pub(crate) use compliance::fitted_compliance;
pub(crate) use compliance::FittedCompliance;
pub use extrapolation::Outside;
pub use ladder::{GravitySpec, Ladder, Rung};
pub(crate) use maps::Maps;
pub use update::{Refit, Refits};

use crate::app::in_data;
use crate::app::readings::{read, refuse_implausible, Request as Readings};
use crate::app::{Warning, WarningKind};
use checks::{cross_validation_size, interval_level, refuse_repeated};
use nalgebra::{DVector, Vector3};
use stiffid_core::common::error::JobOption;
use stiffid_core::common::limits;
use stiffid_core::common::progress::Progress;
use stiffid_core::io::readings::Readings as Data;
use stiffid_core::observation::deflection::base_wrench;
use stiffid_core::observation::frames::DisplacementFrame;
use stiffid_core::{Error, Result, Setup};
use stiffid_metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid_metrology::calibration::fit::{self, Fit};
use stiffid_metrology::calibration::gravity::{self, Gravity};
use stiffid_metrology::calibration::intervals::{self, Coverage, Intervals};
use stiffid_metrology::calibration::validation::{self, Validation};
use stiffid_metrology::calibration::{ErrorModel, Estimate, Geometry};

/// Most postures cross-validation takes (one Gauss-Newton step from the full fit per posture;
/// the held-out readings' intervals the same folds).
pub(crate) const MAX_CROSS_VALIDATION_POSTURES: usize = 5000;

/// Nominal tolerances of the joint errors, as priors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Of a length, m.
    pub length: f64,
    /// Of an angle, rad.
    pub angle: f64,
}

impl Tolerances {
    /// The tolerances of a length, `length_mm` (mm), and of an angle, `angle_deg` (deg).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::Tolerances`]) unless they lie within
    /// [`limits::TOLERANCE_MM`] and [`limits::TOLERANCE_DEG`].
    pub fn from_mm_deg(length_mm: f64, angle_deg: f64) -> Result<Self> {
        match limits::TOLERANCE_MM.contains(length_mm) && limits::TOLERANCE_DEG.contains(angle_deg)
        {
            true => Ok(Tolerances {
                length: length_mm * 1e-3,
                angle: angle_deg.to_radians(),
            }),
            false => Err(Error::InvalidOption {
                option: JobOption::Tolerances,
                message: format!(
                    "expected {} and {}, got {} and {}",
                    limits::TOLERANCE_MM,
                    limits::TOLERANCE_DEG,
                    stiffid_core::common::words::number(length_mm),
                    stiffid_core::common::words::number(angle_deg)
                ),
            }),
        }
    }
}

/// What the job needs.
pub struct Request<'a> {
    /// The readings to fit (the setup, the file's name and text), as `register` reads them.
    pub readings: Readings<'a>,
    /// The joint errors fitted.
    pub geometry: Geometry,
    /// The gravity terms fitted: chosen with the maps by [`ladder`] (`auto`), or given.
    pub gravity: GravitySpec,
    /// The bound on the gravity terms, rad: the prior standard deviation of each term's joint
    /// deflection at the largest torque it meets ([`fit::GravityPrior`]), the same for every
    /// gravity model, chosen by the ladder or given; within [`limits::GRAVITY_BOUND_MRAD`];
    /// `None` for 3 mrad ([`fit::Options::for_campaign`]).
    pub gravity_bound: Option<f64>,
    /// Held-out readings (name, text), predicted by the calibration.
    pub validate: Option<(String, &'a str)>,
    /// Register the tracker anew on the held-out readings (another series: the tracker moved).
    pub reregister: bool,
    /// Leave-one-posture-out cross-validation.
    pub cross_validate: bool,
    /// Priors on the joint errors, if any.
    pub priors: Option<Tolerances>,
    /// Hears the fit (`fit`) and the maps' choice (`joint error maps`), each a stage of total 0,
    /// then the cross-validation's folds (`cross-validation`, one unit per posture); `&()` for
    /// none.
    pub progress: &'a dyn Progress,
    /// The joint error maps fitted ([`stiffid_metrology::calibration::maps`]).
    pub maps: stiffid_metrology::calibration::maps::Spec,
    /// The orders of the carrier's error motions fitted, with external axes
    /// ([`stiffid_metrology::calibration::motions`]; ignored without).
    pub error_motions: stiffid_metrology::calibration::motions::Spec,
    /// The level of the held-out readings' prediction intervals
    /// ([`stiffid_metrology::calibration::intervals`]), within
    /// 0.5 to 0.999, only with `validate`; `None` for
    /// [`stiffid_core::model::prediction::DEFAULT_LEVEL`]; with `update` also the level of the check's
    /// bound ([`drift`]).
    pub level: Option<f64>,
    /// Update a calibrated robot (the setup's robot, a calibrated robot file) from check
    /// readings: the joint offsets, the frame and the measuring points refitted, the rest kept
    /// (`geometry`, `gravity` and `maps` ignored), and the readings checked against the
    /// calibration's held-out errors first ([`drift`]).
    pub update: bool,
    /// With `update`: what it refits ([`update::Refits`], default `offsets,base,tool`).
    pub refit: update::Refits,
    /// With `update`: the robot's own weight as a stiffness file written before the calibrated
    /// robot file carried it holds it ([`stiffid_core::model::Compliance::own_weight`]); the robot
    /// file's (`[gravity]`) take its place, and the two must agree (else [`Error::InvalidOption`]). Kept in
    /// the update's forward model (refitted from there with [`update::Refit::Gravity`]); `None`
    /// for a calibration without gravity terms or a robot file carrying them.
    pub weight: Option<stiffid_core::model::OwnWeight>,
    /// A URDF is asked for: only then the warnings of what a URDF leaves out (the joint error
    /// maps, the measuring points' frame, the sag under the robot's own weight). The report's
    /// URDF text is there either way.
    pub urdf: bool,
}

/// A validation with the nominal model's error beside it.
#[derive(Debug, Clone)]
pub struct Held {
    /// The readings' name (`cross-validation` for leave-one-posture-out).
    pub name: String,
    /// The calibrated model's errors.
    pub calibrated: Validation,
    /// The nominal model's, the tracker registered on the same readings (in sample).
    pub nominal: Validation,
    /// The posture labels of the readings.
    pub labels: Vec<String>,
    /// The prediction interval of each of `calibrated`'s errors, m, when the held-out readings
    /// have them ([`stiffid_metrology::calibration::intervals`]).
    pub intervals: Option<Vec<stiffid_core::model::prediction::Interval>>,
    /// The share of the held-out coordinates inside their intervals.
    pub coverage: Option<Coverage>,
    /// How many held-out coordinates have interval ends from the fit's Gaussian bound, where
    /// the jackknife+ has too few held-out values for a finite one at the level
    /// ([`fit_bound`]).
    pub from_fit: usize,
    /// The held-out postures (indices of `labels`) outside the fitted postures' axis ranges by
    /// more than 1 deg (`--validate`; empty for the cross-validation).
    pub outside: std::collections::BTreeMap<usize, Outside>,
}

/// What the job found. It serialises to its document, `stiffid calibrate --json`, through the
/// borrowed view [`document::Document`] ([`Report::document`]: mm and deg, units in every key),
/// built as it is written.
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup as the user named it (the request's `setup_name`).
    pub setup: String,
    /// The readings file's name.
    pub data_name: String,
    /// The error model.
    pub model: ErrorModel,
    /// The joint errors fitted.
    pub geometry: Geometry,
    /// The gravity terms fitted.
    pub gravity: Gravity,
    /// The bound on the gravity terms the fit used (every gravity model's, [`Request::gravity_bound`]), rad.
    pub gravity_bound: f64,
    /// The fit.
    pub fit: Fit,
    /// The frame registered on the nominal robot (the start).
    pub start_frame: nalgebra::Isometry3<f64>,
    /// The fitted readings' posture labels.
    pub labels: Vec<String>,
    /// The fitted readings' count.
    pub readings: usize,
    /// The fitted readings' errors with the nominal model (tracker registered, points the
    /// setup's): the error the calibration starts from.
    pub nominal: Validation,
    /// The fitted readings' errors with the calibration, in the order of `nominal`'s.
    pub calibrated: Validation,
    /// Each fitted posture's axis angles, rad, in the order of `labels`.
    pub postures: Vec<nalgebra::Vector6<f64>>,
    /// Each fitted posture's external axes' values (SI, the cell's order; empty without
    /// external axes), in the order of `labels`.
    pub external: Vec<stiffid_core::robot::external::ExternalValues>,
    /// The estimated noise per coordinate over the setup's: near 1 when the model explains the
    /// readings to the tracker's noise.
    pub noise_ratio: f64,
    /// The joint error maps: what was asked, the choice and its nested held-out gain.
    pub maps: Maps,
    /// The models tried and their held-out errors, when the model was chosen ([`ladder`]).
    pub ladder: Option<Ladder>,
    /// With external axes: the orders of the carrier's error motions and how they were chosen.
    pub error_motions: Option<stiffid_metrology::calibration::motions::Choice>,
    /// With `update`: the check readings against the calibration's held-out errors, before the
    /// update (`None` when the robot file carries no `[held_out]`, or too few for the level).
    pub check: Option<drift::Check>,
    /// The held-out validation, if asked.
    pub validation: Option<Held>,
    /// The cross-validation, if asked.
    pub cross_validation: Option<Held>,
    /// The calibrated robot as a robot TOML file, or why it cannot be one.
    pub robot_toml: std::result::Result<String, String>,
    /// The calibrated robot as a URDF, or why it cannot be one (the job does not fail for it:
    /// only a front end asked to write it refuses).
    pub urdf: std::result::Result<String, String>,
    /// The setup fragment: the tracker's registration, the measuring points and the corrected
    /// TCP.
    pub fragment: String,
    /// With the setup's `[tool] tcp_mm`: the TCP moved with the measuring points (`tcp`), flange
    /// frame, m: what compensation uses with the calibrated robot.
    pub tcp: Option<nalgebra::Vector3<f64>>,
    /// With gravity terms or loaded readings: the compliance of every parameter of the
    /// setup's model (and the gravity terms), as a
    /// stiffness file holds it (`fitted_compliance`), or why there is none.
    pub compliance: Option<std::result::Result<FittedCompliance, String>>,
    /// Inputs and results to look at before trusting the result.
    pub warnings: Vec<Warning>,
}

/// The observations of a readings file, the frame they are in: every reading, the wrenches in
/// the base frame (a tool-frame wrench turned by the nominal flange), or with `unloaded_only`
/// the unloaded readings alone.
fn observations(setup: &Setup, data: &Data, unloaded_only: bool) -> (Vec<Observation>, MeasuredIn) {
    let measured_in = match data.frame {
        DisplacementFrame::Tracker => MeasuredIn::Tracker,
        _ => MeasuredIn::Base,
    };
    let obs = (data.readings.iter())
        .filter(|r| !unloaded_only || r.unloaded())
        .map(|r| Observation {
            posture: r.posture,
            point: r.point,
            q: r.q,
            measured: r.position,
            wrench: match r.wrench == nalgebra::Vector6::zeros() {
                true => r.wrench,
                false => base_wrench(&setup.robot().frames(&r.q), &r.wrench, data.wrench_frame),
            },
            e: r.e,
            table: r.table,
            direction: r.direction.unwrap_or_default(),
        })
        .collect();
    (obs, measured_in)
}

impl Report {
    /// The document this report is written as (`stiffid calibrate --json`, Python's
    /// `calibrate(...)`), to read: what the command's text and report page print.
    pub fn document(&self) -> document::Document<'_> {
        document::Document::new(self)
    }
}

impl serde::Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// The calibrate job's report, which is its document (serialised through
/// [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the job.
///
/// # Errors
/// Those of [`read`], [`stiffid_metrology::calibration::model`], [`fit::start`], [`fit::fit`], the
/// ladder's ([`ladder`]), [`validation::validate`] and [`validation::cross_validate`], as
/// [`Error::Input`] naming the file; [`Error::InvalidField`] (`cross_validate`) beyond 5000
/// postures, (`validate`) when the held-out readings are in another frame than the fitted;
/// [`Error::InvalidOption`] ([`JobOption::Level`]) for a level outside
/// 0.5 to 0.999 or without `validate`.
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds.
fn find(request: &Request<'_>) -> Result<Report> {
    let setup = request.readings.setup;
    let name = &request.readings.name;
    let (data, mut warnings) = read(&request.readings)?;
    let (obs, measured_in) = observations(setup, &data, false);
    if request.cross_validate {
        cross_validation_size(&obs)?;
    }
    let level = interval_level(request)?;
    // A mirror image needs no fit (the tracker's registration says it): refused before the
    // models are chosen; the residuals are judged after the fit.
    refuse_implausible(&request.readings, &data, None, &[])?;
    let chosen = chosen::choose(request, (&obs, measured_in, data.tables))?;
    let (model, fitted) = (&chosen.model, &chosen.fit);
    let residuals: Vec<_> = (fitted.residuals.as_slice().chunks_exact(3))
        .zip(&data.readings)
        .filter(|(_, r)| r.unloaded())
        .map(|(r, _)| nalgebra::Vector3::from_column_slice(r))
        .collect();
    refuse_implausible(&request.readings, &data, None, &residuals)?;
    refuse_repeated(setup, &obs, model, fitted).map_err(|e| in_data(name, e))?;
    let reference = update::reference(request, model, reference(setup, model)?)?;
    let nominal = held::nominal(&reference, (&obs, &obs), name, &mut warnings)?;
    let check = (request.update)
        .then(|| {
            drift::checked(
                setup.robot(),
                (&nominal, &data.labels),
                (level, setup.noise().reading_sd()),
                &mut warnings,
            )
        })
        .flatten();
    let calibrated =
        validation::validate(model, &fitted.estimate, &obs).map_err(|e| in_data(name, e))?;
    let mut postures = vec![nalgebra::Vector6::zeros(); data.labels.len()];
    let mut external = vec![Default::default(); data.labels.len()];
    for o in &obs {
        postures[o.posture] = o.q;
        external[o.posture] = o.e;
    }
    let noise_ratio = fitted.sigma / setup.noise().reading_sd();
    let (validation, cross_validation) = held::held(
        request,
        (&chosen, &reference, &obs),
        (&nominal, &data.labels, level),
        &mut warnings,
    )?;
    warnings.extend(judge(
        (model, fitted, chosen.ladder.as_ref()),
        noise_ratio,
        name,
    ));
    if let Some(w) = warnings.iter_mut().find(|w| w.kind == WarningKind::Misfit) {
        w.message += &largest_residual(&data, &fitted.residuals);
    }
    warnings.extend(stiffid_metrology::calibration::track_notes::notes(
        setup,
        chosen.error_motions.as_ref(),
        noise_ratio,
    ));
    let held = (validation.as_ref(), cross_validation.as_ref());
    let files = files::files(request, &chosen, held, &mut warnings)?;
    Ok(Report {
        setup: request.readings.setup_name.clone(),
        data_name: name.clone(),
        labels: data.labels.clone(),
        readings: obs.len(),
        geometry: chosen.geometry,
        gravity: chosen.model.gravity().kind(),
        // The campaign's options bound every gravity model ([`fit::Options::for_campaign`]).
        gravity_bound: (chosen.options.gravity).map_or(f64::INFINITY, |g| g.deflection),
        start_frame: chosen.start.frame,
        model: chosen.model,
        fit: chosen.fit,
        nominal,
        calibrated,
        postures,
        external,
        noise_ratio,
        maps: chosen.maps,
        ladder: chosen.ladder,
        error_motions: chosen.error_motions,
        check,
        validation,
        cross_validation,
        robot_toml: files.robot_toml,
        urdf: files.urdf,
        fragment: files.fragment,
        tcp: files.tcp,
        compliance: files.compliance,
        warnings,
    })
}

/// The nominal reference of every validation, whatever the model fitted: the nominal robot,
/// rigid, with the setup's measuring points, in the readings' frame.
///
/// # Errors
/// Those of [`ErrorModel::new`].
fn reference(setup: &Setup, model: &ErrorModel) -> Result<ErrorModel> {
    let robot = model.robot();
    let reference = ErrorModel::new(
        robot,
        &setup.tool().measuring_points,
        model.measured_in(),
        Geometry::None,
        gravity::Terms::none(robot),
    )?;
    match robot.external() {
        Some(_) => reference.with_external_nominal(model.tables()),
        None => reference.with_tables(model.tables()),
    }
}

/// What the held-out readings' intervals are built from.
struct Bounds<'a> {
    /// The jackknife+ of the fitted postures' folds.
    intervals: &'a Intervals,
    /// Their level.
    level: f64,
    /// The fit (its covariance: the bound from the fit where the jackknife+ has no finite end).
    fit: &'a Fit,
    /// The mean square of the folds' held-out error coordinates, m^2 ([`fit_bound`]).
    held_variance: f64,
}

/// The held-out validation: the readings of `text` predicted at `estimate` (the tracker
/// registered anew on them with `reregister`), with the intervals of `bounds`.
fn held_out(
    request: &Request<'_>,
    (model, reference, fitted): (&ErrorModel, &ErrorModel, &[Observation]),
    estimate: &Estimate,
    bounds: Option<Bounds<'_>>,
    name: &str,
    text: &str,
    warnings: &mut Vec<Warning>,
) -> Result<Held> {
    if text == request.readings.text {
        return Err(Error::InvalidField {
            field: "validate".into(),
            message: format!(
                "{name}: the same readings as the fitted {}: the calibration would be judged on \
                 the readings it was fitted to; give readings it was not fitted to",
                request.readings.name
            ),
        });
    }
    let readings = Readings {
        setup: request.readings.setup,
        setup_name: request.readings.setup_name.clone(),
        name: name.to_string(),
        text,
        force: request.readings.force,
    };
    let (data, more) = read(&readings)?;
    warnings.extend(more);
    checks::refuse_unfitted_reflectors(model, &data, &request.readings.name)
        .map_err(|e| in_data(name, e))?;
    let (obs, measured_in) = observations(request.readings.setup, &data, !model.has_loads());
    if measured_in != model.measured_in() {
        return Err(Error::InvalidField {
            field: "validate".into(),
            message: format!(
                "{name}: the held-out readings are in another frame than {}",
                request.readings.name
            ),
        });
    }
    let estimate = match request.reregister {
        false => estimate.clone(),
        true => Estimate {
            frame: fit::start_at(model, &obs, &estimate.values).map_err(|e| in_data(name, e))?,
            values: estimate.values.clone(),
        },
    };
    let calibrated = validation::validate(model, &estimate, &obs).map_err(|e| in_data(name, e))?;
    let mut from_fit = 0;
    let bounds = match bounds {
        None => None,
        Some(b) => {
            let mut bounds = (b.intervals)
                .of(model, &estimate, &obs, b.level, request.reregister)
                .map_err(|e| in_data(name, e))?;
            from_fit = fit_bound::fill(
                &mut bounds,
                (model, b.fit, &estimate),
                &obs,
                (b.level, b.held_variance),
            )
            .map_err(|e| in_data(name, e))?;
            let errors: Vec<_> = calibrated.errors.iter().map(|e| e.error).collect();
            let coverage = intervals::coverage(&bounds, &errors, b.level, b.intervals.folds());
            Some((bounds, coverage))
        }
    };
    let (intervals, coverage) = bounds.unzip();
    let held = Held {
        name: name.to_string(),
        calibrated,
        nominal: held::nominal(reference, (&obs, fitted), name, warnings)?,
        labels: data.labels.clone(),
        intervals,
        coverage,
        from_fit,
        outside: extrapolation::postures_outside(fitted, &obs).0,
    };
    // The gate of the fitted readings: a held-out reading that both the calibrated robot and the
    // nominal robot registered on them miss by more than a robot's error is not of this robot.
    // One the calibration explains is (a real robot's nominal can miss its own readings by
    // centimetres); one the calibration alone misses that far is too, and the calibration
    // extrapolates there: a warning, not a refusal.
    let unloaded = |v: &Validation| -> Vec<_> {
        (v.errors.iter())
            .zip(
                data.readings
                    .iter()
                    .filter(|r| model.has_loads() || r.unloaded()),
            )
            .filter(|(_, r)| r.unloaded())
            .map(|(e, _)| e.error)
            .collect()
    };
    let closer = (unloaded(&held.calibrated).into_iter())
        .zip(unloaded(&held.nominal))
        .map(|(c, n)| if c.norm() <= n.norm() { c } else { n })
        .collect::<Vec<_>>();
    refuse_implausible(&readings, &data, None, &closer)?;
    let limit =
        stiffid_metrology::register::residual_limit(request.readings.setup.noise().reading_sd());
    warnings.extend(extrapolation::outside_ranges(
        name,
        (fitted, &obs),
        &data.labels,
    ));
    warnings.extend(extrapolation::warning(
        (name, !request.reregister),
        (fitted, &obs),
        &data.labels,
        (&held.calibrated, &held.nominal),
        limit,
    ));
    Ok(held)
}

/// The TCP of the calibrated tool (flange frame, m), when the setup gives one: the measuring
/// points absorb what the readings cannot tell from them (joint 6's `theta` and `d`, the
/// flange's errors), and the tool is one rigid body, so the TCP moves with them: by the rigid
/// transform from the setup's measuring points to the fitted ones (Umeyama's least squares,
/// [`stiffid_metrology::register::fit`]; with fewer than three points not on one line, their mean
/// shift).
pub(crate) fn tcp(
    setup: &Setup,
    model: &ErrorModel,
    values: &DVector<f64>,
) -> Option<Vector3<f64>> {
    use stiffid_metrology::register::{fit, Correspondence};
    if !setup.tcp_given() {
        return None;
    }
    let tcp = setup.tool().tcp;
    let pairs: Vec<Correspondence> = (setup.tool().measuring_points.iter().enumerate())
        .map(|(k, p)| Correspondence {
            base: model.point(values, k),
            tracker: *p,
        })
        .collect();
    Some(
        match fit(&pairs) {
            Ok(r) => r.base_from_tracker * nalgebra::Point3::from(tcp),
            Err(_) => {
                let n = pairs.len().max(1) as f64;
                nalgebra::Point3::from(
                    tcp + pairs
                        .iter()
                        .map(|c| c.base - c.tracker)
                        .sum::<Vector3<f64>>()
                        / n,
                )
            }
        }
        .coords,
    )
}

/// The setup fragment: the tracker's registration, the measuring points and the corrected TCP.
fn fragment(model: &ErrorModel, fit: &Fit, tcp: Option<&Vector3<f64>>) -> String {
    let values = &fit.estimate.values;
    let points: Vec<String> = (0..model.points())
        .map(|k| {
            let p = model.point(values, k) * 1e3;
            format!("[{:.6}, {:.6}, {:.6}]", p.x, p.y, p.z)
        })
        .collect();
    let mut text = format!(
        "# robot calibration: residual RMS {:.4} mm\n",
        fit.rms * 1e3
    );
    if model.measured_in() == MeasuredIn::Tracker {
        let t = &fit.estimate.frame;
        let p = t.translation.vector * 1e3;
        let [r, pi, y] = stiffid_core::robot::file::rpy(&t.rotation);
        text += &format!(
            "[tracker]\nbase_from_tracker = {{ xyz_mm = [{:.6}, {:.6}, {:.6}], rpy_deg = [{:.8}, {:.8}, {:.8}] }}\n",
            p.x,
            p.y,
            p.z,
            r.to_degrees(),
            pi.to_degrees(),
            y.to_degrees()
        );
    }
    text += &format!(
        "# in [tool]:\n# measuring_points_mm = [{}]\n",
        points.join(", ")
    );
    match tcp.map(|t| t * 1e3) {
        Some(t) => text + &format!("# tcp_mm = [{:.6}, {:.6}, {:.6}]\n", t.x, t.y, t.z),
        None => text,
    }
}
