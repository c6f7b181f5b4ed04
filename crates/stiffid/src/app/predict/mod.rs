//! The predict job: the forward model (Zhang et al. 2021, Eq. 3-7) of one posture under one
//! wrench: joint torques and deflections, the displacement of every measuring point and of the
//! TCP (with standard deviations from a compliance covariance), and the Cartesian compliance and
//! stiffness of the loaded point ([`stiffid_core::observation::deflection`], [`stiffid_core::observation::cartesian`]),
//! and where the robot gives its masses the mass matrix, the operational-space inertia, natural
//! frequencies and mode shapes of the posture and the breakthrough surge of the wrench's force
//! ([`stiffid_core::observation::dynamics`]).

pub mod document;

use nalgebra::{Matrix6, Vector3, Vector6};
use serde::Serialize;
use stiffid_core::common::limits::Violation;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::model::prediction::{requested_level, Interval};
use stiffid_core::model::region::{extrapolation_warning, Region};
use stiffid_core::model::Compliance;
use stiffid_core::observation::cartesian;
use stiffid_core::observation::deflection::{base_wrench, Frame, PointDeflection, Points};
use stiffid_core::observation::dynamics::{self, Surge};
use stiffid_core::robot::dynamics::free_mass;
use stiffid_core::robot::kinematics::Frames;
use stiffid_core::setup::Arm;
use stiffid_core::{Result, Setup};

/// What to predict.
#[derive(Debug, Clone)]
pub struct Request<'a> {
    /// The setup as the user named it (a built-in setup's name or a file's path): what the
    /// document states.
    pub setup_name: String,
    /// The setup: robot, tool, model.
    pub setup: &'a Setup,
    /// Axis angles q1..q6, rad, within the robot's limits.
    pub q: Vector6<f64>,
    /// The wrench `[f; m]`, N and Nm, in `frame`.
    pub wrench: Vector6<f64>,
    /// The frame of the wrench.
    pub frame: Frame,
    /// Where the wrench acts, flange frame, m; `None`: the setup's loading point.
    pub at: Option<Vector3<f64>>,
    /// The compliance of every parameter of the setup's model (with its covariance, for the
    /// standard deviations, and its prediction calibration, for the prediction intervals);
    /// `None`: the setup's nominal.
    pub compliance: Option<Compliance>,
    /// The level of the prediction intervals, within 0.5 to 0.999, only
    /// with a compliance that carries a prediction calibration; `None` for
    /// [`stiffid_core::model::prediction::DEFAULT_LEVEL`].
    pub level: Option<f64>,
}

/// One tool point's deflection, and its standard deviation when the compliance has a covariance.
#[derive(Debug, Clone)]
pub struct Point {
    /// Its position, base frame, m.
    pub position: Vector3<f64>,
    /// Its deflection under the wrench.
    pub deflection: PointDeflection,
    /// The standard deviation of `deflection.displacement` (m, rad).
    pub std: Option<Vector6<f64>>,
    /// The prediction interval of the translation (m, base frame) when the compliance carries a
    /// prediction calibration ([`stiffid_core::model::prediction`]).
    pub interval: Option<Interval>,
}

/// What the predict job found. It serialises to its document (`stiffid predict --json`,
/// Python's `predict(...)`) through the borrowed view [`document::Document`]
/// ([`Report::document`]: mm, mrad and N, built as it is written).
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup as the user named it (a built-in setup's name or a file's path).
    pub setup: String,
    /// Axis angles, rad.
    pub q: Vector6<f64>,
    /// The wrench as given, N and Nm, in `frame`.
    pub wrench: Vector6<f64>,
    /// The frame of `wrench`.
    pub frame: Frame,
    /// Where the wrench acts, flange frame, m.
    pub at: Vector3<f64>,
    /// The wrench in the base frame, N and Nm.
    pub base_wrench: Vector6<f64>,
    /// The compliance used.
    pub compliance: Compliance,
    /// The level of the prediction intervals.
    pub level: f64,
    /// Every measuring point of the setup's tool, in its order.
    pub measuring_points: Vec<Point>,
    /// The TCP.
    pub tcp: Point,
    /// `C_x` of the loaded point, base frame, SI ([`cartesian::compliance`]).
    pub cartesian_compliance: Matrix6<f64>,
    /// `K_x = C_x^-1` of the loaded point; `None` where `C_x` is singular
    /// ([`cartesian::stiffness`]).
    pub cartesian_stiffness: Option<Matrix6<f64>>,
    /// The robot's mass at this posture, at the loaded point; `None` where the robot gives no
    /// masses or they are placeholders (then a warning).
    pub mass: Option<Mass>,
    /// The axes of `q` outside the region the compliance was identified from
    /// ([`stiffid_core::model::region`]): empty inside; `None` when it records no region.
    pub outside_region: Option<Vec<Violation>>,
    /// What to look at before trusting the report (placeholder masses, a posture outside the
    /// region the stiffness was identified from).
    pub warnings: Vec<Warning>,
}

/// The mass of one posture at the loaded point, and the surge of the wrench's force.
#[derive(Debug, Clone)]
pub struct Mass {
    /// Mass matrix, operational-space inertia, modes ([`dynamics::posture`]).
    pub posture: dynamics::Posture,
    /// The effective mass along the wrench's force with the point free,
    /// `1 / (u^T (J M^-1 J^T)_vv u)`, kg; `None` without a force or at a singular posture.
    pub free_mass: Option<f64>,
    /// The breakthrough surge of the wrench's force (its effective mass held in the other five
    /// directions); `None` without a force or at a singular posture.
    pub surge: Option<Surge>,
}

