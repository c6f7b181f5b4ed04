//! Reflectors fixed in the cell (`T1`, `T2`, ... of a readings file): on a positioner's table,
//! where the positioner's pose `P(e)` carries them (module docs of [`super::external`]), or, in a
//! cell without a positioner, on a fixed part or fixture, each a fixed point of the cell
//! (`P = I`). Each is three free parameters, its coordinates in the part's frame at `e = 0`
//! (cell coordinates), read at `P(e) x_k` through the tracker's registration.

use super::{ErrorModel, Kind, Observation, Parameter, Target};
use nalgebra::{DVector, Isometry3, Point3, Vector3};
use stiffid_core::{Error, Result};

/// The reflectors of an error model: the first one's first parameter, and their count.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Tables {
    start: usize,
    count: usize,
}

impl ErrorModel {
    /// The model with `tables` reflectors fixed in the cell (`table<k>.x`, `.y`, `.z`, m, part
    /// frame at `e = 0`, nominal 0: [`crate::calibration::fit::start`] starts them from their
    /// readings; priority 0): on the positioner's table, or fixed points of a cell without a
    /// positioner (a fixed base or a track). [`ErrorModel::with_external`] adds them for a cell
    /// with external axes; a model without external axes adds them here. 0 adds none.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`workpiece.reflectors_mm`) beyond [`super::MAX_POINTS`]
    /// reflectors, or when the model has reflectors, loads or maps already.
    pub fn with_tables(mut self, tables: usize) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "workpiece.reflectors_mm".into(),
            message,
        };
        if tables > super::MAX_POINTS {
            return Err(invalid(format!(
                "expected 0 to {} reflectors fixed in the cell, got {tables}",
                super::MAX_POINTS
            )));
        }
        if tables == 0 {
            return Ok(self);
        }
        if self.loads.is_some() || self.maps.is_some() || self.tables.count > 0 {
            return Err(invalid(
                "add the reflectors before the loads and the error maps, once".into(),
            ));
        }
        let start = self.parameters.len();
        for k in 0..tables {
            for (axis, n) in ["x", "y", "z"].iter().enumerate() {
                self.parameters.push(Parameter {
                    name: format!("table{}.{n}", k + 1),
                    kind: Kind::Table,
                    target: Target::Table { point: k, axis },
                    nominal: 0.0,
                    priority: 0,
                });
            }
        }
        self.tables = Tables {
            start,
            count: tables,
        };
        Ok(self)
    }

    /// The reflectors fixed in the cell the model fits (on the positioner's table, or fixed
    /// points of a cell without a positioner).
    pub fn tables(&self) -> usize {
        self.tables.count
    }

    /// Reflector `k` (part frame at `e = 0`, m) in `values`.
    ///
    /// # Panics
    /// Beyond [`ErrorModel::tables`].
    pub fn table(&self, values: &DVector<f64>, k: usize) -> Vector3<f64> {
        assert!(k < self.tables.count, "reflector {k} beyond the model's");
        values
            .fixed_rows::<3>(self.tables.start + 3 * k)
            .into_owned()
    }

    /// Reflector `k` at `e` (cell frame, m): `P(e) x_k`.
    pub(super) fn table_position(
        &self,
        values: &DVector<f64>,
        e: &[f64],
        k: usize,
    ) -> Vector3<f64> {
        let x = self.table(values, k);
        (self.positioner_pose(values, e) * Point3::from(x)).coords
    }

    /// Writes the columns of reflector `k`'s reading at `e` into `put(parameter, column)`: the
    /// positioner's parameters' and the reflector's own coordinates' (`P(e)`'s rotation).
    pub(super) fn table_columns(
        &self,
        values: &DVector<f64>,
        e: &[f64],
        k: usize,
        mut put: impl FnMut(usize, Vector3<f64>),
    ) {
        if let Some(x) = &self.external {
            x.positioner_columns(values, e, self.table(values, k), &mut put);
        }
        let rotation = self
            .positioner_pose(values, e)
            .rotation
            .to_rotation_matrix();
        for a in 0..3 {
            put(
                self.tables.start + 3 * k + a,
                rotation.matrix().column(a).into_owned(),
            );
        }
    }

    /// `values` with each reflector's coordinates started from its readings: the mean of
    /// `P(e)^-1 T t` over them (`P` at `values`, `T` the measurement frame `frame`). A reflector
    /// without readings keeps its value.
    pub(crate) fn start_tables(
        &self,
        values: &mut DVector<f64>,
        frame: &Isometry3<f64>,
        observations: &[Observation],
    ) {
        for k in 0..self.tables.count {
            let part: Vec<Vector3<f64>> = (observations.iter())
                .filter(|o| o.table && o.point == k)
                .map(|o| {
                    let cell = frame * Point3::from(o.measured);
                    (self.positioner_pose(values, o.e.as_slice()).inverse() * cell).coords
                })
                .collect();
            if !part.is_empty() {
                let mean = part.iter().sum::<Vector3<f64>>() / part.len() as f64;
                values
                    .fixed_rows_mut::<3>(self.tables.start + 3 * k)
                    .copy_from(&mean);
            }
        }
    }
}
