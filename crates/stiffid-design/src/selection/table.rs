//! The positioner's angles of a calibration group: with reflectors on the positioner's table
//! (`[workpiece] reflectors_mm`), every posture of a calibration group also reads the table's
//! reflectors, with the positioner at angles chosen for the group
//! (`CalibrationDesign::choose_table_angles`) on the calibration design with the positioner's
//! lines, offsets and the reflectors.
//!
//! The candidates are a grid of about [`CANDIDATE_ANGLES`] angles over the positioner's travel
//! ([`table_grid`]: the travel is a feasibility check by construction) and the positioner's
//! values the postures were designed at (so that each posture clears the boxes the positioner
//! carries at one candidate at least, its own), those with the tracker's line of sight to a
//! reflector through an obstacle of the cell left out (the sight from the tracker's head to
//! `SIGHT_END` before the reflector, where its nest and the table are). The arm's own bodies
//! are not checked against these sights. With boxes the positioner carries
//! (`[[cell.obstacle]] carried_by`), a posture is read only at a candidate where its arm, its
//! rope and its lines of sight clear those boxes turned there, by the cell's checks with the
//! design's margin (`design_checker`): the arm's postures are designed with the boxes at rest,
//! the table's angles then keep them clear of the arm.

use crate::observability::{CalibrationCriteria, CalibrationCriterion, CalibrationDesign, Placed};
use crate::search::design_checker;
use nalgebra::Vector6;
use rayon::prelude::*;
use stiffid_core::cell::{capsule_box, Capsule, Part, Thing};
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::{Error, Result, Setup};

/// About how many candidate angles of the positioner a group's table readings are chosen among.
pub const CANDIDATE_ANGLES: usize = 64;

/// How far before a table reflector its line of sight is checked, m.
pub(crate) const SIGHT_END: f64 = 0.05;

/// About `count` values of the positioner's axes of `axes`: a grid of `round(count^(1/k))`
/// values per axis (`k` positioner axes), each at the middles of equal parts of its travel
/// (never its ends: a turntable's two ends are one angle), the carrier's axes at their values
/// in `carrier` (SI, the cell's order). Only `carrier` without a positioner.
pub fn table_grid(
    axes: &ExternalAxes,
    count: usize,
    carrier: &ExternalValues,
) -> Vec<ExternalValues> {
    let k = axes.len() - axes.carrier_len();
    let per = (count.max(1) as f64)
        .powf(1.0 / k.max(1) as f64)
        .round()
        .max(1.0) as usize;
    let mut grid = vec![carrier.as_slice().to_vec()];
    for (i, a) in axes.axes().iter().enumerate().skip(axes.carrier_len()) {
        grid = (grid.iter())
            .flat_map(|e| {
                (0..per).map(move |j| {
                    let mut e = e.clone();
                    e[i] = a.lower + (j as f64 + 0.5) / per as f64 * (a.upper - a.lower);
                    e
                })
            })
            .collect();
    }
    (grid.iter())
        .map(|e| ExternalValues::new(e).expect("the cell's axes"))
        .collect()
}

/// A calibration group whose table readings' angles are chosen.
#[derive(Clone, Copy)]
pub struct Group<'a> {
    /// Its postures (axis angles, rad).
    pub postures: &'a [Vector6<f64>],
    /// The station it was designed at, if one (else the cell's first).
    pub station: Option<ExternalValues>,
    /// Where each posture is read (a campaign over the stations), or empty: every posture at
    /// `station`.
    pub placed: &'a [ExternalValues],
}

/// The group's table readings.
#[derive(Debug, Clone)]
pub struct TableAngles {
    /// The calibration criterion's loss of the group with the table read at the chosen angles.
    pub value: f64,
    /// Every calibration criterion of the group with them.
    pub criteria: CalibrationCriteria,
    /// Where each posture is read: its station with the positioner's angles chosen for it.
    pub placed: Vec<ExternalValues>,
}

