//! The compliance of every parameter of a model and its covariance: what an identification gives
//! and what prediction, validation and compensation use.

use super::prediction::Calibration;
use super::Model;
use super::OwnWeight;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// The compliance `h` of every parameter of a model (drives first, then the virtual springs, as
/// [`Model::parameters`]) and, from an identification, its covariance `Cov(h)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Compliance {
    /// `h`, n values: rad/Nm (drives, rotational springs) or m/N (translational springs).
    pub h: DVector<f64>,
    /// `Cov(h)`, n x n, SI (the products of the parameters' compliance units).
    pub covariance: Option<DMatrix<f64>>,
    /// From an identification cross-validated over postures: what its prediction intervals are
    /// built from ([`crate::model::prediction`]).
    pub prediction: Option<Calibration>,
    /// From a stiffness file written before the calibrated robot file carried them: the gravity
    /// terms a calibration fitted ([`OwnWeight`]). The calibrated robot's own
    /// ([`crate::Robot::own_weight`]) take their place; compensation refuses the two when they
    /// differ.
    pub own_weight: Option<OwnWeight>,
    /// The postures it was identified from, as the region a prediction stays inside
    /// ([`crate::model::region`]).
    pub region: super::Region,
    /// From a model comparison's posture bootstrap: the models the data support and their
    /// resampled parameter sets ([`super::ModelForm`]), the error budget's model-form part.
    pub model_form: Option<super::ModelForm>,
}

impl Compliance {
    /// The six drive compliances (rad/Nm) and their covariance ((rad/Nm)^2): the model of the
    /// drives alone.
    pub fn drives(h: Vector6<f64>, covariance: Option<Matrix6<f64>>) -> Self {
        Self {
            h: DVector::from_column_slice(h.as_slice()),
            covariance: covariance.map(|c| DMatrix::from_column_slice(6, 6, c.as_slice())),
            prediction: None,
            own_weight: None,
            region: super::Region::NotIdentified,
            model_form: None,
        }
    }

    /// The six drive compliances, rad/Nm.
    pub fn drives_h(&self) -> Vector6<f64> {
        Vector6::from_fn(|j, _| self.h[j])
    }

    /// `1 / h` of every parameter, SI (Nm/rad, N/m).
    pub fn stiffness(&self) -> DVector<f64> {
        self.h.map(|v| 1.0 / v)
    }

    /// Checks that it is a compliance of `model`: one finite value per parameter, and an n x n
    /// covariance if any.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`stiffness`) naming the count expected and the model's parameters.
    pub fn check(&self, model: &Model) -> Result<()> {
        let n = model.len();
        let wrong_cov = self
            .covariance
            .as_ref()
            .is_some_and(|c| c.nrows() != n || c.ncols() != n);
        let wrong_prediction = self
            .prediction
            .as_ref()
            .is_some_and(|p| p.parameters() != n);
        if self.h.len() != n
            || wrong_cov
            || wrong_prediction
            || self.h.iter().any(|v| !v.is_finite())
        {
            let names: Vec<String> = model.parameters().into_iter().map(|p| p.name).collect();
            return Err(Error::InvalidField {
                field: "stiffness".into(),
                message: format!(
                    "expected {n} finite values (and an {n}x{n} covariance), one per parameter of the model: {}",
                    names.join(", ")
                ),
            });
        }
        Ok(())
    }
}
