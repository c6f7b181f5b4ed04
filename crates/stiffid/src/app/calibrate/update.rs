//! The update of a calibrated robot from a short check campaign (`calibrate --update`): what
//! drifts between sessions refitted, the rest of the calibration kept.
//!
//! Between sessions a calibrated robot's joint zeros slip (a motor or encoder changed, a
//! collision, a re-mastering), its base moves on its foundation and its tool is re-mounted; its
//! link geometry, its joint error maps and its weight do not change. The update starts from the
//! calibrated robot file (the setup's robot) and fits what [`Refits`] lists: by default the
//! joint angle offsets ([`Refit::Offsets`]), the frame ([`Refit::Base`]: the tracker's
//! registration, or the base frame's error for readings in the base frame) and the measuring
//! points ([`Refit::Tool`]); with [`Refit::Gravity`] the calibration's gravity terms too. What
//! it does not list stays as the calibration left it, in the forward model: the DH table, the
//! error maps and the axis map as the file has them, the measuring points as the setup gives
//! them, and the gravity terms of the calibration's stiffness file ([`Request::weight`]) at
//! their values ([`ErrorModel::with_held`]): the sag under the robot's own weight is predicted,
//! not absorbed by the offsets.
//!
//! On a cell with external axes ([`stiffid_core::robot::external`]) the calibrated robot file carries
//! the track's direction and error motions and the positioner's axis lines: held
//! ([`ErrorModel::with_external_offsets`]); [`Refit::External`] refits each axis's zero offset
//! (a re-mastered encoder), the reflectors on the positioner's table are fitted as in every
//! session. The check readings may be read at several stations and angles.
//!
//! Before the fit the check readings must separate what the list refits as well as a generic
//! campaign does ([`REFERENCE_POSTURES`] random postures): a rank below such a campaign's refuses
//! the list, naming the parameters it identifies and the check readings merge, and what each
//! merges with (joint 1's offset merges into the tracker's registration and joint 6's into the
//! measuring points on any campaign: they are left, not refused). With [`Refit::External`] the
//! check readings must separate at least one external axis's zero offset, else the list is
//! refused naming what each merges with (a track's merges with the tracker's registration
//! without reflectors on a positioner's table; a one-axis positioner's with the reflectors'
//! positions on its table).

use super::{GravitySpec, Request};
use crate::app::purpose::REFERENCE_POSTURES;
use stiffid_core::common::choice::{self, Choice};
use stiffid_core::common::error::JobOption;
use stiffid_core::model::OwnWeight;
use stiffid_core::{Error, Result, Setup};
use stiffid_metrology::calibration::error_model::Observation;
use stiffid_metrology::calibration::gravity::Gravity;
use stiffid_metrology::calibration::identifiability;
use stiffid_metrology::calibration::maps::Spec;
use stiffid_metrology::calibration::{robot_file, ErrorModel, Geometry};

/// The fewest distinct postures an update reads (the readings must separate the six offsets
/// from the frame and the points).
pub(crate) const MIN_POSTURES: usize = 5;

/// What an update refits (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Refit {
    /// The six joint angle offsets.
    Offsets,
    /// The frame: the tracker's registration (the base frame's error for readings in the base
    /// frame). Always refitted: the tracker is registered anew in every session.
    Base,
    /// The measuring points (a re-mounted tool).
    Tool,
    /// The gravity terms of the calibration's stiffness file, started from their values.
    Gravity,
    /// The external axes' zero offsets (a cell's track and positioner: a re-mastered encoder).
    External,
}

impl Choice for Refit {
    const FIELD: &'static str = "update";
    const ALL: &'static [Self] = &[
        Refit::Offsets,
        Refit::Base,
        Refit::Tool,
        Refit::Gravity,
        Refit::External,
    ];
    fn name(self) -> &'static str {
        match self {
            Refit::Offsets => "offsets",
            Refit::Base => "base",
            Refit::Tool => "tool",
            Refit::Gravity => "gravity",
            Refit::External => "external",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Refit::Offsets => "The six joint angle offsets",
            Refit::Base => {
                "The tracker's registration (the base frame's error for base-frame readings)"
            }
            Refit::Tool => "The measuring points",
            Refit::Gravity => "The gravity terms of the calibration's stiffness file",
            Refit::External => "The external axes' zero offsets (a cell's track and positioner)",
        }
    }
}