/// The positioner's angles of `group`'s table readings on `setup` (module docs), for the
/// calibration `criterion` on the design `design_of` gives of a setup (the setup itself, or the
/// arm at its carrier's station on a track: the track's own parameters need a campaign over
/// its stations); `margin` the design's (m). `None` without a positioner or reflectors on its
/// table (reflectors on a fixed part are read as the campaign's steps say, at no angle to
/// choose).
///
/// # Errors
/// [`Error::Input`] (`table`) when no candidate angle has clear lines of sight, a posture meets
/// a box the positioner carries at every candidate, or the chosen angles do not separate the
/// calibration's parameters; those of `design_of`.
pub fn table_angles(
    setup: &Setup,
    margin: Option<f64>,
    criterion: CalibrationCriterion,
    design_of: impl Fn(&Setup) -> Result<CalibrationDesign>,
    group: Group,
) -> Result<Option<TableAngles>> {
    let reflectors = setup.table_reflectors();
    let Some(axes) = (setup.robot().external()).filter(|a| a.len() > a.carrier_len()) else {
        return Ok(None);
    };
    if reflectors.is_empty() {
        return Ok(None);
    }
    let here = group.station.unwrap_or_else(|| axes.stations(1)[0]);
    let where_read: Vec<ExternalValues> = match group.placed.is_empty() {
        true => vec![here; group.postures.len()],
        false => group.placed.to_vec(),
    };
    // One station of a track: the design of the arm there with the positioner.
    let cut = match group.placed.is_empty() {
        true => axes.carrier_len(),
        false => 0,
    };
    let at = match cut {
        0 => setup.clone(),
        _ => setup.at_carrier(here.as_slice())?,
    };
    let design = design_of(&at)?;
    let placed: Vec<Placed> = (group.postures.iter().zip(&where_read))
        .map(|(q, e)| (*q, tail(e, cut)))
        .collect();
    let design_axes = at.robot().external().expect("a positioner");
    let designed_at: Vec<ExternalValues> = (where_read.iter())
        .map(|w| joined(design_axes, &tail(&here, cut), &tail(w, cut)))
        .collect();
    let candidates = candidates(
        &at,
        design_axes,
        &reflectors,
        &tail(&here, cut),
        &designed_at,
    );
    if candidates.is_empty() {
        return Err(no_sight());
    }
    let read_at = |at: &ExternalValues, table: &ExternalValues| {
        let e = joined(design_axes, &tail(at, cut), table);
        joined(axes, at, &lifted(at, &e, cut))
    };
    let reading = Reading {
        postures: group.postures,
        where_read: &where_read,
        candidates: &candidates,
    };
    let allowed = clear_of_carried(setup, margin, reading, read_at);
    if let Some(i) = (allowed.iter().flatten()).position(|a| !a.contains(&true)) {
        return Err(refused(format!("posture {} of the group meets a box the positioner carries (its arm, rope or a line of sight within the clearance) at every candidate angle with clear lines of sight to the reflectors: move the box, the reflectors or the tracker, or choose other postures", i + 1)));
    }
    let count = placed.len();
    let choice =
        design.choose_table_angles(criterion, &placed, &candidates, count, allowed.as_deref())?;
    if !choice.value.is_finite() {
        return Err(refused(format!(
            "the {} postures with the table read at as many angles do not separate the calibration's {} parameters: choose more postures or reflectors",
            placed.len(),
            design.kept().len()
        )));
    }
    let placed: Vec<Placed> = (placed.iter().zip(&choice.chosen))
        .map(|((q, e), &c)| (*q, joined(design_axes, e, &candidates[c])))
        .collect();
    let angles: Vec<ExternalValues> = placed.iter().map(|p| p.1).collect();
    let with = design.with_table_angles(&angles)?;
    Ok(Some(TableAngles {
        value: choice.value,
        criteria: with.evaluate_placed(&placed)?,
        placed: (where_read.iter().zip(&choice.chosen))
            .map(|(at, &c)| read_at(at, &candidates[c]))
            .collect(),
    }))
}

/// The postures of a group, where each is read, and the table's candidate angles.
#[derive(Clone, Copy)]
struct Reading<'a> {
    postures: &'a [Vector6<f64>],
    where_read: &'a [ExternalValues],
    candidates: &'a [ExternalValues],
}

/// Whether each posture (`postures[i]` read where `where_read[i]` puts the external axes) clears
/// the boxes the positioner carries with the table at each of `candidates` (`read_at`: the
/// cell's values of a reading there), by every check's pairs with such a box (module docs);
/// `None` when the cell carries none.
fn clear_of_carried(
    setup: &Setup,
    margin: Option<f64>,
    r: Reading,
    read_at: impl Fn(&ExternalValues, &ExternalValues) -> ExternalValues + Sync,
) -> Option<Vec<Vec<bool>>> {
    let obstacles = &setup.cell()?.obstacles;
    let carried = |t: Thing| matches!(t, Thing::Obstacle(i) if obstacles[i].carried_by.is_some());
    if !obstacles.iter().any(|o| o.carried_by.is_some()) {
        return None;
    }
    let checker = design_checker(setup, margin);
    let clear = |q: &Vector6<f64>, e: &ExternalValues| {
        (checker.margins_at(q, e.as_slice()).iter())
            .filter(|m| carried(m.between.0) || carried(m.between.1))
            .all(|m| m.margin >= 0.0)
    };
    let rows = (r.postures.par_iter().zip(r.where_read))
        .map(|(q, at)| {
            (r.candidates.iter())
                .map(|c| clear(q, &read_at(at, c)))
                .collect()
        })
        .collect();
    Some(rows)
}

