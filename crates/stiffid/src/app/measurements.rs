//! The measurements the identify and validate jobs read: a measurement file, raw readings under
//! load steps, or arrays, turned into the base frame, with where each measurement came from.

use crate::app::in_data;
use nalgebra::Vector6;
use std::io::{BufRead, BufReader, Read};
use stiffid_core::common::warning::Warning;
use stiffid_core::io::measurements::{self, Labels};
use stiffid_core::io::read_text;
use stiffid_core::io::readings::{self, has_load_column};
use stiffid_core::observation::Measurement;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::setup::plausibility;
use stiffid_core::{Error, Result, Setup};
use stiffid_identify::steps::LoadSteps;

/// The measurements to identify from, or to validate a stiffness on.
pub enum Data<R> {
    /// A measurement file ([`stiffid_core::io::measurements`]) that `reader` reads (the caller
    /// opened it: a file, a buffer), named `name` in the report and in errors.
    File {
        /// The file's name, e.g. its path.
        name: String,
        /// Its reader.
        reader: R,
    },
    /// Measurements in the robot base frame, SI units (from arrays).
    Measurements(Vec<Measurement>),
}

/// Where each measurement came from: what a report names a measurement by.
#[derive(Debug, Clone, PartialEq)]
pub struct Origin {
    /// The posture labels (a file's; for arrays `1`, `2`, ... in order).
    pub labels: Labels,
    /// The posture of each measurement, numbered in order of first appearance.
    pub postures: Vec<usize>,
    /// The measuring point of each measurement, 0-based.
    pub points: Vec<usize>,
    /// The axis angles of each posture (rad), by posture number.
    pub angles: Vec<Vector6<f64>>,
    /// The external axes' values of each posture (SI, the cell's order; empty values without
    /// external axes), by posture number.
    pub external: Vec<ExternalValues>,
    /// The line of each measurement in its file (1-based); `None` for arrays.
    pub lines: Option<Vec<u64>>,
    /// The first measurement of each posture (dense number).
    pub first_of_posture: Vec<usize>,
    /// The names of the force and of the displacement columns (a file's header, or the arrays'
    /// argument names), comma-separated.
    pub columns: [String; 2],
}

impl Origin {
    /// The label of measurement `i`'s posture.
    pub(crate) fn label(&self, i: usize) -> &str {
        self.labels.get(self.postures[i])
    }

    /// The labels of dense posture numbers.
    pub(crate) fn labels_of(&self, postures: &[usize]) -> Vec<String> {
        postures
            .iter()
            .map(|&p| self.label(self.first_of_posture[p]).to_string())
            .collect()
    }

    /// The origin of measurements with posture labels `labels`, each measurement's posture
    /// number (dense, in order of first appearance: `labels.len()` of them) and measuring point
    /// (0-based), each posture's axis angles (rad) and external axes' values (SI), the
    /// measurements' lines in their file (`None` for arrays) and the force and displacement
    /// columns' names.
    pub fn new(
        labels: Labels,
        postures: Vec<usize>,
        points: Vec<usize>,
        (angles, external): (Vec<Vector6<f64>>, Vec<ExternalValues>),
        lines: Option<Vec<u64>>,
        columns: [String; 2],
    ) -> Self {
        let mut first_of_posture = vec![usize::MAX; labels.len()];
        for (i, &p) in postures.iter().enumerate().rev() {
            first_of_posture[p] = i;
        }
        Origin {
            labels,
            postures,
            points,
            angles,
            external,
            lines,
            first_of_posture,
            columns,
        }
    }
}

/// A whole measurement file read, parsed and turned into the base frame, and where each
/// measurement came from.
pub(crate) fn read_file<R: Read>(
    setup: &Setup,
    name: &str,
    reader: R,
) -> Result<(measurements::MeasurementFile, Origin)> {
    let text = read_text(name, reader)?;
    let mut file = measurements::parse(&text).map_err(|e| in_data(name, e))?;
    drop(text);
    file.to_base_frame(setup).map_err(|e| in_data(name, e))?;
    let columns = [
        file.layout.force_columns(),
        file.layout.displacement_columns(),
    ];
    let origin = Origin::new(
        Labels::from_iter(&file.labels),
        file.measurements.iter().map(|m| m.posture).collect(),
        file.measurements.iter().map(|m| m.point).collect(),
        posture_angles(&file.measurements),
        Some(file.lines.clone()),
        columns,
    );
    Ok((file, origin))
}

/// Whether the header of the text `source` starts with (its first line that is neither blank nor
/// a `#` comment, within the buffer) names a load column: raw readings under load steps.
pub(crate) fn header_has_loads<R: Read>(source: &mut BufReader<R>) -> bool {
    let Ok(buffer) = source.fill_buf() else {
        return false;
    };
    let text = String::from_utf8_lossy(buffer);
    text.lines()
        .find(|l| !(l.trim().is_empty() || l.starts_with('#')))
        .is_some_and(has_load_column)
}

/// Raw readings under load steps read for a fit ([`stiffid_identify::steps`]): every loaded
/// reading relative to its point's unloaded one, in the base frame, with its line and where it
/// came from.
pub(crate) struct Loaded {
    /// The readings.
    readings: readings::Readings,
    /// The readings' load steps.
    pub(crate) steps: LoadSteps,
    /// The loaded readings as displacement measurements.
    pub(crate) measurements: Vec<Measurement>,
    /// The line of each measurement's reading.
    lines: Vec<u64>,
    /// Where each measurement came from.
    pub(crate) origin: Origin,
}

