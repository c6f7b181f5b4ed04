//! The observation matrix of measured data: [`Measurement`]s checked and stacked into
//! [`Observations`] (`Psi` and `delta`, Eq. 10-11), row order as in [`crate::observation`].

use crate::observation::stiffness::joint_torques;
use crate::observation::{point_rows, SpringLoads};
use crate::robot::external::ExternalValues;
use crate::setup::Arm;
use crate::{Error, MeasurementField, Result};
use nalgebra::{DMatrix, DVector, Vector3, Vector6};
use std::collections::HashMap;

/// Largest accepted displacement of a measuring point, m: a robot deflects by millimetres, so a
/// larger value is a unit or transcription error.
pub(crate) const MAX_DISPLACEMENT: f64 = 1.0;

/// Largest accepted force magnitude, N.
pub(crate) const MAX_FORCE: f64 = 1e6;

/// Largest accepted moment magnitude, Nm.
pub(crate) const MAX_MOMENT: f64 = 1e6;

/// One measured displacement: a measuring point in a posture under a wrench.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// The posture: any number that identifies it (a file's labels are numbered `0, 1, ...` in
    /// order of first appearance). Measurements of the same posture must have the same axis
    /// angles.
    pub posture: usize,
    /// Index of the measuring point in the arm's tool, 0-based.
    pub point: usize,
    /// Axis angles q, rad (controller convention).
    pub q: Vector6<f64>,
    /// The cell's external axis values at the posture (SI, the cell's order,
    /// [`crate::robot::external`]); empty for a robot without external axes. The arm's frames are
    /// [`crate::Robot::frames_at`] `(q, e)`, positions and wrenches in the cell frame.
    pub e: ExternalValues,
    /// Wrench `[f; m]` at the loading point, base frame, N and Nm (Eq. 1).
    pub wrench: Vector6<f64>,
    /// Translation of the measuring point, loaded minus unloaded, base frame, m.
    pub displacement: Vector3<f64>,
}

/// The observation matrix and measured displacements of a list of measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Observations {
    /// `Psi`, `3n x c` for n measurements and the `c` parameters of the arm's model (six drives,
    /// then the virtual springs), m per (rad/Nm) or per (m/N) (Eq. 11), rows in the order of the
    /// [module docs](crate::observation).
    pub psi: DMatrix<f64>,
    /// `delta`, `3n`, m.
    pub delta: DVector<f64>,
    /// The number of distinct postures.
    pub postures: usize,
    /// The posture of each measurement, numbered `0..postures` in order of first appearance.
    pub posture_index: Vec<usize>,
}

impl Observations {
    /// Checks every measurement (`check`) and stacks its three rows of `Psi` and `delta`
    /// (Eq. 10-11, [`assemble`]), in the row order of the [module docs](crate::observation).
    ///
    /// # Errors
    /// Those of `check`.
    pub fn from_measurements(arm: &Arm, measurements: &[Measurement]) -> Result<Self> {
        let (postures, posture_index) = check(arm, measurements)?;
        let n = measurements.len();
        let mut psi = DMatrix::zeros(3 * n, arm.model().len());
        let mut delta = DVector::zeros(3 * n);
        assemble(arm, measurements, &mut psi, &mut delta);
        Ok(Observations {
            psi,
            delta,
            postures,
            posture_index,
        })
    }
}

/// Checks every measurement; returns the number of distinct postures and the posture of each
/// measurement, numbered `0..postures` in order of first appearance. Linear in the measurements
/// whatever the number of postures.
///
/// # Errors
/// [`Error::Measurement`] naming the measurement (1-based) and what is wrong: a measuring point the
/// arm lacks (`point`), a non-finite axis angle or one outside the robot's joint limits (`q1` ..
/// `q6`), a non-finite force or moment or one above [`MAX_FORCE`] / [`MAX_MOMENT`], a non-finite
/// displacement or one above [`MAX_DISPLACEMENT`], or a posture measured at different axis
/// angles (`posture`).
pub(crate) fn check(arm: &Arm, measurements: &[Measurement]) -> Result<(usize, Vec<usize>)> {
    let mut check = Check::default();
    let mut posture_index = Vec::with_capacity(measurements.len());
    check.push(arm, measurements, Some(&mut posture_index))?;
    Ok((check.postures(), posture_index))
}