/// `e` without its first `cut` values.
fn tail(e: &ExternalValues, cut: usize) -> ExternalValues {
    ExternalValues::new(&e.as_slice()[cut..]).expect("fewer axes")
}

/// `e` (the axes after the first `cut`) with the first `cut` values of `at` before it.
fn lifted(at: &ExternalValues, e: &ExternalValues, cut: usize) -> ExternalValues {
    let values: Vec<f64> = (at.as_slice()[..cut].iter())
        .chain(e.as_slice())
        .copied()
        .collect();
    ExternalValues::new(&values).expect("the cell's axes")
}

/// The carrier's values of `at` with the positioner's of `table`.
fn joined(axes: &ExternalAxes, at: &ExternalValues, table: &ExternalValues) -> ExternalValues {
    let mut e = at.as_slice().to_vec();
    let c = axes.carrier_len();
    e[c..].copy_from_slice(&table.as_slice()[c..]);
    ExternalValues::new(&e).expect("the cell's axes")
}

/// The candidate angles (module docs), the carrier at `here`, and the positioner's values
/// `designed_at` the postures were designed at (the boxes it carries there: every posture clears
/// them at its own), each with clear lines of sight to the reflectors.
fn candidates(
    setup: &Setup,
    axes: &ExternalAxes,
    reflectors: &[nalgebra::Vector3<f64>],
    here: &ExternalValues,
    designed_at: &[ExternalValues],
) -> Vec<ExternalValues> {
    let mut grid = table_grid(axes, CANDIDATE_ANGLES, here);
    for e in designed_at {
        if !grid.contains(e) {
            grid.push(*e);
        }
    }
    grid.into_iter()
        .filter(|e| sights_clear(setup, axes, reflectors, e))
        .collect()
}

/// Whether the tracker sees every reflector on the table with the external axes at `e` (module
/// docs): always without a tracker or a cell.
fn sights_clear(
    setup: &Setup,
    axes: &ExternalAxes,
    reflectors: &[nalgebra::Vector3<f64>],
    e: &ExternalValues,
) -> bool {
    let (Some(tracker), Some(cell)) = (setup.tracker(), setup.cell()) else {
        return true;
    };
    let pose = axes.positioner_pose(e.as_slice());
    let obstacles = cell.obstacles_at(setup.robot(), e.as_slice());
    reflectors.iter().all(|x| {
        let point = (pose * nalgebra::Point3::from(*x)).coords;
        let towards = tracker.position - point;
        let length = towards.norm();
        if length <= SIGHT_END {
            return true;
        }
        let sight = Capsule {
            part: Part::Tool,
            a: tracker.position,
            b: point + towards * (SIGHT_END / length),
            radius: 0.0,
        };
        obstacles.iter().all(|o| capsule_box(&sight, o) > 0.0)
    })
}

/// The refusal of a group's table readings with `message`.
fn refused(message: String) -> Error {
    Error::Input {
        source_name: "postures: the table's readings".into(),
        error: Box::new(Error::InvalidField {
            field: "table".into(),
            message,
        }),
    }
}

/// The refusal when no angle of the positioner has clear lines of sight to the reflectors.
fn no_sight() -> Error {
    refused("no angle of the positioner has clear lines of sight from the tracker to every reflector on the table: move the tracker or the reflectors".into())
}

/// Refuses, before any search, a calibration design on `setup` with reflectors on the
/// positioner's table that no angle of the positioner can read: no candidate angle (module
/// docs) at `station` (the cell's first without one) has clear lines of sight from the tracker
/// to every reflector. A cheap check (a line per reflector and candidate), where the search
/// would otherwise run its course first.
///
/// # Errors
/// [`Error::Input`] (`table`) as [`table_angles`] for no clear line of sight.
pub fn check_sights(setup: &Setup, station: Option<ExternalValues>) -> Result<()> {
    let reflectors = setup.table_reflectors();
    let Some(axes) = setup.robot().external() else {
        return Ok(());
    };
    if reflectors.is_empty() || axes.len() == axes.carrier_len() {
        return Ok(());
    }
    let here = station.unwrap_or_else(|| axes.stations(1)[0]);
    match candidates(setup, axes, &reflectors, &here, &[here]).is_empty() {
        true => Err(no_sight()),
        false => Ok(()),
    }
}
