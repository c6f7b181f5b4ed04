//! The sag under the robot's own weight, as compensation adds it.
//!
//! A calibration that fits gravity terms (`stiffid calibrate --gravity`) describes the robot
//! without its sag: its geometry is the rigid chain's, and the joints deflect under the weight of
//! the links by `dq_g(q)` ([`stiffid_metrology::calibration::gravity`]: `c_j tau_j(q)` with the
//! link masses, or the lumped products `c_j m_l` and `c_j m_l s_l` times their unit torques). The
//! robot commanded to `q` then stands at `q + dq_g(q)` before any process force, so compensation
//! solves `loaded_pose(q_c) = T_target` with the sag in the loaded pose; without it the program
//! would carry the whole sag as an error (the geometry fitted without it).

use nalgebra::{DVector, Vector6};
use stiffid_core::model::OwnWeight;
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::{Error, Result, Robot};
use stiffid_metrology::calibration::gravity::{self, Gravity};

/// The own weight's deflection of one robot: its gravity model and term values.
#[derive(Debug, Clone, PartialEq)]
pub struct Weight {
    model: gravity::Terms,
    values: DVector<f64>,
}

impl Weight {
    /// The deflection of `robot` (springs in `springs`) under its weight as `own` gives it: the
    /// model named `own.gravity` built on `robot` (with [`Gravity::Masses`] its link masses),
    /// whose terms must be `own`'s, in order.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`gravity.model`) for a model name that is not `masses`,
    /// `lumped` or `lumped-links`; those of [`gravity::Terms::of`] (a robot without masses for
    /// `masses`); (`gravity.terms`) when the terms differ from the model's (another robot's
    /// file, or other springs).
    pub fn new(robot: &Robot, springs: Coordinates, own: &OwnWeight) -> Result<Self> {
        let kind: Gravity = match own.gravity.parse() {
            Ok(Gravity::None) | Err(_) => {
                return Err(Error::InvalidField {
                    field: "gravity.model".into(),
                    message: format!(
                        "'{}': expected masses, lumped or lumped-links",
                        stiffid_core::common::limits::short(&own.gravity)
                    ),
                })
            }
            Ok(g) => g,
        };
        let model = gravity::Terms::of(robot, kind, springs, Vector6::zeros())?;
        let names: Vec<String> = model.terms().iter().map(|t| t.name()).collect();
        let given: Vec<&str> = own.terms.iter().map(|(n, _)| n.as_str()).collect();
        if names != given {
            return Err(Error::InvalidField {
                field: "gravity.terms".into(),
                message: format!(
                    "{} terms ({}) where the setup's robot and springs give the {} model {} ({}): use the setup the robot was calibrated with",
                    given.len(),
                    stiffid_core::common::limits::short(&given.join(", ")),
                    own.gravity,
                    names.len(),
                    names.join(", ")
                ),
            });
        }
        Ok(Self {
            model,
            values: DVector::from_iterator(own.terms.len(), own.terms.iter().map(|t| t.1)),
        })
    }

    /// The deflection in axis angles (rad) of the robot commanded to `q` (rad).
    pub fn deflection(&self, q: &Vector6<f64>) -> Vector6<f64> {
        self.model.deflection(&self.values.as_view(), q)
    }
}
