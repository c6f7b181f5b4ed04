//! One output directory (`--out DIR` of `simulate` and `reproduce`).

use super::target::{replace, resolve};
use anyhow::{bail, Context, Result};
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};

/// The hidden directory inside a report directory that holds the temporary files while they are
/// written. A run killed mid-write (SIGKILL) leaves it behind; the next run into the same
/// directory removes it. One run at a time writes into a directory (an exclusive lock on it,
/// held to the end of the run): a second one is refused.
pub const TEMP_DIR: &str = ".stiffid-tmp";

/// A directory being filled with a report, checked when the command starts (before computing).
///
/// Dropped without [`ReportDir::finish`] (an error on the way), it removes its temporary files
/// and, if it created the directory, the directory with everything written into it.
#[derive(Debug)]
pub struct ReportDir {
    /// The directory, resolved.
    dir: PathBuf,
    /// [`TEMP_DIR`] inside it.
    tmp: PathBuf,
    /// The top-most directory this run created, if any.
    created: Option<PathBuf>,
    /// The files of an earlier report the report would write (resolved); those this run does
    /// not write again are removed when it succeeds.
    earlier: std::sync::Mutex<Vec<PathBuf>>,
    /// The directory's lock: released when dropped unfinished, else held to the end of the run.
    lock: Option<std::fs::File>,
    done: bool,
}

impl ReportDir {
    /// Checks and opens `dir` (the command-line `option`): it must be a directory or a new path;
    /// an existing directory must be empty, or `reusable` (a previous report of ours), unless
    /// `force` is `Some(true)` (`None`: the command has no `--force`). Every existing entry the report will write (`holds`, given the path relative to
    /// `dir`) must pass [`resolve`] (a regular file, not an input). The directory is created if
    /// missing and proven writable by creating [`TEMP_DIR`] in it.
    ///
    /// # Errors
    /// One line naming the option, the directory and what is wrong.
    pub fn prepare(
        dir: &Path,
        option: &str,
        force: Option<bool>,
        holds: &dyn Fn(&Path) -> bool,
        reusable: &dyn Fn(&Path) -> bool,
    ) -> Result<Self> {
        let name = dir.display();
        match std::fs::metadata(dir) {
            Ok(m) if !m.is_dir() => bail!("{option} {name}: exists and is not a directory"),
            Ok(_) if force != Some(true) && !is_empty(dir)? && !reusable(dir) => bail!(
                "{option} {name}: not empty and not a previous report of this command; choose another {option}{}",
                if force.is_some() { " or pass --force" } else { "" }
            ),
            Ok(_) => {}
            Err(e) if e.kind() == ErrorKind::NotFound && dir.symlink_metadata().is_ok() => {
                bail!("{option} {name}: a symlink to nothing; refusing to write through it")
            }
            Err(e) if e.kind() == ErrorKind::NotFound => {}
            Err(e) => return Err(e).with_context(|| format!("{option} {name}: cannot inspect")),
        }
        let created = create(dir).with_context(|| format!("{option} {name}: cannot create"))?;
        if let Some(top) = &created {
            super::staged::created(top.clone());
        }
        let resolved = dir.canonicalize()?;
        super::staged::claim(&resolved, option)?;
        let lock = lock(&resolved).with_context(|| format!("{option} {name}"))?;
        let report = Self {
            tmp: resolved.join(TEMP_DIR),
            dir: resolved,
            created,
            earlier: Default::default(),
            lock,
            done: false,
        };
        report.check_existing(&report.dir, Path::new(""), holds, option)?;
        if report.tmp.exists() {
            std::fs::remove_dir_all(&report.tmp)
                .with_context(|| format!("{option} {name}: cannot remove {TEMP_DIR}"))?;
        }
        std::fs::create_dir(&report.tmp)
            .with_context(|| format!("{option} {name}: cannot write into it"))?;
        super::staged::scratch(report.tmp.clone());
        Ok(report)
    }

    /// Checks every existing entry under `dir` (`rel` relative to the report) that the report
    /// will write, two levels deep.
    fn check_existing(
        &self,
        dir: &Path,
        rel: &Path,
        holds: &dyn Fn(&Path) -> bool,
        option: &str,
    ) -> Result<()> {
        for entry in std::fs::read_dir(dir)? {
            let entry = entry?;
            let rel = rel.join(entry.file_name());
            let is_dir = entry.file_type()?.is_dir();
            if is_dir && rel.components().count() < 2 && entry.file_name() != TEMP_DIR {
                self.check_existing(&entry.path(), &rel, holds, option)?;
            } else if holds(&rel) {
                resolve(&entry.path(), option)?;
                self.earlier
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .push(entry.path());
            }
        }
        Ok(())
    }