impl Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// The predict job's report, which is its document (serialised through
/// [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the predict job.
///
/// # Errors
/// Those of [`requested_level`] (a level outside 0.5 to 0.999, or
/// without a prediction calibration);
/// [`stiffid_core::Error::OutsideBox`] (field `q_deg[i]`) for an axis angle outside the robot's limits;
/// without a compliance, those of [`stiffid_core::Setup::model_compliance`] (no nominal stiffness); with one, those
/// of [`Compliance::check`] (not one value per parameter of the setup's model).
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds, before its document.
fn find(request: &Request<'_>) -> Result<Report> {
    let Request {
        setup,
        q,
        wrench,
        frame,
        at,
        compliance,
        level,
        ..
    } = request;
    let (q, wrench, frame, at, level) = (*q, *wrench, *frame, *at, *level);
    let field = |a: usize| format!("q_deg[{}]", a + 1);
    setup
        .robot()
        .limits()
        .check(&q, "the robot's limits", field)?;
    let compliance = match compliance {
        Some(c) => {
            c.check(setup.model())?;
            c.clone()
        }
        None => setup.model_compliance("predict without a stiffness")?,
    };
    let level = requested_level(level, compliance.prediction.is_some())?;
    let at = at.unwrap_or(setup.tool().loading_point);
    let frames = setup.robot().frames(&q);
    let base = base_wrench(&frames, &wrench, frame);
    let (masses, warning) = dynamics::mass_model(setup.arm());
    let mass = masses.map(|m| {
        let posture = dynamics::posture(&m, setup.arm(), &frames, &at, &compliance.h);
        let force = base.fixed_rows::<3>(0).into_owned();
        let lambda = posture.operational_inertia;
        let surge = lambda
            .and_then(|l| dynamics::surge(&m, setup.arm(), &frames, &at, &l, &compliance, &force));
        let free = lambda.zip(force.try_normalize(0.0));
        Mass {
            free_mass: free.and_then(|(l, u)| free_mass(&l, &u)),
            posture,
            surge,
        }
    });
    let outside_region = compliance.region.outside(&q);
    let mut warnings = Vec::from_iter(warning);
    warnings.extend(compliance.region.unrecorded_warning());
    if let (Region::Postures(r), Some(axes)) = (&compliance.region, &outside_region)
        && !axes.is_empty()
    {
        let flagged = [(String::new(), axes.clone())];
        warnings.push(extrapolation_warning(r, "the posture lies", &flagged, 0));
    }
    let point = |observed: &Vector3<f64>| {
        point(
            setup.arm(),
            &frames,
            &at,
            observed,
            &base,
            &compliance,
            level,
        )
    };
    let tcp = point(&setup.tool().tcp);
    warnings.extend(large_deflection(&tcp.deflection.joint_deflections));
    Ok(Report {
        setup: request.setup_name.clone(),
        measuring_points: setup.tool().measuring_points.iter().map(point).collect(),
        tcp,
        cartesian_compliance: cartesian::compliance(setup.arm(), &frames, &at, &compliance.h),
        cartesian_stiffness: cartesian::stiffness(setup.arm(), &frames, &at, &compliance.h),
        q,
        wrench,
        frame,
        at,
        base_wrench: base,
        compliance,
        level,
        mass,
        outside_region,
        warnings,
    })
}

/// The deflection of `observed` (flange frame, m) under the base-frame wrench `base` at `at`.
fn point(
    arm: &Arm,
    frames: &Frames,
    at: &Vector3<f64>,
    observed: &Vector3<f64>,
    base: &Vector6<f64>,
    compliance: &Compliance,
    level: f64,
) -> Point {
    let points = Points {
        arm,
        frames,
        loaded: at,
        observed,
    };
    let deflection = points.deflection(base, &compliance.h);
    let std = compliance.covariance.as_ref().map(|c| deflection.std(c));
    let interval = compliance
        .prediction
        .as_ref()
        .map(|p| deflection.interval(p, &compliance.h, level));
    Point {
        position: frames.point(observed),
        deflection,
        std,
        interval,
    }
}

/// The joint deflection, rad, beyond which the linear model of small deflections (paper Eq. 7)
/// says nothing: 1 deg, where a machining robot's joints deflect hundredths of a degree.
const LARGE_DEFLECTION: f64 = 0.017_453_292_519_943_295;

/// A warning when a drive of `dq` (every parameter's deflection, the six drives first, rad)
/// deflects beyond [`LARGE_DEFLECTION`].
fn large_deflection(dq: &nalgebra::DVector<f64>) -> Option<Warning> {
    let j = (0..dq.len().min(6)).max_by(|&a, &b| dq[a].abs().total_cmp(&dq[b].abs()))?;
    (dq[j].abs() > LARGE_DEFLECTION).then(|| {
        Warning::new(
            WarningKind::Plausibility,
            format!(
                "joint {} deflects {} deg under this wrench: the model is linear in small \
                 deflections (hundredths of a degree on a machining robot) and says nothing of \
                 this one; a stiffness in another unit than Nm/rad, or a wrench in another than \
                 N and Nm?",
                j + 1,
                stiffid_core::common::words::number(dq[j].to_degrees())
            ),
        )
    })
}
