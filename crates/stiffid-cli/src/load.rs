//! Turning command-line arguments into robots, setups and angle lists.

use anyhow::{bail, Context, Result};
use nalgebra::{SVector, Vector6};
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use stiffid::internal::common::limits::{self, short, JointBox, Range};
use stiffid::internal::io::stiffness;
use stiffid::internal::io::{self, postures, Capped};
use stiffid::internal::model::Compliance;
use stiffid::internal::setup::reference;
use stiffid::{Robot, Setup};

/// Every file read so far (resolved path, and its device and inode where the system has them), so
/// no output is written over one.
static INPUTS: Mutex<Vec<(PathBuf, Option<FileId>)>> = Mutex::new(Vec::new());

/// A file's identity on its device, the same under every name (hard links): device and inode.
type FileId = (u64, u64);

/// The identity of the file of `meta`: device and inode on Unix; `None` elsewhere (there the
/// resolved path alone tells an input).
#[cfg(unix)]
fn file_id(meta: &std::fs::Metadata) -> Option<FileId> {
    use std::os::unix::fs::MetadataExt;
    Some((meta.dev(), meta.ino()))
}

/// The identity of the file of `meta`: device and inode on Unix; `None` elsewhere (there the
/// resolved path alone tells an input).
#[cfg(not(unix))]
fn file_id(_meta: &std::fs::Metadata) -> Option<FileId> {
    None
}

/// The directories of `--package-path`, where a URDF's `package://` meshes are looked for before
/// a setup's `package_paths`.
static PACKAGE_PATHS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Sets the directories of `--package-path` (once, from the command line).
pub fn set_package_paths(paths: Vec<PathBuf>) {
    *PACKAGE_PATHS.lock().unwrap_or_else(|e| e.into_inner()) = paths;
}

/// The directories of `--package-path`.
pub fn package_paths() -> Vec<PathBuf> {
    PACKAGE_PATHS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .clone()
}

/// Calls `f` with how a URDF's meshes are read: [`bytes`], `--package-path`.
fn with_meshes<T>(f: impl FnOnce(&reference::Meshes) -> T) -> T {
    let paths = package_paths();
    f(&reference::Meshes {
        read: &bytes,
        package_paths: &paths,
    })
}

/// A robot: a robot `.toml` or `.urdf` file if one exists at `arg`, else the preset named `arg`
/// (`tip`: URDF tip link; `stiffid::internal::setup::reference::robot_with_meshes`, a URDF's collision
/// meshes read). The error names what was tried.
pub fn robot(arg: &str, tip: Option<&str>) -> Result<Robot> {
    let robot = with_meshes(|m| reference::robot_with_meshes(arg, tip, existing, m))?;
    let warning = stiffid::internal::setup::plausibility::meshes(&robot);
    crate::output::warnings(&Vec::from_iter(warning));
    Ok(robot)
}

/// A setup from a setup `.toml` file if one exists at `arg`, else the built-in setup named
/// `arg` (`stiffid::internal::setup::reference::setup_with_meshes`). A robot file named in a setup file
/// is looked for relative to the setup file, a URDF's meshes relative to the URDF or in the
/// package paths.
pub fn setup(arg: &str) -> Result<Setup> {
    with_meshes(|m| reference::setup_with_meshes(arg, existing, m)).map(plausible)
}

/// `setup`, its plausibility warnings ([`stiffid::internal::setup::plausibility`]) printed on stderr.
fn plausible(setup: Setup) -> Setup {
    crate::output::warnings(&stiffid::internal::setup::plausibility::warnings(&setup));
    setup
}

/// A setup from its TOML `text`, read from `source_name` in the directory `dir` (where a robot
/// file it names is looked for), with its own `package_paths` only, not `--package-path`; no
/// warnings.
pub fn setup_text_as_written(text: &str, source_name: &str, dir: &Path) -> Result<Setup> {
    let meshes = reference::Meshes {
        read: &bytes,
        package_paths: &[],
    };
    reference::setup_text_with_meshes(text, source_name, dir, existing, &meshes)
}

