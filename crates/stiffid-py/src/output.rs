//! The files Python writes (`calibrate(out=..., urdf_out=...)`), as the command writes its
//! `--out` files: each checked before the job runs (a new name in an existing directory, or a
//! regular file, through a symlink to one; never a directory, a device, a dangling symlink or a
//! file the call reads), written whole after it succeeds (a temporary file beside the target,
//! renamed over it), nothing left behind on failure.

use crate::error::value;
use pyo3::prelude::*;
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// An output file, checked.
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
/// `InputError` naming the argument and the path: a path that exists and is not a regular file,
/// a dangling symlink, a missing directory, an input file, another output's file.
pub fn prepare(
    path: &Path,
    what: &str,
    inputs: &[PathBuf],
    others: &[OutFile],
) -> PyResult<OutFile> {
    let name = path.display();
    let fail = |message: String| value(format!("{what} {name}: {message}"));
    let target = match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == ErrorKind::NotFound => {
            let file_name = path
                .file_name()
                .ok_or_else(|| fail("not a file name".into()))?;
            let parent = match path.parent() {
                Some(p) if !p.as_os_str().is_empty() => p,
                _ => Path::new("."),
            };
            let dir = parent
                .canonicalize()
                .map_err(|_| fail(format!("no directory {}", parent.display())))?;
            dir.join(file_name)
        }
        Err(e) => return Err(fail(format!("cannot inspect: {e}"))),
        Ok(_) => {
            let target = path
                .canonicalize()
                .map_err(|_| fail("a symlink to nothing; refusing to write through it".into()))?;
            if !target.is_file() {
                return Err(fail(
                    "exists and is not a regular file; refusing to replace it".into(),
                ));
            }
            target
        }
    };
    let same = |p: &Path| p.canonicalize().is_ok_and(|c| c == target);
    if let Some(input) = inputs.iter().find(|p| same(p)) {
        let input = input.display();
        return Err(fail(format!(
            "refusing to write over the input file {input}"
        )));
    }
    if let Some(other) = others.iter().find(|o| o.target == target) {
        return Err(fail(format!("the same file as {}", other.what)));
    }
    Ok(OutFile {
        target,
        what: what.to_string(),
    })
}

impl OutFile {
    /// Writes `bytes` as the whole file: a new temporary file beside the target, renamed over it.
    ///
    /// # Errors
    /// `OSError` naming the argument and the file when it cannot be written (the temporary file
    /// removed).
    pub fn write(&self, bytes: &[u8]) -> PyResult<()> {
        self.put(bytes, |temporary, target| {
            std::fs::rename(temporary, target)
        })
    }

    /// Writes `bytes` as a new file: as [`OutFile::write`], but never over a file (one created
    /// since the check included: the temporary file is linked to the target's name, which fails
    /// if the name exists).
    ///
    /// # Errors
    /// `OSError` as for [`OutFile::write`], and for a file that exists.
    pub fn write_new(&self, bytes: &[u8]) -> PyResult<()> {
        self.put(bytes, |temporary, target| {
            std::fs::hard_link(temporary, target).and_then(|_| std::fs::remove_file(temporary))
        })
    }

    /// `bytes` into a new temporary file beside the target, put in place by `place`.
    fn put(
        &self,
        bytes: &[u8],
        place: impl FnOnce(&Path, &Path) -> std::io::Result<()>,
    ) -> PyResult<()> {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let dir = self.target.parent().unwrap_or(Path::new("."));
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temporary = dir.join(format!(".stiffid-{}-{n}.tmp", std::process::id()));
        let error = |e: std::io::Error| {
            pyo3::exceptions::PyOSError::new_err(format!(
                "{} {}: cannot write: {e}",
                self.what,
                self.target.display()
            ))
        };
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temporary)
            .map_err(error)?;
        let written = (file.write_all(bytes).and_then(|_| file.sync_all()))
            .and_then(|_| place(&temporary, &self.target));
        written.map_err(|e| {
            let _ = std::fs::remove_file(&temporary);
            error(e)
        })
    }
}
