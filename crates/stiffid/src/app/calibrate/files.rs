//! What a calibration writes: the calibrated robot as a robot file and a URDF, the setup
//! fragment, the TCP moved with the measuring points, the part's frame located from the table
//! reflectors and the fitted compliance.

use super::chosen::Chosen;
use super::part;
use super::{compliance, fitted_compliance, fragment, tcp, update, FittedCompliance, Held};
use super::{Request, Warning, WarningKind};
use stiffid_core::Result;
use stiffid_metrology::calibration::gravity::Gravity;
use stiffid_metrology::calibration::robot_file;

/// The calibration's files ([`super::Report`] documents each).
pub(super) struct Files {
    pub robot_toml: std::result::Result<String, String>,
    pub urdf: std::result::Result<String, String>,
    pub fragment: String,
    pub tcp: Option<nalgebra::Vector3<f64>>,
    pub compliance: Option<std::result::Result<FittedCompliance, String>>,
}

/// The files of the model `chosen` (with the held-out figures `held` in the robot file), the
/// warnings of what a URDF leaves out when one is asked for.
///
/// # Errors
/// Those of [`update::tool_load`] and of locating the part ([`part::located`]).
pub(super) fn files(
    request: &Request<'_>,
    chosen: &Chosen,
    held: (Option<&Held>, Option<&Held>),
    warnings: &mut Vec<Warning>,
) -> Result<Files> {
    let setup = request.readings.setup;
    let (model, fitted) = (&chosen.model, &chosen.fit);
    let own_weight = compliance::own_weight(model, fitted, update::tool_load(request)?);
    let part = part::located(setup, (model, &fitted.estimate), request.update, warnings)?;
    let robot_toml = update::robot_file(
        request,
        (model, &fitted.estimate),
        held,
        (own_weight.as_ref(), part.as_ref()),
    );
    let mount = setup.workcell().controller().mount;
    let urdf = robot_file::urdf(model, &fitted.estimate, &mount).map_err(|e| e.to_string());
    let asked = request.urdf && urdf.is_ok();
    if let (true, Some(note)) = (asked, robot_file::urdf_leaves_out(model, &fitted.estimate)) {
        warnings.push(Warning::new(WarningKind::LeftOut, note));
    }
    warnings.extend(update::urdf_rigid(asked, own_weight.as_ref()));
    let tcp = tcp(setup, model, &fitted.estimate.values);
    let fragment = fragment(model, fitted, tcp.as_ref());
    let compliance = (model.gravity().kind() != Gravity::None || model.has_loads())
        .then(|| fitted_compliance(setup, model, fitted));
    Ok(Files {
        robot_toml,
        urdf,
        fragment,
        tcp,
        compliance,
    })
}
