//! `stiffid.calibrate`: the robot calibration job of `stiffid calibrate`
//! ([`stiffid::app::calibrate`]) and the calibrated robot's files.

use crate::documents::{to_python, warn};
use crate::error::{self, raise, value};
use crate::output;
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiffid::app::calibrate::document::Document;
use stiffid::app::calibrate::{self as job, Tolerances};
use stiffid::app::readings::Request as Readings;

/// Calibrates the robot from the ``readings`` of a campaign (a CSV path in the ``stiffid
/// register --data`` format: ``posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm``
/// or ``x_mm,y_mm,z_mm`` in the base frame; with load steps every reading, loaded ones fitting the
/// setup model's compliances too, as ``stiffid calibrate``):
/// the robot's geometric errors (``geometry``: ``"none"``, the tracker and the measuring points
/// only, as ``calibrate_cell``; ``"offsets"``, the joint angle offsets too; ``"full"``, the
/// default, every joint error with the dependent ones merged), its deflection under its own
/// weight (``gravity``: ``"auto"``, the default, chosen with ``maps`` by a cross-validation that
/// holds out groups of postures, as ``--gravity auto``; ``"none"``; ``"arm"``, three terms: the
/// upper arm's and the forearm's weight on joints 2 and 3 of an anthropomorphic arm; ``"masses"``, one compliance per joint with the
/// robot's link masses and centres; ``"lumped"``, compliance times the mass moments of the upper
/// arm, forearm and wrist; ``"lumped-links"``, of every link; ``gravity_bound_mrad``, default
/// 3, the bound on the gravity terms: each term's prior deflects its joint by that much at the
/// largest torque it meets, the same for every gravity model, chosen or given, as
/// ``--gravity-bound-mrad``), the tracker's
/// registration and the measuring points, fitted together by Levenberg-Marquardt (docs/model.md,
/// geometric and elastostatic calibration). ``validate``: held-out readings (same format) whose
/// 3D position error the calibration predicts (``reregister=True``: the tracker registered anew
/// on them, another series); ``cross_validate=True``: each posture's error predicted by the fit
/// of the others; ``tolerance_mm`` and ``tolerance_deg`` together: the nominal tolerances of the
/// joints' length and angle errors as priors; ``maps``: the joint error maps fitted, ``"auto"``
/// (chosen by cross-validation inside the readings with 30 distinct postures or more), ``"none"``
/// or joints with harmonics (``"J1,J3:16"``; ``"J2:8b"``, ``"J2:b"`` with a backlash term where
/// the readings carry ``dir1..dir6``), as ``--maps``; ``error_motions``: with a track,
/// the order of its error motions' polynomials, ``"auto"`` (chosen by cross-validation) or an
/// order ``"0"`` to ``"8"``, as ``--error-motions``; ``level``: the level of the
/// ``validate`` readings' prediction intervals (0.5 to 0.999, default 0.95; jackknife+ over the
/// fitted postures, from their leave-one-posture-out errors; with ``update`` also the level of
/// the check's bound), as ``--level``; ``update=True``: the setup's robot a calibrated robot
/// file, the readings a check campaign: the joint offsets, the tracker (or base) and the
/// measuring points refitted, the rest kept (``geometry``, ``gravity`` and ``maps`` ignored),
/// and ``check`` in the document (the readings against the calibration's held-out errors:
/// ``drifted``, ``share_outside``), as ``--update``; ``update_parameters``: what the update
/// refits, ``"offsets,base,tool"`` by default, ``base`` always, ``gravity`` to refit the gravity
/// terms of ``stiffness``, as ``--update LIST``; ``stiffness``: the calibration's stiffness file
/// (``stiffness_out``), its gravity terms kept in the update's forward model, as ``--stiffness``.
/// The same job as ``stiffid calibrate``: returns its
/// document (docs/schemas/calibrate.schema.json) as a dict, equal to ``stiffid calibrate
/// --json``: ``parameters`` (``name``, ``kind``, ``unit``, ``nominal``, ``value``, ``sd``,
/// ``identified``), ``merged``, ``rank``, ``condition``, ``correlations``, ``residual_rms_mm``,
/// ``nominal_rms_mm``, ``noise_std_mm``, ``noise_ratio``, ``maps`` (the choice and its nested
/// held-out gain), ``validation`` and
/// ``cross_validation`` (``rms_mm``, ``max_mm``, ``nominal_rms_mm``, the error of every held-out
/// posture and point; for ``validate`` the ``intervals``, their ``coverage`` and each reading's
/// ``interval_mm``), ``robot_file`` (or ``robot_file_error``), ``urdf`` (or ``urdf_error``),
/// ``fragment``, ``check`` and ``warnings``; the warnings are
/// raised as ``UserWarning`` too.
///
/// ``out``: writes the calibrated robot file (robot TOML, the calibrated DH table and axis map,
/// the setup's tracker and measuring points in comments at its end; point a setup's ``robot`` at
/// it and every function uses the calibrated robot), byte for byte what ``stiffid calibrate
/// --out`` writes; ``InputError`` when the calibrated chain has no DH table (its reason).
/// ``urdf_out``: the calibrated robot as a URDF taking the same axis angles; ``InputError`` when
/// the robot's axis map couples or scales axes (its reason). ``stiffness_out``: the fitted
/// compliances as a stiffness file (what ``stiffid calibrate --stiffness-out`` writes, which
/// ``predict`` and ``compensate`` read), with loaded readings or a gravity model; ``InputError``
/// otherwise (its reason). Each checked before the fit (never
/// over a file the call reads, a directory or a dangling symlink) and written whole after it.
/// ``InputError`` naming the file, line and column for bad readings, and, unless ``force=True``,
/// readings no rigid transform explains (as ``register``: a mirror image of the robot's points, a
/// residual of the calibration beyond the larger of 10 mm and 1000 times the tracker noise).
#[pyfunction]
#[pyo3(signature = (setup, readings, *, geometry="full", gravity="auto", gravity_bound_mrad=3.0, validate=None, reregister=false, cross_validate=false, tolerance_mm=None, tolerance_deg=None, maps="auto", error_motions="auto", level=None, update=false, update_parameters=None, stiffness=None, out=None, urdf_out=None, stiffness_out=None, force=false))]
#[allow(clippy::too_many_arguments)]
pub fn calibrate<'py>(
    py: Python<'py>,
    setup: &Setup,
    readings: PathBuf,
    geometry: &str,
    gravity: &str,
    #[pyo3(from_py_with = crate::count::number)] gravity_bound_mrad: f64,
    validate: Option<PathBuf>,
    reregister: bool,
    cross_validate: bool,
    tolerance_mm: Option<&Bound<'py, PyAny>>,
    tolerance_deg: Option<&Bound<'py, PyAny>>,
    maps: &str,
    error_motions: &str,
    level: Option<&Bound<'_, PyAny>>,
    update: bool,
    update_parameters: Option<&str>,
    stiffness: Option<PathBuf>,
    out: Option<PathBuf>,
    urdf_out: Option<PathBuf>,
    stiffness_out: Option<PathBuf>,
    force: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let priors = priors(tolerance_mm, tolerance_deg)?;
    let level = crate::count::real("level", level)?;
    if reregister && validate.is_none() {
        return Err(value(
            "reregister: only with validate= (the held-out readings)",
        ));
    }
    let (refit, weight) = update_of(setup, update, update_parameters, stiffness.as_ref())?;
    let text = error::read(&readings)?;
    let held = validate.as_ref().map(|p| error::read(p)).transpose()?;
    let mut inputs = setup.files.clone();
    inputs.extend(
        [Some(readings.clone()), validate.clone(), stiffness.clone()]
            .into_iter()
            .flatten(),
    );
    let prepare = |path: &Option<PathBuf>, what, others: &[output::OutFile]| {
        (path.as_ref())
            .map(|p| output::prepare(p, what, &inputs, others))
            .transpose()
    };
    let out_file = prepare(&out, "out", &[])?;
    let urdf_file = prepare(&urdf_out, "urdf_out", out_file.as_slice())?;
    let written: Vec<output::OutFile> = out_file.iter().chain(&urdf_file).cloned().collect();
    let stiffness_file = prepare(&stiffness_out, "stiffness_out", &written)?;
    let request = job::Request {
        readings: Readings {
            setup: &setup.inner,
            setup_name: setup.given.clone(),
            name: readings.display().to_string(),
            text: &text,
            force,
        },
        geometry: geometry.parse().map_err(raise)?,
        gravity: gravity.parse().map_err(raise)?,
        gravity_bound: Some(gravity_bound_mrad * 1e-3),
        validate: (validate.as_ref().zip(held.as_deref()))
            .map(|(p, t)| (p.display().to_string(), t)),
        reregister,
        cross_validate,
        priors,
        progress: &(),
        maps: stiffid::internal::metrology::calibration::maps::Spec::parse(maps).map_err(raise)?,
        error_motions: stiffid::internal::metrology::calibration::motions::Spec::parse(
            error_motions,
        )
        .map_err(raise)?,
        level,
        update,
        refit,
        weight,
        urdf: urdf_out.is_some(),
    };
    let report = py.detach(|| job::run(&request)).map_err(raise)?.report;
    let document = report.document();
    let writes = writes(
        &document,
        [
            out_file.as_ref(),
            urdf_file.as_ref(),
            stiffness_file.as_ref(),
        ],
    )?;
    warn(py, document.warnings)?;
    for (file, text) in writes {
        file.write(text.as_bytes())?;
    }
    to_python(py, &document, &[])
}

