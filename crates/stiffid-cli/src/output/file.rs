//! One output file (`--out FILE`).

use super::target::{replace, resolve, temporary};
use anyhow::{Context, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
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

    /// Where the bytes go (resolved: the symlink's target for a symlink).
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Writes `bytes` as the whole file, put in place when the run succeeds
    /// ([`super::staged`]).
    ///
    /// # Errors
    /// When the file cannot be written (nothing is left behind then).
    pub fn write(&self, bytes: &[u8]) -> Result<()> {
        replace(
            &self.target,
            dir_of(&self.target),
            bytes,
            self.new_only,
            true,
        )
    }
}

impl OutFile {
    /// A writer for the file written piece by piece (a large result that never sits in memory
    /// whole): a temporary file beside the target, staged by [`Writer::finish`] like
    /// [`OutFile::write`]; removed if dropped unfinished.
    ///
    /// # Errors
    /// When the temporary file cannot be created.
    pub fn writer(&self) -> Result<Writer> {
        let (tmp, file) = temporary(dir_of(&self.target))?;
        let file = BufWriter::with_capacity(1 << 16, file);
        Ok(Writer::new(file, tmp, self.target.clone(), self.new_only))
    }
}

/// An [`OutFile`] being written piece by piece ([`OutFile::writer`]).
#[derive(Debug)]
pub struct Writer {
    file: BufWriter<File>,
    tmp: PathBuf,
    target: PathBuf,
    new_only: bool,
    done: bool,
}

impl Writer {
    /// A writer of `file`, the temporary file `tmp`, staged as `target` when finished (only as a
    /// new file with `new_only`); its errors name `target`.
    pub fn new(file: BufWriter<File>, tmp: PathBuf, target: PathBuf, new_only: bool) -> Self {
        Writer {
            file,
            tmp,
            target,
            new_only,
            done: false,
        }
    }

    /// The temporary file being written (to read it back once finished writing).
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Flushes and syncs what was written; the file stays a temporary one until [`Writer::finish`].
    ///
    /// # Errors
    /// When the bytes cannot be written (a full device).
    pub fn sync(&mut self) -> Result<()> {
        self.file
            .flush()
            .and_then(|_| self.file.get_ref().sync_all())
            .with_context(|| format!("{}: cannot write", self.target.display()))
    }

    /// Ends the file: synced, and staged to be put in place when the run succeeds.
    ///
    /// # Errors
    /// As [`Writer::sync`].
    pub fn finish(mut self) -> Result<()> {
        self.sync()?;
        self.done = true;
        let (tmp, target) = (self.tmp.clone(), self.target.clone());
        match self.new_only {
            true => super::staged::create(tmp, target),
            false => super::staged::replace(tmp, target),
        }
        Ok(())
    }
}

impl Writer {
    /// `e` naming the file it was writing (a full device's error names no file).
    fn named(&self, e: std::io::Error) -> std::io::Error {
        std::io::Error::new(
            e.kind(),
            format!("{}: cannot write: {e}", self.target.display()),
        )
    }
}

impl Write for Writer {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.write(buf).map_err(|e| self.named(e))
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush().map_err(|e| self.named(e))
    }
}

impl Drop for Writer {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// The directory of a resolved (absolute) target.
fn dir_of(target: &Path) -> &Path {
    target.parent().unwrap_or(Path::new("/"))
}
