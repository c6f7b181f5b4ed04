//! The files a front end writes (the command's `--out`, Python's `out=`): where a write lands and
//! whether it may, and writing a file whole. One set of rules for both front ends: a new name in
//! an existing directory, or a regular file (through a symlink to one, to its target); never a
//! directory, a device or another non-regular file, a dangling symlink, or a file the run reads;
//! the bytes go to a short temporary name beside the target, synced, then renamed over it (or
//! linked to it, for a file that must be new), so a file is there whole or not at all and
//! nothing is left behind on failure. When the file is put in place is the front end's choice
//! (the command stages it until its run has succeeded, Python puts it at once).

use crate::{Error, Result};
use std::fs::File;
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::temporaries;

/// The file a write to `path` replaces or creates, paths resolved: `path` itself (absolute) for a
/// new name or a regular file, the final target for a symlink to a regular file. `input_at`
/// gives the input file of the run that a resolved path is, if any.
///
/// # Errors
/// [`Error::InvalidField`] with the field `what` (the option or argument, e.g. `--out`) and the
/// path: the path ends with a separator, `.` or `..` (a directory's spelling, even where nothing
/// exists), exists and is not a regular file, is a dangling symlink, its
/// directory does not exist, or it is an input of the run.
pub fn resolve(
    path: &Path,
    what: &str,
    input_at: impl Fn(&Path) -> Option<PathBuf>,
) -> Result<PathBuf> {
    let fail = |message: String| Error::InvalidField {
        field: format!("{what} {}", path.display()),
        message,
    };
    if names_a_directory(path) {
        return Err(fail(
            "ends with a directory separator, '.' or '..': a directory, expected a file name"
                .into(),
        ));
    }
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
                return Err(fail(format!(
                    "exists and is not a regular file ({}); refusing to replace it",
                    kind(&target)
                )));
            }
            target
        }
    };
    match input_at(&target) {
        Some(input) => Err(fail(format!(
            "refusing to write over the input file {}",
            input.display()
        ))),
        None => Ok(target),
    }
}

/// Whether `path` is spelt as a directory: its last component, as written, is empty (a trailing
/// separator), `.` or `..` (`Path::file_name` drops a trailing separator and `.`).
fn names_a_directory(path: &Path) -> bool {
    let text = path.as_os_str().as_encoded_bytes();
    let last = text
        .rsplit(|&b| std::path::is_separator(char::from(b)))
        .next()
        .unwrap_or_default();
    matches!(last, b"" | b"." | b"..")
}

/// What a non-regular file is, in words: "a directory", "a device", "a FIFO", "a socket".
pub(crate) fn kind(path: &Path) -> &'static str {
    std::fs::metadata(path).map_or("not a regular file", |m| kind_of(m.file_type()))
}

/// What a file of type `file_type` is, in words ([`kind`]).
pub(crate) fn kind_of(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        match file_type {
            t if t.is_dir() => "a directory",
            t if t.is_char_device() || t.is_block_device() => "a device",
            t if t.is_fifo() => "a FIFO",
            t if t.is_socket() => "a socket",
            _ => "not a regular file",
        }
    }
    #[cfg(not(unix))]
    match file_type {
        t if t.is_dir() => "a directory",
        _ => "not a regular file",
    }
}

/// A new temporary file in `dir` with a short name (`.stiffid-PID-N.tmp`, under 32 bytes, so any
/// valid target name works), created exclusively and recorded for [`remove_temporaries`]. The
/// first temporary a process makes in a directory first removes the stale ones there
/// (`.stiffid-PID-N.tmp` of a process that is gone).
///
/// # Errors
/// When it cannot be created.
pub fn temporary(dir: &Path) -> std::io::Result<(PathBuf, File)> {
    static COUNT: AtomicUsize = AtomicUsize::new(0);
    temporaries::remove_stale(dir);
    let n = COUNT.fetch_add(1, Ordering::Relaxed);
    let path = dir.join(temporaries::name(std::process::id(), n));
    let file = temporaries::make(&path)?;
    Ok((path, file))
}

pub use temporaries::remove_temporaries;

/// `bytes` written whole to a new [`temporary`] file in `dir`, synced; its path. Nothing is left
/// behind on failure.
///
/// # Errors
/// When the file cannot be created or written (a full device).
pub fn write_temporary(dir: &Path, bytes: &[u8]) -> std::io::Result<PathBuf> {
    write_temporary_as(dir, bytes, true)
}

/// [`write_temporary`], synced to the disk only when `sync` is true. Unsynced, the file is still
/// put in place whole by a rename (a reader or a killed run never sees part of it), but a power
/// cut right after the run may lose it: for files a run writes again at will (a report's page
/// and figures), whose one sync each costs more than drawing them.
///
/// # Errors
/// When the file cannot be created or written (a full device).
pub fn write_temporary_as(dir: &Path, bytes: &[u8], sync: bool) -> std::io::Result<PathBuf> {
    let (tmp, mut file) = temporary(dir)?;
    let written = file.write_all(bytes).and_then(|_| match sync {
        true => file.sync_all(),
        false => Ok(()),
    });
    match written {
        Ok(()) => Ok(tmp),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// Puts the temporary file `tmp` in place as `target` (a resolved path, [`resolve`]): renamed
/// over it (`new_only` false), or as a new file only, never over one created since the check
/// (linked to the name, which fails if the name exists; copied where links are not supported).
/// `tmp` is gone afterwards either way.
///
/// # Errors
/// When `target` became a non-regular file, or (`new_only`) exists; when it cannot be written.
pub fn place(tmp: &Path, target: &Path, new_only: bool) -> std::io::Result<()> {
    let done = match new_only {
        false => replace(tmp, target),
        true => create_new(tmp, target),
    };
    let _ = std::fs::remove_file(tmp);
    done
}

fn replace(tmp: &Path, target: &Path) -> std::io::Result<()> {
    match std::fs::symlink_metadata(target) {
        Ok(m) if !m.is_file() => Err(std::io::Error::other(format!(
            "became {} meanwhile; not replaced",
            kind(target)
        ))),
        _ => std::fs::rename(tmp, target),
    }
}

fn create_new(tmp: &Path, target: &Path) -> std::io::Result<()> {
    let exists =
        || std::io::Error::other("exists (created meanwhile by another program); not replaced");
    match std::fs::hard_link(tmp, target) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == ErrorKind::AlreadyExists => Err(exists()),
        Err(_) => match File::options().write(true).create_new(true).open(target) {
            Ok(mut file) => {
                let copied = File::open(tmp)
                    .and_then(|mut from| std::io::copy(&mut from, &mut file))
                    .and_then(|_| file.sync_all());
                if copied.is_err() {
                    let _ = std::fs::remove_file(target);
                }
                copied.map(|_| ())
            }
            Err(e) if e.kind() == ErrorKind::AlreadyExists => Err(exists()),
            Err(e) => Err(e),
        },
    }
}
