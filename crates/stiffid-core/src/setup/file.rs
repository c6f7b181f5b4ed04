//! The setup TOML file (format in [`super`]): read, converted to SI and built through
//! [`SetupBuilder`], which checks every field.

use super::calibrated;
use super::cell_file::{
    read_cell, read_geometry, read_tracker, CellFile, GeometryFile, TrackerFile,
};
use super::noise_file::NoiseFile;
use super::{mm, CellConstraints, Noise, RopeLoad, Setup, SetupBuilder};
use crate::common::limits::{self, JointBox};
use crate::model::file::ModelFile;
use crate::robot::file::{transform, TransformFile};
use crate::robot::kinematics::Coordinates;
use crate::{Error, Result, Robot};
use nalgebra::{Isometry3, Vector3, Vector6};
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SetupFile {
    name: String,
    #[serde(default)]
    description: String,
    robot: String,
    robot_tip: Option<String>,
    robot_axis_map: Option<crate::robot::file::AxisMapFile>,
    #[serde(default)]
    package_paths: Vec<String>,
    robot_base: Option<TransformFile>,
    robot_flange: Option<TransformFile>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    max_speed_deg_s: Option<[f64; 6]>,
    #[serde(default)]
    springs: Coordinates,
    characteristic_length_mm: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    nominal_stiffness_nm_per_rad: Option<[f64; 6]>,
    tool: ToolFile,
    loading: Option<LoadingFile>,
    noise: NoiseFile,
    bounds: Option<BoundsFile>,
    test: Option<TestFile>,
    constraints: Option<ConstraintsFile>,
    cell: Option<CellFile>,
    robot_geometry: Option<GeometryFile>,
    tracker: Option<TrackerFile>,
    model: Option<ModelFile>,
    workpiece: Option<WorkpieceFile>,
    controller: Option<ControllerFile>,
    masses: Option<MassesFile>,
    robot_accuracy: Option<RobotAccuracyFile>,
    external_axis: Option<Vec<crate::robot::external::file::AxisFile>>,
}

/// `[robot_accuracy]`: how far the robot model's frames may be from the true robot's.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotAccuracyFile {
    frame_sd_mm: f64,
    frame_sd_mrad: f64,
}

/// `[masses]`: how well the robot's and the tool's masses are known.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MassesFile {
    /// Spelt `sd_percent` before every percentage's key ended in `_pct`: still read.
    #[serde(alias = "sd_percent")]
    sd_pct: f64,
}

/// `[controller]`: the kinematics of the controller that runs a generated program.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ControllerFile {
    kinematics: Option<String>,
    joint_targets: Option<String>,
    robot_number: Option<u32>,
    dialect: Option<String>,
    robot: Option<String>,
    robot_tip: Option<String>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    pulses_per_deg: Option<[f64; 6]>,
    external_pulses: Option<Vec<f64>>,
    #[serde(default)]
    tools: Vec<super::numbered::NumberedFrameFile>,
    #[serde(default)]
    bases: Vec<super::numbered::NumberedFrameFile>,
    rapid_speed_mm_s: Option<f64>,
    rapid_joint_pct: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    home_deg: Option<[f64; 6]>,
    #[serde(default)]
    io: BTreeMap<String, super::program_io::IoValue>,
    #[serde(default)]
    radius_wear_mm: BTreeMap<String, f64>,
}