/// The bytes of the file at `path` (a URDF's mesh), `None` if nothing exists there: at most
/// 256 MiB (`MAX_INPUT_BYTES`), remembered as an input; the error names the file.
fn bytes(path: &Path) -> Option<stiffid::Result<Vec<u8>>> {
    use std::io::Read;
    if !path.exists() {
        return None;
    }
    let failed = |e: String| stiffid::Error::Parse {
        source_name: path.display().to_string(),
        message: e,
    };
    let mut data = Vec::new();
    let read = open(path)
        .map_err(|e| failed(format!("{e:#}")))
        .and_then(|mut f| f.read_to_end(&mut data).map_err(|e| failed(e.to_string())));
    Some(read.map(|_| data))
}

/// The text of the file at `path` ([`read`]), `None` if nothing exists there.
fn existing(path: &Path) -> Option<Result<String>> {
    path.exists().then(|| read(path))
}

/// The text of the program at `path`, of its `.dat` when it is a KRL program with one beside it,
/// and the encoding they were read in: UTF-8, else Latin-1 ([`io::program_texts`]), with the
/// file's name in the error. Each file is remembered as an input ([`input_at`]).
pub fn read_program(path: &Path) -> Result<(String, Option<String>, io::Encoding)> {
    let read = |p: &Path| -> Result<Vec<u8>> {
        Ok(io::read_bytes(
            &p.display().to_string(),
            open(p)?.into_inner(),
        )?)
    };
    stiffid::internal::machining::program::read_files(path, read, anyhow::Error::from)
}

/// The files of a controller's backup given with the robot program `program` (`paths`: files, or
/// folders whose files of its language are read, [`stiffid::internal::machining::program::read_backup`]),
/// each named and its text; none without paths. Each file is remembered as an input
/// ([`input_at`]).
pub fn read_backup(paths: &[PathBuf], program: &str) -> Result<Vec<(String, String)>> {
    if paths.is_empty() {
        return Ok(Vec::new());
    }
    let dialect = match stiffid::internal::machining::Language::of_file(program) {
        Ok(stiffid::internal::machining::Language::Robot(d)) => d,
        _ => anyhow::bail!("--backup: only with a robot --program (KRL, RAPID, LS, INFORM): {program} has no controller backup"),
    };
    let read = |p: &Path| -> Result<Vec<u8>> {
        Ok(io::read_bytes(
            &p.display().to_string(),
            open(p)?.into_inner(),
        )?)
    };
    stiffid::internal::machining::program::read_backup(paths, dialect, read, anyhow::Error::from)
        .map_err(|e| e.context("--backup"))
}

/// The text of a file, with its name in the error: at most 256 MiB (`MAX_INPUT_BYTES`), UTF-8
/// ([`io::read_text`]). The file is remembered as an input ([`input_at`]).
pub fn read(path: &Path) -> Result<String> {
    let name = path.display().to_string();
    Ok(io::read_text(&name, open(path)?.into_inner())?)
}

/// The file at `path` opened for reading, a regular file ([`io::input::open`]: never a wait on
/// a FIFO), remembered as an input
/// ([`input_at`]); reading more than 256 MiB (`MAX_INPUT_BYTES`) from it fails.
pub fn open(path: &Path) -> Result<Capped<File>> {
    let name = path.display();
    let file = io::input::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::InvalidInput => anyhow::anyhow!("{name}: {e}"),
        _ => anyhow::Error::new(e).context(format!("{name}: cannot read")),
    })?;
    let meta = file
        .metadata()
        .with_context(|| format!("{name}: cannot read"))?;
    if let Ok(resolved) = path.canonicalize() {
        let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
        inputs.push((resolved, file_id(&meta)));
    }
    Ok(Capped::new(file))
}

