//! Parameters held at given values: in the model's predictions, out of its fit (an update that
//! keeps what a calibration found, `calibrate --update`).
//!
//! A held parameter's column of [`ErrorModel::jacobian_of`] is zero: the identifiability
//! analysis finds it without effect, so a fit leaves it where the model's nominal values put it,
//! while every prediction ([`ErrorModel::predict`], [`ErrorModel::robot_at`]) uses that value.

use super::ErrorModel;
use nalgebra::DMatrix;
use stiffid_core::{Error, Result};

impl ErrorModel {
    /// The model with the parameters of `held` (`(index, value)`, value SI) held at those values:
    /// each one's nominal value becomes its value and its Jacobian column zero (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`parameters`) for an index beyond the parameters, one of the
    /// frame's six (the registration is always fitted), a value not finite, or a model with
    /// loads (their columns are added after the held ones are zeroed).
    pub fn with_held(mut self, held: &[(usize, f64)]) -> Result<Self> {
        let n = self.parameters.len();
        let invalid = |message: String| Error::InvalidField {
            field: "parameters".into(),
            message,
        };
        if self.loads.is_some() {
            return Err(invalid("no parameter is held in a model with loads".into()));
        }
        for &(c, v) in held {
            if !(6..n).contains(&c) || !v.is_finite() {
                return Err(invalid(format!(
                    "expected a parameter 7 to {n} held at a finite value, got {} at {v}",
                    c + 1
                )));
            }
            self.parameters[c].nominal = v;
            self.held.push(c);
        }
        self.held.sort_unstable();
        self.held.dedup();
        Ok(self)
    }

    /// The model with the nominal values of `values` (`(index, value)`, SI; an index beyond the
    /// parameters ignored): where a fit starts them.
    pub fn set_nominal(&mut self, values: &[(usize, f64)]) {
        for &(c, v) in values {
            if let Some(p) = self.parameters.get_mut(c) {
                p.nominal = v;
            }
        }
    }

    /// The parameters held ([`ErrorModel::with_held`]), ascending.
    pub fn held(&self) -> &[usize] {
        &self.held
    }

    /// `j` with the held parameters' columns zeroed.
    pub(super) fn zero_held(&self, j: &mut DMatrix<f64>) {
        for &c in &self.held {
            j.column_mut(c).fill(0.0);
        }
    }
}