/// `[workpiece]`: where a G-code program's part frame sits in the robot base frame.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct WorkpieceFile {
    base_from_part: Option<TransformFile>,
    #[serde(default, deserialize_with = "crate::common::exact::arrays")]
    reflectors_mm: Vec<[f64; 3]>,
    #[serde(default)]
    offsets: BTreeMap<String, TransformFile>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    start_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    g28_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    g30_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    tool_rpy_deg: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolFile {
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    loading_point_mm: Option<[f64; 3]>,
    #[serde(deserialize_with = "crate::common::exact::arrays")]
    measuring_points_mm: Vec<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    tcp_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    tcp_rpy_deg: Option<[f64; 3]>,
    #[serde(default)]
    mass_kg: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    centre_of_mass_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    inertia_kg_m2: Option<[f64; 6]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoadingFile {
    load_n: f64,
    #[serde(deserialize_with = "crate::common::exact::array")]
    anchor_mm: [f64; 3],
    #[serde(default)]
    steps_n: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoundsFile {
    #[serde(deserialize_with = "crate::common::exact::array")]
    lower_deg: [f64; 6],
    #[serde(deserialize_with = "crate::common::exact::array")]
    upper_deg: [f64; 6],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TestFile {
    #[serde(deserialize_with = "crate::common::exact::arrays")]
    postures_deg: Vec<[f64; 6]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ConstraintsFile {
    loading_point_min_z_mm: Option<f64>,
    #[serde(default)]
    anchor_below_loading_point: bool,
}

/// The built-in setups: `(name, TOML)`.
const BUILTIN: &crate::robot::builtin::Table = &[
    (
        "zhang2021-comau-nj165",
        include_str!("../../setups/zhang2021-comau-nj165.toml"),
    ),
    (
        "fanuc-r2000ic-165f",
        include_str!("../../setups/fanuc-r2000ic-165f.toml"),
    ),
];

/// Names of the built-in setups.
pub fn builtin_names() -> impl Iterator<Item = &'static str> {
    crate::robot::builtin::names(BUILTIN)
}

/// The TOML text of a built-in setup.
///
/// # Errors
/// [`Error::Unknown`] if no built-in setup has this name.
pub fn builtin_text(name: &str) -> Result<&'static str> {
    crate::robot::builtin::text(BUILTIN, "setup", name)
}

/// A built-in setup, its robot taken from the presets.
///
/// # Examples
/// The paper's cell (Zhang et al. 2021, Tables 1-3): four measuring points, six noise levels, the
/// bounds of Table 1 inside the robot's joint limits.
/// ```
/// let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165")?;
/// assert_eq!(setup.tool().measuring_points.len(), 4);
/// assert_eq!(setup.noise().levels, [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]);
/// assert!((setup.bounds().upper[1].to_degrees() - 40.0).abs() < 1e-12);
/// assert!(setup.robot().limits().contains(&setup.bounds().upper));
/// assert!(stiffid_core::setup::builtin("no-such-setup").is_err());
/// # Ok::<(), stiffid_core::Error>(())
/// ```
///
/// # Errors
/// [`Error::Unknown`] if no built-in setup has this name.
pub fn builtin(name: &str) -> Result<Setup> {
    parse(builtin_text(name)?, &format!("setup {name}"), |r, _| {
        crate::robot::presets::get(r)
    })
}

/// Parses a setup TOML. `source_name` (the file name) is used in errors; `resolve_robot` turns the
/// `robot` field (and the optional `robot_tip`) into a [`Robot`] (a preset, or a file the caller
/// reads). `parse_with` also hands over the setup's `package_paths`.
///
/// # Errors
/// [`Error::Parse`] for malformed TOML, unknown or missing keys and wrong types;
/// [`Error::InvalidField`] naming the file, the field and the value for everything
/// [`SetupBuilder::build`] checks (for example a stiffness outside
/// [`limits::STIFFNESS_NM_PER_RAD`]) and for bad
/// `[robot_base]`/`[robot_flange]` offsets; [`Error::OutsideBox`] naming the file, the field and
/// the value for bounds or test postures outside the robot's limits; whatever `resolve_robot`
/// returns.
pub fn parse<F>(text: &str, source_name: &str, mut resolve_robot: F) -> Result<Setup>
where
    F: FnMut(&str, Option<&str>) -> Result<Robot>,
{
    parse_with(text, source_name, |r: &RobotRequest| {
        resolve_robot(r.reference, r.tip)
    })
}

/// What a setup file asks of its robot: the `robot` reference, the `robot_tip` link and the
/// `package_paths` (as written, relative to the setup file) where a URDF's `package://` meshes
/// are looked for ([`crate::robot::collision`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RobotRequest<'a> {
    /// The `robot` field: a preset name or a robot file.
    pub reference: &'a str,
    /// The `robot_tip` field (URDF only).
    pub tip: Option<&'a str>,
    /// The `package_paths` field: at most [`MAX_PACKAGE_PATHS`] directories.
    pub package_paths: &'a [String],
    /// The field that names it: `robot`, or `controller.robot` (the robot file the controller
    /// runs).
    pub field: &'a str,
}

/// Most `package_paths` a setup may list.
pub const MAX_PACKAGE_PATHS: usize = 64;

/// [`parse`] with the whole [`RobotRequest`] handed to `resolve_robot` (once for `robot`, once
/// more for `[controller] robot`).
///
/// # Errors
/// Those of [`parse`]; [`Error::InvalidField`] (`package_paths`) for more than
/// [`MAX_PACKAGE_PATHS`] paths or an empty one, (`controller.kinematics`) for a kinematics other
/// than `nominal` or `calibrated`, or `[controller] robot` with `kinematics = "calibrated"`.
pub(crate) fn parse_with<F>(text: &str, source_name: &str, mut resolve_robot: F) -> Result<Setup>
where
    F: FnMut(&RobotRequest) -> Result<Robot>,
{
    let mut file: SetupFile = toml::from_str(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: limits::one_line(&e.to_string()),
    })?;
    check_package_paths(&file.package_paths).map_err(|e| in_file(e, source_name))?;
    let robot = resolve_robot(&RobotRequest {
        reference: &file.robot,
        tip: file.robot_tip.as_deref(),
        package_paths: &file.package_paths,
        field: "robot",
    })?;
    let tables = file.external_axis.is_some();
    let mount_note =
        calibrated::mount(&robot, &file.robot, (file.robot_base, tables), source_name)?;
    let mount = match (&file.robot_base, robot.mount()) {
        (Some(t), _) => Some(transform(Some(*t), "robot_base", source_name)?),
        (None, recorded) => recorded.copied(),
    };
    let part = workpiece(&file, source_name)?;
    let (part, part_note) = calibrated::part(&robot, &file.robot, part, source_name)?;
    if part.is_none()
        && file
            .workpiece
            .as_ref()
            .is_some_and(|w| w.reflectors_mm.is_empty())
    {
        return Err(Error::InvalidField {
            field: format!("{source_name}: workpiece.base_from_part"),
            message: "missing: [workpiece] gives the part's frame in the robot base frame (base_from_part = { xyz_mm = [..], rpy_deg = [..] }); only a setup whose calibrated robot file records the part ([part]) leaves it out".into(),
        });
    }
    let robot = mounted(
        robot,
        &file,
        source_name,
        (mount, file.robot_axis_map.as_ref(), true),
    )?;
    let mut controller = match file.controller.take() {
        None => super::Controller::default(),
        Some(c) => controller(c, &file, source_name, &mut resolve_robot, mount)?,
    };
    if let Some(c) = &controller.robot {
        super::controller_robot::check(&robot, c, &file.robot, source_name)?;
        super::controller_axes::check(&robot, c, &file.robot, source_name)?;
    }
    controller.mount = mount.unwrap_or_default();
    controller.adapter = transform(file.robot_flange, "robot_flange", source_name)?;
    let steps = file.loading.as_ref().is_some_and(|l| !l.steps_n.is_empty());
    let (reading_variance, note) = file
        .noise
        .reading_variance(steps)
        .map_err(|e| in_file(e, source_name))?;
    let mut setup = builder(file, robot, reading_variance)
        .map(|b| b.with_controller(controller))
        .map(|b| match part {
            Some(p) => b.with_workpiece(p),
            None => b,
        })
        .and_then(SetupBuilder::build)
        .map_err(|e| in_file(e, source_name))?;
    setup.notes.extend(note);
    setup.notes.extend(mount_note);
    setup.notes.extend(part_note);
    Ok(setup)
}

