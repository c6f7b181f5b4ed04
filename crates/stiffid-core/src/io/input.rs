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
