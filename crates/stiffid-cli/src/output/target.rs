//! Where a write lands, and whether it may: the checks shared by [`super::OutFile`] and
//! [`super::ReportDir`].

use crate::load;
use anyhow::{bail, Context, Result};
use std::fs::File;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The file a write to `path` replaces or creates, paths resolved: `path` itself (absolute) for a
/// new name or a regular file, the final target for a symlink to a regular file.
///
/// # Errors
/// `option` (the command-line option, e.g. `--out`) and the path named in the message, when the
/// path exists and is not a regular file (a directory, a device, a FIFO, a socket), is a dangling
/// symlink, its directory does not exist, or it is a file the command read.
pub fn resolve(path: &Path, option: &str) -> Result<PathBuf> {
    let name = path.display();
    let target = match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == ErrorKind::NotFound => {
            let file_name = path
                .file_name()
                .with_context(|| format!("{option} {name}: not a file name"))?;
            let parent = match path.parent() {
                Some(p) if !p.as_os_str().is_empty() => p,
                _ => Path::new("."),
            };
            let dir = parent
                .canonicalize()
                .with_context(|| format!("{option} {name}: no directory {}", parent.display()))?;
            dir.join(file_name)
        }
        Err(e) => return Err(e).with_context(|| format!("{option} {name}: cannot inspect")),
        Ok(_) => {
            let target = path.canonicalize().with_context(|| {
                format!("{option} {name}: a symlink to nothing; refusing to write through it")
            })?;
            if !target.is_file() {
                bail!(
                    "{option} {name}: exists and is not a regular file ({}); refusing to replace it",
                    kind(&target)
                );
            }
            target
        }
    };
    if let Some(input) = load::input_at(&target) {
        bail!(
            "{option} {name}: refusing to write over the input file {}",
            input.display()
        );
    }
    Ok(target)
}

/// What a non-regular file is, in words.
#[cfg(unix)]
fn kind(path: &Path) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    match std::fs::metadata(path).map(|m| m.file_type()) {
        Ok(t) if t.is_dir() => "a directory",
        Ok(t) if t.is_char_device() || t.is_block_device() => "a device",
        Ok(t) if t.is_fifo() => "a FIFO",
        Ok(t) if t.is_socket() => "a socket",
        _ => "not a regular file",
    }
}

/// What a non-regular file is, in words.
#[cfg(not(unix))]
fn kind(path: &Path) -> &'static str {
    match std::fs::metadata(path).map(|m| m.file_type()) {
        Ok(t) if t.is_dir() => "a directory",
        _ => "not a regular file",
    }
}

/// A new temporary file in `dir` with a short name (`.stiffid-PID-N.tmp`, under 32 bytes, so any
/// valid target name works), created exclusively.
pub fn temporary(dir: &Path) -> Result<(PathBuf, File)> {
    static COUNT: AtomicUsize = AtomicUsize::new(0);
    let n = COUNT.fetch_add(1, Ordering::Relaxed);
    let path = dir.join(format!(".stiffid-{}-{n}.tmp", std::process::id()));
    let file = File::options()
        .write(true)
        .create_new(true)
        .open(&path)
        .with_context(|| format!("{}: cannot write", dir.display()))?;
    Ok((path, file))
}

/// Writes `bytes` whole to the resolved `target` (see [`resolve`]): into a temporary file in
/// `tmp_dir` (same file system), synced, then renamed over `target` after checking once more that
/// `target` is a regular file or missing. The temporary file is removed on any failure.
pub fn replace(target: &Path, tmp_dir: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let (tmp, mut file) = temporary(tmp_dir)?;
    let written = file
        .write_all(bytes)
        .and_then(|_| file.sync_all())
        .map_err(anyhow::Error::from)
        .and_then(|_| match std::fs::symlink_metadata(target) {
            Ok(m) if !m.is_file() => bail!("became {}", kind(target)),
            _ => Ok(std::fs::rename(&tmp, target)?),
        });
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written.with_context(|| format!("{}: cannot write", target.display()))
}