/// The setup's `[workpiece] base_from_part`, m, checked within the documented ranges.
///
/// # Errors
/// [`Error::InvalidField`] (`workpiece.base_from_part.xyz_mm`, `.rpy_deg`) out of range.
fn workpiece(file: &SetupFile, source_name: &str) -> Result<Option<Isometry3<f64>>> {
    let Some(t) = file.workpiece.as_ref().and_then(|w| w.base_from_part) else {
        return Ok(None);
    };
    let field = "workpiece.base_from_part";
    let check = |name: &str, v: &[f64; 3], range| {
        limits::check(&format!("{field}.{name}"), v, range).map_err(|e| in_file(e, source_name))
    };
    check("xyz_mm", &t.xyz_mm, &limits::LENGTH_MM)?;
    check("rpy_deg", &t.rpy_deg, &limits::ANGLE_DEG)?;
    Ok(Some(t.isometry()))
}

/// `[controller]`: its kinematics and the robot file it runs (resolved as `robot` is, with the
/// setup's offsets).
fn controller<F>(
    c: ControllerFile,
    file: &SetupFile,
    source_name: &str,
    resolve_robot: &mut F,
    mount: Option<Isometry3<f64>>,
) -> Result<super::Controller>
where
    F: FnMut(&RobotRequest) -> Result<Robot>,
{
    use super::Kinematics;
    let kinematics = match c.kinematics.as_deref().map(str::parse::<Kinematics>) {
        None => Kinematics::Nominal,
        Some(Ok(k)) => k,
        Some(Err(e)) => return Err(in_file(e, source_name)),
    };
    let robot = match (&c.robot, kinematics) {
        (None, _) => None,
        (Some(_), Kinematics::Calibrated) => {
            return Err(in_file(
                Error::InvalidField {
                    field: "controller.robot".into(),
                    message: "given with kinematics = \"calibrated\": a controller loaded with the calibrated model runs the setup's robot; leave robot out, or say kinematics = \"nominal\"".into(),
                },
                source_name,
            ))
        }
        (Some(reference), Kinematics::Nominal) => {
            let robot = resolve_robot(&RobotRequest {
                reference,
                tip: c.robot_tip.as_deref(),
                package_paths: &file.package_paths,
                field: "controller.robot",
            })?;
            // A robot file of its own axis map states the controller's axes already: the
            // setup's map (a URDF robot's) is not applied to it again.
            let own_map = *robot.axis_map() != crate::robot::AxisMap::default();
            let map = file.robot_axis_map.as_ref().filter(|_| !own_map);
            // The controller moves the cell's external axes by its own model: its robot file's
            // [[external_axis]] (compared with the setup's, `controller_axes`), never the setup's
            // tables put in their place.
            Some(mounted(robot, file, source_name, (mount, map, false))?)
        }
    };
    let here = |e| in_file(e, source_name);
    Ok(super::Controller {
        kinematics,
        robot,
        pulses: super::Pulses::read(c.pulses_per_deg, c.external_pulses).map_err(here)?,
        tools: super::numbered::read("controller.tools", &c.tools).map_err(here)?,
        bases: super::numbered::read("controller.bases", &c.bases).map_err(here)?,
        program: super::ProgramSettings::read(
            c.rapid_speed_mm_s,
            c.rapid_joint_pct,
            c.home_deg,
            &c.io,
        )
        .map_err(here)?,
        dialect: (c.dialect.as_deref().map(str::parse).transpose()).map_err(here)?,
        radius_wear: super::radius_wear::read(&c.radius_wear_mm).map_err(here)?,
        joint_targets: (c.joint_targets.as_deref().map(str::parse).transpose()).map_err(here)?,
        robot_number: super::workcell::robot_number(c.robot_number).map_err(here)?,
        ..Default::default()
    })
}

