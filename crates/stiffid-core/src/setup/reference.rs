//! Robots and setups named as a user names them: a file if one exists at the reference, else the
//! built-in of that name (a robot preset, a built-in setup). The caller reads files: `read(path)`
//! returns `None` if nothing exists at `path`, else the file's text or the caller's error `E`
//! (which must hold the library's errors: `E: From<Error>`, e.g. `anyhow::Error`).
//!
//! A built-in name wins over a file path that does not exist, so a preset named `...-3.0` is no
//! file; a reference that looks like a path (an extension or a directory) and names neither is
//! [`Error::NotFound`].

use crate::robot::{collision, file, presets, urdf, Bodies};
use crate::{setup, Error, Robot, Setup};
use std::fmt::Display;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Where a URDF's collision meshes come from ([`collision::parse`]): how a file's bytes are read
/// (`None` if nothing exists at the path) and the directories that hold ROS packages
/// (`package://NAME/...` is `DIR/NAME/...`), searched in order.
pub struct Meshes<'a> {
    /// Reads the bytes of a mesh file; `None` if nothing exists at the path.
    pub read: &'a dyn Fn(&Path) -> Option<crate::Result<Vec<u8>>>,
    /// Directories holding ROS packages.
    pub package_paths: &'a [PathBuf],
}

/// A robot: the robot TOML (`.toml`, [`file::parse`]) or URDF (`.urdf`, [`urdf::parse`] with the
/// tip link `tip`) file at `reference` if `read` finds one, else the preset named `reference`
/// ([`presets::get`]).
///
/// # Errors
/// The error of `read`; those of the parser (named after the file); [`Error::Parse`] for a file
/// with another extension, or for a xacro file (`.xacro`, or xacro elements) with the command that
/// expands it; [`Error::Unknown`] for a name that is no preset, [`Error::NotFound`]
/// for a path that is neither a file nor a preset; [`Error::InvalidField`] (`tip link`) for a
/// `tip` given with a preset or a robot TOML, whose chain has no choice of tip.
///
/// # Examples
/// ```
/// use stiffid_core::setup::reference;
/// let no_files = |_: &std::path::Path| None::<stiffid_core::Result<String>>;
/// let robot = reference::robot("fanuc-r2000ic-165f", None, no_files).unwrap();
/// assert_eq!(robot.name(), "FANUC R-2000iC/165F");
/// let e = reference::robot("robots/mine.toml", None, no_files).unwrap_err();
/// assert!(e.to_string().contains("no file robots/mine.toml and no preset"), "{e}");
/// ```
pub fn robot<E, F>(reference: &str, tip: Option<&str>, read: F) -> Result<Robot, E>
where
    E: From<Error>,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    robot_in(Path::new(""), reference, tip, "tip link", &read, None)
}

/// [`robot`] with a URDF's collision geometry: its `<collision>` shapes, meshes read through
/// `meshes`, become the robot's [`Bodies::Shapes`] (a URDF without any keeps the scaled
/// capsules). A mesh not found (no file, a `package://` package in none of the package paths)
/// gives [`Bodies::Missing`]: the robot loads for kinematics and identification, and only the
/// cell's body checks refuse it. [`robot`] reads no mesh and gives every URDF robot capsules.
///
/// # Errors
/// Those of [`robot`] and of [`collision::parse`] but [`Error::MeshNotFound`] (a mesh unreadable
/// or no STL, named).
pub fn robot_with_meshes<E, F>(
    reference: &str,
    tip: Option<&str>,
    read: F,
    meshes: &Meshes,
) -> Result<Robot, E>
where
    E: From<Error>,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    robot_in(
        Path::new(""),
        reference,
        tip,
        "tip link",
        &read,
        Some(meshes),
    )
}

