//! The new-setup job (`stiffid setups new`, Python's `setups_new`): a complete, commented setup
//! for the user's own robot, with every field's unit and meaning, starting values derived from the
//! robot (the prior of [`stiffid_core::setup::prior`]: bounds inside the joint limits, a characteristic
//! length, a nominal stiffness from the payload, a tool scaled to the reach), and the optional
//! fields commented out.

use nalgebra::{Vector3, Vector6};
use std::path::{Path, PathBuf};
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::presets;
use stiffid_core::setup::{prior, Tool};
use stiffid_core::{Error, Result, Robot};

/// What the setup is for.
pub struct Request<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// The robot as the setup file names it: a preset name, or a file path relative to the setup
    /// file's directory ([`robot_reference`]).
    pub robot_ref: &'a str,
    /// A URDF's tip link, if given.
    pub tip: Option<&'a str>,
    /// The directories holding ROS packages, as the setup file names them (relative to its
    /// directory, [`relative_to`]).
    pub package_paths: &'a [String],
    /// The robot's rated payload, kg (0.1 to 2500); `None`: a class guessed from the
    /// robot's reach.
    pub payload_kg: Option<f64>,
}

/// The paper's robot, whose Table 2 stiffness the prior scales.
pub(crate) const REFERENCE_ROBOT: &str = "comau-smart5-nj165-3.0";
/// Bounds stay this far inside the joint limits, deg.
const LIMIT_MARGIN_DEG: f64 = 5.0;
/// The seed of the sampled postures behind the starting values (same robot, same file).
const SEED: u64 = 1;

/// The commented TOML of the new setup.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::PayloadKg`]) for a payload out of its range; those of
/// [`prior::characteristic_length`].
pub fn run(request: &Request<'_>) -> Result<String> {
    let Request {
        robot,
        robot_ref,
        tip,
        package_paths,
        payload_kg,
    } = *request;
    let reach = prior::reach(robot, SEED);
    let reference_reach = prior::reach(&presets::get(REFERENCE_ROBOT)?, SEED);
    let (payload, payload_note) = payload(payload_kg, reach, reference_reach);
    let stiffness =
        prior::nominal_stiffness(payload).map_err(|e| e.for_option(JobOption::PayloadKg))?;
    // The paper's tool (a 160 mm plate 260 mm out, a loading arm 150 mm off axis 6), scaled down
    // for robots smaller than the paper's; mm.
    let scale = (reach / reference_reach).min(1.0);
    let tool = |x: f64, y: f64, z: f64| Vector3::new(x, y, z) * scale;
    let (lower, upper) = bounds_deg(robot);
    let to_rad = |v: &Vector6<f64>| v.map(f64::to_radians);
    let corners = [(80.0, 80.0), (-80.0, 80.0), (-80.0, -80.0), (80.0, -80.0)];
    let tool_mm = Tool {
        loading_point: tool(150.0, 0.0, 200.0),
        measuring_points: corners.iter().map(|&(x, y)| tool(x, y, 260.0)).collect(),
        tcp: tool(80.0, 80.0, 260.0),
        rotation: nalgebra::UnitQuaternion::identity(),
    };
    let l = prior::characteristic_length(
        robot,
        &to_rad(&lower),
        &to_rad(&upper),
        &(tool_mm.tcp * 1e-3),
        SEED,
    )?;
    let points: Vec<String> = tool_mm
        .measuring_points
        .iter()
        .map(|p| list(p.iter(), 1))
        .collect();
    let (stem, tip_line, package_line) = robot_lines(robot_ref, tip, package_paths);
    let reach_mm = reach * 1e3;
    let mut values = vec![
        ("ROBOT_NAME", in_comment(robot.name())),
        ("ROBOT_REF", in_comment(robot_ref)),
        ("NAME", quoted(&format!("{stem}-cell"))),
        (
            "DESCRIPTION",
            quoted(&format!(
                "Stiffness identification cell of the {}",
                robot.name()
            )),
        ),
        ("ROBOT", quoted(robot_ref)),
        ("TIP_LINE", tip_line),
        ("PACKAGE_PATHS_LINE", package_line),
        ("REACH_MM", format!("{reach_mm:.0}")),
        ("LENGTH_MM", format!("{:.1}", l * 1e3)),
        ("PAYLOAD_NOTE", payload_note),
        ("STIFFNESS", list(stiffness.iter(), 0)),
        ("LOADING_POINT", list(tool_mm.loading_point.iter(), 1)),
        (
            "MEASURING_POINTS",
            format!("[\n  {},\n]", points.join(",\n  ")),
        ),
        ("TCP", list(tool(0.0, 0.0, 300.0).iter(), 1)),
        (
            "LOAD_N",
            format!("{:.1}", (50.0 * scale).max(5.0).round() * 10.0),
        ),
        (
            "ANCHOR",
            list([0.65 * reach_mm, 0.5 * reach_mm, 0.0].iter(), 0),
        ),
        ("MARGIN_DEG", format!("{LIMIT_MARGIN_DEG}")),
        ("LOWER", list(lower.iter(), 1)),
        ("UPPER", list(upper.iter(), 1)),
        ("TEST_POSTURE", list(((lower + upper) / 2.0).iter(), 1)),
    ];
    values.extend(cell_values(robot, &tool_mm, reach_mm));
    fill(&values)
}