stiffid_core::common::choice::by_name!(Refit);

/// The list of what an update refits: [`Refit::Base`] and any others, each once. The default
/// is `offsets,base,tool`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refits(Vec<Refit>);

impl Default for Refits {
    fn default() -> Self {
        Refits(vec![Refit::Offsets, Refit::Base, Refit::Tool])
    }
}

impl Refits {
    /// The list named by `text`: names separated by commas (`offsets,base,tool,gravity`).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::Update`]) for an unknown name (naming the known),
    /// a name given twice, or a list without `base`.
    pub fn parse(text: &str) -> Result<Self> {
        let refuse = |message: String| Error::InvalidOption {
            option: JobOption::Update,
            message,
        };
        let mut list = Vec::new();
        for name in text.split(',').map(str::trim) {
            let r = choice::parse::<Refit>(name).map_err(|e| refuse(e.to_string()))?;
            if list.contains(&r) {
                return Err(refuse(format!("{name} is listed twice")));
            }
            list.push(r);
        }
        if !list.contains(&Refit::Base) {
            return Err(refuse(
                "the list needs base: the tracker is registered anew in every session".into(),
            ));
        }
        Ok(Refits(list))
    }

    /// Whether the list holds `r`.
    pub fn contains(&self, r: Refit) -> bool {
        self.0.contains(&r)
    }

    /// The list, in the order given.
    pub(crate) fn list(&self) -> &[Refit] {
        &self.0
    }
}

/// The model the job fits: the request's geometry, gravity and maps, or with `update` the
/// geometry and gravity of the update's list (module docs; the gravity terms those of the
/// calibration's stiffness file).
///
/// # Errors
/// With `update`, [`Error::InvalidOption`] ([`JobOption::Update`]) when the setup's robot is not
/// a calibrated robot file (its name ends with [`stiffid_core::robot::CALIBRATED`]), the list refits
/// the external axes' offsets of a robot without external axes, the readings are loaded or hold
/// fewer than [`MIN_POSTURES`] postures, the list refits the gravity terms without the
/// calibration's stiffness file or that file's gravity model is unknown.
pub(super) fn settings(
    request: &Request<'_>,
    setup: &Setup,
    obs: &[Observation],
) -> Result<(Geometry, GravitySpec, Spec)> {
    if !request.update {
        return Ok((request.geometry, request.gravity, request.maps));
    }
    let refuse = |message: String| {
        Err(Error::InvalidOption {
            option: JobOption::Update,
            message,
        })
    };
    let robot = setup.robot();
    if !robot.name().ends_with(stiffid_core::robot::CALIBRATED) {
        return refuse(format!(
            "the setup's robot {:?} is not a calibrated robot file: point the setup's robot at the file `calibrate --out` wrote",
            robot.name()
        ));
    }
    if robot.external().is_none() && request.refit.contains(Refit::External) {
        return refuse(format!(
            "external: the robot {:?} has no external axes (a track or a positioner)",
            robot.name()
        ));
    }
    if obs.iter().any(Observation::loaded) {
        return refuse(
            "the check readings are loaded (load steps): read the check postures unloaded".into(),
        );
    }
    let mut postures: Vec<usize> = obs.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    if postures.len() < MIN_POSTURES {
        return refuse(format!(
            "expected at least {MIN_POSTURES} check postures, got {}: design them with `select --for check`",
            postures.len()
        ));
    }
    let gravity = match weight(request)? {
        Some(w) => choice::parse::<Gravity>(&w.gravity).map_err(|e| Error::InvalidOption {
            option: JobOption::Update,
            message: format!("the stiffness file's gravity terms: {e}"),
        })?,
        None if request.refit.contains(Refit::Gravity) => {
            return refuse("gravity: the update refits the calibration's gravity terms, and neither the calibrated robot file ([gravity]) nor a stiffness file (--stiffness, Python stiffness=) holds any".into())
        }
        None => Gravity::None,
    };
    let geometry = match request.refit.contains(Refit::Offsets) {
        true => Geometry::Offsets,
        false => Geometry::None,
    };
    Ok((geometry, GravitySpec::Fixed(gravity), Spec::None))
}

