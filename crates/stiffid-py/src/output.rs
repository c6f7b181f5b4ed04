//! The files Python writes (`calibrate(out=..., urdf_out=..., stiffness_out=...)`, `setups_new(out=...)`), by the
//! command's rules ([`stiffid::internal::io::output`]): each checked before the job runs (a new name in an
//! existing directory, or a regular file, through a symlink to one; never a directory, a device,
//! a dangling symlink or a file the call reads), written whole after it succeeds, nothing left
//! behind on failure.

use crate::error::{raise, value};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use stiffid::internal::io::output;

/// An output file, checked.
#[derive(Clone)]
pub struct OutFile {
    /// Where the bytes go (the symlink's target for a symlink).
    target: PathBuf,
    /// The argument that named it, for errors.
    what: String,
}

/// Checks `path`, given as the argument `what`, against the files the call reads (`inputs`) and
/// the other outputs of the call (`others`).
///
/// # Errors
/// `InputError` naming the argument and the path: those of [`output::resolve`], and another
/// output's file.
pub fn prepare(
    path: &Path,
    what: &str,
    inputs: &[PathBuf],
    others: &[OutFile],
) -> PyResult<OutFile> {
    let input_at = |target: &Path| {
        (inputs.iter())
            .find(|p| p.canonicalize().is_ok_and(|c| c == target))
            .cloned()
    };
    let target = output::resolve(path, what, input_at).map_err(raise)?;
    if let Some(other) = others.iter().find(|o| o.target == target) {
        let name = path.display();
        return Err(value(format!(
            "{what} {name}: the same file as {}",
            other.what
        )));
    }
    Ok(OutFile {
        target,
        what: what.to_string(),
    })
}

impl OutFile {
    /// Writes `bytes` as the whole file: a temporary file beside the target, renamed over it.
    ///
    /// # Errors
    /// `OSError` naming the argument and the file when it cannot be written.
    pub fn write(&self, bytes: &[u8]) -> PyResult<()> {
        self.put(bytes, false)
    }

    /// Writes `bytes` as a new file: as [`OutFile::write`], but never over a file (one created
    /// since the check included).
    ///
    /// # Errors
    /// `OSError` as for [`OutFile::write`], and for a file that exists.
    pub fn write_new(&self, bytes: &[u8]) -> PyResult<()> {
        self.put(bytes, true)
    }

    fn put(&self, bytes: &[u8], new_only: bool) -> PyResult<()> {
        let dir = self.target.parent().unwrap_or(Path::new("."));
        let written = output::write_temporary(dir, bytes)
            .and_then(|tmp| output::place(&tmp, &self.target, new_only));
        written.map_err(|e| {
            pyo3::exceptions::PyOSError::new_err(format!(
                "{} {}: cannot write: {e}",
                self.what,
                self.target.display()
            ))
        })
    }
}