/// The checks of `check` over measurements given a part at a time (a file read in chunks):
/// measurements are numbered over all parts, and a posture is compared with its first
/// measurement in any earlier part. Memory: a table entry and the axis angles per posture.
#[derive(Debug, Default)]
pub struct Check {
    table: Table,
    /// The axis angles of each posture's first measurement, by dense number.
    angles: Vec<Vector6<f64>>,
    /// The external axis values of each posture's first measurement, by dense number.
    external: Vec<ExternalValues>,
    /// Measurements checked so far.
    measurements: usize,
}

impl Check {
    /// Checks the next measurements (those of `check`); pushes the dense posture number of each
    /// onto `posture_index` if given.
    ///
    /// # Errors
    /// Those of `check`, numbering measurements over all parts.
    pub fn push(
        &mut self,
        arm: &Arm,
        measurements: &[Measurement],
        mut posture_index: Option<&mut Vec<usize>>,
    ) -> Result<()> {
        for meas in measurements {
            self.measurements += 1;
            let number = self.measurements;
            check_one(arm, number, meas)?;
            let next = (self.angles.len(), number);
            let (index, first) = self.table.entry(meas.posture, next);
            if index == self.angles.len() {
                self.angles.push(meas.q);
                self.external.push(meas.e);
            } else if self.angles[index] != meas.q || self.external[index] != meas.e {
                return Err(Error::Measurement {
                    number,
                    field: MeasurementField::Posture,
                    message: format!(
                        "this posture was measured before at other axis angles (measurement {first}): give each posture its own label"
                    ),
                });
            }
            if let Some(v) = posture_index.as_deref_mut() {
                v.push(index);
            }
        }
        Ok(())
    }

    /// The number of distinct postures so far.
    pub fn postures(&self) -> usize {
        self.angles.len()
    }

    /// The axis angles of `posture` (those of its first measurement), if it was checked.
    pub fn angles(&self, posture: usize) -> Option<&Vector6<f64>> {
        self.table
            .get(posture)
            .map(|(index, _)| &self.angles[index])
    }

    /// The external axis values of `posture` (those of its first measurement), if it was
    /// checked.
    pub fn external(&self, posture: usize) -> Option<&ExternalValues> {
        self.table
            .get(posture)
            .map(|(index, _)| &self.external[index])
    }
}

/// Writes the rows of `measurements` (checked by `check`) into `psi` (`3n x c`) and `delta`
/// (`3n`), in the row order of the [module docs](crate::observation): the six drive columns and
/// the first `c - 6` virtual springs of the arm's model ([`crate::model`]). Frames are computed
/// once per run of measurements with the same axis angles, torques once per run with the same
/// angles and wrench.
///
/// # Panics
/// If `psi` or `delta` do not have three rows per measurement, `psi` has fewer than six columns or
/// more than the model's parameters, or a measuring point is not the arm's.
pub fn assemble(
    arm: &Arm,
    measurements: &[Measurement],
    psi: &mut DMatrix<f64>,
    delta: &mut DVector<f64>,
) {
    assert!(psi.nrows() == 3 * measurements.len() && delta.len() == psi.nrows());
    let mut i = 0;
    while i < measurements.len() {
        // One run of measurements with the same axis angles: its frames (computed in place, not
        // moved: they are large), and the torques of the previous measurement's wrench.
        let first = &measurements[i];
        let frames = arm.robot().frames_at(&first.q, first.e.as_slice());
        let springs = psi.ncols() - 6;
        let mut tau = joint_torques(arm, &frames, &first.wrench);
        let mut loads = SpringLoads::new(arm, &frames, &first.wrench, springs);
        let mut previous = first;
        let same = |m: &&Measurement| m.q == first.q && m.e == first.e;
        while let Some(meas) = measurements.get(i).filter(same) {
            if previous.wrench != meas.wrench {
                tau = joint_torques(arm, &frames, &meas.wrench);
                loads = SpringLoads::new(arm, &frames, &meas.wrench, springs);
            }
            previous = meas;
            let point = &arm.tool().measuring_points[meas.point];
            psi.fixed_view_mut::<3, 6>(3 * i, 0)
                .copy_from(&point_rows(arm, &frames, point, &tau));
            loads.write_rows(&frames, point, psi, 3 * i);
            delta
                .fixed_rows_mut::<3>(3 * i)
                .copy_from(&meas.displacement);
            i += 1;
        }
    }
}

