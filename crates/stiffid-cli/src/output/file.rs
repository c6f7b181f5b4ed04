//! One output file (`--out FILE`).

use super::target::{replace, resolve, temporary};
use anyhow::Result;
use std::path::{Path, PathBuf};

/// An output file, checked when the command starts (after reading its inputs, before computing):
/// see [`resolve`]; its directory proven writable by creating and removing a temporary file.
#[derive(Debug)]
pub struct OutFile {
    /// Where the bytes go (the symlink's target for a symlink).
    target: PathBuf,
}

impl OutFile {
    /// Checks `path`, given with the command-line `option`.
    ///
    /// # Errors
    /// Those of [`resolve`]; a directory that cannot be written.
    pub fn prepare(path: &Path, option: &str) -> Result<Self> {
        let target = resolve(path, option)?;
        let (probe, _file) = temporary(dir_of(&target))?;
        std::fs::remove_file(probe)?;
        Ok(Self { target })
    }

    /// Writes `bytes` as the whole file.
    ///
    /// # Errors
    /// When the file cannot be written (nothing is left behind then).
    pub fn write(&self, bytes: &[u8]) -> Result<()> {
        replace(&self.target, dir_of(&self.target), bytes)
    }
}

/// The directory of a resolved (absolute) target.
fn dir_of(target: &Path) -> &Path {
    target.parent().unwrap_or(Path::new("/"))
}
