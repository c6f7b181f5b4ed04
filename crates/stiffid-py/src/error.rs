//! The library's errors as Python exceptions.

use pyo3::create_exception;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::{PyErr, Python};
use std::fs::File;
use std::path::{Path, PathBuf};
use stiffid::internal::io::{self, Capped};
use stiffid::Error;

create_exception!(
    stiffid,
    StiffidError,
    PyValueError,
    "Every error of stiffid's computations (a ValueError): the library's message, naming the file, line, field or argument."
);
create_exception!(
    stiffid,
    InputError,
    StiffidError,
    "Bad input: a file, field or argument that is malformed, out of its limits or inconsistent."
);
create_exception!(
    stiffid,
    InfeasibleError,
    StiffidError,
    "A search or a pose with no feasible answer: no group of postures within the bounds and the cell, a pose out of reach."
);
create_exception!(
    stiffid,
    UnidentifiableError,
    StiffidError,
    "Data or a design that cannot identify every parameter (the message names them)."
);

create_exception!(
    stiffid,
    GateError,
    StiffidError,
    "A gate the caller set that the result fails (compensate's max_error_mm): the computation ran, and its result lies beyond the bound (the command's exit code 1)."
);

/// Adds the exception classes to the module: `Error` (a `ValueError`) and its subclasses.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<StiffidError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("InfeasibleError", py.get_type::<InfeasibleError>())?;
    m.add("UnidentifiableError", py.get_type::<UnidentifiableError>())?;
    m.add("GateError", py.get_type::<GateError>())?;
    Ok(())
}

/// The library's error as `stiffid.Error`'s subclass for its kind ([`Error::root`]):
/// `InfeasibleError` for a computation that found no answer (no feasible group, a pose out of
/// reach), `UnidentifiableError` for data that cannot identify every parameter, `GateError` for
/// a result beyond a bound the caller set ([`Error::Gate`]), `InputError` for everything else
/// (the input is wrong), with the library's message.
pub fn raise(e: Error) -> PyErr {
    exception(&e, e.to_string())
}

/// [`raise`] with the message after `name` (a file): `name: message`.
pub fn raise_in(name: &str, e: Error) -> PyErr {
    exception(&e, format!("{name}: {e}"))
}

fn exception(e: &Error, message: String) -> PyErr {
    match e.root() {
        Error::Infeasible { .. } | Error::Unreachable { .. } => InfeasibleError::new_err(message),
        Error::Unidentifiable { .. } | Error::TooFewRows { .. } | Error::Inseparable { .. } => {
            UnidentifiableError::new_err(message)
        }
        Error::Gate { .. } => GateError::new_err(message),
        _ => InputError::new_err(message),
    }
}

/// A Python exception where the library's file lookups
/// ([`stiffid::internal::setup::reference`]) want an error that holds the library's errors.
pub struct Failure(pub PyErr);

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure(raise(e))
    }
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        Python::attach(|py| write!(f, "{}", self.0.value(py)))
    }
}

/// The text of the file at `path` for the library's lookups: `None` if nothing exists there.
pub fn read_if_exists(path: &Path) -> Option<Result<String, Failure>> {
    path.exists().then(|| read(path).map_err(Failure))
}

/// The bytes of the file at `path` (a URDF's mesh) for the library's mesh lookups
/// ([`stiffid::internal::setup::reference::Meshes`]), `None` if nothing exists there: at most the input
/// limit ([`Capped`]); the error names the file.
pub fn bytes(path: &Path) -> Option<stiffid::Result<Vec<u8>>> {
    use std::io::Read;
    if !path.exists() {
        return None;
    }
    let failed = |message: String| Error::Parse {
        source_name: path.display().to_string(),
        message,
    };
    let mut data = Vec::new();
    let read = open(path)
        .map_err(|e| failed(Python::attach(|py| e.value(py).to_string())))
        .and_then(|mut f| f.read_to_end(&mut data).map_err(|e| failed(e.to_string())));
    Some(read.map(|_| data))
}

/// An `InputError` (a `ValueError`) with this message.
pub fn value(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}

/// The text of a file, the path in the error (`FileNotFoundError` or `OSError`; `ValueError` for
/// a directory, a file larger than the input limit or not UTF-8 text: [`stiffid::internal::io::read_text`],
/// the command's checks).
pub fn read(path: &Path) -> Result<String, PyErr> {
    let name = path.display().to_string();
    io::read_text(&name, open(path)?.into_inner()).map_err(raise)
}

/// The text of the program at `path`, of its `.dat` when it is a KRL program with one beside it,
/// and the encoding they were read in: UTF-8, else Latin-1 ([`io::program_texts`]); the errors
/// of [`read`].
pub fn read_program(path: &Path) -> Result<(String, Option<String>, io::Encoding), PyErr> {
    let read =
        |p: &Path| io::read_bytes(&p.display().to_string(), open(p)?.into_inner()).map_err(raise);
    stiffid::internal::machining::program::read_files(path, read, raise)
}

/// The files of the controller's backup given with the robot program `program` (`paths`: files,
/// or folders whose files of its language are read,
/// [`stiffid::internal::machining::program::read_backup`]); the errors of [`read`], and `ValueError` for a
/// program without a controller (G-code).
pub fn read_backup(paths: &[PathBuf], program: &str) -> Result<Vec<(String, String)>, PyErr> {
    let dialect = match stiffid::internal::machining::Language::of_file(program) {
        Ok(stiffid::internal::machining::Language::Robot(d)) => d,
        _ => return Err(value(format!("backup: only with a robot program (KRL, RAPID, LS, INFORM): {program} has no controller backup"))),
    };
    let read =
        |p: &Path| io::read_bytes(&p.display().to_string(), open(p)?.into_inner()).map_err(raise);
    stiffid::internal::machining::program::read_backup(paths, dialect, read, raise)
}

/// The file at `path` opened for reading, the path in the error (`FileNotFoundError` or
/// `OSError`; `ValueError` for a directory, a FIFO, a device: [`io::input::open`]); reading more than the input limit from it fails
/// ([`Capped`]).
pub fn open(path: &Path) -> Result<Capped<File>, PyErr> {
    let file = io::input::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::InvalidInput => value(format!("{}: {e}", path.display())),
        _ => os_error(path, e),
    })?;
    Ok(Capped::new(file))
}

/// `FileNotFoundError` or `OSError` for a failure to read the file at `path`.
fn os_error(path: &Path, e: std::io::Error) -> PyErr {
    let name = path.display();
    match e.kind() {
        std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(format!("{name}: no such file"))
        }
        _ => PyOSError::new_err(format!("{name}: cannot read: {e}")),
    }
}