/// The priors of `tolerance_mm` and `tolerance_deg`, both or neither.
fn priors(
    tolerance_mm: Option<&Bound<'_, PyAny>>,
    tolerance_deg: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<Tolerances>> {
    let tolerances = (
        crate::count::real("tolerance_mm", tolerance_mm)?,
        crate::count::real("tolerance_deg", tolerance_deg)?,
    );
    match tolerances {
        (Some(l), Some(a)) => Ok(Some(Tolerances::from_mm_deg(l, a).map_err(raise)?)),
        (None, None) => Ok(None),
        _ => Err(value("tolerance_mm, tolerance_deg: give both or neither")),
    }
}

/// What an update refits (`update_parameters`) and the own weight of its `stiffness` file; both
/// refused without `update`.
fn update_of(
    setup: &Setup,
    update: bool,
    update_parameters: Option<&str>,
    stiffness: Option<&PathBuf>,
) -> PyResult<(job::Refits, Option<stiffid::internal::model::OwnWeight>)> {
    if !update && (update_parameters.is_some() || stiffness.is_some()) {
        return Err(value(
            "update_parameters, stiffness: only with update=True (a calibrated robot updated from check readings)",
        ));
    }
    let refit = (update_parameters.map(job::Refits::parse))
        .transpose()
        .map_err(raise)?
        .unwrap_or_default();
    let weight = match stiffness {
        Some(p) => {
            let name = p.display().to_string();
            let file = stiffid::internal::io::stiffness::parse(&error::read(p)?)
                .map_err(|e| error::raise_in(&name, e))?;
            (file.compliance(setup.inner.model()))
                .map_err(|e| error::raise_in(&name, e))?
                .own_weight
        }
        None => None,
    };
    Ok((refit, weight))
}

/// The texts to write into the files asked (`out`, `urdf_out`, `stiffness_out`), or why one
/// cannot be written (a `ValueError` naming the argument), before anything is written.
fn writes<'a>(
    document: &Document,
    [out, urdf, stiffness]: [Option<&'a output::OutFile>; 3],
) -> PyResult<Vec<(&'a output::OutFile, String)>> {
    let texts = [
        ("out", document.robot_file_out(), document.robot_file_error),
        ("urdf_out", document.urdf.map(String::from), document.urdf_error),
        (
            "stiffness_out",
            document.stiffness_file_out(),
            Some(document.stiffness_file_error.unwrap_or(
                "no compliance is fitted: loaded readings (load steps) or a gravity model (gravity=\"masses\", \"lumped\", \"lumped-links\" or \"arm\") fit them",
            )),
        ),
    ];
    let mut writes = Vec::new();
    for (file, (what, text, why)) in [out, urdf, stiffness].into_iter().zip(texts) {
        match (file, text) {
            (Some(file), Some(text)) => writes.push((file, text)),
            (Some(_), None) => {
                return Err(value(format!("{what}: {}", why.unwrap_or_default())));
            }
            (None, _) => {}
        }
    }
    Ok(writes)
}