/// The payload the prior's stiffness scales with (kg) and the note saying where it comes from:
/// the rated payload given, else a class guessed from the robot's reach against the paper's
/// robot's (m).
fn payload(payload_kg: Option<f64>, reach: f64, reference_reach: f64) -> (f64, String) {
    match payload_kg {
        Some(kg) => (kg, format!("the rated payload given, {kg} kg")),
        None => {
            let kg = prior::payload_class_kg(reach, reference_reach);
            let note = format!("a payload class of about {kg:.0} kg guessed from the reach");
            (kg, note + " (give --payload-kg)")
        }
    }
}

/// The setup's name stem, its `robot_tip` line and its `package_paths` line for the robot as the
/// setup file names it (a preset, a robot TOML or a URDF).
fn robot_lines(
    robot_ref: &str,
    tip: Option<&str>,
    package_paths: &[String],
) -> (String, String, String) {
    let stem = match presets::get(robot_ref) {
        Ok(_) => robot_ref.into(),
        Err(_) => Path::new(robot_ref)
            .file_stem()
            .map_or(robot_ref.into(), |s| s.to_string_lossy()),
    };
    let urdf = Path::new(robot_ref)
        .extension()
        .is_some_and(|e| e == "urdf");
    let tip_line = match tip {
        Some(tip) => format!("robot_tip = {}", quoted(tip)),
        None if urdf => "# robot_tip = \"tool0\"".into(),
        None => "# (this robot is a preset or a robot TOML: it has no tip link to choose)".into(),
    };
    let package_line = match package_paths {
        [] if urdf => "# package_paths = [\"../ros_ws/src\"]".into(),
        [] => "# (a preset or a robot TOML has no meshes to find)".into(),
        paths => format!(
            "package_paths = [{}]",
            paths
                .iter()
                .map(|p| quoted(p))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    (stem.into_owned(), tip_line, package_line)
}

/// The values of the commented-out `[cell]`, `[robot_geometry]` and `[tracker]` sections for a
/// robot of reach `reach_mm` with the tool `tool_mm` (mm): a table behind the robot, the default
/// body radii, a tracker in front of it to the side (the paper's cell at (3000, -2000, 1500) mm for
/// a reach of about 3 m), the flange z axis as every measuring point's normal.
fn cell_values(robot: &Robot, tool_mm: &Tool, reach_mm: f64) -> Vec<(&'static str, String)> {
    let r = |x: f64, y: f64, z: f64| Vector3::new(x, y, z) * reach_mm;
    let si = Tool {
        loading_point: tool_mm.loading_point * 1e-3,
        measuring_points: tool_mm.measuring_points.iter().map(|p| p * 1e-3).collect(),
        tcp: tool_mm.tcp * 1e-3,
        rotation: tool_mm.rotation,
    };
    let geometry = stiffid_core::setup::default_geometry(robot, &si);
    let normals = vec!["[0.0, 0.0, 1.0]"; si.measuring_points.len()];
    vec![
        ("OBSTACLE_MIN", list(r(-0.7, -0.15, 0.0).iter(), 0)),
        ("OBSTACLE_MAX", list(r(-0.45, 0.15, 0.25).iter(), 0)),
        (
            "LINK_RADII",
            list(geometry.link_radii.map(|v| v * 1e3).iter(), 1),
        ),
        ("TOOL_RADIUS", format!("{:.1}", geometry.tool_radius * 1e3)),
        ("TRACKER_POSITION", list(r(1.0, -0.7, 0.5).iter(), 0)),
        ("NORMALS", format!("[{}]", normals.join(", "))),
    ]
}

/// The template of [`run`]: `@NAME@` placeholders, each replaced once.
const TEMPLATE: &str = include_str!("template.toml");

/// [`TEMPLATE`] with every `@KEY@` replaced by its value.
fn fill(values: &[(&str, String)]) -> Result<String> {
    Ok(values
        .iter()
        .fold(TEMPLATE.to_string(), |text, (key, value)| {
            text.replace(&format!("@{key}@"), value)
        }))
}

/// Bounds inside the joint limits by [`LIMIT_MARGIN_DEG`], degrees: the robot's own limits (a
/// UR10's +-360 deg axes keep their whole travel); an unlimited joint (continuous, or a revolute
/// URDF joint without `<limit>`) within +-180 deg, one limited on one side only a turn from it.
fn bounds_deg(robot: &Robot) -> (Vector6<f64>, Vector6<f64>) {
    let limits = robot.limits();
    let bound = |a: usize| -> (f64, f64) {
        let (l, u) = (limits.lower[a].to_degrees(), limits.upper[a].to_degrees());
        let (l, u) = match (l.is_finite(), u.is_finite()) {
            (true, true) => (l, u),
            (true, false) => (l, l + 360.0),
            (false, true) => (u - 360.0, u),
            (false, false) => return (-180.0, 180.0),
        };
        match u - l > 2.0 * LIMIT_MARGIN_DEG {
            true => (l + LIMIT_MARGIN_DEG, u - LIMIT_MARGIN_DEG),
            // A joint narrower than twice the margin keeps its full range.
            false => (l, u),
        }
    };
    (
        Vector6::from_fn(|a, _| bound(a).0),
        Vector6::from_fn(|a, _| bound(a).1),
    )
}

/// `[a, b, c]` with `decimals` digits after the point.
fn list<'a>(values: impl Iterator<Item = &'a f64>, decimals: usize) -> String {
    let v: Vec<String> = values.map(|x| format!("{x:.decimals$}")).collect();
    format!("[{}]", v.join(", "))
}

/// A TOML basic string.
/// `s` for a TOML comment: line breaks and other control characters escaped (`\n`), so a
/// robot name cannot end the comment.
fn in_comment(s: &str) -> String {
    s.chars()
        .map(|c| match c.is_control() {
            true => c.escape_default().to_string(),
            false => c.to_string(),
        })
        .collect()
}

fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// The robot reference as the setup file written to `out` must hold it: a preset name as is; a
/// file path relative to the directory of `out` (or to the current directory without `out`).
///
/// # Errors
/// Those of [`relative_to`] (`field` names the argument).
pub fn robot_reference(robot: &str, out: Option<&Path>, field: &str) -> Result<String> {
    if presets::get(robot).is_ok() {
        return Ok(robot.to_string());
    }
    relative_to(Path::new(robot), out, field)
}

/// The file or directory `path` (given as `field`) relative to the directory of the file `out`
/// (or to the current directory), as a setup file written to `out` must hold it.
///
/// # Errors
/// [`Error::InvalidField`] (`field`) naming the path that does not exist;
/// [`Error::InvalidOption`] ([`JobOption::Out`]) for a directory of `out` that does not.
pub fn relative_to(path: &Path, out: Option<&Path>, field: &str) -> Result<String> {
    let message = |p: &Path, e: std::io::Error| format!("{}: {e}", p.display());
    let file = std::fs::canonicalize(path).map_err(|e| Error::InvalidField {
        field: field.into(),
        message: message(path, e),
    })?;
    let missing = |p: &Path, e| Error::InvalidOption {
        option: JobOption::Out,
        message: message(p, e),
    };
    let dir = match out
        .and_then(Path::parent)
        .filter(|d| !d.as_os_str().is_empty())
    {
        Some(d) => std::fs::canonicalize(d).map_err(|e| missing(d, e))?,
        None => std::env::current_dir().map_err(|e| missing(Path::new("."), e))?,
    };
    Ok(relative(&file, &dir).to_string_lossy().into_owned())
}

/// `path` relative to `dir` (both absolute), through `..` where needed.
pub fn relative(path: &Path, dir: &Path) -> PathBuf {
    let (p, d): (Vec<_>, Vec<_>) = (path.components().collect(), dir.components().collect());
    let common = p.iter().zip(&d).take_while(|(a, b)| a == b).count();
    let mut rel: PathBuf = d[common..].iter().map(|_| "..").collect();
    rel.extend(&p[common..]);
    rel
}