/// The input file (as read) that `target` (a resolved path) is, if any: the same path, or the
/// same file under another name (a hard link).
pub fn input_at(target: &Path) -> Option<PathBuf> {
    let id = std::fs::metadata(target).ok().and_then(|m| file_id(&m));
    let inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    inputs
        .iter()
        .find(|(p, input)| p == target || (id.is_some() && *input == id))
        .map(|(p, _)| p.clone())
}

/// A posture given with `option` (e.g. `--q-deg`): six comma-separated axis angles in degrees,
/// within the robot's joint limits. Returns the angles in degrees and in radians; the error names
/// the option, the axis and the limits.
pub fn posture(text: &str, option: &str, robot: &Robot) -> Result<(Vector6<f64>, Vector6<f64>)> {
    let q_deg = vector::<6>(text, option, &limits::ANGLE_DEG)?;
    let q = q_deg.map(f64::to_radians);
    let field = |a: usize| format!("{option}[{}]", a + 1);
    robot.limits().check(&q, "the robot's limits", field)?;
    let warning = stiffid::internal::setup::plausibility::radians_in_option(option, &q);
    crate::output::warnings(&Vec::from_iter(warning));
    Ok((q_deg, q))
}

/// Exactly `N` comma-separated numbers within `range`, e.g. `--point-mm 150,0,200`; `what` names
/// the option.
pub fn vector<const N: usize>(text: &str, what: &str, range: &Range) -> Result<SVector<f64, N>> {
    let values = numbers(text, what, range)?;
    if values.len() != N {
        bail!(
            "{what}: expected {N} comma-separated numbers, got {}",
            values.len()
        );
    }
    Ok(SVector::from_column_slice(&values))
}

/// Comma-separated numbers within `range`; `what` names the option in errors. At most 64 numbers.
pub fn numbers(text: &str, what: &str, range: &Range) -> Result<Vec<f64>> {
    let fields: Vec<&str> = text.split(',').map(str::trim).take(65).collect();
    if fields.len() > 64 {
        bail!("{what}: more than 64 comma-separated numbers");
    }
    let values = fields
        .iter()
        .enumerate()
        .map(|(i, s)| {
            s.parse::<f64>()
                .with_context(|| format!("{what}: value {} '{}' is not a number", i + 1, short(s)))
        })
        .collect::<Result<Vec<f64>>>()?;
    limits::check(what, &values, range)?;
    Ok(values)
}

/// The compliance of every parameter of `setup`'s model from a stiffness file
/// (`stiffid::internal::io::stiffness`), e.g. the result of `stiffid identify --out`, checked against
/// the model; errors start with the file name.
pub fn stiffness(path: &Path, setup: &Setup) -> Result<Compliance> {
    let text = read(path)?;
    let name = || path.display().to_string();
    let file = stiffness::parse(&text).with_context(name)?;
    file.compliance(setup.model()).with_context(name)
}

/// A postures file (`stiffid::internal::io::postures`), every posture within the robot's joint limits
/// and, if given, the `bounds` (a setup's); angles in rad. Errors start with the file name, then
/// the line and column.
pub fn postures(
    path: &Path,
    robot: &Robot,
    bounds: Option<&JointBox>,
) -> Result<Vec<Vector6<f64>>> {
    let text = read(path)?;
    postures::parse(&text, robot, bounds).with_context(|| path.display().to_string())
}

/// The arm's axis angles of the postures file `path` of a cell whatever its external axes'
/// values: a search's start or pool, which `select` places at its own stations (`--station`).
///
/// # Errors
/// As [`postures`], but for an external axis not at 0.
pub fn arm_postures(
    path: &Path,
    robot: &Robot,
    bounds: Option<&JointBox>,
) -> Result<Vec<Vector6<f64>>> {
    let text = read(path)?;
    let cell = postures::parse_cell(&text, robot, bounds);
    Ok(cell.with_context(|| path.display().to_string())?.q)
}