fn check_package_paths(paths: &[String]) -> Result<()> {
    limits::check_count("package_paths", paths.len(), 0, MAX_PACKAGE_PATHS)?;
    match paths.iter().position(|p| p.trim().is_empty()) {
        Some(i) => Err(Error::InvalidField {
            field: format!("package_paths[{}]", i + 1),
            message: "expected a directory, got an empty path".into(),
        }),
        None => Ok(()),
    }
}

/// A field error placed in the file `source_name` (`"cell.toml: bounds.lower_deg[2]"`).
fn in_file(e: Error, source_name: &str) -> Error {
    match e {
        Error::InvalidField { field, message } => Error::InvalidField {
            field: format!("{source_name}: {field}"),
            message,
        },
        Error::OutsideBox {
            field,
            value_deg,
            within,
            lower_deg,
            upper_deg,
        } => Error::OutsideBox {
            field: format!("{source_name}: {field}"),
            value_deg,
            within,
            lower_deg,
            upper_deg,
        },
        other => other,
    }
}

/// The robot with the setup's offsets: `[robot_base]` places the robot's base frame in the cell
/// (a pedestal: results are then in the cell frame), before the robot's own base transform;
/// `[robot_flange]` adds an adapter plate after its flange. Either is `xyz_mm` and `rpy_deg`
/// (fixed-axis roll, pitch, yaw as URDF), the same as a robot TOML's `[base]` and `[flange]`.
///
/// The setup's `[[external_axis]]` tables, when it has any, replace the robot file's
/// (`external_axis = []` takes them away: the arm on a fixed base); its `max_speed_deg_s`
/// replaces the robot's axis speeds. `mount` is `[robot_base]`, or the mount a calibrated
/// robot's file records; a calibrated robot file holds its mount, which is not applied to it
/// again ([`calibrated::mount`]). `map` is the setup's `[robot_axis_map]` where it applies;
/// `tables`: whether the setup's `[[external_axis]]` apply (not to `[controller] robot`, whose
/// own model of the axes the controller runs).
fn mounted(
    mut robot: Robot,
    f: &SetupFile,
    src: &str,
    (mount, map, tables): (
        Option<Isometry3<f64>>,
        Option<&crate::robot::file::AxisMapFile>,
        bool,
    ),
) -> Result<Robot> {
    if let Some(m) = map {
        robot = axis_mapped(robot, m, src)?;
    }
    if let Some(v) = &f.max_speed_deg_s {
        robot = robot.with_max_speeds(crate::robot::file::max_speeds(Some(v), src)?)?;
    }
    if let Some(tables) = f.external_axis.as_ref().filter(|_| tables) {
        robot = robot.with_external(crate::robot::external::file::build(tables, src)?);
    }
    if let Some(mount) = mount.filter(|_| !robot.is_calibrated()) {
        let base = mount * robot.base();
        robot = robot.with_base(base)?;
    }
    if f.robot_flange.is_some() {
        let flange = robot.flange() * transform(f.robot_flange, "robot_flange", src)?;
        robot = robot.with_flange(flange)?;
    }
    Ok(robot)
}

