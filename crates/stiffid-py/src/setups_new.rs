//! `stiffid.setups_new`: the new-setup job of `stiffid setups new`
//! ([`stiffid::app::setups_new`]).

use crate::documents::warn;
use crate::error::{self, raise, value, Failure};
use crate::output;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use stiffid::app::setups_new::{self as job, relative_to, robot_reference};
use stiffid::internal::robot::Bodies;
use stiffid::internal::setup::reference::{self, Meshes};

/// A complete, commented setup TOML for your own ``robot`` (a preset name, a robot ``.toml`` file
/// or a ``.urdf`` file, ``tip`` its tip link): every field with its unit and meaning, starting
/// values derived from the robot (bounds 5 deg inside the joint limits, a characteristic length,
/// a rough nominal stiffness from ``payload_kg``, the rated payload, 0.1 to 2500 kg, default a class
/// guessed from the reach; a tool scaled to the reach) and the optional sections (cell, tracker,
/// constraints) commented out; ``package_paths`` (directories holding ROS packages, at most 64)
/// find a URDF's meshes and are written into the setup. The same text as ``stiffid setups new``
/// (``--package-path`` for ``package_paths``); returns it, and with ``out`` writes it to that new
/// file (never over an existing one), robot and package paths relative to its directory. The text
/// is loaded back first: it loads as written. ``InputError`` naming the argument.
#[pyfunction]
#[pyo3(signature = (robot, *, tip=None, payload_kg=None, out=None, package_paths=Vec::new()))]
pub fn setups_new(
    py: Python<'_>,
    robot: PathBuf,
    tip: Option<&str>,
    payload_kg: Option<&Bound<'_, PyAny>>,
    out: Option<PathBuf>,
    package_paths: Vec<PathBuf>,
) -> PyResult<String> {
    let payload_kg = crate::count::real("payload_kg", payload_kg)?;
    crate::robot::check_package_paths(&package_paths)?;
    let robot = &*robot.to_string_lossy();
    let meshes = |package_paths| Meshes {
        read: &error::bytes,
        package_paths,
    };
    let loaded =
        reference::robot_with_meshes(robot, tip, error::read_if_exists, &meshes(&package_paths));
    let loaded = loaded.map_err(|e: Failure| e.0)?;
    warn(
        py,
        &Vec::from_iter(stiffid::internal::setup::plausibility::meshes(&loaded)),
    )?;
    let file = match &out {
        Some(p) if p.symlink_metadata().is_ok() => {
            let name = p.display();
            return Err(value(format!(
                "out {name}: exists; setups_new writes a new file only"
            )));
        }
        Some(p) => Some(output::prepare(p, "out", &[], &[])?),
        None => None,
    };
    let at = out.as_deref();
    let robot_ref = robot_reference(robot, at, "robot").map_err(raise)?;
    let paths = (package_paths.iter())
        .map(|p| relative_to(p, at, "package_paths"))
        .collect::<stiffid::Result<Vec<_>>>()
        .map_err(raise)?;
    let request = job::Request {
        robot: &loaded,
        robot_ref: &robot_ref,
        tip,
        package_paths: &paths,
        payload_kg,
    };
    let text = py.detach(|| job::run(&request)).map_err(raise)?;
    // It loads as written: from the file's directory, with its own package paths only.
    let dir = at.and_then(Path::parent).unwrap_or(Path::new(""));
    let name = at.map_or("setups_new".into(), |p| p.display().to_string());
    let written =
        reference::setup_text_with_meshes(&text, &name, dir, error::read_if_exists, &meshes(&[]))
            .map_err(|e: Failure| e.0)?;
    let missing = |r: &stiffid::Robot| matches!(r.bodies(), Bodies::Missing(_));
    if missing(written.robot()) && !missing(&loaded) {
        return Err(value(
            "setups_new: the generated setup does not find the robot's meshes (please report this)",
        ));
    }
    if let Some(f) = file {
        f.write_new(text.as_bytes())?;
    }
    Ok(text)
}
