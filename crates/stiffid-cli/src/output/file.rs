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
    /// Only as a new file: never replacing one, even one created while the run computes.
    new_only: bool,
}

impl OutFile {
    /// Checks `path`, given with the command-line `option`.
    ///
    /// # Errors
    /// Those of [`resolve`]; a directory that cannot be written.
    pub fn prepare(path: &Path, option: &str) -> Result<Self> {
        let target = resolve(path, option)?;
        super::staged::claim(&target, option)?;
        let (probe, _file) = temporary(dir_of(&target))?;
        std::fs::remove_file(probe)?;
        Ok(Self {
            target,
            new_only: false,
        })
    }

    /// [`OutFile::prepare`] for a file that must not exist: checked now, and created at the end
    /// of the run by an atomic no-replace create (a file created meanwhile, by a concurrent run
    /// for example, is never replaced: the run fails).
    ///
    /// # Errors
    /// Those of [`OutFile::prepare`]; `path` exists.
    pub fn prepare_new(path: &Path, option: &str) -> Result<Self> {
        if path.symlink_metadata().is_ok() {
            anyhow::bail!(
                "{option} {}: exists; this command writes a new file only",
                path.display()
            );
        }
        Ok(Self {
            new_only: true,
            ..Self::prepare(path, option)?
        })
    }

    /// Writes `bytes` as the whole file, put in place when the run succeeds
    /// ([`super::staged`]).
    ///
    /// # Errors
    /// When the file cannot be written (nothing is left behind then).
    pub fn write(&self, bytes: &[u8]) -> Result<()> {
        replace(&self.target, dir_of(&self.target), bytes, self.new_only)
    }
}

/// The directory of a resolved (absolute) target.
fn dir_of(target: &Path) -> &Path {
    target.parent().unwrap_or(Path::new("/"))
}