/// `robot` with the setup's `[robot_axis_map]` (a URDF robot, whose joints turn by their own
/// positions, run by a controller whose axes couple them: FANUC's J2/J3 interaction).
///
/// # Errors
/// [`Error::InvalidField`] (`robot_axis_map.matrix[r]`, `.offset_deg`) out of range or a matrix
/// that cannot be inverted, and (`robot_axis_map`) where the robot file gives another
/// `[axis_map]` (an entry or offset more than 1e-12 from the setup's).
fn axis_mapped(robot: Robot, m: &crate::robot::file::AxisMapFile, src: &str) -> Result<Robot> {
    let map = crate::robot::file::axis_map(m, "robot_axis_map", src)?;
    let own = robot.axis_map();
    // A calibrated file writes the map it was calibrated with in degrees: read back, an offset
    // may differ from the setup's in the last bit.
    let apart = (own.matrix - map.matrix)
        .amax()
        .max((own.offset - map.offset).amax());
    if *own != crate::robot::AxisMap::default() && apart > 1e-12 {
        return Err(Error::InvalidField {
            field: format!("{src}: robot_axis_map"),
            message: format!("the robot file '{}' gives its own [axis_map], another one: give the map in one place (the setup's [robot_axis_map] is for a URDF robot)", robot.name()),
        });
    }
    let renamed = |e: Error| match e {
        Error::InvalidField { field, message } => Error::InvalidField {
            field: field.replacen("axis_map", "robot_axis_map", 1),
            message,
        },
        other => other,
    };
    // A URDF's limits bound its joint positions: through the map they bound the axes.
    let limits = match robot.urdf_source() {
        Some(_) => map.axis_limits(robot.limits()),
        None => *robot.limits(),
    };
    robot
        .with_axis_map(map)
        .and_then(|r| r.with_limits(limits))
        .map_err(|e| in_file(renamed(e), src))
}

fn deg6(v: &[f64; 6]) -> Vector6<f64> {
    Vector6::from_iterator(v.iter().map(|d| d.to_radians()))
}