/// With `update`, `model` with what the list keeps held ([`ErrorModel::with_held`]): the
/// measuring points at the setup's without [`Refit::Tool`], the gravity terms at the stiffness
/// file's values (started there with [`Refit::Gravity`]); `model` itself without `update`.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Update`]) when the stiffness file lacks a term of its
/// own gravity model (naming it); those of [`ErrorModel::with_held`].
pub(super) fn kept(request: &Request<'_>, model: ErrorModel) -> Result<ErrorModel> {
    if !request.update {
        return Ok(model);
    }
    let points = 6..6 + 3 * model.points();
    let mut held: Vec<(usize, f64)> = match request.refit.contains(Refit::Tool) {
        true => Vec::new(),
        false => points.map(|c| (c, model.parameters()[c].nominal)).collect(),
    };
    let gravity = gravity_values(request, &model)?;
    let mut started = Vec::new();
    match request.refit.contains(Refit::Gravity) {
        true => started = gravity,
        false => held.extend(gravity),
    }
    let mut model = model.with_held(&held)?;
    model.set_nominal(&started);
    Ok(model)
}

/// With `update` on a cell: `model` (without external axes) with the calibrated robot file's
/// external axes held and their zero offsets fitted with [`Refit::External`]
/// ([`ErrorModel::with_external_offsets`]), `tables` reflectors on the positioner's table; no
/// choice of error motions (they are held).
///
/// # Errors
/// Those of [`ErrorModel::with_external_offsets`], as [`Error::Input`] naming the readings
/// `name`.
pub(super) fn external(
    request: &Request<'_>,
    model: ErrorModel,
    tables: usize,
    name: &str,
) -> Result<(
    ErrorModel,
    Option<stiffid_metrology::calibration::motions::Choice>,
)> {
    let offsets = request.refit.contains(Refit::External);
    let model = model.with_external_offsets(tables, offsets);
    Ok((model.map_err(|e| super::in_data(name, e))?, None))
}

/// The calibration's value of each gravity term of `model` ([`weight`]): `(index, value)`, SI.
fn gravity_values(request: &Request<'_>, model: &ErrorModel) -> Result<Vec<(usize, f64)>> {
    let Some(weight) = weight(request)? else {
        return Ok(Vec::new());
    };
    let start = model.gravity_start();
    (start..start + model.gravity().len())
        .map(|c| {
            let name = &model.parameters()[c].name;
            let value = weight.terms.iter().find(|(n, _)| n == name).map(|t| t.1);
            value.map(|v| (c, v)).ok_or_else(|| Error::InvalidOption {
                option: JobOption::Update,
                message: format!(
                    "the calibration's {} gravity terms lack {name}: give the robot file and the stiffness file of the robot's calibration",
                    weight.gravity
                ),
            })
        })
        .collect()
}

/// With `update` and the calibration's gravity terms: the reference of the check, the rigid
/// reference `rigid` with `model`'s gravity terms held at their values (the calibrated robot
/// as it is, its sag in); `rigid` otherwise.
///
/// # Errors
/// Those of [`ErrorModel::new`] and [`ErrorModel::with_held`].
pub(super) fn reference(
    request: &Request<'_>,
    model: &ErrorModel,
    rigid: ErrorModel,
) -> Result<ErrorModel> {
    if !request.update || model.gravity().is_empty() {
        return Ok(rigid);
    }
    let points: Vec<_> = (0..model.points())
        .map(|k| model.point(&model.nominal(), k))
        .collect();
    let with = ErrorModel::new(
        rigid.robot(),
        &points,
        rigid.measured_in(),
        Geometry::None,
        model.gravity().clone(),
    )?;
    let with = match rigid.robot().external() {
        Some(_) => with.with_external_nominal(model.tables())?,
        None => with.with_tables(model.tables())?,
    };
    let (from, to) = (model.gravity_start(), with.gravity_start());
    let held: Vec<(usize, f64)> = (0..model.gravity().len())
        .map(|i| (to + i, model.nominal()[from + i]))
        .collect();
    with.with_held(&held)
}