/// [`robot`] for a reference written in a file in `dir`: a file path is relative to `dir`;
/// `tip_field` names `tip` as the user gave it (`robot_tip` in a setup).
fn robot_in<E, F>(
    dir: &Path,
    reference: &str,
    tip: Option<&str>,
    tip_field: &str,
    read: &F,
    meshes: Option<&Meshes>,
) -> Result<Robot, E>
where
    E: From<Error>,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    let path = dir.join(reference);
    let name = path.display().to_string();
    let extension = path.extension().and_then(|e| e.to_str());
    let robot = match read(&path) {
        None => presets::get(reference)
            .map_err(|e| not_found(e, "robot", "preset", reference, &path))?,
        Some(text) => {
            let text = text?;
            match extension {
                _ if is_xacro(extension, &text) => Err(xacro(&name))?,
                Some("toml") => file::parse(&text, &name)?,
                Some("urdf") => return Ok(urdf_robot(&text, &name, &path, tip, meshes)?),
                _ => Err(Error::Parse {
                    source_name: name,
                    message: "a robot file must end in .toml or .urdf".into(),
                })?,
            }
        }
    };
    match tip {
        None => Ok(robot),
        Some(tip) => Err(Error::InvalidField {
            field: tip_field.into(),
            message: format!(
                "'{}' given, but only a URDF robot has a tip link to choose ('{}' is a preset or \
                 a robot TOML); leave it out",
                crate::common::limits::short(tip),
                crate::common::limits::short(reference)
            ),
        }
        .into()),
    }
}

/// The URDF robot of `text` (read from `path`, shown as `name`), with its collision shapes when
/// `meshes` says how to read them.
fn urdf_robot(
    text: &str,
    name: &str,
    path: &Path,
    tip: Option<&str>,
    meshes: Option<&Meshes>,
) -> crate::Result<Robot> {
    let mut robot = urdf::parse(text, name, tip)?;
    if let Some(m) = meshes {
        let dir = path.parent().unwrap_or(Path::new(""));
        match collision::parse(text, name, dir, tip, m.package_paths, m.read) {
            Ok(g) if !g.shapes.is_empty() => robot = robot.with_bodies(Bodies::Shapes(Arc::new(g))),
            Ok(_) => {}
            Err(e @ Error::MeshNotFound { .. }) => {
                robot = robot.with_bodies(Bodies::Missing(e.to_string().into()))
            }
            Err(e) => return Err(e),
        }
    }
    Ok(robot)
}

/// Whether a robot file is a xacro macro file: its extension is `.xacro`, or, outside XML comments,
/// it uses a `<xacro:` element or a `${...}` / `$(...)` substitution. The `xmlns:xacro` namespace
/// alone is no sign: ROS's xacro keeps it on the `<robot>` of the URDF it writes.
fn is_xacro(extension: Option<&str>, text: &str) -> bool {
    if extension == Some("xacro") {
        return true;
    }
    let mut rest = text;
    while !rest.is_empty() {
        let (code, after) = match rest.split_once("<!--") {
            Some((code, comment)) => (code, comment.split_once("-->").map_or("", |(_, a)| a)),
            None => (rest, ""),
        };
        if code.contains("<xacro:") || code.contains("${") || code.contains("$(") {
            return true;
        }
        rest = after;
    }
    false
}

/// The error for a xacro file: it must be expanded into a URDF first, by ROS's `xacro` or PyPI's
/// (which finds the packages of `$(find PKG)` through `AMENT_PREFIX_PATH`, as the guide shows).
fn xacro(name: &str) -> Error {
    let urdf = match name.strip_suffix(".xacro") {
        Some(stem) if stem.ends_with(".urdf") => stem.to_string(),
        Some(stem) => format!("{stem}.urdf"),
        None => format!("{}.expanded.urdf", name.trim_end_matches(".urdf")),
    };
    Error::Parse {
        source_name: name.to_string(),
        message: format!(
            "a xacro file (macros, not a URDF): expand it first with xacro (ROS's, or without ROS \
             `pip install xacro ros-ament-index-python`), e.g. `xacro {} > {}`, and give the URDF; \
             without ROS, `$(find PKG)` needs AMENT_PREFIX_PATH=DIR where DIR/share/PKG is the \
             package and DIR/share/ament_index/resource_index/packages/PKG an empty file \
             (the guide's \"Robots from ROS\")",
            crate::common::limits::short(name),
            crate::common::limits::short(&urdf)
        ),
    }
}

