//! The compliances under the applied wrenches of loaded readings: their parameters, observation
//! rows and deflections.

use super::{gravity, ErrorModel, Kind, Parameter, Target};
use nalgebra::{DMatrix, DVector, Vector3, Vector6};
use stiffid_core::{Error, Result};

/// What the deflection under the applied wrenches needs: the setup (its stiffness model,
/// springs' coordinates, loading and measuring points, nominal robot) and the column of each of
/// its model's parameters.
#[derive(Debug, Clone)]
pub(super) struct Loads {
    setup: Box<stiffid_core::Setup>,
    /// The parameter (index in [`ErrorModel::parameters`]) of each parameter of the setup's
    /// model: a gravity compliance with known masses for a drive, else its own.
    pub(super) columns: Vec<usize>,
}

impl ErrorModel {
    /// The model with the compliances of `setup`'s stiffness model ([`stiffid_core::Setup::model`]:
    /// the drives, then the virtual springs) under the wrenches of loaded readings (module docs,
    /// "Loaded readings"): one parameter per model parameter (kind [`Kind::Compliance`], named
    /// `compliance.<name>`, nominal the setup's nominal compliance or 0), after the gravity
    /// terms; with known masses ([`gravity::Term::Compliance`]) a drive's is its gravity
    /// compliance, one parameter for both. The setup is the one whose robot and measuring
    /// points the model was made of.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`loads`) when the model already has them, when the setup's
    /// measuring points are not the model's count, or when the gravity terms' springs are in
    /// other coordinates than the setup's model.
    pub fn with_loads(mut self, setup: &stiffid_core::Setup) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "loads".into(),
            message,
        };
        if self.loads.is_some() {
            return Err(invalid("the model has the loads already".into()));
        }
        if self.maps.is_some() {
            return Err(invalid("add the loads before the error maps".into()));
        }
        if self.external.is_some() {
            return Err(invalid(
                "loaded readings of a cell with external axes are not calibrated: give its unloaded readings".into(),
            ));
        }
        if setup.tool().measuring_points.len() != self.points() {
            return Err(invalid(format!(
                "expected a setup with the model's {} measuring points, got {}",
                self.points(),
                setup.tool().measuring_points.len()
            )));
        }
        let shared = |joint: usize| {
            (self.gravity.terms().iter())
                .position(|t| *t == gravity::Term::Compliance { joint })
                .map(|t| self.gravity_start + t)
        };
        if self.gravity.link_masses().is_some() && self.gravity.coordinates() != setup.springs() {
            return Err(invalid(
                "the gravity compliances' springs are in other coordinates than the setup's model"
                    .into(),
            ));
        }
        let nominal = setup.model_nominal_compliance();
        let mut columns = Vec::new();
        for (index, p) in setup.model().parameters().into_iter().enumerate() {
            if let Some(c) = (index < 6).then(|| shared(index)).flatten() {
                columns.push(c);
                continue;
            }
            columns.push(self.parameters.len());
            self.parameters.push(Parameter {
                name: format!("compliance.{}", p.name),
                kind: Kind::Compliance,
                target: Target::Compliance {
                    index,
                    kind: p.kind,
                },
                nominal: nominal.as_ref().map_or(0.0, |h| h[index]),
                priority: 4,
            });
        }
        self.loads = Some(Loads {
            setup: Box::new(setup.clone()),
            columns,
        });
        Ok(self)
    }

    /// Whether the model has the compliances under the applied wrenches
    /// ([`ErrorModel::with_loads`]).
    pub fn has_loads(&self) -> bool {
        self.loads.is_some()
    }

    /// The parameter (index in [`ErrorModel::parameters`]) of each parameter of the setup's
    /// stiffness model, with loads ([`ErrorModel::with_loads`]).
    pub fn compliance_columns(&self) -> Option<&[usize]> {
        self.loads.as_ref().map(|l| l.columns.as_slice())
    }

    /// The `3 x n` observation rows (`n` the setup's model's parameters; base frame, m per unit
    /// of compliance) of measuring point `k` at commanded axis angles `q` (rad) under `wrench`
    /// (base frame, N, N m, at the loading point): the rows of `Psi`
    /// ([`stiffid_core::observation::write_posture_block`]) on the nominal chain with the setup's
    /// points; `None` without loads or without a wrench.
    pub(crate) fn load_rows(
        &self,
        q: &Vector6<f64>,
        k: usize,
        wrench: &Vector6<f64>,
    ) -> Option<DMatrix<f64>> {
        let loads = self.loads.as_ref()?;
        if *wrench == Vector6::zeros() {
            return None;
        }
        let setup = &loads.setup;
        let frames = setup.robot().frames(q);
        let mut rows = DMatrix::zeros(3, loads.columns.len());
        write_load_rows(setup, &frames, k, wrench, &mut rows, 0);
        Some(rows)
    }

    /// The deflection (base frame, m) of measuring point `k` at commanded `q` under `wrench`
    /// with the compliances of `values` (SI): [`ErrorModel::load_rows`] times them, zero without
    /// loads or wrench.
    pub(crate) fn load_deflection(
        &self,
        values: &DVector<f64>,
        q: &Vector6<f64>,
        k: usize,
        wrench: &Vector6<f64>,
    ) -> Vector3<f64> {
        match (self.load_rows(q, k, wrench), &self.loads) {
            (Some(rows), Some(loads)) => {
                let h = DVector::from_iterator(
                    loads.columns.len(),
                    loads.columns.iter().map(|&c| values[c]),
                );
                Vector3::from_iterator((rows * h).iter().copied())
            }
            _ => Vector3::zeros(),
        }
    }
}

/// Writes the three observation rows of measuring point `k` (the setup's) at the posture
/// `frames` under `wrench` (base frame, N, N m, at the loading point) into rows `row..row + 3`
/// of `psi` (one column per parameter of the setup's model): the drives' (Eq. 11) and the
/// virtual springs' ([`stiffid_core::observation::SpringLoads`]).
fn write_load_rows(
    setup: &stiffid_core::Setup,
    frames: &stiffid_core::Frames,
    k: usize,
    wrench: &Vector6<f64>,
    psi: &mut DMatrix<f64>,
    row: usize,
) {
    use stiffid_core::observation::{point_rows, stiffness::joint_torques, SpringLoads};
    let point = &setup.tool().measuring_points[k];
    let arm = setup.arm();
    let tau = joint_torques(arm, frames, wrench);
    psi.fixed_view_mut::<3, 6>(row, 0)
        .copy_from(&point_rows(arm, frames, point, &tau));
    SpringLoads::new(arm, frames, wrench, psi.ncols() - 6).write_rows(frames, point, psi, row);
}
