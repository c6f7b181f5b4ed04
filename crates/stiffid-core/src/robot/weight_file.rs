//! The `[gravity]` table of a calibrated robot file: the sag under the robot's own weight (and
//! its tool's) as the calibration fitted it ([`crate::model::OwnWeight`]), so that every command
//! reading the robot adds it and any stiffness file combines with it.
//!
//! ```toml
//! [gravity]
//! model = "lumped"                      # masses, lumped, lumped-links or arm
//! tool_mass_kg = 12.5                   # optional: the calibration's [tool] mass_kg
//! tool_centre_of_mass_mm = [0, 0, 120]  # optional: its [tool] centre_of_mass_mm
//! terms = [                             # in the model's order, at most 144
//!   { name = "gravity.c2.link2.m", value_si = 6.1e-7 },
//! ]
//! ```

use crate::common::limits::{self, check_in};
use crate::{Error, Result};
use serde::Deserialize;
use std::fmt::Write;

/// The most gravity terms a robot or stiffness file holds: four mass moments of six links for
/// each of the six springs.
pub(crate) const MAX_GRAVITY_TERMS: usize = 144;

/// The deflection under the robot's own weight as a calibration fitted it
/// (`stiffid calibrate --gravity`, `stiffid_metrology::calibration::gravity`): the gravity model
/// and the value of each of its terms. A calibration with gravity describes the robot without its
/// sag, so compensation adds it (docs/model.md, "Compensation"). The calibrated robot file
/// carries it (`[gravity]`, [`crate::Robot::own_weight`]).
#[derive(Debug, Clone, PartialEq)]
pub struct OwnWeight {
    /// The gravity model: `masses`, `lumped`, `lumped-links` or `arm`.
    pub gravity: String,
    /// Each term's name (`gravity.c2`, `gravity.c2.link3.mx`) and value, SI (rad/(N m) for a
    /// compliance, rad kg/(N m) for a lumped mass, rad kg/N for a lumped first moment), in the
    /// model's term order.
    pub terms: Vec<(String, f64)>,
    /// The tool's mass (kg) the calibration's setup gave (`[tool] mass_kg`), `None` without:
    /// with `masses` the tool joined link 6 in the fit (compensation joins the setup's tool the
    /// same way); lumped terms hold the weight of the tool the robot carried, so compensation
    /// refuses a setup whose tool's mass differs from it.
    pub tool_mass: Option<f64>,
    /// The tool's centre of mass (m, flange frame) the calibration's setup gave with its mass
    /// (`[tool] centre_of_mass_mm`), `None` without (or in a file written before it was
    /// recorded): lumped terms hold the tool's moment about each joint, so compensation refuses
    /// a setup whose tool's weight acts elsewhere ([`TOOL_MOMENT_TOLERANCE_NM`]).
    pub tool_centre: Option<nalgebra::Vector3<f64>>,
}

/// The largest difference of the tool's weight moment, N m (the setup's tool against the one
/// lumped gravity terms hold: mass times gravity times the distance between the two centres of
/// mass) that compensation takes: 1 N m turns a wrist of 1e-5 rad/(N m) by 10 microradians, a
/// few micrometres at the tool.
pub const TOOL_MOMENT_TOLERANCE_NM: f64 = 1.0;

/// One term of a `[gravity]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TermFile {
    name: String,
    value_si: f64,
}

/// A robot file's `[gravity]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GravityFile {
    model: String,
    tool_mass_kg: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    tool_centre_of_mass_mm: Option<[f64; 3]>,
    terms: Vec<TermFile>,
}

/// The own weight of a `[gravity]` table, checked: the model `masses`, `lumped`, `lumped-links` or
/// `arm`, 1 to 144 terms with finite values, a tool mass within [0.001, 10 000] kg, a tool's centre
/// of mass within [`limits::LENGTH_MM`] and only with its mass.
///
/// # Errors
/// [`Error::InvalidField`] naming the file and the field.
pub fn build(file: Option<GravityFile>, source_name: &str) -> Result<Option<OwnWeight>> {
    let Some(g) = file else { return Ok(None) };
    let invalid = |field: String, message: String| Error::InvalidField {
        field: format!("{source_name}: gravity.{field}"),
        message,
    };
    if !matches!(
        g.model.as_str(),
        "masses" | "lumped" | "lumped-links" | "arm"
    ) {
        return Err(invalid(
            "model".into(),
            format!(
                "'{}': expected masses, lumped, lumped-links or arm",
                limits::short(&g.model)
            ),
        ));
    }
    let n = g.terms.len();
    if n == 0 || n > MAX_GRAVITY_TERMS {
        return Err(invalid(
            "terms".into(),
            format!("{n} terms: expected 1 to {MAX_GRAVITY_TERMS}"),
        ));
    }
    if let Some(i) = g.terms.iter().position(|t| !t.value_si.is_finite()) {
        return Err(invalid(
            format!("terms[{}].value_si", i + 1),
            "expected a finite number".into(),
        ));
    }
    if let Some(m) = g.tool_mass_kg {
        check_in(
            source_name,
            "gravity.tool_mass_kg",
            &[m],
            &limits::TOOL_MASS_KG,
        )?;
    }
    if let Some(c) = g.tool_centre_of_mass_mm {
        let field = "gravity.tool_centre_of_mass_mm";
        check_in(source_name, field, &c, &limits::LENGTH_MM)?;
        if g.tool_mass_kg.is_none() {
            return Err(invalid(
                "tool_centre_of_mass_mm".into(),
                "needs tool_mass_kg: the centre of the tool's mass the terms hold".into(),
            ));
        }
    }
    Ok(Some(OwnWeight {
        gravity: g.model,
        terms: g.terms.into_iter().map(|t| (t.name, t.value_si)).collect(),
        tool_mass: g.tool_mass_kg,
        tool_centre: (g.tool_centre_of_mass_mm).map(|c| nalgebra::Vector3::from(c) / 1e3),
    }))
}

/// The `[gravity]` table of `own` (values in full, shortest round-trip), with a comment saying
/// what it is.
pub fn toml(own: &OwnWeight) -> String {
    let mut t = String::from(
        "\n# The sag under the robot's own weight and its tool's, as the calibration fitted it:\n# every command that reads this robot adds it.\n[gravity]\n",
    );
    let _ = writeln!(t, "model = \"{}\"", own.gravity);
    if let Some(m) = own.tool_mass {
        let _ = writeln!(t, "tool_mass_kg = {m:?}");
    }
    if let (Some(_), Some(c)) = (own.tool_mass, own.tool_centre) {
        let c = c * 1e3;
        let _ = writeln!(
            t,
            "tool_centre_of_mass_mm = [{:?}, {:?}, {:?}]",
            c.x, c.y, c.z
        );
    }
    t += "terms = [\n";
    for (name, v) in &own.terms {
        let _ = writeln!(t, "  {{ name = \"{name}\", value_si = {v:?} }},");
    }
    t += "]\n";
    t
}
