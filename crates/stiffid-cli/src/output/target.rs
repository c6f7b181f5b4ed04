//! Where a write lands, and whether it may: the library's rules ([`stiffid::internal::io::output`]) with
//! the command's inputs, shared by [`super::OutFile`] and [`super::ReportDir`].

use crate::load;
use anyhow::{Context, Result};
use std::fs::File;
use std::path::{Path, PathBuf};
use stiffid::internal::io::output;

/// The file a write to `path` replaces or creates ([`output::resolve`]), never one the command
/// read ([`load::input_at`]).
///
/// # Errors
/// Those of [`output::resolve`], naming `option` (the command-line option, e.g. `--out`) and the
/// path.
pub fn resolve(path: &Path, option: &str) -> Result<PathBuf> {
    Ok(output::resolve(path, option, load::input_at)?)
}

/// A new temporary file in `dir` ([`output::temporary`]).
pub fn temporary(dir: &Path) -> Result<(PathBuf, File)> {
    output::temporary(dir).with_context(|| format!("{}: cannot write", dir.display()))
}

/// Writes `bytes` whole to a temporary file in `tmp_dir` (same file system as the resolved
/// `target`, see [`resolve`]), synced when `sync` ([`output::write_temporary_as`]), and stages it
/// to be put in place as `target` when the run succeeds ([`super::staged`]; `new_only`: only if
/// `target` does not exist by then).
pub fn replace(
    target: &Path,
    tmp_dir: &Path,
    bytes: &[u8],
    new_only: bool,
    sync: bool,
) -> Result<()> {
    let tmp = output::write_temporary_as(tmp_dir, bytes, sync)
        .with_context(|| format!("{}: cannot write", target.display()))?;
    match new_only {
        true => super::staged::create(tmp, target.to_path_buf()),
        false => super::staged::replace(tmp, target.to_path_buf()),
    }
    Ok(())
}
