//! The files a front end reads (the command's input files, Python's paths): opened as regular
//! files only. A FIFO, a socket or a device is refused at once with what it is, instead of a read
//! that waits for a writer that never comes (a FIFO is opened without blocking, then refused);
//! a directory is refused too. One rule for both front ends.

use std::fs::File;
use std::io::{Error, ErrorKind};
use std::path::Path;

/// The file at `path` opened for reading: a regular file, or a symlink to one.
///
/// # Errors
/// The operating system's error for a file that cannot be opened (`NotFound`, ...);
/// `ErrorKind::InvalidInput` with "is a directory, expected a file" or "is a FIFO (or a device,
/// a socket), not a regular file; give a file" (`super::output::kind`) for anything but a
/// regular file.
///
/// # Examples
/// ```
/// let e = stiffid_core::io::input::open(std::path::Path::new("/dev/null")).unwrap_err();
/// assert_eq!(e.to_string(), "is a device, not a regular file; give a file");
/// ```
pub fn open(path: &Path) -> std::io::Result<File> {
    let file = options().open(path)?;
    let file_type = file.metadata()?.file_type();
    match file_type.is_file() {
        true => Ok(file),
        false if file_type.is_dir() => Err(Error::new(
            ErrorKind::InvalidInput,
            "is a directory, expected a file",
        )),
        false => Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "is {}, not a regular file; give a file",
                super::output::kind_of(file_type)
            ),
        )),
    }
}

/// Read-only, and on Unix without blocking in `open` (a FIFO with no writer would wait there
/// forever; the flag changes nothing for a regular file's reads).
fn options() -> std::fs::OpenOptions {
    let mut options = File::options();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options
}

/// The file of `path`'s folder and stem whose extension is `extension` in any case, as a
/// controller pairs a program with its data (KUKA's `X.src` and `X.dat`); where several are
/// (`X.dat` and `X.DAT` on a case-sensitive file system: a program and the one a compensation
/// wrote as `X.SRC`), the one whose extension's case follows `path`'s (upper case where all of
/// `path`'s extension is), else the first in path order. `None` where there is none or the
/// folder cannot be listed. One rule for both front ends.
pub fn beside(path: &Path, extension: &str) -> Option<std::path::PathBuf> {
    let stem = path.file_stem()?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let named = |p: &Path| {
        p.file_stem() == Some(stem)
            && (p.extension().and_then(|e| e.to_str()))
                .is_some_and(|e| e.eq_ignore_ascii_case(extension))
    };
    let mut found: Vec<_> = (std::fs::read_dir(dir).ok()?.flatten())
        .map(|e| e.path())
        .filter(|p| named(p))
        .collect();
    found.sort();
    let upper = (path.extension().and_then(|e| e.to_str()))
        .is_some_and(|e| !e.is_empty() && e.chars().all(|c| c.is_ascii_uppercase()));
    let wanted = match upper {
        true => extension.to_ascii_uppercase(),
        false => extension.to_ascii_lowercase(),
    };
    let paired = (found.iter()).position(|p| p.extension().is_some_and(|e| *e == *wanted));
    (!found.is_empty()).then(|| found.swap_remove(paired.unwrap_or(0)))
}

/// The most files a folder given as a controller's backup lists ([`files_under`]).
const MAX_BACKUP_FILES: usize = 10_000;

/// How deep [`files_under`] looks into a folder (a KUKA backup's `KRC/R1/System/$config.dat` is
/// 3 folders down).
const MAX_BACKUP_DEPTH: usize = 8;

/// The files a path given as a controller's backup stands for: the path itself when it is a file
/// (whatever its name), else the regular files under the folder, at most `MAX_BACKUP_DEPTH`
/// folders down, whose name `wanted` takes, in path order. One rule for both front ends (the
/// command's `--backup`, Python's `backup=`); symbolic links to folders are not followed.
///
/// # Errors
/// The operating system's error for a path that cannot be read, naming what it could not read;
/// `ErrorKind::InvalidInput` when the folder holds more than `MAX_BACKUP_FILES` such files.
pub fn files_under(
    path: &Path,
    wanted: &dyn Fn(&str) -> bool,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    if !std::fs::metadata(path)?.is_dir() {
        return Ok(vec![path.to_path_buf()]);
    }
    let mut out = Vec::new();
    let mut folders = vec![(path.to_path_buf(), 0usize)];
    while let Some((folder, depth)) = folders.pop() {
        for entry in std::fs::read_dir(&folder)? {
            let entry = entry?;
            let kind = entry.file_type()?;
            let name = entry.file_name();
            if kind.is_dir() && depth < MAX_BACKUP_DEPTH {
                folders.push((entry.path(), depth + 1));
            } else if kind.is_file() && wanted(&name.to_string_lossy()) {
                out.push(entry.path());
                if out.len() > MAX_BACKUP_FILES {
                    return Err(Error::new(ErrorKind::InvalidInput, format!("holds more than {MAX_BACKUP_FILES} files of the program's language: give the backup's folder of the robot (KUKA KRC/R1, ABB RAPID/TASK1) or the files themselves")));
                }
            }
        }
    }
    out.sort();
    Ok(out)
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_folder_lists_its_wanted_files_below_it_and_a_file_is_itself() {
        let dir = std::env::temp_dir().join(format!("stiffid-backup-{}", std::process::id()));
        let deep = dir.join("KRC/R1/System");
        std::fs::create_dir_all(&deep).unwrap();
        std::fs::write(deep.join("$config.dat"), "DEFDAT $CONFIG\n").unwrap();
        std::fs::write(dir.join("notes.txt"), "").unwrap();
        let dat = |n: &str| n.ends_with(".dat");
        let found = super::files_under(&dir, &dat).unwrap();
        assert_eq!(found, vec![deep.join("$config.dat")]);
        let one = super::files_under(&dir.join("notes.txt"), &dat).unwrap();
        assert_eq!(one, vec![dir.join("notes.txt")]);
        assert!(super::files_under(&dir.join("missing"), &dat).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