    /// Writes `bytes` whole as the file `rel` (relative to the directory; subdirectories are
    /// created), through an existing symlink to its target. Not synced to the disk: a report is
    /// put in place whole by renames when its run succeeds, and written again by running the
    /// command again, while a sync per file cost more than the report's drawing (5 to 15 ms
    /// each on a busy disk, against a few ms of drawing).
    ///
    /// # Errors
    /// Those of [`resolve`]; a file that cannot be written.
    pub fn write(&self, rel: &str, bytes: &[u8]) -> Result<()> {
        let path = self.dir.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("{}: cannot create", parent.display()))?;
        }
        self.earlier
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .retain(|p| *p != path);
        replace(
            &resolve(&path, "report file")?,
            &self.tmp,
            bytes,
            false,
            false,
        )
    }

    /// Writes every file of `files` (each a path relative to the directory and its bytes) as
    /// [`ReportDir::write`] does.
    ///
    /// # Errors
    /// The first of [`ReportDir::write`]'s.
    pub fn write_all<B: AsRef<[u8]>>(&self, files: &[(String, B)]) -> Result<()> {
        files
            .iter()
            .try_for_each(|(rel, bytes)| self.write(rel, bytes.as_ref()))
    }

    /// Writes the file `rel` (as [`ReportDir::write`]) by `fill` (a large result that never sits
    /// in memory whole).
    ///
    /// # Errors
    /// As [`ReportDir::write`]; those of `fill`.
    pub fn write_with(&self, rel: &str, fill: Fill) -> Result<()> {
        let path = self.dir.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("{}: cannot create", parent.display()))?;
        }
        let target = resolve(&path, "report file")?;
        self.earlier
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .retain(|p| *p != path);
        let (tmp, file) = super::target::temporary(&self.tmp)?;
        let mut out = std::io::BufWriter::new(file);
        let written = fill(&mut out).and_then(|()| out.flush());
        if let Err(e) = written {
            let _ = std::fs::remove_file(&tmp);
            return Err(e).with_context(|| format!("{}: cannot write", target.display()));
        }
        super::staged::replace(tmp, target);
        Ok(())
    }

    /// Ends the report: when the run succeeds ([`super::staged::commit`]) its files are put in
    /// place, the files of an earlier report it did not write again (a larger group's
    /// `posture_NN` figures) are removed, and so is the temporary directory.
    ///
    /// # Errors
    /// None today; kept for the callers' `?`.
    pub fn finish(mut self) -> Result<()> {
        self.done = true;
        for path in std::mem::take(&mut *self.earlier.lock().unwrap_or_else(|e| e.into_inner())) {
            super::staged::stale(path);
        }
        super::staged::temp_dir(self.tmp.clone());
        if let Some(lock) = self.lock.take() {
            super::staged::hold(lock);
        }
        Ok(())
    }
}

impl Drop for ReportDir {
    fn drop(&mut self) {
        super::staged::unclaim(&self.dir);
        if self.done {
            return;
        }
        let _ = std::fs::remove_dir_all(&self.tmp);
        if let Some(created) = &self.created {
            let _ = std::fs::remove_dir_all(created);
        }
    }
}

/// What writes a file or stdout, a piece at a time ([`ReportDir::write_with`],
/// [`super::write_stdout_with`]).
pub type Fill<'a> = &'a dyn Fn(&mut dyn Write) -> std::io::Result<()>;

/// How often, 20 ms apart, a lock another holder has is asked for before it is refused.
const LOCK_TRIES: u32 = 10;

/// Takes an exclusive lock on the directory `dir` (held as long as the returned handle), refusing
/// when another process (or another open of it) holds it. A lock just released can still be
/// held for a moment by a child process another thread started (its copy of the descriptor lives
/// until the child starts its program), so a refused lock is asked for again for up to 0.2 s.
fn lock(dir: &Path) -> Result<Option<std::fs::File>> {
    #[cfg(unix)]
    {
        use std::os::unix::io::AsRawFd;
        let handle = std::fs::File::open(dir).context("cannot open")?;
        for _ in 0..LOCK_TRIES {
            // SAFETY: flock on a descriptor we own; LOCK_NB never blocks.
            let locked = unsafe { libc::flock(handle.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
            if locked == 0 {
                return Ok(Some(handle));
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        bail!("another stiffid run is writing into this directory; wait for it to end");
    }
    #[allow(unreachable_code)]
    Ok(None)
}

/// Whether `dir` holds nothing but a stale [`TEMP_DIR`].
fn is_empty(dir: &Path) -> Result<bool> {
    let mut entries =
        std::fs::read_dir(dir).with_context(|| format!("{}: cannot read", dir.display()))?;
    Ok(entries.all(|e| e.is_ok_and(|e| e.file_name() == TEMP_DIR)))
}

/// Creates `dir` and its missing parents; returns the top-most directory created, if any.
fn create(dir: &Path) -> std::io::Result<Option<PathBuf>> {
    let top = dir
        .ancestors()
        .take_while(|a| !a.as_os_str().is_empty() && !a.exists())
        .last()
        .map(Path::to_path_buf);
    std::fs::create_dir_all(dir)?;
    Ok(top)
}
