//! The temporary files a process writes its outputs through (`.stiffid-PID-N.tmp`, module docs
//! of [`super::output`]): recorded, so that a run interrupted by a signal removes them before it
//! exits ([`remove_temporaries`]), and those of processes that are gone (killed outright, by
//! `SIGKILL` or a power cut) removed by the next run that writes into the same directory.

use std::collections::HashSet;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Every temporary file this process has made (a name is never made twice, so removing one
/// that was since put in place or removed is harmless).
static MADE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The directories whose stale temporaries this process has removed.
static SWEPT: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// The name of process `pid`'s `n`-th temporary file.
pub(super) fn name(pid: u32, n: usize) -> String {
    format!(".stiffid-{pid}-{n}.tmp")
}

/// The process id in a temporary file's name, if `file_name` is one.
fn owner(file_name: &str) -> Option<u32> {
    let rest = file_name.strip_prefix(".stiffid-")?.strip_suffix(".tmp")?;
    let (pid, n) = rest.split_once('-')?;
    n.parse::<usize>().ok()?;
    pid.parse().ok()
}

/// Makes the temporary file `path` (created exclusively, for writing) and records it, both under
/// the lock [`remove_temporaries`] takes: a removal sees every temporary made before it, and
/// none is made after it (a signal between the two steps would leave a file behind).
///
/// # Errors
/// When it cannot be created (nothing is recorded).
pub(super) fn make(path: &Path) -> std::io::Result<File> {
    let mut made = MADE.lock().unwrap_or_else(|e| e.into_inner());
    let file = File::options().write(true).create_new(true).open(path)?;
    made.push(path.to_path_buf());
    Ok(file)
}

/// Removes every temporary file this process made that is still there: what a run interrupted
/// by `SIGINT`, `SIGTERM` or `SIGHUP` does before it exits (the command installs the handler).
/// The run exits next, so the record stays locked to the end: a thread that asks for a new
/// temporary meanwhile waits rather than leave one behind.
pub fn remove_temporaries() {
    let mut made = MADE.lock().unwrap_or_else(|e| e.into_inner());
    for path in made.drain(..) {
        let _ = std::fs::remove_file(path);
    }
    std::mem::forget(made);
}

/// Removes, once per directory and process, the temporary files in `dir` whose process is gone:
/// its id names no running process. A process that lives on (or a new one that took its id)
/// keeps them.
pub(super) fn remove_stale(dir: &Path) {
    let mut swept = SWEPT.lock().unwrap_or_else(|e| e.into_inner());
    if !swept
        .get_or_insert_with(HashSet::new)
        .insert(dir.to_path_buf())
    {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let own = std::process::id();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(owner) else {
            continue;
        };
        if pid != own && gone(pid) && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Whether no process has the id `pid` (`kill(pid, 0)` fails with `ESRCH`).
#[cfg(unix)]
fn gone(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    if pid <= 0 {
        return false;
    }
    // SAFETY: signal 0 sends nothing; it only asks whether the process exists.
    let r = unsafe { libc::kill(pid, 0) };
    r == -1 && std::io::Error::last_os_error().raw_os_error() == Some(libc::ESRCH)
}

/// Elsewhere no process is known gone: stale files are left.
#[cfg(not(unix))]
fn gone(_pid: u32) -> bool {
    false
}