/// With `update`: refuses a list the check readings `obs` cannot identify: the rank of their
/// identification Jacobian below a generic campaign's ([`REFERENCE_POSTURES`] random postures of
/// the setup, every measuring point), naming each parameter the campaign separates and they
/// merge, and what it merges with (module docs).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Update`]) for such a list; those of
/// [`ErrorModel::jacobian_of`] and [`identifiability::analyse`].
pub(super) fn identifiable(
    request: &Request<'_>,
    setup: &Setup,
    model: &ErrorModel,
    obs: &[Observation],
) -> Result<()> {
    if !request.update {
        return Ok(());
    }
    let length = setup.characteristic_length().unwrap_or(1.0);
    let analyse = |readings: &[Observation]| {
        let scales = model.column_scales_of(length, readings);
        let priorities: Vec<u8> = model.parameters().iter().map(|p| p.priority).collect();
        let j = model.jacobian_of(&model.nominal(), readings)?;
        identifiability::analyse(&j, &scales, &priorities)
    };
    let (generic, check) = (analyse(&generic(setup, model))?, analyse(obs)?);
    let params = model.parameters();
    // An external axis's zero offset the list refits and the check merges: refused whatever a
    // generic campaign separates (module docs).
    let zero = |c: usize| {
        use stiffid_metrology::calibration::{AxisPart, Target};
        let part = match params[c].target {
            Target::External { part, .. } => Some(part),
            _ => None,
        };
        matches!(part, Some(AxisPart::Offset | AxisPart::Shift)) && !model.held().contains(&c)
    };
    // `external` listed and none of its zero offsets separated: it would refit nothing.
    let lost_zero = request.refit.contains(Refit::External)
        && (0..params.len())
            .filter(|&c| zero(c))
            .all(|c| !check.identified.contains(&c));
    if check.rank >= generic.rank && !lost_zero {
        return Ok(());
    }
    let lost: Vec<String> = (check.merged.iter())
        .filter(|m| generic.identified.contains(&m.parameter) || (lost_zero && zero(m.parameter)))
        .map(|m| {
            let into: Vec<&str> = m
                .into
                .iter()
                .map(|(k, _)| params[*k].name.as_str())
                .collect();
            let why = model.merged_words(m.parameter).map(|w| format!(" ({w})"));
            match into.is_empty() {
                true => format!("{} (no effect at these postures)", params[m.parameter].name),
                false => format!(
                    "{} merges with {}{}",
                    params[m.parameter].name,
                    into.join(", "),
                    why.unwrap_or_default()
                ),
            }
        })
        .collect();
    let names: Vec<&str> = request.refit.list().iter().map(|r| r.name()).collect();
    Err(Error::InvalidOption {
        option: JobOption::Update,
        message: format!(
            "the check readings cannot identify what {} refits: {}; read more or other postures (select --for check) or refit less",
            names.join(","),
            lost.join("; ")
        ),
    })
}

/// The generic campaign the check readings are compared with: [`REFERENCE_POSTURES`] random
/// postures of `setup` with every measuring point of `model`; on a cell dealt over
/// [`crate::app::purpose::REFERENCE_STATIONS`] stations of the carrier's travel, and with
/// `model`'s reflectors on the positioner's table read at each posture's positioner angles
/// (spread over each axis's travel).
fn generic(setup: &Setup, model: &ErrorModel) -> Vec<Observation> {
    let postures = stiffid_design::random_group(setup, REFERENCE_POSTURES, 1);
    let stations = (setup.robot().external())
        .map(|a| a.stations(crate::app::purpose::REFERENCE_STATIONS))
        .unwrap_or_else(|| vec![Default::default()]);
    let axes = setup.robot().external();
    let at = |i: usize| -> stiffid_core::robot::external::ExternalValues {
        let mut e = stations[i % stations.len()].as_slice().to_vec();
        for (j, a) in axes.iter().flat_map(|a| a.axes()).enumerate() {
            if a.role == stiffid_core::robot::external::Role::Positioner {
                let t = ((i + 1) as f64 * (0.618_034 + 0.1 * j as f64)).fract();
                e[j] = a.lower + t * (a.upper - a.lower);
            }
        }
        stiffid_core::robot::external::ExternalValues::new(&e).expect("the cell's axes")
    };
    let reading = |posture: usize, point: usize, q, table: bool| Observation {
        posture,
        point,
        q,
        measured: nalgebra::Vector3::zeros(),
        wrench: nalgebra::Vector6::zeros(),
        e: at(posture),
        table,
        direction: nalgebra::Vector6::zeros(),
    };
    (postures.iter().enumerate())
        .flat_map(|(i, q)| {
            let arm = (0..model.points()).map(move |k| reading(i, k, *q, false));
            arm.chain((0..model.tables()).map(move |k| reading(i, k, *q, true)))
        })
        .collect()
}