/// A setup: the setup TOML file at `reference` if `read` finds one (a robot file it names is
/// looked for relative to the setup file), else the built-in setup named `reference`
/// ([`setup::builtin`]).
///
/// # Errors
/// The error of `read`; those of [`setup::parse`] and [`robot`]; [`Error::Unknown`] for a name
/// that is no built-in setup, [`Error::NotFound`] for a path that is neither a file nor a
/// built-in setup.
///
/// # Examples
/// ```
/// use stiffid_core::setup::reference;
/// let no_files = |_: &std::path::Path| None::<stiffid_core::Result<String>>;
/// let setup = reference::setup("zhang2021-comau-nj165", no_files).unwrap();
/// assert_eq!(setup.robot().name(), "COMAU SMART5 NJ 165-3.0");
/// ```
pub fn setup<E, F>(reference: &str, read: F) -> Result<Setup, E>
where
    E: From<Error> + Display,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    setup_in(reference, read, None)
}

/// [`setup()`] with a URDF robot's collision geometry ([`robot_with_meshes`]); the setup's
/// `package_paths` (relative to the setup file) are searched after `meshes.package_paths`.
///
/// # Errors
/// Those of [`setup()`] and [`robot_with_meshes`].
pub fn setup_with_meshes<E, F>(reference: &str, read: F, meshes: &Meshes) -> Result<Setup, E>
where
    E: From<Error> + Display,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    setup_in(reference, read, Some(meshes))
}

fn setup_in<E, F>(reference: &str, read: F, meshes: Option<&Meshes>) -> Result<Setup, E>
where
    E: From<Error> + Display,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    let path = Path::new(reference);
    match read(path) {
        None => setup::builtin(reference)
            .map_err(|e| not_found(e, "setup", "built-in setup", reference, path).into()),
        Some(text) => {
            let dir = path.parent().unwrap_or(Path::new(""));
            setup_text_in(&text?, reference, dir, read, meshes)
        }
    }
}

/// A setup from its TOML `text`, read from `source_name` in the directory `dir`, where a robot
/// file it names is looked for ([`robot`]).
///
/// # Errors
/// Those of [`setup::parse`]; a robot that cannot be resolved is [`Error::Parse`] naming
/// `source_name` and `robot`, with the message of the robot's error.
pub fn setup_text<E, F>(text: &str, source_name: &str, dir: &Path, read: F) -> Result<Setup, E>
where
    E: From<Error> + Display,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    setup_text_in(text, source_name, dir, read, None)
}

/// [`setup_text`] with a URDF robot's collision geometry, as [`setup_with_meshes`].
///
/// # Errors
/// Those of [`setup_text`] and [`robot_with_meshes`].
pub fn setup_text_with_meshes<E, F>(
    text: &str,
    source_name: &str,
    dir: &Path,
    read: F,
    meshes: &Meshes,
) -> Result<Setup, E>
where
    E: From<Error> + Display,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    setup_text_in(text, source_name, dir, read, Some(meshes))
}

fn setup_text_in<E, F>(
    text: &str,
    source_name: &str,
    dir: &Path,
    read: F,
    meshes: Option<&Meshes>,
) -> Result<Setup, E>
where
    E: From<Error> + Display,
    F: Fn(&Path) -> Option<Result<String, E>>,
{
    Ok(setup::parse_with(text, source_name, |r| {
        let paths: Vec<PathBuf> = meshes
            .iter()
            .flat_map(|m| m.package_paths.iter().cloned())
            .chain(r.package_paths.iter().map(|p| dir.join(p)))
            .collect();
        let meshes = meshes.map(|m| Meshes {
            read: m.read,
            package_paths: &paths,
        });
        robot_in(dir, r.reference, r.tip, "robot_tip", &read, meshes.as_ref()).map_err(|e| {
            Error::Parse {
                source_name: format!("{source_name}: {}", r.field),
                message: e.to_string(),
            }
        })
    })?)
}

/// [`Error::NotFound`] instead of [`Error::Unknown`] for a reference that looks like a file path
/// (an extension or a directory separator).
fn not_found(
    e: Error,
    kind: &'static str,
    builtin: &'static str,
    reference: &str,
    path: &Path,
) -> Error {
    let file_like =
        Path::new(reference).extension().is_some() || Path::new(reference).components().count() > 1;
    match e {
        Error::Unknown { known, .. } if file_like => Error::NotFound {
            kind,
            reference: crate::common::limits::short(reference),
            path: crate::common::limits::short(&path.display().to_string()),
            builtin,
            known,
        },
        e => e,
    }
}