impl Loaded {
    /// The readings of `text` (named `name`): refused naming the data when a posture has no
    /// loaded reading.
    pub(crate) fn read(setup: &Setup, name: &str, text: &str) -> Result<Self> {
        let points = setup.tool().measuring_points.len();
        let readings =
            readings::parse(text, setup.robot(), points).map_err(|e| in_data(name, e))?;
        let mut steps = LoadSteps::new(&readings).map_err(|e| in_data(name, e))?;
        steps.to_base_frame(setup).map_err(|e| in_data(name, e))?;
        let loaded = steps.loaded();
        if let Some(p) = (0..steps.labels.len())
            .find(|&p| !loaded.iter().any(|&i| steps.measurements[i].posture == p))
        {
            return Err(in_data(
                name,
                Error::InvalidField {
                    field: "load_step".into(),
                    message: format!(
                        "posture '{}' has no loaded reading: nothing to identify from it",
                        stiffid_core::common::limits::short(&steps.labels[p])
                    ),
                },
            ));
        }
        let measurements: Vec<Measurement> = loaded
            .iter()
            .map(|&i| steps.measurements[i].clone())
            .collect();
        let lines: Vec<u64> = loaded.iter().map(|&i| steps.lines[i]).collect();
        let origin = Origin::new(
            Labels::from_iter(&steps.labels),
            measurements.iter().map(|m| m.posture).collect(),
            measurements.iter().map(|m| m.point).collect(),
            posture_angles(&measurements),
            Some(lines.clone()),
            readings.columns.clone(),
        );
        Ok(Loaded {
            readings,
            steps,
            measurements,
            lines,
            origin,
        })
    }

    /// `error` of a fit of the measurements, placed in the data `name`: a measurement's number
    /// as its reading's line.
    pub(crate) fn explain(&self, name: &str, error: Error) -> Error {
        let e = match error {
            Error::Measurement { number, .. } => Error::InvalidField {
                field: "readings".into(),
                message: format!(
                    "line {}: {error}",
                    self.lines.get(number.wrapping_sub(1)).copied().unwrap_or(0)
                ),
            },
            e => e,
        };
        in_data(name, e)
    }

    /// Readings in another unit fit a robot of another size: refused whatever a fit found
    /// (after it, so that a file's own errors come first).
    pub(crate) fn check_scale(&self, setup: &Setup, name: &str) -> Result<()> {
        stiffid_metrology::register::refuse_other_scale(setup, &self.readings)
            .map_err(|e| in_data(name, e))
    }
}

/// `f` on the measurements of `data` (a measurement file or raw readings under load steps, as
/// `identify` reads them, turned into the base frame; or arrays): the data's name, where each
/// measurement came from and `f`'s result; `f`'s errors as [`Error::Input`] naming the data (a
/// file's line and column).
///
/// # Errors
/// Those of [`read_file`], of the readings ([`stiffid_core::io::readings::parse`],
/// [`LoadSteps::new`]) and of `f`.
pub(crate) fn on_measurements<R: Read, T>(
    setup: &Setup,
    data: Data<R>,
    f: impl FnOnce(&[Measurement]) -> Result<T>,
) -> Result<(String, Origin, T)> {
    match data {
        Data::File { name, reader } => {
            let mut source = BufReader::with_capacity(1 << 20, reader);
            if header_has_loads(&mut source) {
                let data = Loaded::read(setup, &name, &read_text(&name, source)?)?;
                let found = f(&data.measurements).map_err(|e| data.explain(&name, e))?;
                data.check_scale(setup, &name)?;
                return Ok((name, data.origin, found));
            }
            let (file, origin) = read_file(setup, &name, source)?;
            let found = f(&file.measurements).map_err(|e| in_data(&name, file.explain(e)))?;
            Ok((name, origin, found))
        }
        Data::Measurements(measurements) => {
            let found = f(&measurements).map_err(|e| in_data("arrays", e))?;
            Ok(("arrays".to_string(), arrays_origin(&measurements), found))
        }
    }
}

/// The warning that the data's angles look like radians under `_deg` names, if they do
/// ([`plausibility::radians_as_degrees`]), naming the data.
pub(crate) fn angle_warnings(data_name: &str, origin: &Origin) -> Vec<Warning> {
    plausibility::radians_as_degrees(&origin.angles)
        .map(|mut w| {
            w.message = format!("{data_name}: {}", w.message);
            w
        })
        .into_iter()
        .collect()
}

/// The origin of measurements given as arrays: postures labelled `1`, `2`, ... in order.
pub(crate) fn arrays_origin(measurements: &[Measurement]) -> Origin {
    let postures = measurements.iter().map(|m| m.posture).collect::<Vec<_>>();
    let count = postures.iter().max().map_or(0, |p| p + 1);
    Origin::new(
        Labels::from_iter((1..=count).map(|p| p.to_string())),
        postures,
        measurements.iter().map(|m| m.point).collect(),
        posture_angles(measurements),
        None,
        ["wrench".into(), "displacement_mm".into()],
    )
}

/// The axis angles and external values of each posture of `measurements` (numbered from 0, each
/// with a measurement).
fn posture_angles(measurements: &[Measurement]) -> (Vec<Vector6<f64>>, Vec<ExternalValues>) {
    let count = measurements
        .iter()
        .map(|m| m.posture + 1)
        .max()
        .unwrap_or(0);
    let mut angles = vec![Vector6::zeros(); count];
    let mut external = vec![ExternalValues::NONE; count];
    for m in measurements {
        angles[m.posture] = m.q;
        external[m.posture] = m.e;
    }
    (angles, external)
}
