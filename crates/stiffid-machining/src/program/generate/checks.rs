//! What a language can write, checked before anything is computed: the cell's external axes,
//! the tool's payload, the controller's pulses, and the targets a language writes.

use super::{invalid, Targets, Tool};
use crate::program::Dialect;
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::Role;
use stiffid_core::robot::ExternalAxes;
use stiffid_core::setup::Pulses;
use stiffid_core::{Error, Result};

/// Whether a program of `dialect` with `targets` can be written for a cell with the external
/// axes `axes`: no more axes of a role than the language holds
/// ([`Generator::most_external`](crate::program::Generator::most_external)), and Cartesian targets only
/// with a carrier (a track: the controller takes the tool's pose in its world, the part's
/// frame, and moves the arm on its carriage by the values given), never with a positioner.
///
/// # Errors
/// [`Error::InvalidField`] (`external_axis`) naming the first axis past the language's;
/// [`Error::InvalidOption`] ([`JobOption::Targets`]) naming the positioner's axis for
/// Cartesian targets.
pub(crate) fn check_cell(
    dialect: Dialect,
    targets: Targets,
    axes: Option<&ExternalAxes>,
) -> Result<()> {
    let Some(axes) = axes.filter(|a| !a.is_empty()) else {
        return Ok(());
    };
    let controller = dialect.controller();
    for role in [Role::Carrier, Role::Positioner] {
        let most = (controller.generator()).map_or(0, |g| g.most_external(role));
        let mut of_role = axes.axes().iter().filter(|a| a.role == role);
        if let Some(axis) = of_role.nth(most) {
            return Err(invalid(
                "external_axis",
                format!(
                    "{}: a {} program holds at most {most} {} axes ({}); this one is its {}th",
                    axis.name,
                    controller.key().to_ascii_uppercase(),
                    role_name(role),
                    controller.generator().map_or("", |g| g.external_form(role)),
                    most + 1
                ),
            ));
        }
    }
    let positioner = axes.axes().iter().find(|a| a.role == Role::Positioner);
    if let (Targets::Cartesian, Some(axis)) = (written_targets(dialect, targets), positioner) {
        return Err(Error::InvalidOption {
            option: JobOption::Targets,
            message: format!("cartesian: the cell's positioner axis {} carries the part, and a Cartesian target on it needs the controller's coordinated motion (a base or work object coupled to the positioner), which stiffid does not write; write joint targets (targets = joint)", axis.name),
        });
    }
    Ok(())
}

/// An axis role's name in messages.
fn role_name(role: Role) -> &'static str {
    match role {
        Role::Carrier => "carrier (track)",
        Role::Positioner => "positioner",
    }
}

/// Whether a program of `dialect` with `targets` can be written for `tool`: a RAPID program
/// with Cartesian targets states the tool's mass and centre of mass.
///
/// # Errors
/// [`Error::InvalidField`] (`tool.mass_kg`) when the program needs them and `tool` has none.
pub(crate) fn check_payload(dialect: Dialect, targets: Targets, tool: &Tool) -> Result<()> {
    let needs_mass = (dialect.controller().generator()).is_some_and(|g| g.needs_mass(targets));
    if needs_mass && tool.payload.is_none() {
        return Err(invalid("tool.mass_kg", "a RAPID tooldata needs the tool's mass and centre of mass (the controller refuses a tool of no mass): [tool] mass_kg and centre_of_mass_mm in the setup".into()));
    }
    Ok(())
}

/// Whether a program of `dialect` can be written with the controller's `pulses`: a language
/// that states its axes in pulses (INFORM) needs them.
///
/// # Errors
/// [`Error::InvalidField`] (`controller.pulses_per_deg`) when the program needs them and the
/// setup gives none.
pub(crate) fn check_pulses(dialect: Dialect, pulses: Option<&Pulses>) -> Result<()> {
    let needs = (dialect.controller().generator()).is_some_and(|g| g.needs_pulses());
    match needs && pulses.is_none() {
        true => Err(missing_pulses()),
        false => Ok(()),
    }
}

/// The error of a program in pulses (an INFORM job) written without the controller's pulses.
pub(crate) fn missing_pulses() -> Error {
    Error::InvalidField {
        field: "controller.pulses_per_deg".into(),
        message: "missing: an INFORM job states its positions in encoder pulses, and how many make a degree of each axis is the controller's (its axis parameters): give them in the setup, [controller] pulses_per_deg = [S, L, U, R, B, T] (and external_pulses = [..] per external axis, or the external axes are written in mm and deg)".into(),
    }
}

/// The targets a program of `dialect` is written with when `targets` are asked: the joint
/// targets of a language that writes no pose (INFORM's pulses), else `targets`.
pub(crate) fn written_targets(dialect: Dialect, targets: Targets) -> Targets {
    match (dialect.controller().generator()).is_some_and(|g| !g.writes_cartesian()) {
        true => Targets::Joint,
        false => targets,
    }
}