/// The file's fields in SI units, for [`SetupBuilder::build`] to check.
fn builder(f: SetupFile, robot: Robot, reading_variance: f64) -> Result<SetupBuilder> {
    let measuring_points = f.tool.measuring_points_mm.iter().map(mm).collect();
    let springs = match &f.model {
        Some(m) => m.springs(&robot)?,
        None => Default::default(),
    };
    let mut b = Setup::builder(f.name, robot)
        .with_virtual_springs(springs.model)
        .with_candidate_springs(springs.candidates)
        .with_description(f.description)
        .with_robot_ref(f.robot)
        .with_springs(f.springs)
        .with_measuring_points(measuring_points)
        .with_noise(Noise {
            reading_variance,
            levels: f.noise.level_multiples,
        });
    if let Some(p) = &f.tool.loading_point_mm {
        b = b.with_loading_point(mm(p));
    }
    if let Some(l) = f.loading {
        b = b
            .with_load(RopeLoad {
                load: l.load_n,
                anchor: mm(&l.anchor_mm),
            })
            .with_load_steps(l.steps_n);
    }
    if let Some(bounds) = &f.bounds {
        b = b.with_bounds(JointBox::new(
            deg6(&bounds.lower_deg),
            deg6(&bounds.upper_deg),
        ));
    }
    if let Some(l) = f.characteristic_length_mm {
        b = b.with_characteristic_length(l * 1e-3);
    }
    if let Some(k) = f.nominal_stiffness_nm_per_rad {
        b = b.with_nominal_stiffness(Vector6::from(k));
    }
    b = with_tool(b, &f.tool)?;
    if let Some(a) = &f.robot_accuracy {
        b = b.with_frame_sd(a.frame_sd_mm * 1e-3, a.frame_sd_mrad * 1e-3);
    }
    if let Some(m) = &f.masses {
        b = b.with_mass_sd(m.sd_pct * 1e-2);
    }
    if let Some(t) = f.test {
        b = b.with_test_postures(t.postures_deg.iter().map(deg6).collect());
    }
    if let Some(c) = f.constraints {
        b = b.with_constraints(CellConstraints {
            loading_point_min_z: c.loading_point_min_z_mm.map(|z| z * 1e-3),
            anchor_below_loading_point: c.anchor_below_loading_point,
        });
    }
    if let Some(c) = f.cell {
        b = b.with_cell(read_cell(c));
    }
    if let Some(g) = f.robot_geometry {
        b = read_geometry(g, b);
    }
    if let Some(t) = f.tracker {
        b = b.with_tracker(read_tracker(t)?);
    }
    if let Some(w) = f.workpiece {
        let reflectors = w.reflectors_mm.iter().map(|p| Vector3::from(*p) * 1e-3);
        b = b.with_table_reflectors(reflectors.collect());
        let positions = [w.start_mm, w.g28_mm, w.g30_mm, w.tool_rpy_deg];
        b = b.with_program_frames(super::program_frames::read(&w.offsets, positions)?);
    }
    Ok(b)
}

/// The builder with the `[tool]` table's tool centre point, its turn and its payload.
fn with_tool(mut b: SetupBuilder, tool: &ToolFile) -> Result<SetupBuilder> {
    if let Some(tcp) = &tool.tcp_mm {
        b = b.with_tcp(mm(tcp));
    }
    if let Some(rpy) = &tool.tcp_rpy_deg {
        limits::check("tool.tcp_rpy_deg", rpy, &limits::ANGLE_DEG)?;
        let [r, p, y] = rpy.map(f64::to_radians);
        b = b.with_tcp_rotation(nalgebra::UnitQuaternion::from_euler_angles(r, p, y));
    }
    match (tool.mass_kg, &tool.centre_of_mass_mm) {
        (Some(mass), Some(c)) => {
            b = b.with_payload(crate::setup::Payload {
                mass,
                centre: mm(c),
                inertia: crate::robot::dynamics::body::tensor(
                    tool.inertia_kg_m2.unwrap_or_default(),
                ),
            })
        }
        (None, None) if tool.inertia_kg_m2.is_some() => {
            return Err(Error::InvalidField {
                field: "tool.inertia_kg_m2".into(),
                message: "inertia_kg_m2 needs mass_kg and centre_of_mass_mm".into(),
            })
        }
        (None, None) => {}
        _ => {
            return Err(Error::InvalidField {
                field: "tool.mass_kg".into(),
                message: "mass_kg and centre_of_mass_mm come together: give both or neither".into(),
            })
        }
    }
    Ok(b)
}
