//! The `stiffid` command: checks the standard streams, then runs the command ([`stiffid_cli::run`]).

use std::process::ExitCode;

fn main() -> ExitCode {
    match standard_streams() {
        Ok(()) => stiffid_cli::run(),
        Err(message) => stiffid_cli::fail(&message),
    }
}

/// Whether descriptor 1 was closed when the process started, before Rust's runtime reopened it
/// on `/dev/null` (read-write, as Python's `subprocess.DEVNULL` opens it too, so the two cannot
/// be told apart later): recorded by [`STDOUT_AT_START`].
#[cfg(target_os = "linux")]
static STDOUT_CLOSED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Runs from `.init_array`, before `main` and before Rust's runtime touches the standard streams.
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static STDOUT_AT_START: extern "C" fn() = {
    extern "C" fn record() {
        // SAFETY: fcntl(F_GETFD) only queries the descriptor; -1 (EBADF) means it is closed.
        let closed = unsafe { libc::fcntl(1, libc::F_GETFD) } == -1;
        STDOUT_CLOSED.store(closed, std::sync::atomic::Ordering::Relaxed);
    }
    record
};

/// Checks that stdout is open: a closed descriptor (`>&-`) is an error, since the results would go
/// nowhere; `/dev/null`, however opened, is the user's choice.
fn standard_streams() -> Result<(), String> {
    #[cfg(target_os = "linux")]
    if STDOUT_CLOSED.load(std::sync::atomic::Ordering::Relaxed) {
        return Err("stdout is closed: stiffid writes its results there (redirect it to a file or to /dev/null)".into());
    }
    Ok(())
}