/// The `[held_out]` table of the robot file: the held-out errors of this job's validation (else
/// its cross-validation); with `update` and neither, the calibrated robot file's own (its
/// calibration's errors, carried to the updated robot).
pub(super) fn held_out(
    request: &Request<'_>,
    setup: &Setup,
    validation: Option<&super::Held>,
    cross_validation: Option<&super::Held>,
) -> String {
    match (validation.or(cross_validation), setup.robot().held_out()) {
        (None, Some(h)) if request.update => {
            super::document::held_out_lines(&h.source, h.errors.iter().copied())
        }
        _ => super::document::held_out_table(validation, cross_validation),
    }
}

/// With `update`: the gravity terms of the robot's calibration, the calibrated robot file's
/// (`[gravity]`, [`stiffid_core::Robot::own_weight`]) or, from a robot file without them, those of the
/// calibration's stiffness file ([`Request::weight`]); `None` without `update` or without either.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Update`]) when both hold gravity terms and they differ,
/// naming both.
pub(super) fn weight<'r>(request: &'r Request<'_>) -> Result<Option<&'r OwnWeight>> {
    if !request.update {
        return Ok(None);
    }
    match (request.readings.setup.robot().own_weight(), &request.weight) {
        (Some(r), Some(s)) if (&r.gravity, &r.terms) != (&s.gravity, &s.terms) => {
            Err(Error::InvalidOption {
                option: JobOption::Update,
                message: format!(
                    "the calibrated robot file's [gravity] ({} terms) and the stiffness file's gravity section ({} terms) differ: the robot file carries the calibration's sag, leave out --stiffness (Python stiffness=)",
                    r.gravity, s.gravity
                ),
            })
        }
        (Some(r), _) => Ok(Some(r)),
        (None, s) => Ok(s.as_ref()),
    }
}

/// The tool the calibrated robot file's gravity terms hold, its mass (kg) and centre of mass
/// (m, flange frame): the setup's (`[tool] mass_kg`, `centre_of_mass_mm`), or with `update` of
/// lumped terms the calibration's (the terms are kept).
///
/// # Errors
/// Those of [`weight`].
pub(super) fn tool_load(
    request: &Request<'_>,
) -> Result<(Option<f64>, Option<nalgebra::Vector3<f64>>)> {
    let payload = request.readings.setup.payload();
    Ok(match weight(request)? {
        Some(w) if w.gravity != "masses" => (w.tool_mass, w.tool_centre),
        _ => (payload.map(|p| p.mass), payload.map(|p| p.centre)),
    })
}

/// The calibrated robot file's text ([`robot_file::calibrated_file`]): the robot, its
/// `[held_out]` ([`held_out`]), the mount it was calibrated on, the part's frame it located
/// (`part`) and its sag `own` in the file's link frames; or why there is none.
pub(super) fn robot_file(
    request: &Request<'_>,
    at: (&ErrorModel, &stiffid_metrology::calibration::Estimate),
    (validation, cross_validation): (Option<&super::Held>, Option<&super::Held>),
    own_part: (Option<&OwnWeight>, Option<&nalgebra::Isometry3<f64>>),
) -> std::result::Result<String, String> {
    let setup = request.readings.setup;
    let held = held_out(request, setup, validation, cross_validation);
    // The mount it was calibrated on: the setup's, or the one its calibrated robot records (an
    // update).
    let mount = &setup.workcell().controller().mount;
    robot_file::calibrated_file(at, &held, mount, own_part).map_err(|e| e.to_string())
}

/// The warning that a URDF written (`written`) of a robot with the gravity terms `own` leaves
/// its sag out; none without either.
pub(super) fn urdf_rigid(
    written: bool,
    own: Option<&OwnWeight>,
) -> Option<stiffid_core::common::warning::Warning> {
    let own = own.filter(|_| written)?;
    Some(stiffid_core::common::warning::Warning::new(
        stiffid_core::common::warning::WarningKind::LeftOut,
        format!("the URDF leaves out the sag under the robot's own weight (the {} gravity terms: a URDF has no place for them): a robot read from it is rigid; use the robot file", own.gravity),
    ))
}