fn check_one(arm: &Arm, number: usize, meas: &Measurement) -> Result<()> {
    let error = |field, message: String| Error::Measurement {
        number,
        field,
        message,
    };
    let points = arm.tool().measuring_points.len();
    if meas.point >= points {
        return Err(error(
            MeasurementField::Point,
            format!(
                "measuring point {} does not exist: the setup has {points} (1 to {points})",
                meas.point + 1
            ),
        ));
    }
    let robot = &arm.robot();
    if let Some(v) = robot.limits().first_violation(&meas.q) {
        let message = match v.value.is_finite() {
            false => "the axis angle is not finite".to_string(),
            true => format!(
                "{:.3} deg is outside the robot's limits [{:.2}, {:.2}] deg",
                v.value.to_degrees(),
                v.lower.to_degrees(),
                v.upper.to_degrees()
            ),
        };
        return Err(error(MeasurementField::Axis(v.axis), message));
    }
    check_external(arm, meas).map_err(|message| error(MeasurementField::External, message))?;
    let force: Vector3<f64> = meas.wrench.fixed_rows::<3>(0).into();
    let moment: Vector3<f64> = meas.wrench.fixed_rows::<3>(3).into();
    let magnitudes = [
        (MeasurementField::Force, force, MAX_FORCE, 1.0, "N"),
        (MeasurementField::Moment, moment, MAX_MOMENT, 1.0, "Nm"),
        (
            MeasurementField::Displacement,
            meas.displacement,
            MAX_DISPLACEMENT,
            1e3,
            "mm",
        ),
    ];
    for (field, v, limit, scale, unit) in magnitudes {
        if !v.iter().all(|x| x.is_finite()) {
            return Err(error(field, "expected finite numbers".into()));
        }
        // The largest component where the norm would overflow.
        let size = Some(v.norm()).filter(|n| n.is_finite()).unwrap_or(v.amax());
        if size > limit {
            return Err(error(
                field,
                format!(
                    "magnitude {:.4e} {unit} is above the limit {:.0e} {unit}: check the unit of the columns",
                    size * scale,
                    limit * scale
                ),
            ));
        }
    }
    Ok(())
}

/// Posture -> (its dense number, its first measurement, 1-based): a table indexed by the
/// posture number while the numbers are small (as a file's are) and fit in 32 bits (8 bytes per
/// posture), else a hash map.
#[derive(Debug)]
enum Table {
    /// `UNSEEN` before the posture is seen.
    Dense(Vec<(u32, u32)>),
    Sparse(HashMap<usize, (usize, usize)>),
}

/// The entry of a posture not seen yet in [`Table::Dense`].
const UNSEEN: (u32, u32) = (u32::MAX, 0);

impl Default for Table {
    fn default() -> Self {
        Table::Dense(Vec::new())
    }
}

/// Postures numbered above this many times the postures seen (plus a margin) go to a hash map.
const DENSE_GROWTH: usize = 2;

impl Table {
    /// The entry of `posture`, if it was seen.
    fn get(&self, posture: usize) -> Option<(usize, usize)> {
        match self {
            Table::Dense(v) => v.get(posture).filter(|e| **e != UNSEEN).map(|e| widen(*e)),
            Table::Sparse(m) => m.get(&posture).copied(),
        }
    }

    /// The entry of `posture`, `next` if it is new.
    fn entry(&mut self, posture: usize, next: (usize, usize)) -> (usize, usize) {
        if let Table::Dense(v) = self {
            let fits = next.0 < u32::MAX as usize && next.1 < u32::MAX as usize;
            let near = posture <= DENSE_GROWTH * v.len() + 4096;
            if !fits || (posture >= v.len() && !near) {
                let map = v
                    .iter()
                    .enumerate()
                    .filter(|(_, e)| **e != UNSEEN)
                    .map(|(p, e)| (p, widen(*e)))
                    .collect();
                *self = Table::Sparse(map);
            } else if posture >= v.len() {
                v.resize(posture + 1, UNSEEN);
            }
        }
        match self {
            Table::Dense(v) => {
                let slot = &mut v[posture];
                if *slot == UNSEEN {
                    *slot = (next.0 as u32, next.1 as u32);
                }
                widen(*slot)
            }
            Table::Sparse(m) => *m.entry(posture).or_insert(next),
        }
    }
}

fn widen((index, first): (u32, u32)) -> (usize, usize) {
    (index as usize, first as usize)
}

/// The measurement's external axis values against the cell's axes: one per axis, within its
/// travel; none for a robot without external axes.
fn check_external(arm: &Arm, meas: &Measurement) -> std::result::Result<(), String> {
    match arm.robot().external() {
        None if meas.e.is_empty() => Ok(()),
        None => Err(format!(
            "the robot has no external axes, the measurement gives {}",
            meas.e.as_slice().len()
        )),
        Some(axes) => axes
            .check(meas.e.as_slice(), "e")
            .map_err(|e| e.to_string()),
    }
}
