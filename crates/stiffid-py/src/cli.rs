//! The `stiffid` command inside the Python package: the wheel's `stiffid` script (see
//! `python/stiffid/_cli.py`) runs the same command-line program as the `stiffid` binary, so a
//! user who installs the wheel has both without a Rust toolchain.

use pyo3::prelude::*;
use std::ffi::OsString;

/// Runs the `stiffid` command on `argv` (the program's name first, as `sys.argv`) and ends the
/// process with its exit code (0 success, 1 a gate the result failed, 2 bad input), as the binary does. It never returns: the
/// command owns the process from here (its outputs are flushed by the exit).
#[pyfunction]
pub fn _cli(py: Python<'_>, argv: Vec<OsString>) -> PyResult<()> {
    let code = py.detach(|| stiffid_cli::run_from(argv));
    std::process::exit(i32::from(code))
}
