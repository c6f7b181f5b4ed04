//! The sag under the robot's own weight, as compensation adds it.
//!
//! A calibration that fits gravity terms (`stiffid calibrate --gravity`) describes the robot
//! without its sag: its geometry is the rigid chain's, and the joints deflect under the weight of
//! the links by `dq_g(q)` ([`stiffid_metrology::calibration::gravity`]: `c_j tau_j(q)` with the
//! link masses, or the lumped products `c_j m_l` and `c_j m_l s_l` times their unit torques). The
//! robot commanded to `q` then stands at `q + dq_g(q)` before any process force, so compensation
//! solves `loaded_pose(q_c) = T_target` with the sag in the loaded pose; without it the program
//! would carry the whole sag as an error (the geometry fitted without it).
//!
//! The calibrated robot file carries the terms (`[gravity]`, [`stiffid_core::Robot::own_weight`]), so any
//! stiffness file combines with it; a stiffness file written before carries them in its `gravity`
//! section, read when the robot has none. The tool's weight enters once: with
//! `masses` the setup's tool joins link 6 ([`gravity::with_tool`]), lumped terms hold the tool the
//! robot carried in the calibration; either way the process compliance does not carry it again
//! ([`tool_load`]).

use nalgebra::{DVector, Vector6};
use stiffid_core::common::words::number;
use stiffid_core::model::{Compliance, OwnWeight};
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::robot::weight_file::TOOL_MOMENT_TOLERANCE_NM;
use stiffid_core::setup::{Arm, Payload};
use stiffid_core::{Error, Result, Robot};
use stiffid_metrology::calibration::gravity::{self, Gravity};

/// The own weight's deflection of one robot: its gravity model and term values.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Weight {
    model: gravity::Terms,
    values: DVector<f64>,
}

impl Weight {
    /// The deflection of `robot` (springs in `springs`) carrying `tool` under its weight as
    /// `own` gives it: the model named `own.gravity` built on `robot` (with [`Gravity::Masses`]
    /// its link masses, `tool` joined to link 6), whose terms must be `own`'s, in order.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`gravity.model`) for a model name that is not `masses`,
    /// `lumped`, `lumped-links` or `arm`; those of [`gravity::Terms::of`] (a robot without masses for
    /// `masses`); (`gravity.terms`) when the terms differ from the model's (another robot's
    /// file, or other springs); (`tool.mass_kg`) when lumped terms hold a tool of another mass
    /// than `tool`'s, (`tool.centre_of_mass_mm`) one whose weight acts elsewhere
    /// ([`TOOL_MOMENT_TOLERANCE_NM`]).
    pub(crate) fn new(
        robot: &Robot,
        springs: Coordinates,
        own: &OwnWeight,
        tool: Option<&Payload>,
    ) -> Result<Self> {
        let kind: Gravity = match own.gravity.parse() {
            Ok(Gravity::None) | Err(_) => {
                return Err(Error::InvalidField {
                    field: "gravity.model".into(),
                    message: format!(
                        "'{}': expected masses, lumped, lumped-links or arm",
                        stiffid_core::common::limits::short(&own.gravity)
                    ),
                })
            }
            Ok(g) => g,
        };
        let weighed = match kind {
            Gravity::Masses => gravity::with_tool(robot, tool.map(Payload::body)),
            _ => {
                check_tool(own, tool)?;
                robot.clone()
            }
        };
        let model = gravity::Terms::of(&weighed, kind, springs, Vector6::zeros())?;
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
    pub(crate) fn deflection(&self, q: &Vector6<f64>) -> Vector6<f64> {
        self.model.deflection(&self.values.as_view(), q)
    }
}

impl Weight {
    /// The sag of `arm` under its own weight: the gravity terms of its calibrated robot
    /// ([`stiffid_core::Robot::own_weight`]), else those of `compliance` (a stiffness file written
    /// before the robot file carried them); `None` without either.
    ///
    /// # Errors
    /// Those of [`Weight::new`]; [`Error::InvalidField`] (`gravity`) when both carry terms and
    /// they differ, naming both.
    pub(crate) fn of(arm: &Arm, compliance: &Compliance) -> Result<Option<Self>> {
        let own = match (arm.robot().own_weight(), &compliance.own_weight) {
            (Some(r), Some(s)) if (&r.gravity, &r.terms) != (&s.gravity, &s.terms) => {
                return Err(Error::InvalidField {
                    field: "gravity".into(),
                    message: format!(
                        "the calibrated robot file's [gravity] ({} terms) and the stiffness file's gravity section ({} terms) differ: the robot file carries the calibration's sag, give a stiffness file without one",
                        r.gravity, s.gravity
                    ),
                })
            }
            (Some(r), _) => r,
            (None, Some(s)) => s,
            (None, None) => return Ok(None),
        };
        Self::new(arm.robot(), arm.springs(), own, arm.payload()).map(Some)
    }
}

/// The tool whose weight the process compliance carries at every point (its wrench joins the
/// process's): the setup's tool, unless the sag under the robot's own weight already holds it
/// (`Weight::of`: with `masses` the tool joins link 6, lumped terms hold it).
pub fn tool_load<'a>(arm: &'a Arm, compliance: &Compliance) -> Option<&'a Payload> {
    let sagging = arm.robot().own_weight().is_some() || compliance.own_weight.is_some();
    arm.payload().filter(|_| !sagging)
}

/// Refuses a setup's `tool` whose mass differs from the one lumped terms `own` hold.
fn check_tool(own: &OwnWeight, tool: Option<&Payload>) -> Result<()> {
    match (own.tool_mass, tool) {
        (Some(m), Some(t)) if (m - t.mass).abs() > 1e-9 * m.max(t.mass) => {
            Err(Error::InvalidField {
                field: "tool.mass_kg".into(),
                message: format!(
                    "{} kg in the setup, where the calibrated robot's {} gravity terms hold a tool of {} kg ([gravity] tool_mass_kg in its file): its weight would count twice or wrong; calibrate with this tool, or give the tool of the calibration",
                    t.mass, own.gravity, m
                ),
            })
        }
        (Some(m), Some(t)) => check_centre(own, m, t),
        _ => Ok(()),
    }
}

/// Refuses a setup's tool `t` (of the mass `m` lumped terms `own` hold) whose centre of mass
/// lies so far from the one the terms were calibrated with that its weight's moment differs by
/// more than [`TOOL_MOMENT_TOLERANCE_NM`]: `m g |c_setup - c_calibration|`.
fn check_centre(own: &OwnWeight, m: f64, t: &Payload) -> Result<()> {
    let Some(c) = own.tool_centre else {
        return Ok(());
    };
    let moment = m * stiffid_core::setup::GRAVITY * (t.centre - c).norm();
    if moment <= TOOL_MOMENT_TOLERANCE_NM {
        return Ok(());
    }
    let mm = |v: &nalgebra::Vector3<f64>| {
        let v = v * 1e3;
        format!("[{}, {}, {}]", number(v.x), number(v.y), number(v.z))
    };
    Err(Error::InvalidField {
        field: "tool.centre_of_mass_mm".into(),
        message: format!(
            "{} mm in the setup, where the calibrated robot's {} gravity terms hold the tool of {} kg at {} mm ([gravity] tool_centre_of_mass_mm in its file): its weight's moment differs by {} N m, more than the {} N m lumped terms allow; calibrate with this tool, or give the tool of the calibration",
            mm(&t.centre),
            own.gravity,
            number(m),
            mm(&c),
            number(moment),
            number(TOOL_MOMENT_TOLERANCE_NM)
        ),
    })
}
